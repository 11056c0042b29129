#pragma once
/// @file
/// The k-crank mechanism built in ODE, shared by the constant-speed run (constant_speed_run.h) and the free run
/// (free_run.h): ONE construction, the crank either driven by its hinge's velocity motor or free and carrying the
/// scene's flywheel. Private to the folder (it includes ODE's header).

#include <ode/ode.h>

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "crankcheck/ode_models/constant_speed_run.h"

namespace crankcheck::ode_models {

/// How the crank is held: by its hinge's velocity motor at start.omega (the constant-speed run), or free with the
/// scene's flywheel inertia added to the crank body's (the free run: no motor row at all).
enum class CrankDrive { kMotor, kFreeWithFlywheel };

struct OdeWorldDeleter {
  void operator()(dxWorld* w) const { dWorldDestroy(w); }  // destroys its bodies and joints
};

/// Cylinder j's bodies and joints, and what a step's reads need of its geometry.
struct OdeCylinderBodies {
  dBodyID rod = nullptr, piston = nullptr;
  dJointID crank_pin = nullptr, wrist_pin = nullptr, slider = nullptr;
  dJointFeedback crank_pin_feedback{}, wrist_pin_feedback{}, slider_feedback{};
  Vec2 e{}, n{};       ///< the cylinder's axis and its normal
  double delta = 0.0;  ///< [m] the pin offset: the piston's line is x e + delta n
  double z = 0.0;      ///< [m] the plane of the rod and the piston
  double v_p = 0.0;    ///< [m/s] the piston's velocity along e before the step
};

/// The built mechanism. ODE holds pointers to the feedback members: the model never moves once built.
struct OdeModel {
  /// A QuickStep model holds ODE's one process-wide random generator (its constraint reordering draws from it) from
  /// its build, which seeds it, to its end: two QuickStep runs on two threads would draw from each other's sequence.
  /// Declared first, released last.
  std::unique_lock<std::mutex> random_generator;
  std::unique_ptr<dxWorld, OdeWorldDeleter> world;
  dBodyID crank = nullptr;
  dJointID crank_hinge = nullptr;   ///< the crank's hinge about Z at O
  dJointFeedback crank_feedback{};
  std::vector<OdeCylinderBodies> cylinders;

  OdeModel() = default;
  OdeModel(const OdeModel&) = delete;
  OdeModel& operator=(const OdeModel&) = delete;
};

/// Throws std::invalid_argument("ODE run: " + what) unless ok.
void requireOdeOption(bool ok, const std::string& what);

/// Builds m in `model` (empty) at o.start with o's solver settings (erp, cfm, iterations, rotation mode); the step,
/// the steps and the motor's limit are the caller's. kMotor: the crank's hinge motor holds start.omega with at most
/// o.motor_max_torque. kFreeWithFlywheel: no motor; the crank's inertia about Z is increased by m.flywheel_inertia.
/// @throws std::invalid_argument naming the key ODE cannot build ([[balance_shaft]], a massless rod, piston or crank,
///   a rod or crank without inertia about its centre of mass; for the free run a missing [flywheel].inertia) or a bad
///   option (dt, steps, start, quick_step_iterations, erp, cfm).
void buildOdeModel(OdeModel& model, const Mechanism& m, const OdeRunOptions& o, CrankDrive drive);

/// The crank body's rotation about Z read from ODE (atan2 of its rotation matrix), unwrapped against `previous`.
double readCrankAngle(const OdeModel& model, double previous);

/// Advances the world by one step of o.dt with o's solver.
void stepOdeModel(const OdeModel& model, const OdeRunOptions& o);

}  // namespace crankcheck::ode_models
