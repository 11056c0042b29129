#pragma once
/// @file
/// The free runs of the engines that run free, judged by the measures a user's time-stepped run is judged by
/// (run_measures.h): `crankcheck grade --free-run`'s references and its report's table of engines, `crankcheck stepped`'s
/// and report part stepped_engines' free runs. Each run is the mechanism under gravity alone with its crankshaft free
/// (carrying the flywheel), released at phi = 0 with omega0, by one of two routes (crankcheck::Route): an engine that
/// simulates (Engine::simulate) by one of its integrators at one accuracy in the engine's own sense
/// (Engine::accuracy_meaning); an engine that steps free (Engine::step_free) at one of its settings and a fixed step.
///
/// Where a run's speed stands: an integrator that updates the velocity before the position (semi-implicit Euler, as
/// MuJoCo's Euler and implicit integrators step) records at each step the position at t_i and the velocity that moved
/// it there, phi_i = phi_{i-1} + (t_i - t_{i-1}) phi_dot_i: a backward difference, which stands half a step behind
/// t_i (Trajectory::omega_half_step_behind). calcEngineRuns recognises such a run by that identity, held to rounding
/// at every step, rather than by the engine's name; a run whose speed is its own state at t_i (Runge-Kutta, Simbody's
/// integrators) fails it by the step's change of speed times the step.

#include <string>
#include <vector>

#include "crankcheck/solver/free_run.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/solver/stepped_run.h"
#include "crankcheck/validation/run_measures.h"
#include "crankcheck/validation/table.h"

