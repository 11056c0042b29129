#include "motion_command.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "crankcheck/validation/commands/motion.h"
#include "crankcheck/validation/evaluation_json.h"
#include "help_format.h"
#include "json_output.h"
#include "scene_input.h"
#include "crankcheck/validation/errors.h"
#include "flag_checks.h"

namespace crankcheck::app {

void addMotionOptions(CLI::App& command, MotionOptions& options) {
  command.add_option("scene", options.scene_path, "Scene file (TOML); needs [flywheel].inertia and speed_rpm > 0")
      ->required();
  command.add_option("--format", options.format, "Output format")
      ->check(CLI::IsMember({"table", "json"}))
      ->capture_default_str();
  command.add_option("--integrator", options.integrator, "Simbody integrator")
      ->check(CLI::IsMember(validation::listIntegrators(true)))
      ->capture_default_str();
  command.add_option("--accuracy", options.accuracy, "Simbody integrator's accuracy (its relative error per step)")
      ->check(FiniteRange(1e-14, 1e-1))
      ->capture_default_str();
  command.add_option("--mujoco-integrator", options.mujoco_integrator, "MuJoCo integrator (mujoco-soft, mujoco-soft-stiff)")
      ->check(CLI::IsMember(validation::listIntegrators(false)))
      ->capture_default_str();
  command.add_option("--mujoco-step", options.mujoco_step,
                     "MuJoCo's fixed time step as a fraction of one revolution at the release speed")
      ->check(FiniteRange(1e-6, 1e-1))
      ->capture_default_str();
  command.add_option("--stepped-step", options.stepped_step,
                     "The fixed time step of the engines that step free (" + describeEngineNames(Route::kStepFree) +
                         ") as a fraction of one revolution at the release speed")
      ->check(FiniteRange(1e-5, 1e-1))
      ->capture_default_str();
  command.add_option("--stepped-settings", options.stepped_settings,
                     "The settings of the engines that step free, for each that has settings of that name (the "
                     "others run at their defaults; crankcheck stepped --help says what each changes)")
      ->check(CLI::IsMember(validation::listSteppedSettings()))
      ->capture_default_str();
}


std::string runMotion(const MotionOptions& options) {
  const Mechanism m = loadScene(options.scene_path);
  // Each flag pair goes to the engines that offer its integrator (Engine::integrators).
  validation::FreeRunChoices choices = validation::getDefaultFreeRunSettings();
  validation::chooseIntegrator(choices, options.integrator, options.accuracy);
  validation::chooseIntegrator(choices, options.mujoco_integrator, options.mujoco_step);
  validation::chooseSteppedRun(choices, options.stepped_settings, options.stepped_step);
  std::vector<validation::MotionRun> results;
  std::vector<validation::SatOut> sat_out;  // an engine that cannot build the scene sits out, named with its reason
  try {
    results = validation::calcMotion(m, choices, &sat_out);
  } catch (const std::invalid_argument& e) {
    throw UsageError(options.scene_path + ": " + e.what());
  } catch (const std::runtime_error& e) {
    throw UsageError(options.scene_path + ": " + e.what());
  }
  if (options.format == "json") {
    nlohmann::ordered_json doc;
    for (const validation::MotionRun& r : results) doc[r.engine] = validation::motionRunToJson(r);
    doc["sat_out"] = validation::satOutToJson(sat_out);
    return dumpJson(doc);
  }
  char buffer[512];
  // Within 100 columns: the scene's path and the settings on lines of their own.
  std::snprintf(buffer, sizeof buffer,
                "released at phi = 0 with %.6g rpm (Simbody: %s, accuracy %.0e; MuJoCo: %s, step %.0e "
                "of a revolution; stepped engines: %s, step %.0e of a revolution)\n%-17s %15s %16s %12s %12s "
                "%12s %10s\n",
                m.speed_rpm, options.integrator.c_str(), options.accuracy,
                options.mujoco_integrator.c_str(), options.mujoco_step, options.stepped_settings.c_str(), options.stepped_step,
                "engine", "delta_gravity", "delta_no_gravity",
                "omega_min", "omega_max", "omega_mean", "drift");
  std::string out = "free run of " + showPath(options.scene_path) + "\n" + buffer;
  std::string not_measured;
  for (const validation::MotionRun& r : results) {
    if (!r.not_measured.empty()) {
      not_measured += escapeText(r.engine) + " not measured: " + escapeText(formatOneLine(r.not_measured)) + "\n";
      continue;
    }
    char drift[32] = "-";
    if (!r.integrator.empty()) std::snprintf(drift, sizeof drift, "%.3e", r.energy_drift);
    std::snprintf(buffer, sizeof buffer, "%-17s %15.8e %16.8e %12.9g %12.9g %12.9g %10s\n", r.engine.c_str(),
                  r.delta_gravity, r.delta_no_gravity, r.omega_min, r.omega_max, r.omega_mean, drift);
    out += buffer;
  }
  return wrapText(out, kHelpWidth) + wrapText(not_measured, kHelpWidth) + wrapText(formatSatOut(sat_out), kHelpWidth) +
         wrapText("(omega [rad/s]; drift: the energy's, max |E(t) - E(0)| / E(0) per revolution, gravity on; an "
                  "engine that steps: the closed forms' energy at its phi and omega)\n",
                  kHelpWidth) +
         describeRigidShaft(m);
}

}  // namespace crankcheck::app
