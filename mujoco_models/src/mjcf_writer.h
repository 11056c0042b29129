#pragma once
// The MJCF writer: the text of the k-crank model (calcMjcf, declared in k_crank_mujoco_model.h) and of the soft
// elastic crank train (calcTrainMjcf), built from the same pieces (the head, the crankshaft bodies, the cylinders,
// the loops). No MuJoCo header here. Private to the library.

#include <string>

#include "crankcheck/mujoco_models/k_crank_mujoco_model.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::mujoco_models {

/// The shortest text that reads back as the same double (MJCF is parsed with strtod-like rules).
std::string num(double x);

/// The elastic crank train as MuJoCo's users build it (crank_train.h, simulateCrankTrainSoft): one MJCF, the bodies
/// nested from the flywheel inward, each on a hinge relative to its neighbour toward W with that section's stiffness
/// and damping, the throws' cylinders and loops as calcMjcf's, each throw's damping a fixed tendon over the hinges
/// from W to it. `flywheel_inertia` [kg m^2]: W's.
std::string calcTrainMjcf(const Mechanism& m, Variant variant, double flywheel_inertia);

}  // namespace crankcheck::mujoco_models
