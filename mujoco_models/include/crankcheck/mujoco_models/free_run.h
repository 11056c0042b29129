#pragma once
/// @file
/// The free run of the k-crank mechanism in MuJoCo (crankcheck/solver/free_run.h's result and settings). No MuJoCo
/// header here: MuJoCo stays in src/.

#include "crankcheck/mujoco_models/k_crank_mujoco_model.h"
#include "crankcheck/solver/free_run.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::mujoco_models {

/// The free run as MuJoCo's users run it: the soft model of `variant` (kSoftDefault or kSoftStiff) with the crankshaft
/// free (carrying I_w), released at phi = 0 with speed omega0 from the exactly closed state, stepped by one of
/// MuJoCo's integrators at a fixed time step, its loops held by MuJoCo's soft constraint solver. Energy (MuJoCo's
/// potential + kinetic) and the crank's angle and speed are recorded at every step.
/// settings.integrator: "Euler" (semi-implicit), "RK4" (default), "implicit" (MuJoCo 2.2.2's three);
/// settings.accuracy: the time step as a fraction of one revolution at omega0 (e.g. 1e-3: 1000 steps a revolution).
/// The first revolution's extremes are taken at the steps, its period by linear interpolation of the crank angle.
/// @throws std::invalid_argument for the exact variant, a scene without [flywheel], omega0 <= 0, an unknown
///         integrator or a step outside (0, 0.1]; std::runtime_error if the run blows up or does not complete.
FreeRunResult simulateFreeRun(const Mechanism& m, double omega0, Variant variant, const FreeRunSettings& settings);

}  // namespace crankcheck::mujoco_models
