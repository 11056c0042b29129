#pragma once
/// @file
/// The k-crank mechanism in the Open Dynamics Engine (Debian libode-dev 0.16, built in double precision), driven at the
/// scene's constant crank speed from a start state handed in (crankcheck/solver/stepped_run.h: StartState, the exact
/// state at phi = 0 that the caller computes) and stepped by ODE's own solver, with every joint's reaction read from
/// ODE's joint feedback. Never links the analytic library and computes no closed form of the loop: every body's
/// position and velocity at the start come from the StartState. ODE stays inside src/: this header includes no ODE
/// header. stepped_engine.h describes the two engines of the registry built on this run.
///
/// The model (docs/CONVENTIONS.md for frames and symbols): the crankshaft is one body on a hinge about Z at O, driven
/// by the hinge's velocity motor (dParamVel = omega). Per cylinder j a rod (mass m_k at z_k from the wrist pin, inertia
/// I_o - m_k z_k^2 about its centre of mass) on a hinge about Z at the crank pin B_j, and a piston (a particle of mass
/// m_o) on a hinge about Z at the wrist pin A_j and a slider along e_j on the line A_j = x_p e_j + delta_j n_j. The rod
/// and the piston of cylinder j lie in the plane z = z_j; the crank's point masses m_s, m_p of every throw are lumped
/// into one body in the plane z = 0 (their axial spread only moves the bearing's moments, which are not recorded).
///
/// The axial positions z_j place the rods and pistons along the shaft but change none of the planar forces recorded
/// here (every hinge is about Z); the out-of-plane reactions of these redundant 3-D joints are not recorded.
///
/// Gas: with [gas], each step applies -p A e_j to piston j (dBodyAddForce, CONVENTIONS "Layouts, axial positions, gas
/// and shaking"), p at the cylinder's cycle angle at the step's START (calcGasForce of the crank angle phi_start): the
/// force ODE integrates through the step is the one of the instant its solved forces belong to.
///
/// The instants (tests/ode/ode_run_test.cc measures them against the closed forms): x_p and phi belong to the step's
/// end; v_p, the piston body's velocity after the step, to its MIDDLE: it is the velocity that carries the positions
/// from the step's start to its end (ODE's semi-implicit Euler), a secant; the forces and the drive torque ODE solves
/// during a step, and a_p (the velocity change / dt: the force's effect), to its START: ODE solves them with the
/// joints linearised at the positions the step starts from, so they match the exact ones there to second order in
/// dt, while read at the step's middle they carry a half step's lag (first order) and at its end twice that.
/// The first steps are a start-up transient: the exact state at phi = 0 already satisfies the velocity constraints,
/// so the first step applies almost none of the inertia load; the error shrinks by about (1 - ERP) per step after.
///
/// Why a motor rather than a velocity reset: the motor is a constraint row ODE solves with the joints, so its torque
/// (the drive torque) comes from ODE's own feedback and every other reaction is consistent with it; a reset of the
/// crank's speed between steps would leave the drive torque to be inferred from a momentum balance outside ODE.

#include <array>
#include <limits>
#include <vector>

#include "crankcheck/scene/mechanism.h"
#include "crankcheck/solver/stepped_run.h"

