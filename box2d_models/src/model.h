#pragma once
/// @file
/// Internal to box2d_models: the one construction of the Box2D model (constant_speed_run.h describes it) that both the
/// driven run and the free run step. The driven run turns the crank joint's motor on; the free run leaves it off and
/// adds the flywheel's inertia to the crank body.

#include <box2d/box2d.h>

#include <memory>
#include <string>
#include <vector>

#include "crankcheck/box2d_models/constant_speed_run.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/solver/stepped_run.h"

namespace crankcheck::box2d_models::detail {

/// What differs between the driven and the free model.
struct ModelOptions {
  /// true: the crank joint's motor holds the crank at start.omega ("unlimited" torque); false: no motor.
  bool motor = true;
  /// [kg m^2] added to the crank body's inertia about O (the flywheel, in the free run), >= 0.
  double extra_crank_inertia = 0.0;
};

/// One cylinder's bodies and joints, and its piston's line.
struct CylinderJoints {
  b2Body* rod = nullptr;
  b2Body* piston = nullptr;
  b2RevoluteJoint* crank_pin = nullptr;
  b2RevoluteJoint* wrist_pin = nullptr;
  b2PrismaticJoint* slider = nullptr;
  crankcheck::Vec2 e{}, n{};
  double delta = 0.0;  ///< [m] the piston's line: A . n = delta
};

/// The built world: the crank on its joint at O, every cylinder's rod and piston.
struct Model {
  std::unique_ptr<b2World> world;
  b2Body* crank = nullptr;
  b2RevoluteJoint* crank_joint = nullptr;
  std::vector<CylinderJoints> cylinders;
};

/// Builds m in Box2D at o.start (every body's position and velocity, the crank turning at o.start.omega), with
/// o.warm_starting; checks o's step, steps, iterations and start (its cylinders), refuses what Box2D cannot build
/// and a step Box2D would cap at the crank speed o.start.omega.
/// @throws std::invalid_argument as runBox2dAtConstantSpeed (constant_speed_run.h) names each case.
Model buildModel(const Mechanism& m, const Box2dRunOptions& o, const ModelOptions& options);

/// [m] The largest separation at this instant of one of c's joints (each revolute joint's anchor as its two bodies
/// carry it, the piston off its line).
double calcLoopError(const CylinderJoints& c);

/// The coordinate of p along e.
double along(const b2Vec2& p, const crankcheck::Vec2& e);

}  // namespace crankcheck::box2d_models::detail
