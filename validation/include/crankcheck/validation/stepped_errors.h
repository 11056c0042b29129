#pragma once
/// @file
/// A stepped engine's run (crankcheck/solver/stepped_run.h) measured against the closed forms: every quantity it reports
/// at the instant it belongs to, over one turn after the start-up transient, relative to the quantity's scale; the
/// observed order of convergence between two steps. The engines are listed by validation/engines.h
/// listEngines(Route::kStepAtSpeed); `crankcheck stepped` and the report's part `stepped_engines` print these.

#include <string>
#include <vector>

#include "crankcheck/scene/mechanism.h"
#include "crankcheck/solver/engine.h"
#include "crankcheck/solver/stepped_run.h"

namespace crankcheck::validation {

/// The name measureSteppedRun gives the loops' separation (Trajectory::loop_error, relative to the position scale).
inline constexpr const char* kLoopErrorName = "loop_error";

/// One quantity's worst error over the measured turn.
struct SteppedError {
  std::string quantity;         ///< the catalogue's name (quantities.h) or kLoopErrorName
  double worst_rel_error = 0.0; ///< [-] max over samples, cylinders and components of |engine - exact| / scale
  double where_phi_deg = 0.0;   ///< [deg] the instant of the worst, in [0, 360)
  double step_fraction = 0.0;   ///< where within the step the engine's value was read (QuantityInstant)
};

/// The measure of one run.
struct SteppedMeasure {
  std::vector<SteppedError> errors;  ///< in the catalogue's order, kLoopErrorName last
  double seconds_per_step = 0.0;     ///< [s] the engine's own (Trajectory::seconds_per_step)
  long settling_steps = 0;           ///< steps run before the measured turn
  long measured_steps = 0;           ///< steps of the measured turn
};

/// The steps a run settles before its turn is measured: the engine's start-up transient (an engine's solver corrects
/// a loop's error by a share erp per step: the transient falls below 1e-6 of itself after log(1e-6) / log(1 - erp)
/// steps, 62 at erp 0.2), and at least one whole turn: max(kSettlingSteps, one turn's steps).
inline constexpr long kSettlingSteps = 64;

/// The steps of one turn at m's speed with step dt: ceil(2 pi / (|omega| dt)).
/// @throws std::invalid_argument if omega is 0 or dt <= 0, naming them.
long calcStepsPerTurn(const Mechanism& m, double dt);

/// Checks that a step of dt turns the crank of m by at most kMaxStepAngle (stepped_run.h) at m's speed.
/// @throws std::invalid_argument naming the step, its angle and the largest step that is measured, otherwise
void checkStepAngle(const Mechanism& m, double dt);

/// The errors of `run` (a stepped engine's run of m held at its speed: Engine::run), its steps from `first` on
/// (first >= 1: each step from sample i - 1 to sample i), against the closed forms (the analytic engine) at each
/// quantity's instant. Components the mechanism does not define (isComponentDefined) are skipped.
/// @throws std::invalid_argument if the run reports a quantity m does not define, if its values and loop errors are
///         not one per sample, if `first` is 0, or if it has no sample from `first` on.
std::vector<SteppedError> calcSteppedErrors(const Mechanism& m, const Trajectory& run, size_t first);

/// Runs `engine` on m at `settings` and step dt from the exact state at phi = 0 (the analytic engine's, calcStartState):
/// settling steps (above), then one turn measured.
/// @throws as Engine::run; std::invalid_argument for settings the engine does not have (naming its settings).
SteppedMeasure measureSteppedRun(const Engine& engine, const Mechanism& m, const std::string& settings, double dt);

/// The observed order of convergence from the errors e1 at step dt1 and e2 at dt2: log(e1 / e2) / log(dt1 / dt2).
/// NaN when either error is not positive or the steps are equal.
double calcObservedStepOrder(double e1, double dt1, double e2, double dt2);

}  // namespace crankcheck::validation
