#pragma once
/// @file
/// The k-crank mechanism in Box2D 2.4 (Debian libbox2d-dev 2.4.1: single precision float, planar), driven at the
/// scene's constant crank speed from the exact state at phi = 0 and stepped by Box2D's own solver, with every joint's
/// reaction read from Box2D's joints. Never links the analytic library: the few closed forms of the initial state are
/// written again in the source. Box2D stays inside src/: this header includes no Box2D header.
///
/// The model (docs/CONVENTIONS.md for frames and symbols), all in the plane XY (the axial positions z_j are dropped:
/// they change none of the planar forces): a static ground body; the crankshaft a dynamic body on a b2RevoluteJoint
/// at O with its motor on (motorSpeed omega, maxMotorTorque `motor_max_torque`); per cylinder j a rod (mass m_k, its
/// centre of mass z_k from the wrist pin, inertia I_o - m_k z_k^2 about it) on revolute joints at the crank pin B_j
/// and the wrist pin A_j, and a piston (mass m_o) on a b2PrismaticJoint to the ground along e_j through
/// delta_j n_j. The bodies carry no fixtures (their mass set directly), so nothing collides.
///
/// Units: Box2D works in "meters, kilograms, seconds" with b2_lengthUnitsPerMeter = 1 in Debian's build, so the scene's
/// SI values go in unchanged. Its length tolerances are tuned for moving objects of 0.1-10 m: b2_linearSlop 5 mm (the
/// joint position solver stops iterating once every joint's error, measured before its correction, is below it) and
/// b2_angularSlop 2 degrees; a crank train is at the small end (r a few cm), so those slops are a large share of r:
/// each step runs at least one position pass whatever the slop, more only while an error exceeds 5 mm.
///
/// Box2D's per-step caps (b2_common.h, compiled into the library, not settable): a body moves at most
/// b2_maxTranslation = 2 m and turns at most b2_maxRotation = pi/2 rad per step; beyond them its velocity is scaled
/// down (the velocity itself, not only the step's motion). At the scenes' speeds the translation cap never bites
/// (2 m per step needs 480 m/s at 1/240 s) but the rotation cap does: at dt = 1/240 s the crank can turn at most
/// 3600 rpm; a 6000 rpm scene at that step runs slower than its motor asks. `capped_steps` counts the steps where the
/// crank asked more than pi/2. Sleep (a body at rest for b2_timeToSleep = 0.5 s stops) is switched off.
///
/// The instants (tests/box2d/box2d_run_test.cc measures them against the closed forms): positions (x_p, phi) belong
/// to the step's end; the impulses Box2D solves in a step (read as forces with GetReactionForce(1/dt) and
/// GetMotorTorque(1/dt)) are solved with the Jacobians at the step's start (phi_start). Box2D's velocity solve has no
/// position feedback (the position error is removed by a separate pass that moves the bodies and leaves their
/// velocities), so a step's impulse takes the bodies from the velocity tangent to the previous configuration to the
/// velocity tangent to this one: the forces match the exact ones best half a step before the step's start (the
/// previous step's middle), and every reading of them is first order in dt; read at the step's start, middle or end
/// each half step adds the same lag.
///
/// Single precision: every position, velocity and impulse is a float (eps_f = 1.19e-7), so the loop cannot close
/// below about eps_f times the position scale, and a step's impulse, the difference of two float velocities of size
/// v ~ r omega a dt apart, carries a rounding that grows like 1 / dt: the forces stop converging near dt = 1e-5 s at
/// the scenes' speeds (tests/box2d/box2d_run_test.cc, SinglePrecisionFloorsTheConvergence).

#include <array>
#include <limits>
#include <vector>

#include "crankcheck/scene/mechanism.h"

namespace crankcheck::box2d_models {

using Vec2 = std::array<double, 2>;

/// The settings of a constant-speed run. Defaults: what Box2D's users take (its testbed's 8 velocity and 3 position
/// iterations) and the step of a typical game, 1/240 s.
struct Box2dRunOptions {
  double dt = 1.0 / 240.0;       ///< [s] the step, > 0 (passed to Box2D as a float)
  /// Number of steps; 0: enough whole steps to cover `revolutions` turns of the crank (ceil).
  long steps = 0;
  double revolutions = 1.0;      ///< turns of the crank, > 0, when steps == 0 (needs omega != 0)
  int velocity_iterations = 8;   ///< b2World::Step's velocityIterations, >= 1: sequential-impulse sweeps
  int position_iterations = 3;   ///< b2World::Step's positionIterations, >= 1: position-correction sweeps at most
  /// [N m] maxMotorTorque of the crank's motor, > 0: the largest torque it may apply. The default stands for
  /// "unlimited" (Box2D clamps the motor impulse to it times dt in float; the largest float / 1e3 keeps that finite).
  double motor_max_torque = 1e35;
  bool warm_starting = true;     ///< b2World::SetWarmStarting (Box2D's default true)
};

/// One cylinder at one step. Forces as Box2D reports them: GetReactionForce(1/dt), on the joint's body B.
struct Box2dCylinderSample {
  double x_p = 0.0;            ///< [m] the piston's coordinate along e_j at the step's end
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
  double phi_start = 0.0;      ///< [rad] the crank's angle at the step's start (the previous sample's phi; 0 first)
  double drive_torque = 0.0;   ///< [N m] about +Z, the motor's torque on the crank (GetMotorTorque(1/dt))
  Vec2 bearing_force{};        ///< [N] on the crank from the frame at O (the crank joint's GetReactionForce(1/dt))
  double bearing_error = 0.0;  ///< [m] the crank joint's anchor separation at the step's end
  double crank_speed = 0.0;    ///< [rad/s] the crank body's angular velocity at the step's end
};

/// A constant-speed run.
struct Box2dRun {
  std::vector<Box2dSample> samples;               ///< one per step, in order
  std::vector<std::vector<Box2dCylinderSample>> cylinders;  ///< per step, per cylinder
  long capped_steps = 0;       ///< steps whose crank turn omega dt asked more than b2_maxRotation (pi/2)
  double seconds_per_step = 0.0;  ///< [s] wall time of the stepping (reads included) divided by the steps
};

/// Builds m's mechanism in Box2D, sets it at the exact state at phi = 0 and the scene's speed, drives the crank at
/// omega with its joint's motor and steps it `o.steps` times (or for `o.revolutions` turns), recording each step.
/// @throws std::invalid_argument naming the key of what Box2D cannot build: `[gas]` (not modelled here),
///   `[[balance_shaft]]`, `[rod].mass` or `[piston].mass` of 0, `[rod].inertia_about_wrist_pin` equal to m_k z_k^2,
///   `[crank].mass` and counterweight_mass both 0, or a bad option (dt, steps, revolutions with speed 0, iterations,
///   motor_max_torque).
Box2dRun runBox2dAtConstantSpeed(const Mechanism& m, const Box2dRunOptions& o);

}  // namespace crankcheck::box2d_models
