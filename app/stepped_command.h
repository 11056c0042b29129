#pragma once
/// @file
/// `crankcheck stepped SCENE [--engine NAME|all] [--settings NAME|all] [--dt S,S,...] [--free [--revolutions N]]
/// [--format table|json]`: the
/// physics engines people ship (validation/engines.h listEngines(Route::kStepAtSpeed)), each driven at the scene's constant speed
/// from the exact state and stepped by its own solver at a series of time steps and at each of its settings; every
/// quantity it reports against the closed forms at the instant it belongs to, the observed orders, the cost per step;
/// --free: each engine's free run judged by the time-stepped grade's measures (validation/engine_runs.h).
/// docs/stepped-engines.md.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace crankcheck::app {

struct SteppedOptions {
  std::string scene_path;
  std::string engine = "all";
  std::string settings = "all";
  std::vector<double> steps;  ///< [s]; empty: validation::getDefaultSteppedSteps
  std::string format = "table";
  bool free = false;       ///< the free runs (no drive, the flywheel, gravity alone) instead of the driven ones
  int revolutions = 5;     ///< of a free run
  double work_limit = 600.0;  ///< [s] the longest estimated work started (validation/work_limit.h)
};

void addSteppedOptions(CLI::App& command, SteppedOptions& options);

/// @throws UsageError for a bad scene or flag, a scene without speed, settings no chosen engine has, a scene the
/// chosen engines all refuse (nothing measured), or a sweep past validation::kMaxSteppedSteps steps or estimated past
/// --work-limit (validation::checkSteppedWork).
std::string runStepped(const SteppedOptions& options);

}  // namespace crankcheck::app
