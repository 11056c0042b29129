#pragma once
/// @file
/// The k-crank mechanism in Box2D 2.4 (Debian libbox2d-dev 2.4.1: single precision float, planar), driven at the
/// scene's constant crank speed from a given start state (crankcheck/solver/stepped_run.h: StartState, built by the
/// caller from an exact evaluation) and stepped by Box2D's own solver, with every joint's reaction read from Box2D's
/// joints. Never links the analytic library and computes no closed form: the start comes in. Box2D stays inside src/:
/// this header includes no Box2D header.
///
/// The model (docs/CONVENTIONS.md for frames and symbols), all in the plane XY (the axial positions z_j are dropped:
/// they change none of the planar forces, but Box2D cannot carry the shaking moment's X and Y they make): a static
/// ground body; the crankshaft a dynamic body on a b2RevoluteJoint at O with its motor on (motorSpeed omega,
/// maxMotorTorque "unlimited"); per cylinder j a rod (mass m_k, its centre of mass z_k from the wrist pin, inertia
/// I_o - m_k z_k^2 about it) on revolute joints at the crank pin B_j and the wrist pin A_j, and a piston (mass m_o)
/// on a b2PrismaticJoint to the ground along e_j through delta_j n_j. The bodies carry no fixtures (their mass set
/// directly), so nothing collides. With [gas], each step applies -p_j A e_j to piston j's centre
/// (Box2D holds an applied force over the whole step), p_j at the crank's angle half a step before the step's start:
/// the instant of the step's impulses (below), so that the gas share of each reaction belongs where its inertial share
/// does.
///
/// The free run (free_run.h) builds this same model with the motor off and the flywheel on the crank.
///
/// Units: Box2D works in "meters, kilograms, seconds" with b2_lengthUnitsPerMeter = 1 in Debian's build, so the scene's
/// SI values go in unchanged. Its length tolerances are tuned for moving objects of 0.1-10 m: b2_linearSlop 5 mm (the
/// joint position solver stops iterating once every joint's error, measured before its correction, is below it) and
/// b2_angularSlop 2 degrees; a crank train is at the small end (r a few cm), so those slops are a large share of r:
/// each step runs at least one position pass whatever the slop, more only while an error exceeds 5 mm.
///
/// Box2D's per-step caps (b2_common.h, compiled into the library, not settable): a body moves at most
/// b2_maxTranslation = 2 m and turns at most b2_maxRotation = pi/2 rad per step; beyond them Box2D scales the body's
/// velocity down and the run would silently be at another speed. The run refuses such a step instead: the crank
/// turning |omega| dt > pi/2 (at 1/240 s: above 3600 rpm), the rod turning faster than that, or a body's centre
/// moving more than 2 m in a step (bounded from the crank's speed, below). Sleep is switched off.
///
/// The instants (tests/box2d/box2d_run_test.cc measures them against the closed forms): positions (x_p) belong to the
/// step's end; v_p, the velocity Box2D's velocity solve makes tangent to the configuration at the step's start,
/// belongs to the step's start; the impulses Box2D solves in a step (read as forces with GetReactionForce(1/dt) and
/// GetMotorTorque(1/dt)) and a_p (the step's velocity change / dt) take the bodies from the velocity tangent to the
/// previous configuration to the one tangent to this one: the pin and bearing forces and a_p belong half a step
/// before the step's start (the previous step's middle), first order in dt. The drive torque's and the wall force's
/// first-order errors are partly not that lag (they change little with the instant they are read at): read a quarter
/// step before the start they are smallest (measured on the single, the inline four and the V8, with and without gas).
///
/// Single precision: every position, velocity and impulse is a float (eps_f = 1.19e-7), so the loop cannot close
/// below about eps_f times the position scale, and a step's impulse, the difference of two float velocities a dt
/// apart, carries a rounding that grows like 1 / dt: the forces stop converging near dt = 1e-5 s at the scenes'
/// speeds, the crank-pin force at 2e-5..7e-5 of the force scale (tests/box2d/box2d_run_test.cc,
/// SinglePrecisionFloorsTheConvergence).

#include <array>
#include <string>
#include <vector>

#include "crankcheck/scene/mechanism.h"
#include "crankcheck/solver/stepped_run.h"

