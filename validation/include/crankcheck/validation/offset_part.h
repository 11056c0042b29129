#pragma once
/// @file
/// Report part `offset` (14): what the centric formulas cost on an offset (desaxe) engine, and what the offset buys.
/// Everything of the part is here: its task's tables, its sentences; report.cc only places it.
///
/// The engine: the base scene's parts as one standing cylinder, four-stroke, with the example spark-ignition pressure
/// table (bore 2 r) at 6000 rpm and gravity, its pin offset delta swept over delta / r in [-0.5, 0.5] (production pin
/// offsets are |delta| / r = 0.01 .. 0.04; desaxe cylinders reach 0.5).
/// Tables (CSV stems, columns; reports/README.md):
///   offset         quantity,offset_over_r,max_rel_error,simbody_max_rel_error
///                  the largest error over the working cycle of the centric form (delta = 0: x_p, a_p, wall_force,
///                  drive_torque of the centric engine at the same crank angle) against the offset engine, relative
///                  to the quantity's scale (x_p: the stroke; a_p: r omega^2; forces: the force scale; torque: the
///                  torque scale), and the largest |analytic - Simbody| of the offset engine on the same samples
///   offset_thrust  engine,offset_over_r,peak_major_thrust,peak_minor_thrust,thrust_reversal_deg,max_abs_drive_torque
///                  the side thrust N_w over the working cycle: its largest value on the major-thrust side (N_w > 0:
///                  the wall on -n, docs/CONVENTIONS-crankcheck.md "Pin offset"), its largest on the minor side (as a
///                  positive number), the crank angle nearest the firing outer dead centre (within 90 degrees) where
///                  N_w changes sign (the piston crosses over: slap), and the largest |drive torque|; engines
///                  analytic and simbody

#include <string>
#include <vector>

#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/report_part.h"

namespace crankcheck::validation {

/// The offsets delta / r of the part: -0.5 .. 0.5 (5 of them with `quick`).
std::vector<double> listOffsetFractions(bool quick);

/// The part's tables on `parts` (its crank, rod, piston and flywheel) at one offset delta / r = `offset_over_r` (the
/// campaign runs one task per offset: the tables add up); the 0.25-degree samples of one working cycle (2 degrees
/// with `quick`).
TableSet calcOffsetTables(const Mechanism& parts, double offset_over_r, bool quick);

/// The part as the report shows it: heading, caption, sentences read from the data; an empty heading without data.
ReportPart describeOffsetPart(const TableSet& tables);

}  // namespace crankcheck::validation
