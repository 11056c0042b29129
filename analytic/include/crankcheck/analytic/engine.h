#pragma once
/// @file
/// The analytic engine for the harness (crankcheck/solver/engine.h): "analytic", the closed forms of this library
/// (calcEvaluation, reactions.h). Gated: it must agree with every other exact engine.

#include <vector>

#include "crankcheck/solver/engine.h"

namespace crankcheck::analytic {

std::vector<Engine> describeEngines();

}  // namespace crankcheck::analytic
