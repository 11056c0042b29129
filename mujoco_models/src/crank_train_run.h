#pragma once
// The elastic crank train's run to periodic (crank_train.h), shared by its exact route (crank_train.cc) and its soft
// route (k_crank_mujoco_model.cc): one policy, Simbody's (simbody_models/crank_train.h). Private to the library.

#include <vector>

#include "crankcheck/scene/crank_train_run.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::mujoco_models {

/// One route's integration of the train, cycle by cycle, in s = omega t [rad] counted from 0 at each cycle's start.
class CycleRun {
 public:
  virtual ~CycleRun() = default;
  /// A new cycle at s = 0, at the loose start's accuracy or at the final one; `scale` [rad]: the largest deviation of
  /// the cycle before (0 before the first).
  virtual void startCycle(bool loose, double scale) = 0;
  /// Integrates to s = target [rad] of this cycle, target in (s, cycle].
  virtual void stepTo(double target) = 0;
  /// The bodies' deviations x = psi - omega t [rad] and their rates dx/ds [rad/rad], front first.
  virtual void readState(std::vector<double>& x, std::vector<double>& x_s) const = 0;
  virtual long long countSteps() const = 0;
};

/// The options with each 0 replaced by its default (`accuracy`, `periodicity`, and CrankTrainRunOptions{}'s samples and
/// max_cycles), after the scene's checks. @throws std::invalid_argument "key: rule (MuJoCo's elastic crank train)" for
/// a scene without [crankshaft], a speed <= 0, an invalid mechanism or bad options.
CrankTrainRunOptions resolveCrankTrainOptions(const Mechanism& m, const CrankTrainRunOptions& asked, double accuracy,
                                              double periodicity);

/// @throws std::invalid_argument "key: rule (MuJoCo's elastic crank train)".
[[noreturn]] void refuseCrankTrain(const std::string& key, const std::string& rule);

/// Simbody's policy: from the run's state at s = 0, cycle by cycle (64 probes each), loose (when `loose_start`) until
/// the deviations and rates at a cycle's start change by less than 1000 x periodicity of the largest deviation over the
/// cycle, then at the final accuracy until they change by less than periodicity; then one more cycle sampled at
/// options.samples equal steps into the twists (section i: x_{i+1} - x_i, the last -x_{n-1}).
/// @throws std::runtime_error if not periodic after options.max_cycles cycles or the deviations become non-finite.
CrankTrainRun runToPeriodic(CycleRun& run, double cycle, const CrankTrainRunOptions& options, bool loose_start);

}  // namespace crankcheck::mujoco_models
