#pragma once
/// @file
/// `crankcheck motion SCENE [--format table|json] [--integrator ...] [--accuracy A]`: the free run under gravity
/// (released at phi = 0 with the scene's speed, no drive, no load), by the analytic energy integral and by Simbody.

#include <CLI/CLI.hpp>
#include <string>

namespace crankcheck::app {

struct MotionOptions {
  std::string scene_path;
  std::string format = "table";
  std::string integrator = "RungeKuttaMerson";
  double accuracy = 1e-10;
};

void addMotionOptions(CLI::App& command, MotionOptions& options);

/// @throws UsageError for a bad scene or flag, or a scene the free run cannot use (no flywheel, no speed).
std::string runMotion(const MotionOptions& options);

}  // namespace crankcheck::app
