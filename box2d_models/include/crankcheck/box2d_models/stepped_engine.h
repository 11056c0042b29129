#pragma once
/// @file
/// The Box2D model as a stepped engine of the registry (crankcheck/solver/engine.h: Engine, its stepped routes): "box2d", Box2D 2.4 in single
/// precision, planar, at its testbed's defaults and at tightened iterations. Its runs and their instants are those of
/// runBox2dAtConstantSpeed (constant_speed_run.h), its free runs runBox2dFree's (free_run.h).

#include <vector>

#include "crankcheck/solver/engine.h"

namespace crankcheck::box2d_models {

/// The Box2D engines: one, "box2d", with settings "defaults" (8 velocity and 3 position iterations, warm starting)
/// and "tightened" (50 and 20). Its step_at_speed throws std::invalid_argument for an unknown settings name (naming the
/// engine's settings), a scene speed of 0, a key Box2D cannot build or a step Box2D would cap (runBox2dAtConstantSpeed);
/// its step_free (the same settings) for a scene without [flywheel].inertia as well (runBox2dFree).
std::vector<Engine> describeEngines();

}  // namespace crankcheck::box2d_models
