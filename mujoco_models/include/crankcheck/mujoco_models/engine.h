#pragma once
/// @file
/// MuJoCo's engines for the harness (crankcheck/solver/engine.h): "mujoco" (exact: hard multipliers, gated),
/// "mujoco-soft" and "mujoco-soft-stiff" (MuJoCo's own soft constraint solver at its default and at its stiffest
/// settings: reported, not gated). See k_crank_mujoco_model.h.

#include <vector>

#include "crankcheck/solver/engine.h"

namespace crankcheck::mujoco_models {

std::vector<Engine> describeEngines();

}  // namespace crankcheck::mujoco_models
