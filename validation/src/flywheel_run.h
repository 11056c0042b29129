#pragma once
// The engines' free runs over a working cycle that confirm the exact energy integral's speed fluctuation (analytic
// flywheel.h and motion.h): which engines run them and how. The flywheel part (parts/flywheel.cc) runs them on its
// curve's inertias, the scene sections' flywheel topic (your_engine/dynamics.cc) on each scene's own flywheel.

#include <vector>

#include "crankcheck/solver/engine.h"
#include "crankcheck/solver/free_run.h"

namespace crankcheck::validation {

/// The accuracy of a gated engine's free run (Simbody's integrator accuracy), quick and full alike: what the check
/// needs. The runs confirm the exact energy integral's delta, against which Norton's method is judged (its error on the
/// example scenes: 11 % to 265 %); at 3e-7 Simbody's delta agrees with the exact one to 3.6e-3 (relative, the full
/// campaign), 30 times below the smallest of those errors, at 0.8 of the cost of 1e-7 (which agreed to 1.7e-3; 1e-6 to
/// 1.7e-2, 1e-8 to 3.9e-4, 1e-10 to 1.2e-6). bench/README.md has the measurements ("The flywheel's Simbody runs at
/// accuracy 3e-7").
inline constexpr double kFlywheelRunAccuracy = 3e-7;

/// The reference engines whose free run takes the gas forces and the load (Engine::simulates_loads): Simbody's.
std::vector<const Engine*> listLoadedRunEngines();

/// How `engine` runs the working cycle: its first integrator, two revolutions, gravity on, the scene's gas and the
/// constant `load_torque` [N m] when `gas`; a gated engine at kFlywheelRunAccuracy, a soft way (Engine::gated false) at
/// its own default accuracy (Engine::default_accuracy: its fixed step).
FreeRunSettings makeFlywheelRunSettings(const Engine& engine, bool gas, double load_torque);

}  // namespace crankcheck::validation
