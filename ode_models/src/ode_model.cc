#include "ode_model.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>
#include <type_traits>

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

void refuse(const std::string& key, const std::string& why) {
  throw std::invalid_argument("ODE cannot build this scene: " + key + " " + why);
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

}  // namespace

void requireOdeOption(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("ODE run: " + what);
}

void buildOdeModel(OdeModel& model, const Mechanism& m, const OdeRunOptions& o, CrankDrive drive) {
  const int k = m.machine.cylinders;
  const double omega = o.start.omega;
  requireOdeOption(std::isfinite(o.dt) && o.dt > 0.0, "dt must be a positive number of seconds");
  requireOdeOption(o.steps > 0, "steps must be > 0");
  requireOdeOption(static_cast<int>(o.start.cylinders.size()) == k && std::isfinite(o.start.phi) && std::isfinite(omega),
                "start must hold the state of each of the mechanism's " + std::to_string(k) + " cylinders");
  requireOdeOption(o.quick_step_iterations >= 1, "quick_step_iterations must be >= 1");
  requireOdeOption(o.erp > 0.0 && o.erp <= 1.0, "erp must be in (0, 1]");
  requireOdeOption(std::isfinite(o.cfm) && o.cfm >= 0.0, "cfm must be >= 0");
  if (drive == CrankDrive::kMotor) requireOdeOption(o.motor_max_torque > 0.0, "motor_max_torque must be > 0");
  if (drive == CrankDrive::kFreeWithFlywheel && !(m.flywheel_inertia && *m.flywheel_inertia >= 0.0))
    refuse("[flywheel].inertia", "is needed for a free run (the crank carries the scene's flywheel)");
  checkSteppedScene(m, "ODE");
  const double rod_inertia = calcRodCentroidalInertia(m);
  const LumpedCrank lumped = calcLumpedCrank(m, "ODE");
  const double crank_mass = lumped.mass, cx = lumped.p_OBcm[0], cy = lumped.p_OBcm[1];
  // About the centre of mass, along Z; the free run's flywheel turns with the crank about O, so its inertia adds.
  const double crank_inertia =
      lumped.inertia_about_cm + (drive == CrankDrive::kFreeWithFlywheel ? *m.flywheel_inertia : 0.0);

  initOde();
  // QuickStep reorders its constraints at random every few iterations from ODE's one process-wide generator
  // (dRandInt): seeded here and held by this model to its end (OdeModel::random_generator), each run repeats exactly
  // whatever ran before it or beside it in the process (unseeded, a second `motion` in one Python session differed
  // from the first in the 12th digit). dWorldStep draws nothing: its runs neither seed nor wait.
  if (o.solver == OdeSolver::kQuickStep) {
    static std::mutex generator;
    model.random_generator = std::unique_lock<std::mutex>(generator);
    dRandSetSeed(0);
  }
  model.world.reset(dWorldCreate());
  dWorldID w = model.world.get();
  dWorldSetGravity(w, 0.0, -m.machine.gravity, 0.0);
  dWorldSetERP(w, o.erp);
  dWorldSetCFM(w, o.cfm);
  dWorldSetQuickStepNumIterations(w, o.quick_step_iterations);

  // The crankshaft turned by start.phi from its pose at phi = 0: centre of mass c, velocity omega Z x c. Only its
  // inertia about Z acts (the hinge holds the other two axes, and at a spin about Z a diagonal tensor has no
  // gyroscopic moment), so all three are that.
  dBodyID crank = model.crank = dBodyCreate(w);
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
  dJointID crank_hinge = model.crank_hinge = dJointCreateHinge(w, nullptr);
  dJointAttach(crank_hinge, crank, nullptr);
  dJointSetHingeAnchor(crank_hinge, 0.0, 0.0, 0.0);
  dJointSetHingeAxis(crank_hinge, 0.0, 0.0, 1.0);
  if (drive == CrankDrive::kMotor) {
    dJointSetHingeParam(crank_hinge, dParamVel, omega);
    dJointSetHingeParam(crank_hinge, dParamFMax, o.motor_max_torque);
  }  // free: the hinge's motor keeps ODE's dParamFMax 0, so it adds no constraint row
  dJointSetFeedback(crank_hinge, &model.crank_feedback);

  model.cylinders.assign(static_cast<std::size_t>(k), OdeCylinderBodies{});
  for (int j = 0; j < k; ++j) {
    OdeCylinderBodies& c = model.cylinders[static_cast<std::size_t>(j)];
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
}

double readCrankAngle(const OdeModel& model, double previous) {
  const dReal* rotation = dBodyGetRotation(model.crank);
  const double angle = std::atan2(rotation[4], rotation[0]);
  return previous + std::remainder(angle - previous, 2.0 * std::numbers::pi);
}

void stepOdeModel(const OdeModel& model, const OdeRunOptions& o) {
  if (o.solver == OdeSolver::kStep) {
    dWorldStep(model.world.get(), o.dt);
  } else {
    dWorldQuickStep(model.world.get(), o.dt);
  }
}

}  // namespace crankcheck::ode_models
