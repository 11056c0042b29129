#pragma once
/// @file
/// The k-crank mechanism in Bullet 3.24's btMultiBody (Featherstone's articulated-body algorithm in reduced
/// coordinates; Debian libbullet-dev's double-precision build, bullet-float64), driven at the scene's constant crank
/// speed from a StartState handed in (crankcheck/solver/stepped_run.h: built by the caller from an exact evaluation)
/// and stepped by Bullet's own solver. Never links the analytic library and computes no closed form of the loop.
/// Bullet stays inside src/: this header includes no Bullet header.
///
/// The model (docs/CONVENTIONS.md for frames and symbols): one btMultiBody with a fixed base at O. Its links: the
/// crankshaft (a revolute joint about Z at O, every throw's m_s and m_p lumped into one body in the plane z = 0); per
/// cylinder j a piston (a prismatic joint from the base along e_j on the line A_j = x_p e_j + delta_j n_j, plane
/// z = z_j; its joint coordinate is x_p) and a rod (a revolute joint about Z at the crank pin B_j, child of the crank).
/// The tree is open at the wrist pins: each loop is closed by a btMultiBodyPoint2Point between the rod and the piston
/// at A_j, a constraint Bullet's sequential-impulse (projected Gauss-Seidel) solver holds each step with the crank's
/// btMultiBodyJointMotor (velocity target omega). The crank pin, the bearing and the slider are joints of the tree:
/// their reactions are not constraint impulses, Bullet reports them through btMultiBodyJointFeedback (the articulated
/// force across each joint, set by the free pass and added to by a second pass with the constraint forces). Against
/// the closed forms (tests/bullet/bullet_run_test.cc): the pistons' feedback is the wall's force (second order at the
/// step's start); the rods' and the crank's are NOT the crank-pin and bearing forces, nor twice them (Bullet's issues
/// #4604 and #2966): the second pass counts the links' velocity-dependent load again, so without gravity the
/// feedback less its free pass's share (crank_pin_feedback_free, bearing_feedback_free) is the force to first order
/// in dt; gravity leaves a remainder of the links' weights' size.
///
/// Bullet's step (stepSimulation(dt, 0): one step of exactly dt, no fixed-step substepping and no interpolation of
/// the reported state): the free velocities from the articulated-body algorithm at the step's start, then the
/// constraint impulses solved on the rows built at the step's start positions, then the positions integrated with
/// the constrained velocities (semi-implicit Euler). The instants (tests/bullet/bullet_run_test.cc verifies them):
/// positions (x_p, phi) belong to the step's end; the impulses (the drive torque, the wrist-pin force) and the joint
/// feedback to its start: read at the step's middle or end they carry a half or a whole step's lag (first order).
/// v_p (the piston's joint speed after the step) belongs to the step's middle (semi-implicit Euler moves x_p by it:
/// it is the slope of x_p over the step) and a_p (its change over the step / dt) to the step's start: the change is
/// the acceleration the solver found at the start positions.
/// The first steps are a start-up transient: the exact state at phi = 0 already satisfies the velocity constraints,
/// so the first step applies almost none of the inertia load; the error shrinks by about (1 - ERP) per step after.
///
/// Bullet's defaults that change the physics, each an option here with Bullet's default: btMultiBody's linear and
/// angular damping 0.04 (each link gets a force -m v (0.04 + 0.04 |v|) and a torque likewise from its angular
/// velocity, in every step; the motor pays for it), its cap of every joint speed at 100 (rad/s or m/s: every velocity
/// update, the constraint impulses' included, is clamped to it, so a crank asked for 3000 rpm, 314 rad/s, turns at
/// 100 rad/s and its loops stay open by centimetres), and a constraint's largest impulse per row, 100 N s (it binds
/// only when force times dt exceeds it: not on the example scenes at 1/240 s).
///
/// The free run (runBulletFree) is the same model without the motor, the crank carrying the scene's flywheel. Against
/// the exact free run (tests/bullet/bullet_free_run_test.cc) its phase after two revolutions converges at orders 1.2
/// to 2 with Bullet's speed cap and damping off; at Bullet's defaults the cap holds a crank released faster than
/// 100 rad/s at 100 rad/s and the damping drains its energy every step.
///
/// Gas ([gas]): each piston link gets the external force -p A e_j every step, p = calcGasPressure at its cycle angle
/// phi - firing_j (docs/CONVENTIONS.md "Gas") at the step's start, held through the step.

#include <array>
#include <limits>
#include <vector>

#include "crankcheck/scene/mechanism.h"
#include "crankcheck/solver/stepped_run.h"

