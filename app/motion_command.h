#pragma once
/// @file
/// `crankcheck motion SCENE [--format table|json] [--integrator ...] [--accuracy A] [--mujoco-integrator ...]
/// [--mujoco-step S] [--stepped-step S] [--stepped-settings NAME]`: the free run under gravity
/// (released at phi = 0 with the scene's speed, no drive, no load), by the analytic energy integral, by every engine
/// that simulates (Simbody; MuJoCo's soft solver at its default and stiffest settings) and by every engine that steps
/// free (ODE, Bullet, Box2D at their defaults or the settings named).

#include <CLI/CLI.hpp>
#include <string>

#include "crankcheck/validation/commands/motion.h"

namespace crankcheck::app {

struct MotionOptions {
  std::string scene_path;
  std::string format = "table";
  std::string integrator = "RungeKuttaMerson";
  double accuracy = 1e-10;
  std::string mujoco_integrator = "RK4";
  double mujoco_step = 1e-3;  ///< MuJoCo's fixed time step as a fraction of a revolution
  /// The step of the engines that step free (ODE, Bullet, Box2D) as a fraction of a revolution
  double stepped_step = validation::kDefaultSteppedMotionStep;
  std::string stepped_settings = "defaults";  ///< the settings of each engine that steps free and has them
};

void addMotionOptions(CLI::App& command, MotionOptions& options);

/// @throws UsageError for a bad scene or flag, or a scene the free run cannot use (no flywheel, no speed).
std::string runMotion(const MotionOptions& options);

}  // namespace crankcheck::app
