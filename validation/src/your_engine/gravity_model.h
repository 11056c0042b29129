#pragma once
// The gravity model of a scene as given, for the loads and gravity topics: an engine's reduced gravity model where it
// builds the scene (engines.h buildGravityModel), else its full model of the scene at rest (a reduced model may be
// built for one bank alone: Simbody's). Either gives Q = dU/dphi by calcQ.

#include <memory>

#include "crankcheck/solver/engine.h"

namespace crankcheck::validation::your_engine {

/// @throws as Engine::build when the full model cannot be built either.
std::unique_ptr<EngineModel> buildSceneGravityModel(const Engine& engine, const Mechanism& m);

}  // namespace crankcheck::validation::your_engine
