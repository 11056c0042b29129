#include "crankcheck/box2d_models/constant_speed_run.h"

#include <box2d/box2d.h>

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "model.h"

namespace crankcheck::box2d_models {
namespace {

Vec2 toVec2(const b2Vec2& v) { return {v.x, v.y}; }
b2Vec2 toB2(double x, double y) { return b2Vec2(static_cast<float>(x), static_cast<float>(y)); }
double separation(const b2Vec2& p, const b2Vec2& q) { return std::hypot(double(p.x) - q.x, double(p.y) - q.y); }

}  // namespace

std::string getBox2dVersion() {
  return "Box2D " + std::to_string(b2_version.major) + "." + std::to_string(b2_version.minor) + "." +
         std::to_string(b2_version.revision);
}

Box2dRun runBox2dAtConstantSpeed(const Mechanism& m, const Box2dRunOptions& o) {
  if (!(m.machine.speed != 0.0))
    throw std::invalid_argument("Box2D cannot build this scene: [engine].speed_rpm must be != 0: the Box2D run is "
                                "driven at the scene's speed");
  if (!(o.start.omega == m.machine.speed))
    throw std::invalid_argument("Box2D run: the start state's crank speed must be the scene's");
  const detail::Model model = detail::buildModel(m, o, {.motor = true, .extra_crank_inertia = 0.0});
  const int k = m.machine.cylinders;
  const double omega = m.machine.speed;
  b2World* world = model.world.get();
  b2Body* crank = model.crank;
  b2RevoluteJoint* crank_joint = model.crank_joint;
  const std::vector<detail::CylinderJoints>& cylinders = model.cylinders;

  const float dt = static_cast<float>(o.dt);
  const float inv_dt = 1.0f / dt;
  Box2dRun run;
  run.samples.reserve(static_cast<std::size_t>(o.steps));
  run.cylinders.reserve(static_cast<std::size_t>(o.steps));
  std::vector<double> v_before(static_cast<std::size_t>(k));
  for (int j = 0; j < k; ++j) v_before[static_cast<std::size_t>(j)] = o.start.cylinders[static_cast<std::size_t>(j)].v_p;
  double phi = crank->GetAngle();
  const auto started = std::chrono::steady_clock::now();
  for (long i = 0; i < o.steps; ++i) {
    if (m.gas) {
      // CONVENTIONS "Gas": the force on piston j is -p_j A e_j (calcGasForce: p_j A at the cycle angle
      // phi - firing_j), at the crank angle half a step before the step's start, the instant the step's impulses
      // belong to (the inertial share of each reaction): the velocity solve balances an applied force at the step's
      // configuration, so p at the step's start would put the gas share of each reaction at the start and the
      // inertial share half a step before, and no one instant would fit both (measured on the inline four with gas
      // at 1e-5 s: the crank-pin force's error 2.2e-4 of the force scale at -1/2, 5.6e-5 at the start; 2.0e-5 at
      // -1/2 with p taken there, as without gas). Box2D clears applied forces after each step.
      for (int j = 0; j < k; ++j) {
        const detail::CylinderJoints& c = cylinders[static_cast<std::size_t>(j)];
        const double f = calcGasForce(m, j, phi - 0.5 * omega * o.dt);
        c.piston->ApplyForceToCenter(toB2(-f * c.e[0], -f * c.e[1]), true);
      }
    }
    world->Step(dt, o.velocity_iterations, o.position_iterations);
    Box2dSample sample;
    sample.t = static_cast<double>(i + 1) * o.dt;
    sample.phi_start = phi;
    phi = crank->GetAngle();
    sample.phi = phi;
    sample.crank_speed = crank->GetAngularVelocity();
    sample.drive_torque = crank_joint->GetMotorTorque(inv_dt);
    sample.bearing_force = toVec2(crank_joint->GetReactionForce(inv_dt));
    sample.bearing_error = separation(crank_joint->GetAnchorA(), crank_joint->GetAnchorB());
    std::vector<Box2dCylinderSample> per_cylinder;
    per_cylinder.reserve(static_cast<std::size_t>(k));
    for (int j = 0; j < k; ++j) {
      const detail::CylinderJoints& c = cylinders[static_cast<std::size_t>(j)];
      Box2dCylinderSample cs;
      const b2Vec2 p = c.piston->GetPosition();
      cs.x_p = detail::along(p, c.e);
      cs.v_p = detail::along(c.piston->GetLinearVelocity(), c.e);
      cs.a_p = (cs.v_p - v_before[static_cast<std::size_t>(j)]) / o.dt;
      v_before[static_cast<std::size_t>(j)] = cs.v_p;
      cs.crank_pin_force = toVec2(c.crank_pin->GetReactionForce(inv_dt));
      cs.wrist_pin_force = toVec2(c.wrist_pin->GetReactionForce(inv_dt));
      cs.slider_force = toVec2(c.slider->GetReactionForce(inv_dt));
      cs.wall_force = cs.slider_force[0] * c.n[0] + cs.slider_force[1] * c.n[1];
      cs.loop_error = detail::calcLoopError(c);
      per_cylinder.push_back(cs);
    }
    run.samples.push_back(sample);
    run.cylinders.push_back(std::move(per_cylinder));
  }
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - started;
  run.seconds_per_step = elapsed.count() / static_cast<double>(o.steps);
  return run;
}

}  // namespace crankcheck::box2d_models
