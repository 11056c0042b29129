#pragma once
/// @file
/// `crankcheck flywheel SCENE --fluctuation C [--format table|json]`: the flywheel inertia at which the steady run at
/// the scene's mean speed under a constant load (the cycle mean of the gas torque) fluctuates by delta = C: exact
/// (the energy integral with J(phi), analytic/flywheel.h), by Norton's method (13.9) with the delta it really gives,
/// and Simbody's run with the exact inertia and the load over a working cycle from the steady state (the delta it
/// measures and the return of its energy).

#include <CLI/CLI.hpp>
#include <string>

namespace crankcheck::app {

struct FlywheelOptions {
  std::string scene_path;
  double fluctuation = 0.0;
  std::string format = "table";
};

void addFlywheelOptions(CLI::App& command, FlywheelOptions& options);

/// @throws UsageError for a bad scene or flag, a scene without [gas] or speed, C outside (0, 1).
std::string runFlywheel(const FlywheelOptions& options);

}  // namespace crankcheck::app
