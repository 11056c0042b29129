#pragma once
/// @file
/// Report part `flywheel` (15): flywheel sizing (Norton 13.9) judged. Everything of the part is here: its task's
/// tables and its sentences; report.cc only places it.
///
/// Tables (CSV stems, columns; reports/README.md):
///   flywheel         scene,flywheel_inertia,exact_delta,simbody_delta
///                    for each campaign scene with [gas] (the example scenes with gas in the default campaign), the
///                    steady run's delta against the flywheel inertia I_f (exact energy integral; Simbody's run over a
///                    working cycle at some of the points, empty elsewhere), I_f from 0.3 to 3 times the exact inertia
///                    for C = 0.01
///   flywheel_sizing  scene,cycle,k,speed_rpm,exact_inertia,norton_inertia,norton_error,norton_delta
///                    the exact and Norton's I_f for C = 0.01 of the campaign's gas scenes; norton_error = norton /
///                    exact - 1, norton_delta the delta Norton's inertia really gives
///   flywheel_norton  speed_rpm,k,exact_inertia,norton_inertia,norton_error,norton_delta
///                    the same for the base scene's parts as an inline k-cylinder four-stroke with the example
///                    spark-ignition pressures (bore 2 r), k = 1, 2, 3, 4, 6, at 1500, 3000 and 6000 rpm (rows where no
///                    flywheel is needed for C = 0.01 are left out)

#include <string>
#include <vector>

#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/report_part.h"

namespace crankcheck::validation {

/// The points of a scene's curve (`flywheel`) at which Simbody runs: every third of 13, the exact inertia among
/// them; with `quick`, the exact inertia's alone.
std::vector<int> listFlywheelRunPoints(bool quick);

/// The part's three tables with rows of one scene (none when it has no [gas] or needs no flywheel for C = 0.01):
/// `point` < 0: its `flywheel_sizing` row and the curve's points Simbody does not run; else the curve's point `point`
/// (one of listFlywheelRunPoints) with Simbody's run. The campaign runs one task for each, and one for the sweep: the
/// tables add up.
TableSet calcFlywheelSceneTables(const Mechanism& scene, bool quick, int point);

/// The part's three tables with the rows of the sweep on `parts` (`flywheel_norton`).
TableSet calcFlywheelNortonTables(const Mechanism& parts, bool quick);

/// The part as the report shows it: heading, figure caption, sentences read from the data; an empty heading
/// without data.
ReportPart describeFlywheelPart(const TableSet& tables);

}  // namespace crankcheck::validation
