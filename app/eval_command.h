#pragma once
/// @file
/// `crankcheck eval SCENE [--phi-deg LIST] [--engine analytic|simbody|mujoco|mujoco-soft|mujoco-soft-stiff|both|all] [--format table|json]`

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace crankcheck::app {

struct EvalOptions {
  std::string scene_path;
  std::string phi_deg = "0,90,180,270";  ///< comma-separated degrees, parsed by parseAngleList
  std::string engine = "analytic";
  std::string format = "table";
  bool split = false;  ///< also the drive torque as gas + inertia + gravity parts, each engine run with the others off
};

/// Parses a comma-separated list of finite angles in degrees ("0,37.5,-90"). An empty list, an empty item
/// ("0,,90"), a non-number or a non-finite value is refused: nothing is ever substituted.
/// @throws UsageError "FLAG: rule" naming the bad item.
std::vector<double> parseAngleList(const std::string& text, const std::string& flag);

void addEvalOptions(CLI::App& command, EvalOptions& options);

/// What eval printed, and whether every check it made held (the split's parts add up to the whole).
struct EvalOutput {
  std::string text;
  bool checks_hold = true;
};

/// Loads the scene, evaluates every angle with the chosen engine(s) and returns the formatted output.
/// @throws UsageError for a bad scene or flag value.
EvalOutput runEval(const EvalOptions& options);

}  // namespace crankcheck::app
