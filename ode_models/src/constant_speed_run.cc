#include "crankcheck/ode_models/constant_speed_run.h"

#include <ode/ode.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "ode_model.h"

namespace crankcheck::ode_models {
namespace {

Vec3 toVec3(const dReal* v) { return {v[0], v[1], v[2]}; }

double distance(const dVector3 p, const dVector3 q) {
  return std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
}

}  // namespace

OdeRun runOdeAtConstantSpeed(const Mechanism& m, const OdeRunOptions& o) {
  if (!(std::fabs(m.machine.speed) > 0.0))
    throw std::invalid_argument("ODE cannot build this scene: [engine].speed_rpm must be != 0 (the ODE run is driven at "
                                "the scene's constant speed)");
  OdeModel model;
  buildOdeModel(model, m, o, CrankDrive::kMotor);
  const int k = m.machine.cylinders;
  const long steps = o.steps;
  OdeRun run;
  dWorldID w = model.world.get();
  run.world = {dWorldGetLinearDamping(w), dWorldGetAngularDamping(w), dWorldGetMaxAngularSpeed(w),
               dWorldGetAutoDisableFlag(w) != 0};
  run.samples.reserve(static_cast<std::size_t>(steps));
  double phi = o.start.phi;
  const auto started = std::chrono::steady_clock::now();
  for (long i = 0; i < steps; ++i) {
    // The step's forces belong to its start (the constraints are linearised at the positions it starts from), so
    // the drive torque's arm is the crank's centre of mass before the step.
    const dReal* c_start = dBodyGetPosition(model.crank);
    const double arm_x = c_start[0], arm_y = c_start[1];
    // The gas at the step's start (CONVENTIONS: -p_j A e_j on piston j, p at the cycle angle phi - firing_j).
    if (m.gas)
      for (int j = 0; j < k; ++j) {
        const OdeCylinderBodies& c = model.cylinders[static_cast<std::size_t>(j)];
        const double f = calcGasForce(m, j, phi);
        dBodyAddForce(c.piston, -f * c.e[0], -f * c.e[1], 0.0);
      }
    stepOdeModel(model, o);
    OdeSample sample;
    sample.t = static_cast<double>(i + 1) * o.dt;
    sample.phi_start = phi;
    // The crank's rotation about Z (it starts at the identity): unwrapped against the previous step's angle.
    phi = readCrankAngle(model, phi);
    sample.phi = phi;
    sample.crank_speed = dBodyGetAngularVel(model.crank)[2];
    // The drive torque about O: the joint's torque about the crank's centre of mass plus (c - O) x f.
    sample.bearing_force = toVec3(model.crank_feedback.f1);
    sample.drive_torque = model.crank_feedback.t1[2] + arm_x * model.crank_feedback.f1[1] - arm_y * model.crank_feedback.f1[0];
    dVector3 anchor;
    dJointGetHingeAnchor(model.crank_hinge, anchor);
    sample.bearing_error = std::hypot(anchor[0], anchor[1], anchor[2]);
    sample.cylinders.reserve(static_cast<std::size_t>(k));
    for (OdeCylinderBodies& c : model.cylinders) {
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
