#pragma once
/// @file
/// Bullet's btMultiBody (constant_speed_run.h) as a stepped engine of the registry (crankcheck/solver/engine.h: Engine, its stepped routes):
/// its settings by name, each step's quantities read from Bullet's own API with the instant each belongs to.

#include <vector>

#include "crankcheck/solver/engine.h"

namespace crankcheck::bullet_models {

/// The Bullet engine "bullet" (btMultiBody, double precision) with its settings "defaults" (Bullet's own: the joint
/// speed cap 100, the damping 0.04, the loops' impulse cap 100 N s, 10 solver iterations, ERP 0.2), "neutralised"
/// (the cap, the damping and the impulse cap off) and "tightened" (neutralised, with the solver tightened).
/// Its step_free (runBulletFree) takes the same settings; its speed belongs to the step's middle.
/// Its step_at_speed throws std::invalid_argument for an unknown settings name (naming it and the settings), a scene speed of
/// 0, and what runBulletAtConstantSpeed refuses.
std::vector<Engine> describeEngines();

}  // namespace crankcheck::bullet_models
