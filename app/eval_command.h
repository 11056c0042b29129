#pragma once
/// @file
/// `crankcheck eval SCENE [--phi-deg LIST] [--engine analytic|simbody|both] [--format table|json]`

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace crankcheck::app {

struct EvalOptions {
  std::string scene_path;
  std::vector<double> phi_deg{0.0, 90.0, 180.0, 270.0};
  std::string engine = "analytic";
  std::string format = "table";
};

void addEvalOptions(CLI::App& command, EvalOptions& options);

/// Loads the scene, evaluates every angle with the chosen engine(s) and returns the formatted output.
/// @throws UsageError for a bad scene or flag value.
std::string runEval(const EvalOptions& options);

}  // namespace crankcheck::app
