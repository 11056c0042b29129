#pragma once
// What MuJoCo's two crank-train routes share (its exact one, crank_train.cc; its soft one, crank_train_soft.cc):
// their options and refusals. Both run to periodic by every engine's one policy (crankcheck/solver/periodic_run.h).
// Private to the library.

#include <vector>

#include "crankcheck/solver/crank_train_run.h"
#include "crankcheck/solver/periodic_run.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::mujoco_models {

/// The options with each 0 replaced by its default (`accuracy`, `periodicity`, and CrankTrainRunOptions{}'s samples and
/// max_cycles), after the scene's checks. @throws std::invalid_argument "key: rule (MuJoCo's elastic crank train)" for
/// a scene without [crankshaft], a speed <= 0, an invalid mechanism or bad options.
CrankTrainRunOptions resolveCrankTrainOptions(const Mechanism& m, const CrankTrainRunOptions& asked, double accuracy,
                                              double periodicity);

/// @throws std::invalid_argument "key: rule (MuJoCo's elastic crank train)".
[[noreturn]] void refuseCrankTrain(const std::string& key, const std::string& rule);

}  // namespace crankcheck::mujoco_models
