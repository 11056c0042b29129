#pragma once
/// @file
/// Where a campaign spends its time (issue 28, "measure first"): what each engine of the registry did on the
/// calling thread while profiling is on: model builds, evaluations and the seconds they took. Off by default, at no
/// cost (the registry's models are then the engines' own); `crankcheck validate --profile FILE` turns it on and
/// writes one row per task and engine (docs/performance.md).
///
/// Work that does not go through the registry (a part that calls an engine's own functions, the analytic batch
/// kernels) is not attributed to an engine: it is the task's seconds less its engines' seconds.

#include <cstddef>
#include <map>
#include <memory>
#include <string>

#include "crankcheck/solver/engine.h"

namespace crankcheck::validation {

/// What one engine did on one thread.
struct EngineUse {
  size_t builds = 0;             ///< models built
  size_t evaluations = 0;        ///< EngineModel::evaluate calls
  double build_seconds = 0.0;    ///< [s] wall time in the builds
  double evaluate_seconds = 0.0; ///< [s] wall time in the evaluations
};

/// Turns the counting on or off for every thread (set it before the work starts).
void setProfiling(bool on);
bool isProfiling();

/// The calling thread's counters, by engine name; clear() them before a task and read them after.
std::map<std::string, EngineUse>& getThreadEngineUse();

/// `build` of an engine, counted while profiling is on (listEngines() wraps every engine with it): the build's time,
/// and the model wrapped so that each evaluation is counted and timed on the thread that calls it.
std::unique_ptr<EngineModel> buildCounted(const Engine::BuildFunction& build, const std::string& engine, const Mechanism& m);

}  // namespace crankcheck::validation
