#pragma once
/// @file
/// The computation of `crankcheck flywheel`: the flywheel inertia at which the steady run at the scene's mean speed
/// under a constant load (the cycle mean of the gas torque) fluctuates by C, exact and by Norton's method
/// (analytic/flywheel.h), and the run of every engine of the registry that simulates with loads
/// (Engine::simulates_loads) with the exact inertia and the load over one working cycle from the steady state.

#include <string>
#include <vector>

#include "crankcheck/analytic/flywheel.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::validation {

/// One engine's run with the exact flywheel over one working cycle.
struct FlywheelEngineRun {
  std::string engine;         ///< Engine::name
  std::string library;        ///< Engine::library ("Simbody 3.7.0")
  double fluctuation = 0.0;   ///< the delta it measures, (omega_max - omega_min) / omega_mean
  double energy_drift = 0.0;  ///< how far its energy returns, max |E(t) - E(0)| / E(0) per revolution
  double omega_mean = 0.0;    ///< [rad/s]
};

struct FlywheelResult {
  analytic::FlywheelSizing sizing;
  std::vector<FlywheelEngineRun> runs;  ///< every engine that simulates with loads, in the registry's order
};

/// Sizes the flywheel of m for the speed fluctuation C (0 < C < 1) and runs every engine that simulates with loads
/// with it: the exact inertia in place of the scene's, the gas, the load, released at phi = 0 with the steady run's
/// speed there, over one working cycle, at the engine's first integrator and default accuracy.
/// @throws std::invalid_argument "KEY: rule" for a scene without [gas] or speed, or an engine's refusal (its message);
///         std::domain_error as analytic::calcFlywheelSizing when no flywheel gives C;
///         UncomputableError (errors.h) when the sizing's root does not converge ("what") or an engine's run does not
///         finish ("LIBRARY's run with the exact flywheel: what", LIBRARY without its version).
FlywheelResult calcFlywheel(const Mechanism& m, double fluctuation);

}  // namespace crankcheck::validation
