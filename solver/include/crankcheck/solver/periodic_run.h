#pragma once
/// @file
/// The one policy by which every engine's elastic crank train (Engine::simulate_crank_train) runs to its periodic
/// steady state: Simbody's bodies (simbody_models/crank_train.h), MuJoCo's exact route and its soft chains
/// (mujoco_models/crank_train.h). Each engine integrates its own model behind CycleRun; nothing here knows a formula
/// of the train, only the deviations x_i = psi_i - omega t [rad] and their rates dx_i/ds (s = omega t) at a cycle's
/// start.

#include <optional>
#include <vector>

#include "crankcheck/solver/crank_train_run.h"

namespace crankcheck {

/// One engine's integration of a train, cycle by cycle, in s = omega t [rad] counted from 0 at each cycle's start.
class CycleRun {
 public:
  virtual ~CycleRun() = default;
  /// A new cycle at s = 0, integrated at `accuracy` (the engine's error per step; a fixed-step route ignores it);
  /// `scale` [rad]: the largest deviation over the cycle before (0 before the first).
  virtual void startCycle(double accuracy, double scale) = 0;
  /// Integrates to s = target [rad] of this cycle, target in (s, cycle]; every state it ends on an integrated one.
  virtual void stepTo(double target) = 0;
  /// The bodies' deviations x = psi - omega t [rad] and their rates dx/ds [rad/rad], front first.
  virtual void readState(std::vector<double>& x, std::vector<double>& x_s) const = 0;
  /// The state the cycle map acts on, at a cycle's start: by default the deviations and their rates joined (x, x_s),
  /// where the engine assembles the rest from them (Simbody's pistons and rods); a route whose bodies carry state of
  /// their own gives all of it (MuJoCo's soft chains: every joint's position and speed but the driven flywheel's).
  virtual std::vector<double> readCycleState() const;
  /// Puts the run at a cycle's start (s = 0) in this state (readCycleState's form). False, with the state unchanged,
  /// for one the engine cannot assemble.
  virtual bool moveTo(const std::vector<double>& cycle_state) = 0;
  virtual long long countSteps() const = 0;
};

/// Reduced rank extrapolation of a cycle map's fixed point from its iterates y_0 .. y_{k+1} (states at successive
/// cycle starts, CycleRun::readCycleState; at least 3, of one size): the weights gamma (sum 1) that make sum gamma_j (y_{j+1} - y_j) least in
/// the 2-norm, and the estimate sum gamma_j y_{j+1}. For a linear map y -> M y + b with M - I invertible and k + 1 at
/// least the degree of M's minimal polynomial on y_0's error it is the fixed point, exactly; near a fixed point of a
/// smooth map, the error of the iterates' slowest modes (a lightly damped train's) is removed to first order.
/// Empty when the estimate is not trusted: when its residual |sum gamma_j (y_{j+1} - y_j)| is not below a tenth of
/// the last difference |y_{k+1} - y_k| (nothing gained), or sum |gamma_j| exceeds 1e4 (the iterates' own error, e.g.
/// the integration's, amplified that much).
std::optional<std::vector<double>> findExtrapolatedFixedPoint(const std::vector<std::vector<double>>& iterates);

/// How runToPeriodic runs.
struct PeriodicPolicy {
  /// The accuracy of the first cycles (>= options.accuracy): the accuracy in use falls from it a decade at a time
  /// as the cycle-to-cycle change falls, the run's own error per cycle (about 1000 x its accuracy, measured on
  /// Simbody's and MuJoCo's trains) kept a tenth of the change it measures, to options.accuracy. Equal to
  /// options.accuracy: one stage (a fixed-step route).
  double first_accuracy = 0.0;
  /// The most cycles whose starts an extrapolation reads (findExtrapolatedFixedPoint over that many + 1): from the
  /// 4th cycle at one accuracy (or since the last move) each cycle tries the last up to this many; 0: none.
  int extrapolation_window = 0;
};

/// The window of extrapolation that the routes use (findExtrapolatedFixedPoint's k + 1 at most), measured on the
/// gate's trains (the example four at 6000 and 5450 rpm, the marine six at 105 rpm; Simbody 21 s for the three, 23 s
/// with every extrapolation over exactly 6 cycles, 38 s with none).
inline constexpr int kExtrapolationWindow = 6;

/// CrankTrainRunOptions::max_steps at 0: 4e6 steps, about 2 min of MuJoCo's exact route (35 us a step on the example
/// four), 140 x its largest gate run (28587 steps, the four at 6000 rpm), and about 1000 cycles of the soft routes at
/// their default step (1/4096 of a cycle). Simbody, at 0.37 ms a step, sets its own (simbody_models/crank_train.h).
inline constexpr long long kCrankTrainMaxSteps = 4'000'000;

/// From the run's state at s = 0, cycle by cycle (64 probes each: the largest deviation of the cycle), until the
/// deviations and rates at a cycle's start change by less than options.periodicity of that largest deviation at
/// options.accuracy; the accuracy staged (PeriodicPolicy::first_accuracy); from the 4th cycle at one accuracy the run
/// is moved to the extrapolated fixed point of the last cycles' starts when it is trusted and the engine can assemble
/// it: the stopping rule is the same, measured over whole integrated cycles after the last move. Then one more
/// cycle sampled at options.samples equal steps into the twists (section i: x_{i+1} - x_i, the last -x_{n-1}).
/// `what` starts the messages ("mujoco", "simbody").
/// @throws std::runtime_error if not periodic after options.max_cycles cycles, past options.max_steps steps (0:
///         kCrankTrainMaxSteps; checked after every stepTo, which the engine bounds itself), or the deviations become
///         non-finite.
CrankTrainRun runToPeriodic(CycleRun& run, double cycle, const CrankTrainRunOptions& options,
                            const PeriodicPolicy& policy, const char* what);

}  // namespace crankcheck
