#include "crankcheck/box2d_models/stepped_engine.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "crankcheck/box2d_models/constant_speed_run.h"
#include "crankcheck/box2d_models/free_run.h"

namespace crankcheck::box2d_models {
namespace {

constexpr const char* kName = "box2d";

/// Box2D's testbed defaults: 8 velocity and 3 position iterations, warm starting on.
constexpr int kDefaultVelocityIterations = 8, kDefaultPositionIterations = 3;
/// Tightened: past where either sweep stops changing anything (measured on the single and the inline four at 1/240,
/// 1e-3 and 1e-4 s): the velocity solve's errors are the same to 1% from 16 sweeps on (50 = 3 times that); the
/// position pass closes the single's loop at 1/240 s 4.3 times better with 10 sweeps than 3, no better with 20 or 50
/// (20 = 2 times that). Below 1/240 s one position sweep already leaves every joint under Box2D's 5 mm slop.
constexpr int kTightVelocityIterations = 50, kTightPositionIterations = 20;

/// Where each reported quantity belongs within a step (constant_speed_run.h explains each): the fraction at which
/// its error against the closed forms is smallest (tests/box2d/box2d_run_test.cc, EachQuantityBelongsToItsInstant).
std::vector<QuantityInstant> reportedQuantities() {
  return {{QuantityId::kDriveTorque, -0.25},    {QuantityId::kBearingForce, -0.5},
          {QuantityId::kPistonPosition, 1.0},  {QuantityId::kPistonVelocity, 0.0},
          {QuantityId::kPistonAcceleration, -0.5}, {QuantityId::kCrankPinForce, -0.5},
          {QuantityId::kWristPinForce, -0.5},  {QuantityId::kWallForce, -0.25}};
}

/// The run's options at the named settings (the driven and the free run share them).
Box2dRunOptions toRunOptions(double dt, long steps, const std::string& settings, const StartState& start) {
  Box2dRunOptions o;
  o.dt = dt;
  o.steps = steps;
  o.start = start;
  if (settings == "defaults") {
    o.velocity_iterations = kDefaultVelocityIterations;
    o.position_iterations = kDefaultPositionIterations;
  } else if (settings == "tightened") {
    o.velocity_iterations = kTightVelocityIterations;
    o.position_iterations = kTightPositionIterations;
  } else {
    throw std::invalid_argument(std::string(kName) + " has no settings \"" + settings +
                                "\"; its settings are defaults, tightened");
  }
  return o;
}

Trajectory runSteppedBox2d(const Mechanism& m, const ConstantSpeedRunOptions& options) {
  if (!(m.machine.speed != 0.0))
    throw std::invalid_argument("[engine].speed_rpm must be != 0: " + std::string(kName) + " is driven at the scene's speed");
  const Box2dRun run =
      runBox2dAtConstantSpeed(m, toRunOptions(options.dt, options.steps, options.settings, options.start));
  const int k = m.machine.cylinders;
  Trajectory out;
  out.reported = reportedQuantities();
  out.seconds_per_step = run.seconds_per_step;
  for (std::size_t i = 0; i < run.samples.size(); ++i) {
    const Box2dSample& s = run.samples[i];
    out.time.push_back(s.t);
    out.phi.push_back(s.phi);
    out.omega.push_back(s.crank_speed);
    out.omega_time.push_back(s.t - options.dt);  // the step's start, as the free run's (box2d_models/free_run.h)
    Evaluation& values = out.values.emplace_back(makeUnreportedEvaluation(kName, k));
    values.phi = s.phi;
    values.drive_torque = s.drive_torque;
    values.bearing_force = s.bearing_force;
    double loop = s.bearing_error;
    for (int j = 0; j < k; ++j) {
      const Box2dCylinderSample& c = run.cylinders[i][static_cast<std::size_t>(j)];
      CylinderEvaluation& v = values.cylinders[static_cast<std::size_t>(j)];
      v.x_p = c.x_p;
      v.v_p = c.v_p;
      v.a_p = c.a_p;
      v.crank_pin_force = c.crank_pin_force;
      v.wrist_pin_force = c.wrist_pin_force;
      v.wall_force = c.wall_force;
      loop = std::max(loop, c.loop_error);
    }
    out.loop_error.push_back(loop);
  }
  return out;
}

Trajectory runFreeSteppedBox2d(const Mechanism& m, const SteppedFreeRunOptions& options) {
  return runBox2dFree(m, toRunOptions(options.dt, options.steps, options.settings, options.start));
}

}  // namespace

std::vector<Engine> describeEngines() {
  Engine e;
  e.gated = false;  // measured, never gated
  e.name = kName;
  e.library = getBox2dVersion() + " (single precision)";
  e.method = "planar rigid bodies on revolute and prismatic joints, the crank on a speed motor; sequential impulses "
             "(velocity) then a nonlinear Gauss-Seidel position pass, symplectic Euler, float";
  e.settings = {"defaults", "tightened"};
  e.settings_meaning = {
      "Box2D's testbed: 8 velocity and 3 position iterations, warm starting",
      "50 velocity and 20 position iterations, warm starting: past where the sweeps stop changing the run (16 and "
      "10); closes the loop 4 times better at 1/240 s, changes nothing below 1e-3 s"};
  e.instants = "x_p at the step's end; v_p at its start (the velocity solve makes it tangent to the start's "
               "configuration); the pin and bearing forces and a_p (the step's velocity change / dt) half a step before its "
               "start: they carry the velocity from the previous configuration's tangent to this one's; the drive "
               "torque and the wall force, whose first-order error is partly not a lag, a quarter step before it";
  e.cannot_build = "[[balance_shaft]] (no geared coupling); the axial positions' shaking moment X, Y (planar); a step "
                   "turning the crank or a rod more than b2_maxRotation (pi/2) or moving a body more than "
                   "b2_maxTranslation (2 m); a body of zero mass or inertia";
  e.step_at_speed = runSteppedBox2d;
  e.step_free = runFreeSteppedBox2d;
  return {e};
}

}  // namespace crankcheck::box2d_models
