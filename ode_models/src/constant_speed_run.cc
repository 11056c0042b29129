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

/// Places `body` in the plane z at the planar state s: its centre of mass, its rotation s.angle about Z, their rates.
void setPlanarBody(dBodyID body, const PlanarBodyState& s, double z, bool finite_rotation) {
  dBodySetPosition(body, s.p_WBcm_W[0], s.p_WBcm_W[1], z);
  dMatrix3 rotation;
  dRFromAxisAndAngle(rotation, 0.0, 0.0, 1.0, s.angle);
  dBodySetRotation(body, rotation);
  dBodySetLinearVel(body, s.v_WBcm_W[0], s.v_WBcm_W[1], 0.0);
  dBodySetAngularVel(body, 0.0, 0.0, s.omega);
  dBodySetFiniteRotationMode(body, finite_rotation ? 1 : 0);
}

struct CylinderBodies {
  dBodyID rod = nullptr, piston = nullptr;
  dJointID crank_pin = nullptr, wrist_pin = nullptr, slider = nullptr;
  dJointFeedback crank_pin_feedback{}, wrist_pin_feedback{}, slider_feedback{};
  Vec2 e{}, n{};       // the cylinder's axis and its normal
  double delta = 0.0;  // [m] the pin offset: the piston's line is x e + delta n
  double z = 0.0;      // [m] the plane of the rod and the piston
  double v_p = 0.0;    // [m/s] the piston's velocity along e before the step
};

}  // namespace

