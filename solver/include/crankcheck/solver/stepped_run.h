#pragma once
/// @file
/// The seam of a stepped engine: a physics engine that advances the mechanism by fixed time steps with its own
/// constraint solver (ODE, Bullet, Box2D), as robotics and games run it. Such an engine answers no "value at crank
/// angle phi": it is driven at the scene's constant crank speed from the exact state at phi = 0, and each of its
/// steps reports the quantities it can read from its own API, each belonging to a stated instant of the step (a
/// position to the step's end, a solved force to its start, ...). validation/ measures those against the closed forms
/// at that instant (validation/stepped_errors.h). Plain values, no engine behind them.

#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "crankcheck/scene/evaluation.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/scene/quantities.h"
#include "crankcheck/solver/trajectory.h"

namespace crankcheck {

/// [rad] The largest crank angle one step of a run may turn for the run to be measured: a quarter turn. Over a turn
/// of fewer than four steps the worst error is read at three instants or fewer (at 1 s and 3000 rpm every step lands
/// on the same angle, 50 turns on), the orders between such steps are of aliases, and a free run's extremes and
/// crossings, read by interpolation through six samples, would span more than a turn.
inline constexpr double kMaxStepAngle = std::numbers::pi / 2;

/// One body's planar state in the global frame (docs/CONVENTIONS.md): its centre of mass, its angle about +Z, their
/// rates.
struct PlanarBodyState {
  Vec2 p_WBcm_W{};      ///< [m] centre of mass
  double angle = 0.0;   ///< [rad] the body's rotation about +Z from its pose at which the model is built
  Vec2 v_WBcm_W{};      ///< [m/s]
  double omega = 0.0;   ///< [rad/s] about +Z
};

/// Cylinder j's rod and piston and their pins at the start of a run.
struct CylinderStartState {
  Vec2 p_WB_W{};             ///< [m] the crank pin B_j
  Vec2 p_WA_W{};             ///< [m] the wrist pin A_j
  Vec2 e{}, n{};             ///< the cylinder's axis e_j and its normal n_j (CONVENTIONS)
  double x_p = 0.0;          ///< [m] A_j along e_j
  double v_p = 0.0;          ///< [m/s]
  /// The rod: its angle is the direction of A_j -> B_j about +Z (atan2), not measured from a built pose.
  PlanarBodyState rod;
  PlanarBodyState piston;    ///< its angle 0, its omega 0: the piston slides
};

/// The state a stepped run starts from: every body's position and velocity at phi = 0 and the scene's speed.
struct StartState {
  double phi = 0.0;          ///< [rad]
  double omega = 0.0;        ///< [rad/s] the crank's speed
  std::vector<CylinderStartState> cylinders;
};

/// The start state from `exact`, an engine's Evaluation of m at phi = exact.phi and m's speed (validation/ hands in
/// the analytic engine's: the start is the run's input, not what is measured). Rigid-body kinematics only: the crank
/// pin from the crank's angle, the wrist pin x_p e + delta n, the rod from its angle beta (CylinderEvaluation::
/// rod_angle, the rod body turning at -rod_omega about +Z), each centre of mass's velocity v_A + w x (cm - A).
/// @throws std::invalid_argument if exact has not one cylinder per cylinder of m.
StartState calcStartState(const Mechanism& m, const Evaluation& exact);

/// The crankshaft as the stepped engines' models build it: one rigid body in the plane z = 0 lumping every throw's m_s
/// at r_s on its crank line and m_p at r_p opposite, at phi = 0 (the throws' axial spread only moves the bearing's
/// moments, which these models do not record). Scene data, not a closed form of the loop.
struct LumpedCrank {
  double mass = 0.0;              ///< [kg]
  Vec2 p_OBcm{};                  ///< [m] its centre of mass at phi = 0
  double inertia_about_o = 0.0;   ///< [kg m^2] about Z through O
  double inertia_about_cm = 0.0;  ///< [kg m^2] about Z through its centre of mass
};

/// m's crankshaft lumped (LumpedCrank).
/// @throws std::invalid_argument "LIBRARY cannot build this scene: [crank].mass ..." for a crank without mass, or
///         "... [crank].com_radius ..." for one without inertia about its centre of mass.
LumpedCrank calcLumpedCrank(const Mechanism& m, const std::string& library);

/// The refusals every stepped model shares, each naming its key: `[[balance_shaft]]` (no geared coupling in these
/// models), `[rod].mass` or `[piston].mass` of 0 (a body needs a mass), `[rod].inertia_about_wrist_pin` not above
/// m_k z_k^2 (a rod without inertia about its centre of mass).
/// @throws std::invalid_argument "LIBRARY cannot build this scene: KEY rule".
void checkSteppedScene(const Mechanism& m, const std::string& library);

/// [kg m^2] The rod's inertia about its centre of mass, I_o - m_k z_k^2 (Steiner).
double calcRodCentroidalInertia(const Mechanism& m);

/// An Evaluation of `cylinders` cylinders by `engine` with every quantity of the catalogue NaN (quantities.h): a stepped
/// engine's sample before it fills what it reports (Trajectory::values).
Evaluation makeUnreportedEvaluation(const std::string& engine, int cylinders);

/// How to run.
struct ConstantSpeedRunOptions {
  double dt = 1.0 / 240.0;   ///< [s] the step, > 0
  long steps = 0;            ///< steps to take, > 0
  /// One of SteppedEngine::settings: "defaults" (the library's own), or the engine's other named settings.
  std::string settings = "defaults";
  StartState start;          ///< the exact state at phi = 0 (calcStartState)
};

/// How to run free: no drive and no gas; the crank carries the scene's flywheel (Mechanism::flywheel_inertia about O,
/// added to the crank body's inertia), released from `start` (the exact state at phi = 0 and the release speed
/// start.omega) under the scene's gravity.
struct SteppedFreeRunOptions {
  double dt = 1.0 / 240.0;   ///< [s] the step, > 0
  long steps = 0;            ///< steps to take, > 0
  std::string settings = "defaults";  ///< one of SteppedEngine::settings
  StartState start;          ///< the exact state at phi = 0 and the release speed
};

/// What an engine's documentation or its upstream issues say about a quantity it reports, where the measurement bears
/// on it: the report (part stepped_engines) states the note beside the measured errors and the command that shows them.
struct SteppedEngineNote {
  std::string quantity;  ///< the catalogue's name (quantities.h)
  std::string note;      ///< the claim, its source, and what the measurement found, in one sentence
};

/// A stepped engine of the registry (validation/engines.h listSteppedEngines): measured, never gated.
struct SteppedEngine {
  std::string name;       ///< as on the command line: "ode", "ode-quickstep", "bullet", "box2d"
  std::string library;    ///< with its version: "ODE 0.16.2"
  std::string method;     ///< one line: the model and the solver
  /// The settings it runs at, "defaults" first; settings_meaning[i] says what settings[i] changes, in one line.
  std::vector<std::string> settings, settings_meaning;
  std::string instants;   ///< one line: where each reported quantity belongs within a step, and why
  /// The layouts and keys it cannot build, in one line (each refused by name with std::invalid_argument).
  std::string cannot_build;
  /// Runs m at its constant speed (m.machine.speed != 0). The trajectory has one sample per step (time[i] = (i + 1)
  /// dt; the start, options.start, is the caller's), the crank's angle and speed after the step as the engine's API
  /// gives them (omega at its omega_time), and the quantities it reports (`reported`, `values`, `loop_error`).
  /// @throws std::invalid_argument naming the scene key the engine cannot build, or a bad option;
  ///         std::runtime_error if the library fails during the run.
  std::function<Trajectory(const Mechanism& m, const ConstantSpeedRunOptions& options)> run;
  /// Notes on quantities whose measurement confirms or contradicts the engine's documentation or upstream reports.
  std::vector<SteppedEngineNote> notes;
  /// Runs m free (SteppedFreeRunOptions). m needs a flywheel (Mechanism::flywheel_inertia). The trajectory has one
  /// sample per step (time[i] = (i + 1) dt: the release is not among them), phi and omega as the engine's own API
  /// gives them after the step, and omega_time the instant each omega belongs to, found by measurement: the step's
  /// middle for a semi-implicit Euler step whose velocity after the step carried the position from its start to its
  /// end (ODE, Bullet); its start where a position pass moves the body again after the velocity solve (Box2D).
  /// @throws std::invalid_argument for a mechanism without flywheel, a scene key the engine cannot build or a bad
  ///         option; std::runtime_error if the library fails during the run.
  std::function<Trajectory(const Mechanism& m, const SteppedFreeRunOptions& options)> run_free;
};

}  // namespace crankcheck
