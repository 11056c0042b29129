#include "crankcheck/ode_models/constant_speed_run.h"

#include <ode/ode.h>

#include <chrono>
#include <cstdarg>
#include <cstdio>
#include <cmath>
#include <memory>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>

namespace crankcheck::ode_models {
namespace {

static_assert(std::is_same_v<dReal, double>, "crankcheck's ODE models need ODE built in double precision (dDOUBLE)");

/// ODE reports a failed internal check (a NaN in a singular solve, for instance) through its error and debug
/// handlers, which abort the process by default; these throw instead, so a run that ODE cannot carry ends as an
/// exception of the caller's.
[[noreturn]] void throwOdeError(int errnum, const char* msg, va_list ap) {
  char text[512];
  std::vsnprintf(text, sizeof text, msg, ap);
  throw std::runtime_error("ODE internal error " + std::to_string(errnum) + ": " + text);
}

/// ODE's global state (its thread-local data, the collision library) is set up once per process and never torn
/// down: dInitODE2 may be called once per thread that uses ODE, dAllocateODEDataForThread per thread.
void initOde() {
  static std::once_flag once;
  std::call_once(once, [] {
    dInitODE2(0);
    dSetErrorHandler(throwOdeError);
    dSetDebugHandler(throwOdeError);
  });
  dAllocateODEDataForThread(dAllocateMaskAll);
}

struct WorldDeleter {
  void operator()(dxWorld* w) const { dWorldDestroy(w); }  // destroys its bodies and joints
};

/// The exact state of cylinder j at crank angle phi and speed omega (docs/CONVENTIONS.md "Frames and signs" and
/// "Pin offset"): sin beta = lambda sin theta - delta / l, x_p = r cos theta + l cos beta, the rod's angular velocity
/// about +Z is -beta_dot.
struct CylinderState {
  double gamma = 0.0, delta = 0.0, z = 0.0;
  std::array<double, 2> e{}, n{};
  std::array<double, 2> a{}, b{};     // [m] wrist pin A, crank pin B (global X, Y)
  double x_p = 0.0, v_p = 0.0;       // [m], [m/s] along e
  double rod_angular_velocity = 0.0;  // [rad/s] about +Z
};

CylinderState calcCylinderState(const Mechanism& m, int j, double phi, double omega) {
  const double r = m.crank.radius, l = m.rod.length;
  CylinderState s;
  s.gamma = getBankAngle(m, j);
  s.delta = getPinOffset(m, j);
  s.z = getAxialPosition(m, j);
  s.e = {std::cos(s.gamma), std::sin(s.gamma)};
  s.n = {-s.e[1], s.e[0]};
  const double theta = phi + getThrowAngle(m, j) - s.gamma;
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
  if (!ok) throw std::invalid_argument("ODE run: " + what);
}

void refuse(const std::string& key, const std::string& why) {
  throw std::invalid_argument("ODE cannot build this scene: " + key + " " + why);
}

Vec3 toVec3(const dReal* v) { return {v[0], v[1], v[2]}; }

double distance(const dVector3 p, const dVector3 q) {
  return std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
}

void setPlanarBody(dBodyID body, double x, double y, double z, double vx, double vy, double angular_velocity_z,
                   bool finite_rotation) {
  dBodySetPosition(body, x, y, z);
  dBodySetLinearVel(body, vx, vy, 0.0);
  dBodySetAngularVel(body, 0.0, 0.0, angular_velocity_z);
  dBodySetFiniteRotationMode(body, finite_rotation ? 1 : 0);
}

struct CylinderBodies {
  dBodyID rod = nullptr, piston = nullptr;
  dJointID crank_pin = nullptr, wrist_pin = nullptr, slider = nullptr;
  dJointFeedback crank_pin_feedback{}, wrist_pin_feedback{}, slider_feedback{};
  CylinderState initial;
};

}  // namespace

OdeRun runOdeAtConstantSpeed(const Mechanism& m, const OdeRunOptions& o) {
  const int k = m.machine.cylinders;
  const double omega = m.machine.speed;
  requireOption(std::isfinite(o.dt) && o.dt > 0.0, "dt must be a positive number of seconds");
  requireOption(o.steps >= 0, "steps must be >= 0");
  requireOption(o.steps > 0 || (std::isfinite(o.revolutions) && o.revolutions > 0.0 && omega != 0.0),
                "revolutions must be > 0 with a crank speed != 0 when steps is 0");
  requireOption(o.quick_step_iterations >= 1, "quick_step_iterations must be >= 1");
  requireOption(o.erp > 0.0 && o.erp <= 1.0, "erp must be in (0, 1]");
  requireOption(std::isfinite(o.cfm) && o.cfm >= 0.0, "cfm must be >= 0");
  requireOption(o.motor_max_torque > 0.0, "motor_max_torque must be > 0");
  if (m.gas) refuse("[gas]", "is not modelled by the ODE run yet (drop it: Mechanism::gas.reset())");
  if (!m.balance_shafts.empty()) refuse("[[balance_shaft]]", "has no geared coupling in this ODE model");
  if (!(m.rod.mass > 0.0)) refuse("[rod].mass", "must be > 0 (an ODE body needs a mass)");
  if (!(m.piston.mass > 0.0)) refuse("[piston].mass", "must be > 0 (an ODE body needs a mass)");
  const double rod_inertia = m.rod.inertia_about_wrist_pin - m.rod.mass * m.rod.com_from_wrist_pin * m.rod.com_from_wrist_pin;
  if (!(rod_inertia > 0.0))
    refuse("[rod].inertia_about_wrist_pin", "must exceed m_k z_k^2 (ODE needs the rod's inertia about its centre of mass > 0)");

  // The crank: every throw's m_s at r_s on its crank line and m_p at r_p opposite, one body in the plane z = 0.
  double crank_mass = 0.0, first_x = 0.0, first_y = 0.0, inertia_o = 0.0;
  for (int j = 0; j < k; ++j) {
    const double beta = getThrowAngle(m, j);
    crank_mass += m.crank.mass + m.crank.counterweight_mass;
    first_x += (m.crank.mass * m.crank.com_radius - m.crank.counterweight_mass * m.crank.counterweight_radius) * std::cos(beta);
    first_y += (m.crank.mass * m.crank.com_radius - m.crank.counterweight_mass * m.crank.counterweight_radius) * std::sin(beta);
    inertia_o += m.crank.mass * m.crank.com_radius * m.crank.com_radius +
                 m.crank.counterweight_mass * m.crank.counterweight_radius * m.crank.counterweight_radius;
  }
  if (!(crank_mass > 0.0)) refuse("[crank].mass", "and counterweight_mass are 0 (an ODE body needs a mass)");
  const double cx = first_x / crank_mass, cy = first_y / crank_mass;
  const double crank_inertia = inertia_o - crank_mass * (cx * cx + cy * cy);  // about the centre of mass, along Z
  if (!(crank_inertia > 0.0))
    refuse("[crank].com_radius", "and counterweight_radius leave the crank no inertia about its centre of mass");

  initOde();
  std::unique_ptr<dxWorld, WorldDeleter> world(dWorldCreate());
  dWorldID w = world.get();
  dWorldSetGravity(w, 0.0, -m.machine.gravity, 0.0);
  dWorldSetERP(w, o.erp);
  dWorldSetCFM(w, o.cfm);
  dWorldSetQuickStepNumIterations(w, o.quick_step_iterations);

  // The crankshaft at phi = 0: centre of mass c, velocity omega Z x c. Only its inertia about Z acts (the hinge holds
  // the other two axes, and at a spin about Z a diagonal tensor has no gyroscopic moment), so all three are that.
  dBodyID crank = dBodyCreate(w);
  {
    dMass mass;
    dMassSetParameters(&mass, crank_mass, 0.0, 0.0, 0.0, crank_inertia, crank_inertia, crank_inertia, 0.0, 0.0, 0.0);
    dBodySetMass(crank, &mass);
    setPlanarBody(crank, cx, cy, 0.0, -omega * cy, omega * cx, omega, o.finite_rotation);
  }
  dJointID crank_hinge = dJointCreateHinge(w, nullptr);
  dJointAttach(crank_hinge, crank, nullptr);
  dJointSetHingeAnchor(crank_hinge, 0.0, 0.0, 0.0);
  dJointSetHingeAxis(crank_hinge, 0.0, 0.0, 1.0);
  dJointSetHingeParam(crank_hinge, dParamVel, omega);
  dJointSetHingeParam(crank_hinge, dParamFMax, o.motor_max_torque);
  dJointFeedback crank_feedback{};
  dJointSetFeedback(crank_hinge, &crank_feedback);

  std::vector<CylinderBodies> cylinders(static_cast<std::size_t>(k));
  for (int j = 0; j < k; ++j) {
    CylinderBodies& c = cylinders[static_cast<std::size_t>(j)];
    const CylinderState s = calcCylinderState(m, j, 0.0, omega);
    c.initial = s;
    // The rod: its centre of mass G on A -> B at z_k / l; v_G = v_A + w_rod Z x (G - A). Inertia I_o - m_k z_k^2 about
    // every axis (only Z acts, as for the crank).
    const double f = m.rod.com_from_wrist_pin / m.rod.length;
    const double gx = s.a[0] + f * (s.b[0] - s.a[0]), gy = s.a[1] + f * (s.b[1] - s.a[1]);
    const double vax = s.v_p * s.e[0], vay = s.v_p * s.e[1];
    c.rod = dBodyCreate(w);
    dMass rod_mass;
    dMassSetParameters(&rod_mass, m.rod.mass, 0.0, 0.0, 0.0, rod_inertia, rod_inertia, rod_inertia, 0.0, 0.0, 0.0);
    dBodySetMass(c.rod, &rod_mass);
    setPlanarBody(c.rod, gx, gy, s.z, vax - s.rod_angular_velocity * (gy - s.a[1]),
                  vay + s.rod_angular_velocity * (gx - s.a[0]), s.rod_angular_velocity, o.finite_rotation);
    // The piston: a particle at A. Its slider holds every rotation, so its inertia never acts; any positive value
    // will do, the rod's keeps the system's scale.
    c.piston = dBodyCreate(w);
    dMass piston_mass;
    dMassSetParameters(&piston_mass, m.piston.mass, 0.0, 0.0, 0.0, rod_inertia, rod_inertia, rod_inertia, 0.0, 0.0, 0.0);
    dBodySetMass(c.piston, &piston_mass);
    setPlanarBody(c.piston, s.a[0], s.a[1], s.z, vax, vay, 0.0, o.finite_rotation);

    c.crank_pin = dJointCreateHinge(w, nullptr);
    dJointAttach(c.crank_pin, c.rod, crank);
    dJointSetHingeAnchor(c.crank_pin, s.b[0], s.b[1], s.z);
    dJointSetHingeAxis(c.crank_pin, 0.0, 0.0, 1.0);
    dJointSetFeedback(c.crank_pin, &c.crank_pin_feedback);
    c.wrist_pin = dJointCreateHinge(w, nullptr);
    dJointAttach(c.wrist_pin, c.piston, c.rod);
    dJointSetHingeAnchor(c.wrist_pin, s.a[0], s.a[1], s.z);
    dJointSetHingeAxis(c.wrist_pin, 0.0, 0.0, 1.0);
    dJointSetFeedback(c.wrist_pin, &c.wrist_pin_feedback);
    c.slider = dJointCreateSlider(w, nullptr);
    dJointAttach(c.slider, c.piston, nullptr);
    dJointSetSliderAxis(c.slider, s.e[0], s.e[1], 0.0);
    dJointSetFeedback(c.slider, &c.slider_feedback);
  }

  const long steps = o.steps > 0 ? o.steps
                                 : static_cast<long>(std::ceil(o.revolutions * 2.0 * std::numbers::pi /
                                                               (std::abs(omega) * o.dt) - 1e-9));
  OdeRun run;
  run.samples.reserve(static_cast<std::size_t>(steps));
  double phi = 0.0;
  const auto started = std::chrono::steady_clock::now();
  for (long i = 0; i < steps; ++i) {
    // The step's forces belong to its start (the constraints are linearised at the positions it starts from), so
    // the drive torque's arm is the crank's centre of mass before the step.
    const dReal* c_start = dBodyGetPosition(crank);
    const double arm_x = c_start[0], arm_y = c_start[1];
    if (o.solver == OdeSolver::kStep) {
      dWorldStep(w, o.dt);
    } else {
      dWorldQuickStep(w, o.dt);
    }
    OdeSample sample;
    sample.t = static_cast<double>(i + 1) * o.dt;
    sample.phi_start = phi;
    // The crank's rotation about Z (it starts at the identity): unwrapped against the previous step's angle.
    const dReal* rotation = dBodyGetRotation(crank);
    const double angle = std::atan2(rotation[4], rotation[0]);
    phi += std::remainder(angle - phi, 2.0 * std::numbers::pi);
    sample.phi = phi;
    // The drive torque about O: the joint's torque about the crank's centre of mass plus (c - O) x f.
    sample.bearing_force = toVec3(crank_feedback.f1);
    sample.drive_torque = crank_feedback.t1[2] + arm_x * crank_feedback.f1[1] - arm_y * crank_feedback.f1[0];
    dVector3 anchor;
    dJointGetHingeAnchor(crank_hinge, anchor);
    sample.bearing_error = std::hypot(anchor[0], anchor[1], anchor[2]);
    sample.cylinders.reserve(static_cast<std::size_t>(k));
    for (const CylinderBodies& c : cylinders) {
      OdeCylinderSample cs;
      const dReal* p = dBodyGetPosition(c.piston);
      const CylinderState& s = c.initial;
      cs.x_p = p[0] * s.e[0] + p[1] * s.e[1];
      cs.crank_pin = {toVec3(c.crank_pin_feedback.f1), toVec3(c.crank_pin_feedback.f2)};
      cs.wrist_pin = {toVec3(c.wrist_pin_feedback.f1), toVec3(c.wrist_pin_feedback.f2)};
      cs.slider_force = toVec3(c.slider_feedback.f1);
      cs.wall_force = cs.slider_force[0] * s.n[0] + cs.slider_force[1] * s.n[1];
      dVector3 a1, a2;
      dJointGetHingeAnchor(c.crank_pin, a1);
      dJointGetHingeAnchor2(c.crank_pin, a2);
      double error = distance(a1, a2);
      dJointGetHingeAnchor(c.wrist_pin, a1);
      dJointGetHingeAnchor2(c.wrist_pin, a2);
      error = std::max(error, distance(a1, a2));
      const double off_line = p[0] * s.n[0] + p[1] * s.n[1] - s.delta;
      error = std::max(error, std::hypot(off_line, p[2] - s.z));
      cs.loop_error = error;
      sample.cylinders.push_back(cs);
    }
    run.samples.push_back(std::move(sample));
  }
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - started;
  run.seconds_per_step = steps > 0 ? elapsed.count() / static_cast<double>(steps) : 0.0;
  return run;
}

}  // namespace crankcheck::ode_models
