#include "flywheel_command.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "crankcheck/scene/scene_writer.h"
#include "crankcheck/validation/commands/flywheel.h"
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
  validation::FlywheelResult result;
  try {
    result = validation::calcFlywheel(m, options.fluctuation);
  } catch (const std::domain_error& e) {
    throw UsageError(options.scene_path + ": --fluctuation " + formatShortest(options.fluctuation) + ": " + e.what());
  } catch (const std::invalid_argument& e) {
    throw UsageError(options.scene_path + ": " + e.what());
  } catch (const UncomputableError& e) {
    throw UncomputableError(options.scene_path + ": " + e.what());
  }
  const analytic::FlywheelSizing& s = result.sizing;
  if (options.format == "json") {
    nlohmann::ordered_json doc;
    doc["load_torque"] = s.load_torque;
    doc["exact"] = {{"flywheel_inertia", s.exact_inertia}, {"fluctuation", s.exact.delta}, {"omega0", s.exact.omega0},
                    {"omega_min", s.exact.omega_min}, {"omega_max", s.exact.omega_max}, {"omega_mean", s.exact.omega_mean}};
    doc["norton"] = {{"flywheel_inertia", s.norton_inertia}, {"fluctuation", s.norton.delta}, {"energy", s.norton_energy}};
    for (const validation::FlywheelEngineRun& r : result.runs)
      doc[r.engine] = {{"fluctuation", r.fluctuation}, {"energy_drift", r.energy_drift}, {"omega_mean", r.omega_mean}};
    return dumpJson(doc);
  }
  // One row per method: the exact sizing, Norton's, each engine's run with the exact inertia.
  char line[1400];
  std::snprintf(line, sizeof line,
                "at %.6g rpm (mean), speed fluctuation C = %.6g, load torque %.9g N m (the gas "
                "torque's cycle mean: what the gas delivers to the shaft, the negative of the mean of the drive "
                "torque's gas part; below 0 where the shaft drives the machine, a compressor)\n"
                "%-10s %26s %16s\n"
                "%-10s %26.12g %16.9e\n"
                "%-10s %26.12g %16.9e\n",
                m.speed_rpm, options.fluctuation, s.load_torque, "method",
                "flywheel inertia [kg m^2]", "fluctuation", "exact", s.exact_inertia, s.exact.delta, "norton",
                s.norton_inertia, s.norton.delta);
  std::string text = "flywheel for " + showPath(options.scene_path) + "\n" + line;
  for (const validation::FlywheelEngineRun& r : result.runs) {
    std::snprintf(line, sizeof line, "%-10s %26.12g %16.9e\n", r.engine.c_str(), s.exact_inertia, r.fluctuation);
    text += line;
  }
  std::snprintf(line, sizeof line, "(norton: Norton 13.9, E = %.9g J between the extremes of the torque's integral",
                s.norton_energy);
  text += line;
  for (const validation::FlywheelEngineRun& r : result.runs) {
    std::snprintf(line, sizeof line,
                  ";\n %s: run with the exact inertia over one working cycle, its energy returns to %.2e", r.engine.c_str(),
                  r.energy_drift);
    text += line;
  }
  text += ")\n";
  return wrapText(text, kHelpWidth) + describeRigidShaft(m);
}

}  // namespace crankcheck::app
