#pragma once
/// @file
/// The computation of `crankcheck stepped` and of the report's part `stepped_engines`: each stepped engine
/// (validation/engines.h listEngines(Route::kStepAtSpeed): the physics engines people ship) on one scene, at each of its settings
/// and a series of time steps, every quantity it reports against the closed forms at the instant it belongs to
/// (stepped_errors.h), the order observed between neighbouring steps and the cost per step. Typed rows, declared once.

#include <string>
#include <vector>

#include "crankcheck/scene/mechanism.h"
#include "crankcheck/solver/engine.h"
#include "crankcheck/solver/stepped_run.h"
#include "crankcheck/validation/table.h"

namespace crankcheck::validation {

/// One quantity of one run (engine, settings, step).
struct SteppedErrorRow {
  std::string scene, engine, settings;
  double dt = 0.0;               ///< [s]
  std::string quantity;          ///< the catalogue's name or kLoopErrorName
  double worst_rel_error = 0.0;  ///< [-] over the measured turn, relative to the quantity's scale
  double where_phi_deg = 0.0;    ///< [deg]
  double step_fraction = 0.0;    ///< [-] the instant it is read at: 0 the step's start, 1 its end
};
extern const Schema<SteppedErrorRow> kSteppedErrorsTable;  ///< data/stepped_errors.csv

/// The cost of one run (engine, settings, step): a measurement, apart from the errors (which a rerun repeats exactly).
struct SteppedCostRow {
  std::string scene, engine, settings;
  double dt = 0.0;               ///< [s]
  double ns_per_step = 0.0;      ///< [ns] the engine's stepping and reads, wall time over the run's steps
};
extern const Schema<SteppedCostRow> kSteppedCostTable;  ///< data/stepped_cost.csv

/// The order observed for one quantity between two neighbouring steps of the series (calcObservedStepOrder).
struct SteppedOrderRow {
  std::string scene, engine, settings, quantity;
  double dt_coarse = 0.0, dt_fine = 0.0;  ///< [s]
  double order = 0.0;                     ///< [-]; NaN where an error is 0
};
extern const Schema<SteppedOrderRow> kSteppedOrdersTable;  ///< data/stepped_orders.csv

/// A run an engine refused: a scene it cannot build (settings and dt empty), or a step it cannot take; engine "all":
/// a step past a quarter turn, refused for every engine before any ran (checkStepAngle).
struct SteppedRefusalRow {
  std::string scene, engine, settings;
  double dt = 0.0;               ///< [s]; 0: every step (the scene)
  std::string reason;            ///< the engine's one line
};
extern const Schema<SteppedRefusalRow> kSteppedRefusalsTable;  ///< data/stepped_refusals.csv

/// Who refused, in words: "every engine" for engine "all", else the engine's name.
inline std::string nameRefuser(const SteppedRefusalRow& r) { return r.engine == "all" ? "every engine" : r.engine; }

struct SteppedSweep {
  std::vector<SteppedErrorRow> errors;
  std::vector<SteppedCostRow> costs;
  std::vector<SteppedOrderRow> orders;
  std::vector<SteppedRefusalRow> refusals;
};

/// The steps [s] of the series by default: 1/240 s (a typical robotics or game step) down to 1e-5 s.
std::vector<double> getDefaultSteppedSteps();

/// The most steps a sweep may take (checkSteppedWork; its runs keep the measured turn's samples): ample for the
/// default series on the slowest example scene (the marine six at 105 rpm: 1.3e6 steps at 1e-5 s). Their time is
/// bounded apart from this, by their measured cost (--work-limit).
inline constexpr double kMaxSteppedSteps = 2e6;

/// One engine's runs at one settings and step, as the work before it starts counts them.
struct SteppedJob {
  const Engine* engine = nullptr;
  std::string settings;
  double dt = 0.0;     ///< [s]
  double steps = 0.0;  ///< the steps the runs take in all (settling included)
};

/// The driven sweep's jobs (calcSteppedSweep's runs): each engine of `engines` at each of `settings` it has (empty:
/// its every settings) and each of `steps`, its steps max(kSettlingSteps, a turn) + a turn.
/// @throws std::invalid_argument as calcStepsPerTurn.
std::vector<SteppedJob> listSteppedJobs(const Mechanism& m, const std::vector<const Engine*>& engines,
                                        const std::vector<std::string>& settings, const std::vector<double>& steps);

/// The steps of the first probe that measures the cost of an engine's step on a scene (checkSteppedWork): a run of
/// 1 + n steps less a run of one, so that building the model is not counted; n = kProbeSteps, then 4 times as many
/// while a probe stays under 50 ms, up to 64 kProbeSteps.
inline constexpr long kProbeSteps = 16;

/// A ceiling on the cost of one step of any stepped engine on a scene of up to four cylinders [s], times (k / 4)^3
/// beyond: 200 us, ten times the dearest measured on four (ODE's direct solve: about 20 us; 85 us on the marine six,
/// 200 us on the V8, 53 ms on k = 64, all within it). Work within the limit at this ceiling is not probed.
inline constexpr double kStepCostCeiling = 2e-4;

/// The time the jobs' work would take [s], and how it was estimated ("1.3e6 steps; the dearest step, ode
/// tightened's, measured at 53 ms"): their steps at kStepCostCeiling where that stays within `budget_seconds` (no probe),
/// else at each engine's and settings' cost of a step measured on m (as checkSteppedWork says).
/// @throws UsageError past kMaxSteppedSteps, naming `what` and `smaller`
struct SteppedWorkEstimate {
  double seconds = 0.0;
  std::string how;
};
SteppedWorkEstimate estimateSteppedWork(const Mechanism& m, const std::vector<SteppedJob>& jobs, double budget_seconds,
                                        const std::string& what, const std::string& smaller);

/// Checks the jobs' work before it starts (work_limit.h): their steps in all within kMaxSteppedSteps (the runs keep a
/// turn's samples), then their time, each job's steps times the cost of a step of its engine and settings measured on m
/// by a probe at the job's step, within `limit_seconds` (no probe where the jobs' steps at kStepCostCeiling are). A job
/// whose engine cannot build m (its probe throws) is not counted: the sweep refuses it by name.
/// @param what the work in the messages ("the stepped engines' runs on FILE")
/// @param smaller how to ask for less ("a larger --dt")
/// @throws UsageError past either limit, naming `what`, the estimate, `smaller` and --work-limit
void checkSteppedWork(const Mechanism& m, const std::vector<SteppedJob>& jobs, double limit_seconds,
                      const std::string& what, const std::string& smaller);

/// Runs every engine of `engines` at each of `settings` (empty: each engine's every settings; a name an engine does
/// not have is skipped for it) and each of `steps` (sorted here from the largest) on m, named `scene` in the rows.
/// A scene an engine cannot build, or a step it refuses (std::invalid_argument, std::runtime_error), is a refusal row.
/// @throws std::invalid_argument if m has no speed or a step is <= 0.
SteppedSweep calcSteppedSweep(const Mechanism& m, const std::string& scene, const std::vector<const Engine*>& engines,
                              const std::vector<std::string>& settings, std::vector<double> steps);

}  // namespace crankcheck::validation
