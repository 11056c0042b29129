#pragma once
/// @file
/// The one notion of an engine (a solver) the harness has: a named way of computing the mechanism, with the routes it
/// offers: evaluate the Evaluation at a crank angle (the gate), simulate the free run by its integrators, step the
/// mechanism by fixed time steps held at speed or free (the physics engines people ship), run the elastic crank
/// train. Each engine folder (analytic/, simbody_models/, mujoco_models/, ode_models/, bullet_models/, box2d_models/)
/// describes its engines with this plain type; validation/src/engines.cc lists them in one registry (one
/// registration line per folder), filtered by route, and the CLI, the gate, the campaign and the report loop over
/// that list. Header only, no engine library behind it.

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "crankcheck/solver/crank_train_run.h"
#include "crankcheck/scene/evaluation.h"
#include "crankcheck/solver/free_run.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/solver/step_options.h"
#include "crankcheck/solver/trajectory.h"

namespace crankcheck {

/// One engine's model of one mechanism, built once and evaluated at many crank angles. Not thread-safe: one object
/// per thread (engines keep warm starts and scratch space).
class EngineModel {
 public:
  virtual ~EngineModel() = default;
  /// Everything of Evaluation at crank angle phi [rad] of cylinder 0 and the mechanism's constant speed omega
  /// (engine.speed [rad/s]). Units and signs: CONVENTIONS.md.
  /// @throws std::invalid_argument if phi is not finite; std::runtime_error if the engine fails at phi.
  virtual Evaluation evaluate(double phi) = 0;
  /// evaluate(phi) for a caller that reads no U and no Q: the motion and the loads at the scene's speed (every other
  /// field, the same numbers as evaluate()'s). An engine whose U and Q cost a solve of their own (Simbody's static pass
  /// at rest: a fifth of its evaluation) skips them and sets both NaN; the others return evaluate()'s.
  /// @throws as evaluate().
  virtual Evaluation evaluateMotion(double phi) { return evaluate(phi); }
  /// A warm start for an engine that assembles its mechanism at each angle (Simbody): the next assembly starts from
  /// `donor`'s configuration where the donor was last evaluated, when the donor is the same engine's model of the same
  /// mechanism up to its bank angles (a sweep over gamma: the joint coordinates are each cylinder's own). Changes no
  /// converged result beyond roundoff, only what the assembly has left to iterate; the others ignore it.
  virtual void startAssemblyFrom(const EngineModel& donor) { (void)donor; }
  /// Sets the crank speed omega [rad/s] of every later evaluate() (the mechanism's engine.speed, and speed_rpm with
  /// it): speed is a state, not a geometry, so one model serves every speed of its mechanism.
  /// @throws std::invalid_argument if omega is not finite.
  virtual void setSpeed(double omega) = 0;
  /// Q [N m] = dU/dphi at phi alone (the holding torque: the same Q as evaluate()'s, by the engine's cheapest route
  /// to it). @throws as evaluate().
  virtual double calcQ(double phi) { return evaluate(phi).Q; }
  /// Q [N m] at phi by the engine's second route, independent of evaluate()'s (Engine::second_q_route says which:
  /// Simbody's minus gravity's virtual power at unit crank speed).
  /// @throws std::logic_error if the engine offers none (Engine::second_q_route empty).
  virtual double calcSecondRouteQ(double phi) {
    (void)phi;
    throw std::logic_error("this engine has no second route to Q");
  }
};

/// What an engine's documentation or its upstream issues say about a quantity it reports, where the measurement bears
/// on it: the report (part stepped_engines) states the note beside the measured errors and the command that shows them.
struct EngineNote {
  std::string quantity;  ///< the catalogue's name (quantities.h)
  std::string note;      ///< the claim, its source, and what the measurement found, in one sentence
};

/// What an engine can be asked to do: each route is one member of Engine, empty where the engine does not offer it.
enum class Route {
  kEvaluate,     ///< Engine::build: the Evaluation at a crank angle (the gate, eval, the campaign's comparisons)
  kSimulate,     ///< Engine::simulate: the free run by the engine's integrators (`crankcheck motion`, the flywheel)
  kStepAtSpeed,  ///< Engine::step_at_speed: fixed time steps held at the scene's speed (`crankcheck stepped`)
  kStepFree,     ///< Engine::step_free: fixed time steps, the crank free with its flywheel (grade's engines table)
  kCrankTrain,   ///< Engine::simulate_crank_train: the elastic crank train's steady state (`crankcheck torsion`)
};

struct Engine;
/// True when `engine` offers `route` (its member for the route is set).
bool offersRoute(const Engine& engine, Route route);

/// An engine, or one way of computing with an engine's library ("mujoco" and "mujoco-soft" are two ways of one
/// library; "ode" and "ode-quickstep" two solvers of one). Every member beyond the name, the library and the method
/// belongs to a route (Route) and is empty (or false) where the engine does not offer it.
struct Engine {
  std::string name;         ///< as on the command line and in JSON: "analytic", "simbody", "mujoco", "ode", ...
  std::string library;      ///< the library that computes, with its version: "Simbody 3.7.0", "MuJoCo 2.2.2"
  std::string method;       ///< one line: how it computes (for --help, the docs and the report)
  /// True when the engine claims exactness: the gate holds it to the agreement rule (64 eps x scale x conditioning)
  /// against every other gated engine. False: its errors are measured and reported, never gated (a soft solver).
  bool gated = true;
  /// True for the closed forms under test (the analytic engine): the engine every other engine is compared with. The
  /// others, gated, are its references (validation/engines.h listReferenceEngines).
  bool closed_form = false;
  /// Route::kEvaluate: builds the engine's model of m.
  /// @throws std::invalid_argument if the engine cannot build m (the message names the scene key and the rule), or
  ///         cannot hold its promised accuracy on it (found by its own check on a probe before any value is given:
  ///         a residual of its equations; the message says what was measured);
  ///         std::runtime_error if the engine's library fails.
  using BuildFunction = std::function<std::unique_ptr<EngineModel>(const Mechanism& m)>;
  BuildFunction build;

