#pragma once
/// @file
/// What an engine's free run reports (Engine::simulate, crankcheck/solver/engine.h): the mechanism with its crankshaft
/// free (carrying the flywheel I_w), released at phi = 0 with speed omega0, no drive, no load, integrated by one of
/// the engine's integrators. Plain values, no engine behind them.

#include <string>
#include <vector>

#include "crankcheck/solver/trajectory.h"

namespace crankcheck {

/// How to run: the integrator by the engine's own name for it, and its accuracy in the engine's own sense
/// (Engine::accuracy_meaning: Simbody's relative accuracy; MuJoCo's fixed time step as a fraction of a revolution).
struct FreeRunSettings {
  std::string integrator;
  double accuracy = 1e-10;
  int revolutions = 2;  ///< how far to integrate; every step is recorded
  bool gravity = true;
  /// The flywheel's run (engines with Engine::simulates_loads): the scene's gas forces on the pistons and a constant
  /// load torque [N m] against the crank; delta and the energy's return are then measured over the first working cycle
  /// (720 degrees four-stroke, 360 two-stroke), which `revolutions` must cover.
  bool gas = false;
  double load_torque = 0.0;
};

struct FreeRunResult {
  /// At every step: time strictly increasing, phi unwrapped, omega at its sample's time (omega_time empty).
  Trajectory trajectory;
  std::vector<double> energy;                       ///< [J] KE + PE at each of the trajectory's samples
  double omega_min = 0.0, omega_max = 0.0;          ///< [rad/s] over the first revolution
  double omega_mean = 0.0;                          ///< [rad/s] 2 pi / time of the first revolution
  double delta = 0.0;                               ///< (omega_max - omega_min) / omega_mean
  double energy_drift_per_revolution = 0.0;         ///< max |E(t) - E(0)| / E(0) over the run, per revolution
  int steps = 0;                                    ///< integrator steps taken
};

}  // namespace crankcheck
