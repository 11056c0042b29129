#include "motion_command.h"

#include <cstdio>
#include <stdexcept>

#include "crankcheck/analytic/motion.h"
#include "crankcheck/simbody_models/free_run.h"
#include "json_output.h"
#include "scene_input.h"
#include "crankcheck/validation/errors.h"

namespace crankcheck::app {

void addMotionOptions(CLI::App& command, MotionOptions& options) {
  command.add_option("scene", options.scene_path, "Scene file (TOML); needs [flywheel].inertia and speed_rpm > 0")
      ->required();
  command.add_option("--format", options.format, "Output format")
      ->check(CLI::IsMember({"table", "json"}))
      ->capture_default_str();
  command.add_option("--integrator", options.integrator, "Simbody integrator")
      ->check(CLI::IsMember({"RungeKuttaMerson", "CPodes", "SemiExplicitEuler2"}))
      ->capture_default_str();
  command.add_option("--accuracy", options.accuracy, "Simbody integrator accuracy")
      ->check(CLI::Range(1e-14, 1e-1))
      ->capture_default_str();
}

namespace {

struct EngineResult {
  double delta_gravity, delta_no_gravity, omega_min, omega_max, omega_mean;
};

nlohmann::ordered_json toJson(const EngineResult& r) {
  return {{"delta_gravity", r.delta_gravity}, {"delta_no_gravity", r.delta_no_gravity}, {"omega_min", r.omega_min},
          {"omega_max", r.omega_max}, {"omega_mean", r.omega_mean}};
}

}  // namespace

std::string runMotion(const MotionOptions& options) {
  const Mechanism m = loadScene(options.scene_path);
  if (!m.flywheel_inertia)
    throw UsageError(options.scene_path + ": [flywheel].inertia: missing key (the free run needs the flywheel inertia)");
  if (!(m.engine.speed > 0.0))
    throw UsageError(options.scene_path + ": [engine].speed_rpm: must be > 0 for the free run (the release speed)");
  const double w0 = m.engine.speed;
  EngineResult a{}, s{};
  try {
    const analytic::FreeRun with = analytic::calcFreeRun(m, w0, true), without = analytic::calcFreeRun(m, w0, false);
    a = {with.delta, without.delta, with.omega_min, with.omega_max, with.omega_mean};
  } catch (const std::domain_error& e) {
    throw UsageError(options.scene_path + ": [engine].speed_rpm: " + e.what());
  }
  simbody_models::FreeRunOptions run;
  run.integrator = options.integrator == "CPodes"               ? simbody_models::IntegratorKind::kCPodes
                   : options.integrator == "SemiExplicitEuler2" ? simbody_models::IntegratorKind::kSemiExplicitEuler2
                                                                : simbody_models::IntegratorKind::kRungeKuttaMerson;
  run.accuracy = options.accuracy;
  try {
    run.gravity = true;
    const simbody_models::FreeRunResult with = simbody_models::simulateFreeRun(m, w0, run);
    run.gravity = false;
    const simbody_models::FreeRunResult without = simbody_models::simulateFreeRun(m, w0, run);
    s = {with.delta, without.delta, with.omega_min, with.omega_max, with.omega_mean};
  } catch (const std::invalid_argument& e) {
    throw UsageError(options.scene_path + ": " + e.what());
  }
  if (options.format == "json") {
    nlohmann::ordered_json doc;
    doc["analytic"] = toJson(a);
    doc["simbody"] = toJson(s);
    return dumpJson(doc);
  }
  char buffer[1024];
  std::snprintf(buffer, sizeof buffer,
                "free run of %s released at phi = 0 with %.6g rpm (Simbody: %s, accuracy %.0e)\n"
                "%-9s %16s %16s %14s %14s %14s\n"
                "%-9s %16.9e %16.9e %14.9g %14.9g %14.9g\n"
                "%-9s %16.9e %16.9e %14.9g %14.9g %14.9g\n",
                options.scene_path.c_str(), m.speed_rpm, options.integrator.c_str(), options.accuracy, "engine",
                "delta_gravity", "delta_no_gravity", "omega_min", "omega_max", "omega_mean", "analytic",
                a.delta_gravity, a.delta_no_gravity, a.omega_min, a.omega_max, a.omega_mean, "simbody", s.delta_gravity,
                s.delta_no_gravity, s.omega_min, s.omega_max, s.omega_mean);
  return buffer;
}

}  // namespace crankcheck::app