OdeRun runOdeAtConstantSpeed(const Mechanism& m, const OdeRunOptions& o) {
  const int k = m.machine.cylinders;
  const double omega = o.start.omega;
  if (!(std::fabs(m.machine.speed) > 0.0))
    refuse("[engine].speed_rpm", "must be != 0 (the ODE run is driven at the scene's constant speed)");
  requireOption(std::isfinite(o.dt) && o.dt > 0.0, "dt must be a positive number of seconds");
  requireOption(o.steps > 0, "steps must be > 0");
  requireOption(static_cast<int>(o.start.cylinders.size()) == k && std::isfinite(o.start.phi) && std::isfinite(omega),
                "start must hold the state of each of the mechanism's " + std::to_string(k) + " cylinders");
  requireOption(o.quick_step_iterations >= 1, "quick_step_iterations must be >= 1");
  requireOption(o.erp > 0.0 && o.erp <= 1.0, "erp must be in (0, 1]");
  requireOption(std::isfinite(o.cfm) && o.cfm >= 0.0, "cfm must be >= 0");
  requireOption(o.motor_max_torque > 0.0, "motor_max_torque must be > 0");
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

  // The crankshaft turned by start.phi from its pose at phi = 0: centre of mass c, velocity omega Z x c. Only its
  // inertia about Z acts (the hinge holds the other two axes, and at a spin about Z a diagonal tensor has no
  // gyroscopic moment), so all three are that.
  dBodyID crank = dBodyCreate(w);
  {
    dMass mass;
    dMassSetParameters(&mass, crank_mass, 0.0, 0.0, 0.0, crank_inertia, crank_inertia, crank_inertia, 0.0, 0.0, 0.0);
    dBodySetMass(crank, &mass);
    const double c0 = std::cos(o.start.phi), s0 = std::sin(o.start.phi);
    PlanarBodyState state;
    state.p_WBcm_W = {c0 * cx - s0 * cy, s0 * cx + c0 * cy};
    state.angle = o.start.phi;
    state.omega = omega;
    state.v_WBcm_W = {-omega * state.p_WBcm_W[1], omega * state.p_WBcm_W[0]};
    setPlanarBody(crank, state, 0.0, o.finite_rotation);
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
    const CylinderStartState& s = o.start.cylinders[static_cast<std::size_t>(j)];
    c.e = s.e;
    c.n = s.n;
    c.delta = getPinOffset(m, j);
    c.z = getAxialPosition(m, j);
    c.v_p = s.v_p;
    // The rod: inertia I_o - m_k z_k^2 about every axis (only Z acts, as for the crank).
    c.rod = dBodyCreate(w);
    dMass rod_mass;
    dMassSetParameters(&rod_mass, m.rod.mass, 0.0, 0.0, 0.0, rod_inertia, rod_inertia, rod_inertia, 0.0, 0.0, 0.0);
    dBodySetMass(c.rod, &rod_mass);
    setPlanarBody(c.rod, s.rod, c.z, o.finite_rotation);
    // The piston: a particle at A. Its slider holds every rotation, so its inertia never acts; any positive value
    // will do, the rod's keeps the system's scale.
    c.piston = dBodyCreate(w);
    dMass piston_mass;
    dMassSetParameters(&piston_mass, m.piston.mass, 0.0, 0.0, 0.0, rod_inertia, rod_inertia, rod_inertia, 0.0, 0.0, 0.0);
    dBodySetMass(c.piston, &piston_mass);
    setPlanarBody(c.piston, s.piston, c.z, o.finite_rotation);

    c.crank_pin = dJointCreateHinge(w, nullptr);
    dJointAttach(c.crank_pin, c.rod, crank);
    dJointSetHingeAnchor(c.crank_pin, s.p_WB_W[0], s.p_WB_W[1], c.z);
    dJointSetHingeAxis(c.crank_pin, 0.0, 0.0, 1.0);
    dJointSetFeedback(c.crank_pin, &c.crank_pin_feedback);
    c.wrist_pin = dJointCreateHinge(w, nullptr);
    dJointAttach(c.wrist_pin, c.piston, c.rod);
    dJointSetHingeAnchor(c.wrist_pin, s.p_WA_W[0], s.p_WA_W[1], c.z);
    dJointSetHingeAxis(c.wrist_pin, 0.0, 0.0, 1.0);
    dJointSetFeedback(c.wrist_pin, &c.wrist_pin_feedback);
    c.slider = dJointCreateSlider(w, nullptr);
    dJointAttach(c.slider, c.piston, nullptr);
    dJointSetSliderAxis(c.slider, s.e[0], s.e[1], 0.0);
    dJointSetFeedback(c.slider, &c.slider_feedback);
  }

  const long steps = o.steps;
  OdeRun run;
  run.world = {dWorldGetLinearDamping(w), dWorldGetAngularDamping(w), dWorldGetMaxAngularSpeed(w),
               dWorldGetAutoDisableFlag(w) != 0};
  run.samples.reserve(static_cast<std::size_t>(steps));
  double phi = o.start.phi;
  const auto started = std::chrono::steady_clock::now();
  for (long i = 0; i < steps; ++i) {
    // The step's forces belong to its start (the constraints are linearised at the positions it starts from), so
    // the drive torque's arm is the crank's centre of mass before the step.
    const dReal* c_start = dBodyGetPosition(crank);
    const double arm_x = c_start[0], arm_y = c_start[1];
    // The gas at the step's start (CONVENTIONS: -p_j A e_j on piston j, p at the cycle angle phi - firing_j).
    if (m.gas)
      for (int j = 0; j < k; ++j) {
        const CylinderBodies& c = cylinders[static_cast<std::size_t>(j)];
        const double f = calcGasForce(m, j, phi);
        dBodyAddForce(c.piston, -f * c.e[0], -f * c.e[1], 0.0);
      }
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
    for (CylinderBodies& c : cylinders) {
      OdeCylinderSample cs;
      const dReal* p = dBodyGetPosition(c.piston);
      const dReal* v = dBodyGetLinearVel(c.piston);
      cs.x_p = p[0] * c.e[0] + p[1] * c.e[1];
      cs.v_p = v[0] * c.e[0] + v[1] * c.e[1];
      cs.a_p = (cs.v_p - c.v_p) / o.dt;
      c.v_p = cs.v_p;
      cs.crank_pin = {toVec3(c.crank_pin_feedback.f1), toVec3(c.crank_pin_feedback.f2)};
      cs.wrist_pin = {toVec3(c.wrist_pin_feedback.f1), toVec3(c.wrist_pin_feedback.f2)};
      cs.slider_force = toVec3(c.slider_feedback.f1);
      cs.wall_force = cs.slider_force[0] * c.n[0] + cs.slider_force[1] * c.n[1];
      dVector3 a1, a2;
      dJointGetHingeAnchor(c.crank_pin, a1);
      dJointGetHingeAnchor2(c.crank_pin, a2);
      double error = distance(a1, a2);
      dJointGetHingeAnchor(c.wrist_pin, a1);
      dJointGetHingeAnchor2(c.wrist_pin, a2);
      error = std::max(error, distance(a1, a2));
      const double off_line = p[0] * c.n[0] + p[1] * c.n[1] - c.delta;
      error = std::max(error, std::hypot(off_line, p[2] - c.z));
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
