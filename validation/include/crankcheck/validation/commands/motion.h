#pragma once
/// @file
/// The computation of `crankcheck motion` and of the Python module's Scene.motion: the free run under gravity
/// (released at phi = 0 with the scene's speed, no drive, no load) by the analytic energy integral and by every engine
/// of the registry that simulates (Engine::simulate), each with its own integrator and accuracy.

#include <map>
#include <string>
#include <vector>

#include "crankcheck/solver/free_run.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/engines.h"

namespace crankcheck::validation {

/// How each engine that simulates runs, by engine name (Engine::name). An engine that simulates and has no entry runs
/// at its defaults (getDefaultFreeRunSettings).
using FreeRunChoices = std::map<std::string, FreeRunSettings>;

/// Every engine that simulates at its defaults: its first integrator (Engine::integrators) and its default accuracy
/// (Engine::default_accuracy, in the engine's own sense: Engine::accuracy_meaning).
FreeRunChoices getDefaultFreeRunSettings();

/// Chooses `integrator` at `accuracy` (in the engine's own sense) for every engine of `choices` that offers that
/// integrator (Engine::integrators), the others left as they are. A user's integrator names its engines: the CLI's
/// --integrator and --mujoco-integrator, the Python module's integrator and mujoco_integrator.
/// @return how many engines took it.
int chooseIntegrator(FreeRunChoices& choices, const std::string& integrator, double accuracy);

/// One way's free run: the analytic energy integral or one engine's simulation.
struct MotionRun {
  std::string engine;             ///< the engine's name; "analytic" for the energy integral
  std::string integrator;         ///< the engine's integrator; "" for the energy integral
  double accuracy = 0.0;          ///< the integrator's accuracy in the engine's sense; 0 for the energy integral
  double delta_gravity = 0.0;     ///< (omega_max - omega_min) / omega_mean with gravity
  double delta_no_gravity = 0.0;  ///< the same without gravity
  double omega_min = 0.0, omega_max = 0.0, omega_mean = 0.0;  ///< [rad/s] with gravity
  double energy_drift = 0.0;      ///< max |E(t) - E(0)| / E(0) per revolution, gravity on (the energy integral: 0)
  int steps = 0;                  ///< integrator steps with gravity (the energy integral: 0)
  FreeRunResult with_gravity;     ///< the engine's run with gravity step by step (empty for the energy integral)
};

/// The free run of m at its speed: the energy integral first, then every engine that simulates in the registry's
/// order, each with its choice from `choices` (or its defaults). `sat_out`: null, an engine whose build refuses m
/// (Engine::build: a rule of its own, or an accuracy it cannot hold there) is an error "ENGINE: reason"; given, it
/// sits out, added there with its reason, and the others run (the energy integral always does).
/// @throws std::invalid_argument "KEY: rule" for a scene the free run cannot use (no [flywheel].inertia, no speed,
///         a speed the energy integral cannot reach round) or "ENGINE: what" where an engine refuses it;
///         std::runtime_error "ENGINE: LIBRARY could not run: what" when an engine's run fails.
std::vector<MotionRun> calcMotion(const Mechanism& m, const FreeRunChoices& choices,
                                  std::vector<SatOut>* sat_out = nullptr);

}  // namespace crankcheck::validation
