#pragma once
/// @file
/// The computation of `crankcheck motion` and of the Python module's Scene.motion: the free run under gravity
/// (released at phi = 0 with the scene's speed, no drive, no load) by the analytic energy integral, by every engine
/// of the registry that simulates (Route::kSimulate: Engine::simulate), each with its own integrator and accuracy, and
/// by every engine that steps free (Route::kStepFree: ODE, Bullet, Box2D), each at its defaults and a fixed step.

#include <map>
#include <string>
#include <vector>

#include "crankcheck/solver/free_run.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/engines.h"

namespace crankcheck::validation {

/// How each engine that runs free runs, by engine name (Engine::name). An engine that simulates has an integrator
/// and an accuracy in its own sense; an engine that steps free has one of its settings (Engine::settings) as
/// `integrator` and its step as a fraction of a revolution at the release speed as `accuracy`. An engine without an
/// entry runs at its defaults (getDefaultFreeRunSettings).
using FreeRunChoices = std::map<std::string, FreeRunSettings>;

/// [-] The step of an engine that steps free, as a fraction of a revolution at the release speed, by default: a
/// thousandth (2e-5 s at 3000 rpm; the whole run of two revolutions 2200 steps).
inline constexpr double kDefaultSteppedMotionStep = 1e-3;

/// Every engine that simulates at its defaults: its first integrator (Engine::integrators) and its default accuracy
/// (Engine::default_accuracy, in the engine's own sense: Engine::accuracy_meaning); every engine that steps free at
/// its "defaults" settings and kDefaultSteppedMotionStep.
FreeRunChoices getDefaultFreeRunSettings();

/// Chooses the step, a fraction of a revolution at the release speed, of every engine of `choices` that steps free,
/// and `settings` for each of them that has settings of that name (Engine::settings; the others keep theirs).
/// @return how many engines took the settings.
int chooseSteppedRun(FreeRunChoices& choices, const std::string& settings, double fraction);

/// The integrators of the engines that simulate (Engine::integrators), each once, in the registry's order: of the
/// gated ones (Simbody's: RungeKuttaMerson, CPodes, SemiExplicitEuler2) or of the others (MuJoCo's soft ways: RK4,
/// Euler, implicit). What the CLI's --integrator and --mujoco-integrator, and the Python module's integrator and
/// mujoco_integrator, take.
std::vector<std::string> listIntegrators(bool gated);

/// The settings of the engines that step free (Engine::settings), each once, in the registry's order: what the CLI's
/// --stepped-settings and the Python module's stepped_settings take.
std::vector<std::string> listSteppedSettings();

/// Chooses `integrator` at `accuracy` (in the engine's own sense) for every engine of `choices` that offers that
/// integrator (Engine::integrators), the others left as they are. A user's integrator names its engines: the CLI's
/// --integrator and --mujoco-integrator, the Python module's integrator and mujoco_integrator.
/// @return how many engines took it.
int chooseIntegrator(FreeRunChoices& choices, const std::string& integrator, double accuracy);

/// One way's free run: the analytic energy integral, one engine's simulation or one engine's fixed steps.
struct MotionRun {
  std::string engine;             ///< the engine's name; "analytic" for the energy integral
  std::string integrator;         ///< the engine's integrator (an engine that steps: its settings); "" for the integral
  double accuracy = 0.0;          ///< the integrator's accuracy in the engine's sense (an engine that steps: its step
                                  ///< [s]); 0 for the energy integral
  double delta_gravity = 0.0;     ///< (omega_max - omega_min) / omega_mean with gravity
  double delta_no_gravity = 0.0;  ///< the same without gravity
  double omega_min = 0.0, omega_max = 0.0, omega_mean = 0.0;  ///< [rad/s] with gravity
  double energy_drift = 0.0;      ///< max |E(t) - E(0)| / E(0) per revolution, gravity on (the energy integral: 0)
  int steps = 0;                  ///< integrator steps with gravity (the energy integral: 0)
  FreeRunResult with_gravity;     ///< the engine's run with gravity step by step (empty for the energy integral);
                                  ///< an engine that steps: from the release, its energy the closed forms' at each
                                  ///< sample's phi and omega
  /// An engine that steps free and whose run cannot be measured (it does not turn a revolution: a speed cap, its
  /// damping; or its library fails during the run): why, in one line; every number above then 0. Empty: measured.
  std::string not_measured;
};

/// The free run of m at its speed: the energy integral first, then every engine that simulates in the registry's
/// order, each with its choice from `choices` (or its defaults), then every engine that steps free likewise, for two
/// revolutions of the exact run and a tenth more. Every run's delta and omega extremes are its first revolution's,
/// its speed interpolated between its samples as grade reads a run (run_measures.h calcSpeedFluctuation; a stepped
/// run's release is its first sample). An integrator's drift is of its engine's own energy; a stepped run's, of the
/// closed forms' energy (1/2) J(phi) omega^2 + U(phi) at its samples. `sat_out`: null, an engine whose build refuses m
/// (Engine::build: a rule of its own, or an accuracy it cannot hold there) is an error "ENGINE: reason"; given, it
/// sits out, added there with its reason, and the others run (the energy integral always does).
/// @throws std::invalid_argument "KEY: rule" for a scene the free run cannot use (no [flywheel].inertia, no speed,
///         a speed the energy integral cannot reach round) or "ENGINE: what" where an engine refuses it;
///         std::runtime_error "ENGINE: LIBRARY could not run: what" when an engine's run fails.
std::vector<MotionRun> calcMotion(const Mechanism& m, const FreeRunChoices& choices,
                                  std::vector<SatOut>* sat_out = nullptr);

}  // namespace crankcheck::validation
