#include "crankcheck/bullet_models/stepped_engine.h"

#include <LinearMath/btScalar.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "crankcheck/bullet_models/constant_speed_run.h"
#include "crankcheck/scene/quantities.h"

namespace crankcheck::bullet_models {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// "Bullet 3.24 (btMultiBody, double precision)" from btGetVersion() (major * 100 + minor).
std::string describeLibrary() {
  const int version = btGetVersion();
  return "Bullet " + std::to_string(version / 100) + "." + std::to_string(version % 100) + " (double precision)";
}

/// The run options of a settings name; std::invalid_argument naming it and the settings otherwise.
BulletRunOptions getSettings(const std::string& name, const std::vector<std::string>& names) {
  BulletRunOptions o;  // Bullet's own defaults
  if (name == "defaults") return o;
  if (name != "neutralised" && name != "tightened") {
    std::string list;
    for (const std::string& s : names) list += (list.empty() ? "" : ", ") + s;
    throw std::invalid_argument("bullet has no settings \"" + name + "\"; its settings are " + list);
  }
  o.max_coordinate_velocity = kInfinity;
  o.linear_damping = 0.0;
  o.angular_damping = 0.0;
  o.loop_max_impulse = kInfinity;
  if (name == "tightened") {
    // ERP 1: the whole loop error corrected each step, not a fifth of it; 100 iterations: enough that more change
    // nothing. tests/bullet/bullet_run_test.cc (TightenedSettingsEachEarnTheirPlace) measures both.
    o.erp = 1.0;
    o.solver_iterations = 100;
  }
  return o;
}

Trajectory runStepped(const Mechanism& m, const ConstantSpeedRunOptions& options, const std::vector<std::string>& names) {
  BulletRunOptions o = getSettings(options.settings, names);
  if (!(std::fabs(m.machine.speed) > 0.0))
    throw std::invalid_argument("[engine].speed_rpm must be != 0: bullet is driven at the scene's constant speed");
  o.dt = options.dt;
  o.steps = options.steps;
  o.start = options.start;
  const BulletRun run = runBulletAtConstantSpeed(m, o);
  const int k = m.machine.cylinders;
  Trajectory out;
  out.seconds_per_step = run.seconds_per_step;
  out.reported = {{QuantityId::kPistonPosition, 1.0},  {QuantityId::kPistonVelocity, 0.5},
                  {QuantityId::kPistonAcceleration, 0.0}, {QuantityId::kDriveTorque, 0.0},
                  {QuantityId::kBearingForce, 0.0},    {QuantityId::kCrankPinForce, 0.0},
                  {QuantityId::kWristPinForce, 0.0},   {QuantityId::kWallForce, 0.0}};
  const Evaluation blank = makeUnreportedEvaluation("bullet", k);
  for (const BulletSample& b : run.samples) {
    out.time.push_back(b.t);
    out.phi.push_back(b.phi);
    out.omega.push_back(b.crank_speed);
    out.omega_time.push_back(b.t - 0.5 * options.dt);  // semi-implicit Euler: the step's middle, as the free run's
    Evaluation& values = out.values.emplace_back(blank);
    double& loop_error = out.loop_error.emplace_back(0.0);
    values.phi = b.phi;
    values.drive_torque = b.drive_torque;
    values.bearing_force = {b.bearing_feedback[0], b.bearing_feedback[1]};
    for (int j = 0; j < k; ++j) {
      const BulletCylinderSample& c = b.cylinders[static_cast<std::size_t>(j)];
      CylinderEvaluation& e = values.cylinders[static_cast<std::size_t>(j)];
      e.x_p = c.x_p;
      e.v_p = c.v_p;
      e.a_p = c.a_p;
      e.crank_pin_force = {c.crank_pin_feedback[0], c.crank_pin_feedback[1]};
      e.wrist_pin_force = {c.wrist_pin[0], c.wrist_pin[1]};
      e.wall_force = c.wall_force;
      loop_error = std::max(loop_error, c.loop_error);
    }
  }
  return out;
}

Trajectory runSteppedFree(const Mechanism& m, const SteppedFreeRunOptions& options, const std::vector<std::string>& names) {
  BulletRunOptions o = getSettings(options.settings, names);
  o.dt = options.dt;
  o.steps = options.steps;
  o.start = options.start;
  return runBulletFree(m, o);
}

}  // namespace

std::vector<Engine> describeEngines() {
  Engine e;
  e.gated = false;  // measured, never gated
  e.name = "bullet";
  e.library = describeLibrary();
  e.method = "btMultiBody (Featherstone, reduced coordinates) with the wrist pins closed by btMultiBodyPoint2Point and "
             "the crank driven by a btMultiBodyJointMotor; sequential-impulse (projected Gauss-Seidel) solver, "
             "semi-implicit Euler";
  e.settings = {"defaults", "neutralised", "tightened"};
  e.settings_meaning = {
      "Bullet's own: every joint speed capped at 100 (rad/s, m/s), damping 0.04, loop impulse cap 100 N s, "
      "10 solver iterations, ERP 0.2",
      "the speed cap, the damping and the loop impulse cap off; Bullet's 10 iterations and ERP 0.2 kept",
      "neutralised, with ERP 1 (the whole loop error corrected each step) and 100 solver iterations"};
  e.instants = "x_p at the step's end; v_p (the joint speed after the step, the slope x_p moves by) at its middle; "
               "a_p (the speed's change / dt), the impulses (drive torque, wrist pin) and the joint feedback (bearing, crank pin, wall) at its start "
               "(solved on the rows built at the start's positions)";
  e.cannot_build = "[[balance_shaft]]; a zero [rod].mass, [piston].mass or crank mass; a rod with no inertia about its "
                   "centre of mass";
  const std::vector<std::string> names = e.settings;
  e.step_at_speed = [names](const Mechanism& m, const ConstantSpeedRunOptions& options) { return runStepped(m, options, names); };
  // What Bullet's upstream reports say about the rods' and the crank's joint feedback, and what the measurement found
  // (tests/bullet/bullet_run_test.cc, JointFeedbackIsTheForcePlusTheFreePassAgain).
  const std::string feedback =
      "Bullet's issues #4604 and #2966 report btMultiBody's joint feedback doubled in 3.24 (a fix was merged after "
      "3.24, the version Debian ships); measured here it is not twice the force but the force plus the link's "
      "velocity-dependent load of the free pass counted a second time: subtracting that share leaves the true force to "
      "first order in the step (tests/bullet: JointFeedbackIsTheForcePlusTheFreePassAgain), so the feedback itself does "
      "not converge";
  e.notes = {{"crank_pin_force", feedback}, {"bearing_force", feedback}};
  e.step_free = [names](const Mechanism& m, const SteppedFreeRunOptions& options) { return runSteppedFree(m, options, names); };
  return {e};
}

}  // namespace crankcheck::bullet_models
