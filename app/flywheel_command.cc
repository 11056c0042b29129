#include "flywheel_command.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "crankcheck/analytic/flywheel.h"
#include "crankcheck/scene/scene_writer.h"
#include "crankcheck/simbody_models/free_run.h"
#include "crankcheck/validation/errors.h"
#include "help_format.h"
#include "json_output.h"
#include "scene_input.h"

namespace crankcheck::app {

void addFlywheelOptions(CLI::App& command, FlywheelOptions& options) {
  command.add_option("scene", options.scene_path, "Scene file (TOML) with a [gas] table and speed_rpm > 0")->required();
  command.add_option("--fluctuation", options.fluctuation,
                     "The speed fluctuation C = (omega_max - omega_min) / omega_mean to size for, 0 < C < 1")
      ->required();
  command.add_option("--format", options.format, "Output format")
      ->check(CLI::IsMember({"table", "json"}))
      ->capture_default_str();
}

std::string runFlywheel(const FlywheelOptions& options) {
  if (!(options.fluctuation > 0.0 && options.fluctuation < 1.0))
    throw UsageError("--fluctuation: must be in (0, 1) (got " + formatShortest(options.fluctuation) + ")");
  const Mechanism m = loadScene(options.scene_path);
  if (!m.gas)
    throw UsageError(options.scene_path + ": [gas]: missing table (flywheel sizing needs the working torque of a gas cycle)");
  if (!(m.engine.speed > 0.0)) throw UsageError(options.scene_path + ": [engine].speed_rpm: must be > 0 (the mean speed)");
  analytic::FlywheelSizing s;
  try {
    s = analytic::calcFlywheelSizing(m, options.fluctuation);
  } catch (const std::domain_error& e) {
    throw UsageError(options.scene_path + ": --fluctuation " + formatShortest(options.fluctuation) + ": " + e.what());
  } catch (const std::runtime_error& e) {  // a root that does not converge: refused, not printed
    throw UncomputableError(options.scene_path + ": " + e.what());
  }
  // Simbody: the exact flywheel in place of the scene's, the load, the gas, released at phi = 0 with the steady run's
  // speed there, over one working cycle.
  Mechanism with = m;
  with.flywheel_inertia = s.exact_inertia;
  simbody_models::FreeRunOptions run;
  run.gas = true;
  run.load_torque = s.load_torque;
  run.revolutions = m.engine.cycle == Cycle::kFourStroke ? 2 : 1;
  run.accuracy = 1e-10;
  simbody_models::FreeRunResult simbody;
  try {
    simbody = simbody_models::simulateFreeRun(with, s.exact.omega0, run);
  } catch (const std::invalid_argument& e) {
    throw UsageError(options.scene_path + ": " + e.what());
  } catch (const std::runtime_error& e) {  // a run too stiff to finish: refused, not printed
    throw UncomputableError(options.scene_path + ": Simbody's run with the exact flywheel: " + e.what());
  }
  if (options.format == "json") {
    nlohmann::ordered_json doc;
    doc["load_torque"] = s.load_torque;
    doc["exact"] = {{"flywheel_inertia", s.exact_inertia}, {"fluctuation", s.exact.delta}, {"omega0", s.exact.omega0},
                    {"omega_min", s.exact.omega_min}, {"omega_max", s.exact.omega_max}, {"omega_mean", s.exact.omega_mean}};
    doc["norton"] = {{"flywheel_inertia", s.norton_inertia}, {"fluctuation", s.norton.delta}, {"energy", s.norton_energy}};
    doc["simbody"] = {{"fluctuation", simbody.delta}, {"energy_drift", simbody.energy_drift_per_revolution},
                      {"omega_mean", simbody.omega_mean}};
    return dumpJson(doc);
  }
  char text[1400];
  std::snprintf(text, sizeof text,
                "flywheel for %s\nat %.6g rpm (mean), speed fluctuation C = %.6g, load torque %.9g N m (the gas "
                "torque's cycle mean)\n"
                "%-10s %26s %16s\n"
                "%-10s %26.12g %16.9e\n"
                "%-10s %26.12g %16.9e\n"
                "%-10s %26.12g %16.9e\n"
                "(norton: Norton 13.9, E = %.9g J between the extremes of the torque's integral;\n"
                " simbody: run with the exact inertia over one working cycle, its energy returns to %.2e)\n",
                options.scene_path.c_str(), m.speed_rpm, options.fluctuation, s.load_torque, "method",
                "flywheel inertia [kg m^2]", "fluctuation", "exact", s.exact_inertia, s.exact.delta, "norton",
                s.norton_inertia, s.norton.delta, "simbody", s.exact_inertia, simbody.delta, s.norton_energy,
                simbody.energy_drift_per_revolution);
  return wrapText(text, kHelpWidth) + describeRigidShaft(m);
}

}  // namespace crankcheck::app
