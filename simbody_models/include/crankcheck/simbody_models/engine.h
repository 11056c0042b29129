#pragma once
/// @file
/// Simbody's engine for the harness (crankcheck/solver/engine.h): "simbody", the full KCrankModel (k_crank_model.h).
/// Gated: it must agree with every other exact engine.

#include <vector>

#include "crankcheck/solver/engine.h"

namespace crankcheck::simbody_models {

std::vector<Engine> describeEngines();

}  // namespace crankcheck::simbody_models
