#include "model.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

namespace crankcheck::box2d_models::detail {
namespace {

static_assert(b2_lengthUnitsPerMeter == 1.0f, "crankcheck's Box2D model passes SI lengths unscaled");

void requireOption(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("Box2D run: " + what);
}

std::string formatNumber(double x) {
  std::ostringstream out;
  out.precision(4);
  out << x;
  return out.str();
}

/// Refuses a step at which Box2D would cap a body's motion, the crank turning at crank_speed [rad/s] (b2Island::Solve scales the body's velocity down when
/// dt |w| > b2_maxRotation or dt |v| > b2_maxTranslation): the run would silently go at another speed.
/// Bounds over the turn (CONVENTIONS "Pin offset": sin beta = lambda sin theta - delta / l): the crank turns at
/// |omega|; the rod at |beta_dot| = r |omega cos theta| / (l cos beta) <= r |omega| / (l cos beta_max), sin beta_max =
/// (r + |delta|) / l; the wrist pin moves at |v_p| = r |omega| |sin theta + tan beta cos theta| <= r |omega| /
/// cos beta_max; the rod's centre at most |v_A| + |beta_dot| z_k, the crank's centre at |omega| |c|.
void refuseCappedSteps(const Mechanism& m, double crank_speed, double dt, double crank_com_radius) {
  const double omega = std::fabs(crank_speed), r = m.crank.radius, l = m.rod.length;
  const double max_rotation = b2_maxRotation, max_translation = b2_maxTranslation;
  if (omega * dt > max_rotation)
    throw std::invalid_argument("Box2D run: a step of " + formatNumber(dt) + " s turns the crank by " +
                                formatNumber(omega * dt) + " rad, more than Box2D's b2_maxRotation (pi/2), which " +
                                "would cap its speed; take a step below " + formatNumber(max_rotation / omega) + " s");
  double max_offset = 0.0;
  for (int j = 0; j < m.machine.cylinders; ++j) max_offset = std::max(max_offset, std::fabs(getPinOffset(m, j)));
  const double sin_beta = std::min((r + max_offset) / l, 1.0);
  const double cos_beta = std::sqrt(1.0 - sin_beta * sin_beta);
  const double rod_omega = r * omega / (l * cos_beta);
  if (rod_omega * dt > max_rotation)
    throw std::invalid_argument("Box2D run: a step of " + formatNumber(dt) + " s turns a rod by up to " +
                                formatNumber(rod_omega * dt) + " rad, more than Box2D's b2_maxRotation (pi/2), which " +
                                "would cap its speed");
  const double v_piston = r * omega / cos_beta;
  const double v_rod = v_piston + rod_omega * std::fabs(m.rod.com_from_wrist_pin);
  const double v_max = std::max({v_piston, v_rod, omega * crank_com_radius});
  if (v_max * dt > max_translation)
    throw std::invalid_argument("Box2D run: a step of " + formatNumber(dt) + " s moves a body's centre by up to " +
                                formatNumber(v_max * dt) + " m, more than Box2D's b2_maxTranslation (2 m), which " +
                                "would cap its speed");
}

b2Vec2 toB2(double x, double y) { return b2Vec2(static_cast<float>(x), static_cast<float>(y)); }
b2Vec2 toB2(const crankcheck::Vec2& v) { return toB2(v[0], v[1]); }
double separation(const b2Vec2& p, const b2Vec2& q) { return std::hypot(double(p.x) - q.x, double(p.y) - q.y); }

/// A dynamic body without fixtures: its origin at `origin`, turned by `angle`, mass properties set directly (center:
/// the centre of mass in the body's frame; inertia about the body's origin, as b2MassData wants it).
b2Body* createBody(b2World& world, b2Vec2 origin, double angle, double mass, b2Vec2 center, double inertia_about_origin) {
  b2BodyDef def;
  def.type = b2_dynamicBody;
  def.position = origin;
  def.angle = static_cast<float>(angle);
  def.allowSleep = false;
  b2Body* body = world.CreateBody(&def);
  b2MassData data;
  data.mass = static_cast<float>(mass);
  data.center = center;
  data.I = static_cast<float>(inertia_about_origin);
  body->SetMassData(&data);
  return body;
}

}  // namespace

double along(const b2Vec2& p, const crankcheck::Vec2& e) { return double(p.x) * e[0] + double(p.y) * e[1]; }

Model buildModel(const Mechanism& m, const Box2dRunOptions& o, const ModelOptions& options) {
  const int k = m.machine.cylinders;
  const double omega = o.start.omega;
  requireOption(std::isfinite(o.dt) && o.dt > 0.0, "dt must be a positive number of seconds");
  requireOption(o.steps > 0, "steps must be > 0");
  requireOption(o.velocity_iterations >= 1, "velocity_iterations must be >= 1");
  requireOption(o.position_iterations >= 1, "position_iterations must be >= 1");
  requireOption(static_cast<int>(o.start.cylinders.size()) == k,
                "the start state has " + std::to_string(o.start.cylinders.size()) + " cylinders, the scene " +
                    std::to_string(k));
  requireOption(std::isfinite(omega), "the start state's crank speed must be a number");
  requireOption(std::isfinite(options.extra_crank_inertia) && options.extra_crank_inertia >= 0.0,
                "the crank's added inertia must be >= 0");
  checkSteppedScene(m, "Box2D");
  const double rod_inertia = calcRodCentroidalInertia(m);
  // The crank: one body whose origin is O, its frame the crank's at phi = 0 (turned by start.phi).
  const LumpedCrank lumped = calcLumpedCrank(m, "Box2D");
  const double crank_mass = lumped.mass, cx = lumped.p_OBcm[0], cy = lumped.p_OBcm[1];
  const double inertia_o = lumped.inertia_about_o + options.extra_crank_inertia;
  refuseCappedSteps(m, omega, o.dt, std::hypot(cx, cy));

  Model model;
  model.world = std::make_unique<b2World>(toB2(0.0, -m.machine.gravity));
  b2World* world = model.world.get();
  world->SetAllowSleeping(false);
  world->SetWarmStarting(o.warm_starting);
  world->SetContinuousPhysics(false);  // no fixtures, nothing to collide: time of impact has nothing to do

  b2BodyDef ground_def;  // static, at the origin
  b2Body* ground = world->CreateBody(&ground_def);

  // The crankshaft: origin O, turned by start.phi; its centre's velocity omega Z x c (SetLinearVelocity is the
  // centre's), c turned with the body.
  const double phi0 = o.start.phi;
  b2Body* crank = createBody(*world, b2Vec2(0.0f, 0.0f), phi0, crank_mass, toB2(cx, cy), inertia_o);
  const double c0x = std::cos(phi0) * cx - std::sin(phi0) * cy, c0y = std::sin(phi0) * cx + std::cos(phi0) * cy;
  crank->SetAngularVelocity(static_cast<float>(omega));
  crank->SetLinearVelocity(toB2(-omega * c0y, omega * c0x));
  b2RevoluteJointDef crank_def;
  crank_def.Initialize(ground, crank, b2Vec2(0.0f, 0.0f));
  crank_def.enableMotor = options.motor;
  crank_def.motorSpeed = static_cast<float>(omega);
  // "Unlimited": Box2D clamps the motor's impulse to maxMotorTorque dt in float; the largest float / 1e3 keeps that
  // finite at any step.
  crank_def.maxMotorTorque = 1e35f;
  model.crank = crank;
  model.crank_joint = static_cast<b2RevoluteJoint*>(world->CreateJoint(&crank_def));

  std::vector<CylinderJoints>& cylinders = model.cylinders;
  cylinders.resize(static_cast<std::size_t>(k));
  for (int j = 0; j < k; ++j) {
    CylinderJoints& c = cylinders[static_cast<std::size_t>(j)];
    const CylinderStartState& s = o.start.cylinders[static_cast<std::size_t>(j)];
    c.e = s.e;
    c.n = s.n;
    c.delta = s.p_WA_W[0] * s.n[0] + s.p_WA_W[1] * s.n[1];
    // The rod: origin at its centre of mass, turned to the direction A -> B.
    c.rod = createBody(*world, toB2(s.rod.p_WBcm_W), s.rod.angle, m.rod.mass, b2Vec2(0.0f, 0.0f), rod_inertia);
    c.rod->SetLinearVelocity(toB2(s.rod.v_WBcm_W));
    c.rod->SetAngularVelocity(static_cast<float>(s.rod.omega));
    // The piston: origin at A. Its prismatic joint holds its rotation, so its inertia never acts; the rod's keeps the
    // system's scale.
    c.piston = createBody(*world, toB2(s.piston.p_WBcm_W), 0.0, m.piston.mass, b2Vec2(0.0f, 0.0f), rod_inertia);
    c.piston->SetLinearVelocity(toB2(s.piston.v_WBcm_W));

    b2RevoluteJointDef crank_pin;
    crank_pin.Initialize(crank, c.rod, toB2(s.p_WB_W));
    c.crank_pin = static_cast<b2RevoluteJoint*>(world->CreateJoint(&crank_pin));
    b2RevoluteJointDef wrist_pin;
    wrist_pin.Initialize(c.rod, c.piston, toB2(s.p_WA_W));
    c.wrist_pin = static_cast<b2RevoluteJoint*>(world->CreateJoint(&wrist_pin));
    b2PrismaticJointDef slider;
    slider.Initialize(ground, c.piston, toB2(s.p_WA_W), toB2(s.e));
    c.slider = static_cast<b2PrismaticJoint*>(world->CreateJoint(&slider));
  }
  return model;
}

double calcLoopError(const CylinderJoints& c) {
  double error = separation(c.crank_pin->GetAnchorA(), c.crank_pin->GetAnchorB());
  error = std::max(error, separation(c.wrist_pin->GetAnchorA(), c.wrist_pin->GetAnchorB()));
  return std::max(error, std::abs(along(c.piston->GetPosition(), c.n) - c.delta));
}

}  // namespace crankcheck::box2d_models::detail
