#pragma once
/// @file
/// The validation campaign behind `crankcheck validate`: a list of independent tasks (so that they can run on
/// several threads or be cut into shards), each producing rows of the report's tables.
///
/// Every maximum over a turn is found so that it does not depend on the grid (extremum.h: the exact harmonics or
/// Brent's method on the best samples), on the same grid in the quick and the full campaign; `resolved` = 0 marks a
/// number at rounding level (a bound, not a measured maximum).
///
/// Tables (CSV stems, columns in docs of reports/README.md):
///   crosscheck            family,engine,case,lambda,quantity,worst_rel_error,where_phi_deg,where_speed_rpm,tolerance_rel,
///                         pass (engine: the engine compared with the analytic one; pass: pass/FAIL for gated engines,
///                         reported for soft ones, which are measured, never gated)
///   every report part's tables: in the part's file, validation/src/parts/KEY.cc (Part::tables lists them)
///   scenes                family,scene,cylinders,cycle,acting,gamma_deg,speed_rpm,r,l,lambda,m_o,m_k,z_k,I_o,m_s,r_s,
///                         m_p,r_p,g,I_w (I_w empty: the scene has no flywheel)
///   notes                 note (what the campaign left out, and why; only when there is something to say)

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/table.h"
#include "crankcheck/validation/campaign_scenes.h"
#include "crankcheck/validation/task.h"

namespace crankcheck::validation {

struct CampaignOptions {
  bool quick = false;               ///< fewer lambdas, angles and methods: a smoke test of the whole report
  std::vector<Mechanism> scenes;    ///< the families to cross-check; empty = the built-in default campaign
  /// The keys of the report parts to run (`validate --parts`), each once; empty = every part. The cross-checks (the
  /// verdict) always run. @see checkPartKeys
  std::vector<std::string> parts;
  /// [s] the longest estimated work a part may start (`validate --work-limit`, work_limit.h): a part whose work on
  /// these scenes is estimated past it refuses the campaign before any work (Part::checkWork).
  double work_limit = 600.0;
  /// The engines that cannot build one of the scenes (findSatOut, engines.h): the caller runs the campaign inside a
  /// SatOutScope of them, and the report's notes name each one, its scene and its reason.
  std::vector<SatOut> sat_out;
};

/// The campaign: cross-checks of every family over lambda (its own and 0.1 .. 0.9), and the data of every report
/// figure. With options.scenes the first scene is the base of the lambda sweeps and figures.
/// @throws UsageError when a part's work is estimated past options.work_limit (Part::checkWork).
std::vector<Task> buildCampaign(const CampaignOptions& options);


}  // namespace crankcheck::validation
