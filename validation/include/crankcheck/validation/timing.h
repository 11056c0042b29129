#pragma once
/// @file
/// Cost per call of several functions, measured side by side in one Google Benchmark run (in-process), so that
/// the report's speed figures are ratios of one run on one machine.

#include <chrono>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace crankcheck::validation {

/// [s] The wall time since `start` (a work limit's probe, a profile, a part's route costs).
inline double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Runs each function under Google Benchmark for at least `min_seconds` and returns nanoseconds per call by name.
/// The functions must defeat the optimizer themselves (benchmark::DoNotOptimize on their result).
std::map<std::string, double> measureNanosecondsPerCall(
    const std::vector<std::pair<std::string, std::function<void()>>>& functions, double min_seconds);

/// The least time [s] each timed function runs for in the campaign's timing tables (speed_vs_error, engine_cost):
/// 0.02 s in the full campaign (thousands of calls of a closed form, about ten of Simbody's k = 12 evaluation; the
/// tables are ratios of one run, taken while other tasks run on the other cores), 0.002 s in the quick one (a smoke
/// test of the tables: a hundred calls of a closed form or more, one or two of Simbody's k = 12 evaluation).
inline double getTimingSeconds(bool quick) { return quick ? 0.002 : 0.02; }

}  // namespace crankcheck::validation