namespace crankcheck::box2d_models {

using Vec2 = std::array<double, 2>;

/// The settings of a constant-speed run. Defaults: what Box2D's users take (its testbed's 8 velocity and 3 position
/// iterations, warm starting on) and the step of a typical game, 1/240 s.
struct Box2dRunOptions {
  double dt = 1.0 / 240.0;       ///< [s] the step, > 0 (passed to Box2D as a float)
  long steps = 0;                ///< number of steps, > 0
  int velocity_iterations = 8;   ///< b2World::Step's velocityIterations, >= 1: sequential-impulse sweeps
  int position_iterations = 3;   ///< b2World::Step's positionIterations, >= 1: position-correction sweeps at most
  bool warm_starting = true;     ///< b2World::SetWarmStarting (Box2D's default true)
  /// The state at the run's start (calcStartState of an exact evaluation): every body's position and velocity, the
  /// crank's angle and speed (start.omega must be m.machine.speed), one cylinder per cylinder of m.
  StartState start;
};

/// One cylinder at one step. Forces as Box2D reports them: GetReactionForce(1/dt), on the joint's body B.
struct Box2dCylinderSample {
  double x_p = 0.0;            ///< [m] the piston's coordinate along e_j at the step's end
  double v_p = 0.0;            ///< [m/s] the piston's velocity along e_j at the step's end
  double a_p = 0.0;            ///< [m/s^2] the step's change of v_p over dt (the first step's from start.v_p)
  Vec2 crank_pin_force{};      ///< [N] on the rod from the crank (the crank-pin joint, crank A, rod B)
  Vec2 wrist_pin_force{};      ///< [N] on the piston from the rod (the wrist-pin joint, rod A, piston B)
  Vec2 slider_force{};         ///< [N] on the piston from the wall (the prismatic joint, ground A, piston B)
  double wall_force = 0.0;     ///< [N] N_w = slider_force . n_j (CONVENTIONS: the wall pushes the piston with N_w n)
  /// [m] the largest separation, at the step's end, of a joint of this cylinder: each revolute joint's anchor as
  /// its two bodies carry it (GetAnchorA, GetAnchorB), the piston's distance from its line.
  double loop_error = 0.0;
};

/// One step: positions at its end (t), forces those Box2D solved for during it.
struct Box2dSample {
  double t = 0.0;              ///< [s] the step's end
  double phi = 0.0;            ///< [rad] the crank body's angle at the step's end (Box2D's, continuous over turns)
  double phi_start = 0.0;      ///< [rad] the crank's angle at the step's start (the previous sample's phi; start.phi first)
  double drive_torque = 0.0;   ///< [N m] about +Z, the motor's torque on the crank (GetMotorTorque(1/dt))
  Vec2 bearing_force{};        ///< [N] on the crank from the frame at O (the crank joint's GetReactionForce(1/dt))
  double bearing_error = 0.0;  ///< [m] the crank joint's anchor separation at the step's end
  double crank_speed = 0.0;    ///< [rad/s] the crank body's angular velocity at the step's end
};

/// A constant-speed run.
struct Box2dRun {
  std::vector<Box2dSample> samples;               ///< one per step, in order
  std::vector<std::vector<Box2dCylinderSample>> cylinders;  ///< per step, per cylinder
  double seconds_per_step = 0.0;  ///< [s] wall time of the stepping (reads included) divided by the steps
};

/// "Box2D MAJOR.MINOR.REVISION", read from the library's b2_version.
std::string getBox2dVersion();

/// Builds m's mechanism in Box2D at o.start, drives the crank at omega with its joint's motor and steps it o.steps
/// times, recording each step.
/// @throws std::invalid_argument naming the key of what Box2D cannot build: `[[balance_shaft]]`, `[rod].mass`
///   or `[piston].mass` of 0, `[rod].inertia_about_wrist_pin` equal to m_k z_k^2, `[crank].mass` and
///   counterweight_mass both 0, `[engine].speed_rpm` 0; a step Box2D would cap ("a step of DT s turns the crank by X
///   rad, more than Box2D's b2_maxRotation (pi/2) ...", the same for the rod and b2_maxTranslation); or a bad option
///   (dt, steps, iterations, a start state not of m's cylinders or speed).
Box2dRun runBox2dAtConstantSpeed(const Mechanism& m, const Box2dRunOptions& o);

}  // namespace crankcheck::box2d_models