namespace crankcheck::ode_models {

using Vec3 = std::array<double, 3>;

/// ODE's two steppers: dWorldStep (a direct, "big matrix" solve of the constraint forces) and dWorldQuickStep
/// (projected Gauss-Seidel, a fixed number of iterations).
enum class OdeSolver { kStep, kQuickStep };

/// The settings of a constant-speed run. Defaults: ODE's own defaults (0.16 in double precision) and the step of a
/// typical user, 1/240 s.
struct OdeRunOptions {
  double dt = 1.0 / 240.0;       ///< [s] the step, > 0
  long steps = 1;                ///< number of steps, > 0
  /// The state at the run's start: the crank at start.phi turning at start.omega (the scene's speed, != 0), each
  /// cylinder's rod and piston (calcStartState). Must have one cylinder per cylinder of the mechanism.
  StartState start;
  OdeSolver solver = OdeSolver::kStep;
  int quick_step_iterations = 20;  ///< dWorldSetQuickStepNumIterations (ODE's default 20), >= 1
  double erp = 0.2;              ///< dWorldSetERP, in (0, 1] (ODE's default 0.2): the share of a joint's error fixed per step
  /// dWorldSetCFM, >= 0 (ODE's default in double precision 1e-10). The hinges and sliders of a planar loop are
  /// redundant in 3-D: with too little mixing (0, 1e-16) ODE's solve is singular and the run throws.
  double cfm = 1e-10;
  /// dBodySetFiniteRotationMode for every body. ODE's default (false) turns a body by 2 atan(w dt / 2) per step
  /// instead of w dt (the first-order quaternion update, normalised); true turns it exactly by w dt.
  bool finite_rotation = false;
  /// [N m] dParamFMax of the crank's motor: the largest torque it may apply; infinite: the speed is held whatever it costs.
  double motor_max_torque = std::numeric_limits<double>::infinity();
};

/// The reactions of one joint between two bodies, as ODE's dJointFeedback gives them: the force on each body [N],
/// global X, Y, Z (on body2 is minus on body1 for these joints, to the solver's rounding).
struct OdeJointForce {
  Vec3 on_first{};   ///< [N] on the first body named with the field
  Vec3 on_second{};  ///< [N] on the second (the frame's share is not reported by ODE: zero for joints to the world)
};

/// One cylinder at one step.
struct OdeCylinderSample {
  double x_p = 0.0;            ///< [m] the piston's coordinate along e_j (its body's position . e_j) at the step's end
  double v_p = 0.0;            ///< [m/s] the piston body's velocity . e_j after the step
  double a_p = 0.0;            ///< [m/s^2] (v_p after the step - v_p before it) / dt
  OdeJointForce crank_pin{};   ///< on the rod (first) and on the crank (second), from the hinge at B_j
  OdeJointForce wrist_pin{};   ///< on the piston (first) and on the rod (second), from the hinge at A_j
  Vec3 slider_force{};         ///< [N] on the piston from the wall (the slider to the world)
  double wall_force = 0.0;     ///< [N] N_w = slider_force . n_j (CONVENTIONS: the wall pushes the piston with N_w n)
  /// [m] the largest separation, at the step's end, of a joint of this cylinder: each hinge's anchor as body 1 and
  /// body 2 carry it (dJointGetHingeAnchor, ...Anchor2), the piston's distance from its line (the slider's error).
  double loop_error = 0.0;
};

/// One step: positions at its end (t), forces those ODE solved for during it.
struct OdeSample {
  double t = 0.0;              ///< [s] the step's end
  /// [rad] the crank angle at the step's end: the crank body's rotation about Z, unwrapped (continuous over turns).
  double phi = 0.0;
  /// [rad] the crank angle at the step's start (the previous sample's phi; start.phi for the first step): the
  /// instant the step's forces and drive torque belong to.
  double phi_start = 0.0;
  double crank_speed = 0.0;    ///< [rad/s] the crank body's angular velocity about Z after the step
  double drive_torque = 0.0;   ///< [N m] about +Z at O, the motor and hinge's torque on the crank (feedback)
  Vec3 bearing_force{};        ///< [N] on the crank from the frame at O: the crank hinge's feedback force
  double bearing_error = 0.0;  ///< [m] the crank hinge's anchor separation at the step's end
  std::vector<OdeCylinderSample> cylinders;
};

/// ODE's world defaults that would change the physics rather than the solver's accuracy, as the run's world reports
/// them (dWorldGet...): the run sets none of them.
struct OdeWorldDefaults {
  double linear_damping = 0.0;      ///< [-] dWorldGetLinearDamping: the share of a body's velocity removed per step
  double angular_damping = 0.0;     ///< [-] dWorldGetAngularDamping
  double max_angular_speed = 0.0;   ///< [rad/s] dWorldGetMaxAngularSpeed: a cap on every body's spin (infinite: none)
  bool auto_disable = false;        ///< dWorldGetAutoDisableFlag: bodies at rest are frozen
};

/// A constant-speed run.
struct OdeRun {
  std::vector<OdeSample> samples;   ///< one per step, in order
  OdeWorldDefaults world;           ///< the world's physics-changing defaults, read back from ODE
  double seconds_per_step = 0.0;    ///< [s] wall time of the stepping (feedback reads included) divided by the steps
};

/// Builds m's mechanism in ODE, sets it at o.start (every body's position, orientation, linear and angular velocity),
/// drives the crank at start.omega with its hinge's motor and steps it `o.steps` times, recording each step.
/// @throws std::invalid_argument naming the key of what ODE cannot build: `[[balance_shaft]]`, `[rod].mass` or
///   `[piston].mass` of 0 (a body needs a mass), `[rod].inertia_about_wrist_pin` equal to m_k z_k^2 (a rod without
///   rotational inertia about its centre of mass), `[engine].speed_rpm` of 0 (the run is driven at the scene's
///   speed), or a bad option (dt, steps, start, quick_step_iterations, erp, cfm, motor_max_torque).
/// @throws std::runtime_error when one of ODE's internal checks fails during the run (ODE would abort the process;
///   here its error and debug handlers throw), e.g. a singular solve at too small a cfm.
OdeRun runOdeAtConstantSpeed(const Mechanism& m, const OdeRunOptions& o);

}  // namespace crankcheck::ode_models