namespace crankcheck::validation {

/// One run to make: an engine of the registry (validation/engines.h) that runs free, and how:
/// - an engine that simulates (Route::kSimulate): one of its integrators (by the engine's own name for it) and its
///   accuracy in the engine's sense (Engine::accuracy_meaning);
/// - an engine that steps free (Route::kStepFree): one of its settings (Engine::settings) and the time step [s].
struct EngineRunSpec {
  std::string engine;
  std::string integrator;  ///< the integrator, or the settings of an engine that steps
  double accuracy = 0.0;   ///< the accuracy in the engine's sense, or the step [s] of an engine that steps
};

/// One run, measured.
struct EngineRunRow {
  std::string scene;                   ///< the mechanism's name (Mechanism::name)
  std::string engine;
  std::string integrator;
  double accuracy = 0.0;               ///< [-] as in the spec
  std::string accuracy_meaning_short;  ///< what `accuracy` is, in a few words (Engine::accuracy_meaning's first clause)
  double energy_trend_per_revolution = 0.0;  ///< [1 / revolution] calcEnergyTrend
  double delta = 0.0;                  ///< [-] the run's speed fluctuation over its first revolution (calcSpeedFluctuation)
  double delta_exact = 0.0;            ///< [-] the exact free run's, released with the run's speed at phi = 0
  double delta_error_rel = 0.0;        ///< [-] (delta - delta_exact) / delta_exact
  double phi_max_error = 0.0;          ///< [rad] where omega is largest, the run's minus the exact, wrapped to (-pi, pi]
  double phi_min_error = 0.0;          ///< [rad] where omega is smallest, likewise (both against the nearest of
                                       ///< equal extremes: calcSpeedFluctuation)
  double phase_error_at_horizon = 0.0; ///< [rad] calcPhaseError at horizon_s
  double horizon_s = 0.0;              ///< [s] `revolutions` exact turns from the release, or the run's last sample if
                                       ///< the run ends sooner (a run that gains speed)
  int revolutions = 0;                 ///< the revolutions run (FreeRunSettings::revolutions)
  int steps = 0;                       ///< the integrator's steps (FreeRunResult::steps)
  std::string omega_reading;           ///< where the run's speed stands: "at the step" or "half a step behind" (a
                                       ///< backward difference: see the file's comment)
  double cpu_seconds_per_revolution = 0.0;  ///< [s] processor time of the engine's run (std::clock) / revolutions
};

/// An engine's free run (FreeRunResult::trajectory, each omega at its sample's time as the engine reports it) with the
/// instant its omega stands at found by measurement: omega_half_step_behind set when every step satisfies
/// phi_i - phi_{i-1} = (t_i - t_{i-1}) omega_i to rounding (16 eps x (|phi_i| + |omega_i| t_i): the rounding of the
/// position's and of the clock's sums), a backward difference (MuJoCo's Euler and implicit steps).
/// @throws std::invalid_argument if time, phi and omega differ in size or have fewer than 2 samples.
Trajectory findOmegaInstants(const Trajectory& run);

/// Runs each spec on m (no gas: the free run under gravity alone) released at phi = 0 with omega0 [rad/s] for
/// `revolutions` revolutions, and measures each run (run_measures.h), in the order of the specs. Every spec is checked
/// before the first run. An engine that steps runs `revolutions` revolutions of the exact run and a tenth more from
/// the exact state at phi = 0 (calcStartState), and its release is its run's first sample (withRelease); in its row
/// `integrator` is the settings' name and `accuracy` the step [s]. Such a run the engine refuses (a scene it cannot
/// build, a step too long for it: Engine::step_free throws), or one the measures cannot judge (it stops turning or
/// falls short of a revolution: a speed cap, damping), has no row; its one line goes to `refusals` when given.
/// @throws std::invalid_argument if omega0 is not finite and > 0, revolutions < 1, m has [gas] or no flywheel inertia,
///         or a spec names an engine the registry does not have, an engine that does not run free, an integrator or
///         settings the engine does not have (the message lists the engine's), or an accuracy or step that is not
///         finite and > 0; std::runtime_error (from an engine that simulates) if a run fails; std::domain_error if the
///         exact run does not turn over.
/// With load.gas: the run under the scene's gas against its cycle-mean load (run_measures.h RunLoad; the engines that
/// take the gas and a load, Engine::simulates_loads; energy_trend_per_revolution is then per working cycle and the
/// phase error's horizon the run's end).
std::vector<EngineRunRow> calcEngineRuns(const Mechanism& m, double omega0, int revolutions,
                                         const std::vector<EngineRunSpec>& specs, const RunLoad& load = {},
                                         std::vector<std::string>* refusals = nullptr);

/// The runs the report shows, for every engine of the registry that simulates, read from the engine's description
/// (no engine is named here):
/// - an engine whose accuracy is a tolerance (a gated engine, Engine::gated: Simbody's integrators): its default
///   integrator at 1e4, 1e2 and 1 times its default accuracy (1e-6, 1e-8, 1e-10), each other integrator of order
///   above 1 at 1e2 times (1e-8), each of order 1 at 1e4 times (1e-6; a first-order integrator's steps grow as the
///   inverse of the accuracy);
/// - an engine stepped at a fixed step (not gated: MuJoCo's soft ways): its default integrator (RK4) at its default
///   step, whose fourth-order error there is already far below the soft constraints' own loss (a tenth of the step
///   would cost ten times as much and change nothing the table shows), and its next (semi-implicit Euler, first
///   order) at the default step and a tenth of it.
/// quick: the runs at the default accuracy or step alone, and the gated engine's other integrators left out.
/// The steps and accuracies are chosen by cost: the whole set runs in a few seconds of one core on the example scenes
/// over 5 revolutions (calcEngineRuns' cpu_seconds_per_revolution says what each run cost).
/// Then every engine that steps free at its defaults at 1e-3 and 1e-4 s (quick: 1e-4 s), steps at which every one of
/// them runs the example scenes (Box2D refuses steps that turn the crank more than pi/2).
/// With load.gas: only the engines that take the gas and a load (Engine::simulates_loads; none that steps).
std::vector<EngineRunSpec> listDefaultEngineRuns(bool quick, const RunLoad& load = {});

/// A stepped engine's free run (Engine::step_free: one sample per step, omega at its omega_time) with the
/// release (t = 0, phi0, omega0) first: the release is the run's first state, so what the engine does to it in its
/// first step is measured. Where omega belongs to its step's start or before it (omega_time.front() <= 0: Box2D), the
/// first step's omega is the engine's reading of the release and stands there in its place.
/// @throws std::invalid_argument if time, phi, omega and omega_time differ in size or have fewer than 2 samples.
Trajectory withRelease(const Trajectory& run, double phi0, double omega0);

/// The table `free_run_engines`: one row per run (EngineRunRow's members, in order).
const Schema<EngineRunRow>& getFreeRunEnginesSchema();

/// The table `stepped_free_runs` of report part stepped_engines: the stepped engines' free runs, the same columns but
/// the processor time (a measurement; every other column a rerun repeats exactly).
const Schema<EngineRunRow>& getSteppedFreeRunsSchema();

}  // namespace crankcheck::validation