  /// Route::kSimulate: the free run (`crankcheck motion`), for engines that simulate; empty `integrators`: none.
  std::vector<std::string> integrators;  ///< the names FreeRunSettings::integrator takes; the first is the default
  std::string accuracy_meaning;          ///< what FreeRunSettings::accuracy means for this engine, and its default
  double default_accuracy = 0.0;
  /// @throws std::invalid_argument for a mechanism without flywheel, omega0 <= 0 or an unknown integrator;
  ///         std::runtime_error if the run fails or the crank does not complete the revolutions.
  std::function<FreeRunResult(const Mechanism& m, double omega0, const FreeRunSettings& settings)> simulate;
  std::vector<int> integrator_orders;  ///< the order of accuracy of each of `integrators` (1: first order)
  /// True when simulate() takes FreeRunSettings::gas and load_torque (the flywheel's working cycle); false: it
  /// refuses them with std::invalid_argument.
  bool simulates_loads = false;

  // Optional routes beyond build() and simulate(), each empty (or false) where the engine offers none. A report part
  // asks which engines offer a route (validation/engines.h) and never names an engine.

  /// What EngineModel::calcSecondRouteQ computes ("virtual power"); empty: no second route.
  std::string second_q_route;
  /// A cheaper model of gravity alone at rest: its evaluate() fills phi, U and Q only (the rest NaN). Where an engine
  /// has none, build() of the scene at rest gives the same U and Q (validation/engines.h buildGravityModel).
  BuildFunction build_gravity;
  /// build() with the constraints solved to a relative `accuracy` instead of to rounding (a cost-accuracy trade).
  std::function<std::unique_ptr<EngineModel>(const Mechanism& m, double accuracy)> build_at_accuracy;
  /// Q [N m] at rest at phi_i = phi0 + i step, i = 0 .. n - 1, by a route that computes a whole grid at once.
  std::function<std::vector<double>(const Mechanism& m, double phi0, double step, size_t n)> calc_q_on_grid;
  /// The elastic crank train's periodic steady state (`crankcheck torsion`, the report's torsion part) of a scene with
  /// `[crankshaft]` at its speed. @throws std::invalid_argument if the engine cannot build the train (the message names
  /// the rule); std::runtime_error if no periodic state is reached.
  std::function<CrankTrainRun(const Mechanism& m, const CrankTrainRunOptions& options)> simulate_crank_train;
  /// One line: how simulate_crank_train reaches the steady state and what its options' accuracy means, with defaults.
  std::string crank_train_method;
  /// True when simulate_crank_train claims the exact steady state (gated against the analytic engine's to the
  /// integrators' accuracy); false: a soft solver's run, its difference reported, never gated.
  bool crank_train_gated = false;

  // Route::kStepAtSpeed and Route::kStepFree: the physics engines people ship, advancing the mechanism by fixed time
  // steps with their own constraint solvers (crankcheck/solver/stepped_run.h), measured and never gated.

  /// The settings the stepped routes run at, "defaults" first; settings_meaning[i] says what settings[i] changes, in
  /// one line.
  std::vector<std::string> settings, settings_meaning;
  std::string instants;   ///< one line: where each reported quantity belongs within a step, and why
  /// The layouts and keys the stepped routes cannot build, in one line (each refused by name with
  /// std::invalid_argument).
  std::string cannot_build;
  /// Runs m at its constant speed (m.machine.speed != 0). The trajectory has one sample per step (time[i] = (i + 1)
  /// dt; the start, options.start, is the caller's), the crank's angle and speed after the step as the engine's API
  /// gives them (omega at its omega_time), and the quantities it reports (`reported`, `values`, `loop_error`).
  /// @throws std::invalid_argument naming the scene key the engine cannot build, or a bad option;
  ///         std::runtime_error if the library fails during the run.
  std::function<Trajectory(const Mechanism& m, const ConstantSpeedRunOptions& options)> step_at_speed;
  /// Runs m free (SteppedFreeRunOptions). m needs a flywheel (Mechanism::flywheel_inertia). The trajectory has one
  /// sample per step (time[i] = (i + 1) dt: the release is not among them), phi and omega as the engine's own API
  /// gives them after the step, and omega_time the instant each omega belongs to, found by measurement: the step's
  /// middle for a semi-implicit Euler step whose velocity after the step carried the position from its start to its
  /// end (ODE, Bullet); its start where a position pass moves the body again after the velocity solve (Box2D).
  /// @throws std::invalid_argument for a mechanism without flywheel, a scene key the engine cannot build or a bad
  ///         option; std::runtime_error if the library fails during the run.
  std::function<Trajectory(const Mechanism& m, const SteppedFreeRunOptions& options)> step_free;
  /// Notes on quantities whose measurement confirms or contradicts the engine's documentation or upstream reports.
  std::vector<EngineNote> notes;
};

inline bool offersRoute(const Engine& engine, Route route) {
  switch (route) {
    case Route::kEvaluate: return static_cast<bool>(engine.build);
    case Route::kSimulate: return static_cast<bool>(engine.simulate);
    case Route::kStepAtSpeed: return static_cast<bool>(engine.step_at_speed);
    case Route::kStepFree: return static_cast<bool>(engine.step_free);
    case Route::kCrankTrain: return static_cast<bool>(engine.simulate_crank_train);
  }
  return false;
}

}  // namespace crankcheck
