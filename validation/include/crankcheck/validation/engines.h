#pragma once
/// @file
/// Every engine the harness knows, in one list (validation/src/engines.cc): the CLI's --engine, the gate, the
/// campaign and the report loop over it. An engine is an Engine (crankcheck/scene/engine.h) described by its own
/// folder; adding one is that folder plus one registration line in engines.cc (README, "Engines").

#include <string>
#include <vector>

#include "crankcheck/scene/engine.h"

namespace crankcheck::validation {

/// analytic, simbody, mujoco, mujoco-soft, mujoco-soft-stiff (the order of the report's tables).
const std::vector<Engine>& listEngines();

/// The engine called `name`. @throws std::invalid_argument naming the known engines if there is none.
const Engine& findEngine(const std::string& name);

/// The names of listEngines(), joined by `separator`.
std::string joinEngineNames(const std::string& separator);

/// Builds every engine's model of m once, before any long work: a scene some engine cannot build is refused now.
/// @throws UsageError "PATH: --engine NAME: KEY: rule" (exit status 2) for the first engine that cannot.
void checkEveryEngineBuilds(const Mechanism& m, const std::string& path);

/// The gated (exact) engines other than "analytic": the references the analytic engine and graded programs are
/// compared with (simbody, mujoco).
std::vector<const Engine*> listReferenceEngines();

}  // namespace crankcheck::validation