namespace crankcheck::bullet_models {

using Vec3 = std::array<double, 3>;

/// The settings of a constant-speed run. Defaults: Bullet 3.24's own defaults (btContactSolverInfo, btMultiBody,
/// btMultiBodyConstraint) and the step of a typical user, 1/240 s.
struct BulletRunOptions {
  double dt = 1.0 / 240.0;          ///< [s] the step, > 0
  long steps = 1;                   ///< number of steps, > 0
  /// The state at the run's start (calcStartState): the crank's angle and speed, each cylinder's pins, x_p, v_p and
  /// its rod's angle and angular velocity; one cylinder per cylinder of the mechanism.
  StartState start;
  int solver_iterations = 10;       ///< btContactSolverInfo::m_numIterations (Bullet's default 10), >= 1
  /// btContactSolverInfo::m_erp and m_erp2, in (0, 1] (Bullet's default 0.2 for both): the share of a loop's
  /// position error a step corrects (for a row whose error Bullet's contact logic counts as a "penetration", > 0 along
  /// the row's normal, the whole error is corrected whatever erp is).
  double erp = 0.2;
  double linear_damping = 0.04;     ///< btMultiBody::setLinearDamping, >= 0 (Bullet's default 0.04)
  double angular_damping = 0.04;    ///< btMultiBody::setAngularDamping, >= 0 (Bullet's default 0.04)
  double max_coordinate_velocity = 100.0;  ///< btMultiBody::setMaxCoordinateVelocity [rad/s or m/s], > 0 (default 100)
  double loop_max_impulse = 100.0;  ///< [N s] the point-to-point rows' largest impulse, > 0 (Bullet's default 100)
  /// [N m s] the crank motor's largest impulse per step; infinite: the speed is held whatever it costs.
  double motor_max_impulse = std::numeric_limits<double>::infinity();
};

/// One cylinder at one step.
struct BulletCylinderSample {
  double x_p = 0.0;            ///< [m] the piston's joint coordinate along e_j at the step's end
  double v_p = 0.0;            ///< [m/s] the piston's joint speed along e_j at the step's end
  double a_p = 0.0;            ///< [m/s^2] the change of its joint speed over the step / dt
  /// [N] on the piston from the rod at A_j (global X, Y, Z): the point-to-point constraint's applied impulses / dt.
  Vec3 wrist_pin{};
  /// [N] the rod's joint feedback (btMultiBodyJointFeedback, its force part, global axes): what Bullet reports as the
  /// force on the rod from the crank at B_j. NOT that force: see the file's comment.
  Vec3 crank_pin_feedback{};
  /// [N] its share from Bullet's free pass (the articulated-body algorithm without the constraints, global axes).
  Vec3 crank_pin_feedback_free{};
  /// [N] the piston's joint feedback (global axes): the force on the piston from the wall (its component along e_j,
  /// the free axis, is 0).
  Vec3 slider_feedback{};
  double wall_force = 0.0;    ///< [N] N_w = slider_feedback . n_j
  /// [m] the wrist pin's separation at the step's end: the pivot as the rod and as the piston carry it.
  double loop_error = 0.0;
};

/// One step: positions at its end (t), impulses those Bullet solved for during it.
struct BulletSample {
  double t = 0.0;              ///< [s] the step's end
  /// [rad] the crank's angle at the step's end: the start's phi plus the crank joint's coordinate (continuous)
  double phi = 0.0;
  /// [rad] the crank angle at the step's start (the previous sample's phi; the start's for the first step): the
  /// instant the step's impulses belong to.
  double phi_start = 0.0;
  double crank_speed = 0.0;    ///< [rad/s] the crank joint's speed after the step (its angular velocity about +Z)
  double drive_torque = 0.0;   ///< [N m] about +Z on the crank: the motor's applied impulse / dt
  /// [N] the crank's joint feedback (global axes): what Bullet reports as the force on the crankshaft from the frame
  /// at O. NOT that force: see the file's comment.
  Vec3 bearing_feedback{};
  /// [N] its share from Bullet's free pass (global axes).
  Vec3 bearing_feedback_free{};
  std::vector<BulletCylinderSample> cylinders;
};

/// A constant-speed run.
struct BulletRun {
  std::vector<BulletSample> samples;  ///< one per step, in order
  double seconds_per_step = 0.0;      ///< [s] wall time of the stepping (reads included) divided by the steps
};

/// Builds m's mechanism as a btMultiBody in the pose of o.start (every joint coordinate 0 there but the pistons'
/// x_p), sets the joints' speeds from it, drives the crank at o.start.omega with its joint motor and steps it
/// `o.steps` times, recording each step.
/// @throws std::invalid_argument naming the key of what this model cannot build: `[[balance_shaft]]`, `[rod].mass`
///   or `[piston].mass` of 0 (a link needs a mass), `[rod].inertia_about_wrist_pin` equal to m_k z_k^2,
///   `[crank].mass` (no crank mass), `[engine].speed_rpm` of 0, or a bad option (dt, steps, start with another
///   number of cylinders, solver_iterations, erp, linear_damping, angular_damping, max_coordinate_velocity,
///   loop_max_impulse, motor_max_impulse).
BulletRun runBulletAtConstantSpeed(const Mechanism& m, const BulletRunOptions& o);

/// The same model run free (the one construction of runBulletAtConstantSpeed, without its motor): no drive, no gas
/// (a scene's [gas] is left out), the crank's inertia about O increased by the scene's flywheel inertia, released
/// from o.start (every joint's speed from it, the crank's at the release speed o.start.omega) under the scene's
/// gravity and stepped `o.steps` times at o.dt with o's solver settings and Bullet's defaults as o sets them (the
/// damping and the joint speed cap act on the free crank as on every link; motor_max_impulse does not apply).
/// Records after each step its end's time, the crank's angle (o.start.phi plus its joint coordinate, continuous) and
/// its joint speed (about +Z), which belongs to the step's middle (omega_time half a step behind: semi-implicit Euler
/// moves the angle by dt times the speed after the step).
/// @throws std::invalid_argument naming `[flywheel].inertia` when the scene has none (or a negative one), what
///   runBulletAtConstantSpeed refuses but the speed (the release speed may be any finite number), or a bad option.
Trajectory runBulletFree(const Mechanism& m, const BulletRunOptions& o);

}  // namespace crankcheck::bullet_models
