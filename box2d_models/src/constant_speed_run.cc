#include "crankcheck/box2d_models/constant_speed_run.h"

#include <box2d/box2d.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>

namespace crankcheck::box2d_models {
namespace {

static_assert(b2_lengthUnitsPerMeter == 1.0f, "crankcheck's Box2D model passes SI lengths unscaled");

/// The exact state of cylinder j at crank angle phi and speed omega (docs/CONVENTIONS.md "Frames and signs" and
/// "Pin offset"): sin beta = lambda sin theta - delta / l, x_p = r cos theta + l cos beta, the rod's angular velocity
/// about +Z is -beta_dot.
struct CylinderState {
  double delta = 0.0;
  std::array<double, 2> e{}, n{};
  std::array<double, 2> a{}, b{};     // [m] wrist pin A, crank pin B
  double x_p = 0.0, v_p = 0.0;       // [m], [m/s] along e
  double rod_angular_velocity = 0.0;  // [rad/s] about +Z
};

CylinderState calcCylinderState(const Mechanism& m, int j, double phi, double omega) {
  const double r = m.crank.radius, l = m.rod.length;
  CylinderState s;
  const double gamma = getBankAngle(m, j);
  s.delta = getPinOffset(m, j);
  s.e = {std::cos(gamma), std::sin(gamma)};
  s.n = {-s.e[1], s.e[0]};
  const double theta = phi + getThrowAngle(m, j) - gamma;
  const double sin_beta = (r * std::sin(theta) - s.delta) / l;
  const double cos_beta = std::sqrt(1.0 - sin_beta * sin_beta);
  const double beta_dot = r * std::cos(theta) * omega / (l * cos_beta);
  s.x_p = r * std::cos(theta) + l * cos_beta;
  s.v_p = -r * std::sin(theta) * omega - l * sin_beta * beta_dot;
  s.rod_angular_velocity = -beta_dot;
  const double crank_angle = phi + getThrowAngle(m, j);
  s.b = {r * std::cos(crank_angle), r * std::sin(crank_angle)};
  s.a = {s.x_p * s.e[0] + s.delta * s.n[0], s.x_p * s.e[1] + s.delta * s.n[1]};
  return s;
}

void requireOption(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("Box2D run: " + what);
}

void refuse(const std::string& key, const std::string& why) {
  throw std::invalid_argument("Box2D cannot build this scene: " + key + " " + why);
}

b2Vec2 toB2(double x, double y) { return b2Vec2(static_cast<float>(x), static_cast<float>(y)); }
Vec2 toVec2(const b2Vec2& v) { return {v.x, v.y}; }
double separation(const b2Vec2& p, const b2Vec2& q) { return std::hypot(double(p.x) - q.x, double(p.y) - q.y); }

/// A dynamic body without fixtures: its origin at `origin`, angle 0, mass properties set directly (center: the
/// centre of mass in the body's frame; inertia about the body's origin, as b2MassData wants it).
b2Body* createBody(b2World& world, double x, double y, double mass, b2Vec2 center, double inertia_about_origin) {
  b2BodyDef def;
  def.type = b2_dynamicBody;
  def.position = toB2(x, y);
  def.allowSleep = false;
  b2Body* body = world.CreateBody(&def);
  b2MassData data;
  data.mass = static_cast<float>(mass);
  data.center = center;
  data.I = static_cast<float>(inertia_about_origin);
  body->SetMassData(&data);
  return body;
}

struct CylinderJoints {
  b2Body* rod = nullptr;
  b2Body* piston = nullptr;
  b2RevoluteJoint* crank_pin = nullptr;
  b2RevoluteJoint* wrist_pin = nullptr;
  b2PrismaticJoint* slider = nullptr;
  CylinderState initial;
};

}  // namespace

Box2dRun runBox2dAtConstantSpeed(const Mechanism& m, const Box2dRunOptions& o) {
  const int k = m.machine.cylinders;
  const double omega = m.machine.speed;
  requireOption(std::isfinite(o.dt) && o.dt > 0.0, "dt must be a positive number of seconds");
  requireOption(o.steps >= 0, "steps must be >= 0");
  requireOption(o.steps > 0 || (std::isfinite(o.revolutions) && o.revolutions > 0.0 && omega != 0.0),
                "revolutions must be > 0 with a crank speed != 0 when steps is 0");
  requireOption(o.velocity_iterations >= 1, "velocity_iterations must be >= 1");
  requireOption(o.position_iterations >= 1, "position_iterations must be >= 1");
  requireOption(o.motor_max_torque > 0.0 && o.motor_max_torque <= 1e35, "motor_max_torque must be in (0, 1e35]");
  if (m.gas) refuse("[gas]", "is not modelled by the Box2D run yet (drop it: Mechanism::gas.reset())");
  if (!m.balance_shafts.empty()) refuse("[[balance_shaft]]", "has no geared coupling in this Box2D model");
  if (!(m.rod.mass > 0.0)) refuse("[rod].mass", "must be > 0 (a Box2D body needs a mass)");
  if (!(m.piston.mass > 0.0)) refuse("[piston].mass", "must be > 0 (a Box2D body needs a mass)");
  const double rod_inertia = m.rod.inertia_about_wrist_pin - m.rod.mass * m.rod.com_from_wrist_pin * m.rod.com_from_wrist_pin;
  if (!(rod_inertia > 0.0))
    refuse("[rod].inertia_about_wrist_pin", "must exceed m_k z_k^2 (Box2D needs the rod's inertia about its centre of mass > 0)");

  // The crank: every throw's m_s at r_s on its crank line and m_p at r_p opposite, one body whose origin is O.
  double crank_mass = 0.0, first_x = 0.0, first_y = 0.0, inertia_o = 0.0;
  for (int j = 0; j < k; ++j) {
    const double beta = getThrowAngle(m, j);
    crank_mass += m.crank.mass + m.crank.counterweight_mass;
    first_x += (m.crank.mass * m.crank.com_radius - m.crank.counterweight_mass * m.crank.counterweight_radius) * std::cos(beta);
    first_y += (m.crank.mass * m.crank.com_radius - m.crank.counterweight_mass * m.crank.counterweight_radius) * std::sin(beta);
    inertia_o += m.crank.mass * m.crank.com_radius * m.crank.com_radius +
                 m.crank.counterweight_mass * m.crank.counterweight_radius * m.crank.counterweight_radius;
  }
  if (!(crank_mass > 0.0)) refuse("[crank].mass", "and counterweight_mass are 0 (a Box2D body needs a mass)");
  const double cx = first_x / crank_mass, cy = first_y / crank_mass;
  if (!(inertia_o - crank_mass * (cx * cx + cy * cy) > 0.0))
    refuse("[crank].com_radius", "and counterweight_radius leave the crank no inertia about its centre of mass");

  auto world = std::make_unique<b2World>(toB2(0.0, -m.machine.gravity));
  world->SetAllowSleeping(false);
  world->SetWarmStarting(o.warm_starting);
  world->SetContinuousPhysics(false);  // no fixtures, nothing to collide: time of impact has nothing to do

  b2BodyDef ground_def;  // static, at the origin
  b2Body* ground = world->CreateBody(&ground_def);

  // The crankshaft: origin O, centre of mass c, its velocity omega Z x c (SetLinearVelocity is the centre's).
  b2Body* crank = createBody(*world, 0.0, 0.0, crank_mass, toB2(cx, cy), inertia_o);
  crank->SetAngularVelocity(static_cast<float>(omega));
  crank->SetLinearVelocity(toB2(-omega * cy, omega * cx));
  b2RevoluteJointDef crank_def;
  crank_def.Initialize(ground, crank, b2Vec2(0.0f, 0.0f));
  crank_def.enableMotor = true;
  crank_def.motorSpeed = static_cast<float>(omega);
  crank_def.maxMotorTorque = static_cast<float>(o.motor_max_torque);
  auto* crank_joint = static_cast<b2RevoluteJoint*>(world->CreateJoint(&crank_def));

  std::vector<CylinderJoints> cylinders(static_cast<std::size_t>(k));
  for (int j = 0; j < k; ++j) {
    CylinderJoints& c = cylinders[static_cast<std::size_t>(j)];
    const CylinderState s = calcCylinderState(m, j, 0.0, omega);
    c.initial = s;
    // The rod: origin at its centre of mass G on A -> B at z_k / l; v_G = v_A + w_rod Z x (G - A).
    const double f = m.rod.com_from_wrist_pin / m.rod.length;
    const double gx = s.a[0] + f * (s.b[0] - s.a[0]), gy = s.a[1] + f * (s.b[1] - s.a[1]);
    const double vax = s.v_p * s.e[0], vay = s.v_p * s.e[1];
    c.rod = createBody(*world, gx, gy, m.rod.mass, b2Vec2(0.0f, 0.0f), rod_inertia);
    c.rod->SetLinearVelocity(toB2(vax - s.rod_angular_velocity * (gy - s.a[1]), vay + s.rod_angular_velocity * (gx - s.a[0])));
    c.rod->SetAngularVelocity(static_cast<float>(s.rod_angular_velocity));
    // The piston: origin at A. Its prismatic joint holds its rotation, so its inertia never acts; the rod's keeps the
    // system's scale.
    c.piston = createBody(*world, s.a[0], s.a[1], m.piston.mass, b2Vec2(0.0f, 0.0f), rod_inertia);
    c.piston->SetLinearVelocity(toB2(vax, vay));

    b2RevoluteJointDef crank_pin;
    crank_pin.Initialize(crank, c.rod, toB2(s.b[0], s.b[1]));
    c.crank_pin = static_cast<b2RevoluteJoint*>(world->CreateJoint(&crank_pin));
    b2RevoluteJointDef wrist_pin;
    wrist_pin.Initialize(c.rod, c.piston, toB2(s.a[0], s.a[1]));
    c.wrist_pin = static_cast<b2RevoluteJoint*>(world->CreateJoint(&wrist_pin));
    b2PrismaticJointDef slider;
    slider.Initialize(ground, c.piston, toB2(s.a[0], s.a[1]), toB2(s.e[0], s.e[1]));
    c.slider = static_cast<b2PrismaticJoint*>(world->CreateJoint(&slider));
  }

  const long steps = o.steps > 0 ? o.steps
                                 : static_cast<long>(std::ceil(o.revolutions * 2.0 * std::numbers::pi /
                                                               (std::abs(omega) * o.dt) - 1e-9));
  const float dt = static_cast<float>(o.dt);
  const float inv_dt = 1.0f / dt;
  Box2dRun run;
  run.samples.reserve(static_cast<std::size_t>(steps));
  run.cylinders.reserve(static_cast<std::size_t>(steps));
  const bool capped = std::abs(omega) * o.dt > 0.5 * std::numbers::pi;
  double phi = 0.0;
  const auto started = std::chrono::steady_clock::now();
  for (long i = 0; i < steps; ++i) {
    world->Step(dt, o.velocity_iterations, o.position_iterations);
    if (capped) ++run.capped_steps;
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
    for (const CylinderJoints& c : cylinders) {
      Box2dCylinderSample cs;
      const CylinderState& s = c.initial;
      const b2Vec2 p = c.piston->GetPosition();
      cs.x_p = p.x * s.e[0] + p.y * s.e[1];
      cs.crank_pin_force = toVec2(c.crank_pin->GetReactionForce(inv_dt));
      cs.wrist_pin_force = toVec2(c.wrist_pin->GetReactionForce(inv_dt));
      cs.slider_force = toVec2(c.slider->GetReactionForce(inv_dt));
      cs.wall_force = cs.slider_force[0] * s.n[0] + cs.slider_force[1] * s.n[1];
      double error = separation(c.crank_pin->GetAnchorA(), c.crank_pin->GetAnchorB());
      error = std::max(error, separation(c.wrist_pin->GetAnchorA(), c.wrist_pin->GetAnchorB()));
      error = std::max(error, std::abs(p.x * s.n[0] + p.y * s.n[1] - s.delta));
      cs.loop_error = error;
      per_cylinder.push_back(cs);
    }
    run.samples.push_back(sample);
    run.cylinders.push_back(std::move(per_cylinder));
  }
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - started;
  run.seconds_per_step = steps > 0 ? elapsed.count() / static_cast<double>(steps) : 0.0;
  return run;
}

}  // namespace crankcheck::box2d_models
