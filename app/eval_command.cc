#include "eval_command.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <memory>

#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/scales.h"
#include "help_format.h"
#include "json_output.h"
#include "scene_input.h"
#include "crankcheck/validation/errors.h"

namespace crankcheck::app {

void addEvalOptions(CLI::App& command, EvalOptions& options) {
  command.add_option("scene", options.scene_path, "Scene file (TOML), see docs/SCENE-FORMAT.md")->required();
  command.add_option("--phi-deg", options.phi_deg, "Crank angles of cylinder 0 [deg], comma separated; any size (reduced exactly modulo 720)")
      ->capture_default_str();
  std::vector<std::string> choices{"both", "all"};
  std::string both;
  for (const Engine* e : validation::listBothEngines()) both += (both.empty() ? "" : " and ") + e->name;
  for (const Engine& e : validation::listEngines()) choices.push_back(e.name);
  command.add_option("--engine", options.engine,
                     "Which engine computes the results: " + validation::joinEngineNames(", ") +
                         "; both (" + both + ") or all")
      ->check(CLI::IsMember(choices))
      ->capture_default_str();
  command.add_option("--format", options.format, "Output format")
      ->check(CLI::IsMember({"table", "json"}))
      ->capture_default_str();
  command.add_flag("--split", options.split,
                   "Also the drive torque as gas_torque + inertia_torque + gravity_torque, each engine run with the other "
                   "loads off; exit status 1 if the parts do not add up to the whole");
}

std::vector<double> parseAngleList(const std::string& text, const std::string& flag) {
  if (text.empty()) throw UsageError(flag + ": empty; give at least one angle, e.g. " + flag + " 0,90");
  std::vector<double> angles;
  size_t begin = 0;
  for (int item = 1;; ++item) {
    const size_t end = std::min(text.find(',', begin), text.size());
    // The item without the spaces around it ("0, 90" is two angles), and without a leading '+'; then a decimal
    // number as C++ reads it (std::from_chars: no hexadecimal, no locale), subnormal values as they are.
    std::string field = text.substr(begin, end - begin);
    const size_t first = field.find_first_not_of(' '), last = field.find_last_not_of(' ');
    field = first == std::string::npos ? std::string() : field.substr(first, last - first + 1);
    const std::string where = flag + ": item " + std::to_string(item) + " of \"" + text + "\"";
    if (field.empty()) throw UsageError(where + ": empty (nothing is assumed in its place)");
    const char* digits = field.data() + (field[0] == '+' && field.size() > 1 && field[1] != '-' ? 1 : 0);
    double value = 0.0;
    const auto [stop, error] = std::from_chars(digits, field.data() + field.size(), value);
    if (error == std::errc::result_out_of_range)
      throw UsageError(where + ": \"" + field + "\" is past the range of a number (a finite number of degrees)");
    if (error != std::errc() || stop != field.data() + field.size())
      throw UsageError(where + ": \"" + field + "\" is not a number");
    if (!std::isfinite(value)) throw UsageError(where + ": must be a finite number of degrees");
    angles.push_back(value);
    if (end == text.size()) break;
    begin = end + 1;
  }
  return angles;
}

namespace {

// The drive torque split into its parts, by one engine at one angle: each part is the drive torque of the same
// engine with the other loads off (withLoads); the parts must add up to the whole (the equations are linear in the
// loads at a given motion).
struct TorqueSplit {
  double gas = 0.0, inertia = 0.0, gravity = 0.0, whole = 0.0, tolerance = 0.0;
  double sum() const { return gas + inertia + gravity; }
  bool holds() const { return std::fabs(sum() - whole) <= tolerance; }
};

// The three load cases of the split, in the order gas, inertia, gravity.
std::vector<Mechanism> splitCases(const Mechanism& m) {
  return {withLoads(m, true, false, false), withLoads(m, false, true, false), withLoads(m, false, false, true)};
}

}  // namespace

EvalOutput runEval(const EvalOptions& options) {
  const std::vector<double> angles_deg = parseAngleList(options.phi_deg, "--phi-deg");
  const Mechanism m = loadScene(options.scene_path);
  const std::vector<Mechanism> cases = options.split ? splitCases(m) : std::vector<Mechanism>{};
  // Every model is built before any angle is evaluated: an engine that cannot build the scene stops the command with
  // one line (exit status 2) and nothing printed.
  struct Models {
    const Engine* engine;
    std::unique_ptr<EngineModel> whole;
    std::vector<std::unique_ptr<EngineModel>> split;  // gas, inertia, gravity
  };
  std::vector<Models> models;
  for (const Engine* engine : validation::selectEngines(options.engine)) {
    try {
      Models built{engine, engine->build(m), {}};
      for (const Mechanism& c : cases) built.split.push_back(engine->build(c));
      models.push_back(std::move(built));
    } catch (const std::exception& e) {
      throw UsageError(options.scene_path + ": --engine " + engine->name + ": " + e.what());
    }
  }
  const validation::Scales scales = validation::calcScales(m);
  const double split_tolerance = validation::kAgreementMultiple * validation::kEps * scales.torque * scales.acceleration_conditioning;

  // One row per angle and engine, the engines in the registry's order (analytic first).
  std::vector<Evaluation> results;
  std::vector<double> results_phi_deg;  // the user's angle of each result, printed as given
  std::vector<TorqueSplit> splits;
  for (double phi_deg : angles_deg) {
    const double phi = crankAngleFromDegrees(phi_deg);  // any finite angle, reduced exactly (mechanism.h)
    for (Models& model : models) {
      try {
        results.push_back(model.whole->evaluate(phi));
        if (options.split)
          splits.push_back({model.split[0]->evaluate(phi).drive_torque, model.split[1]->evaluate(phi).drive_torque,
                            model.split[2]->evaluate(phi).drive_torque, results.back().drive_torque, split_tolerance});
      } catch (const std::exception& e) {
        throw UsageError(options.scene_path + ": --engine " + model.engine->name + ": " + model.engine->library +
                         " could not evaluate phi = " + std::to_string(phi_deg) + " deg: " + e.what());
      }
      results_phi_deg.push_back(phi_deg);
    }
  }
  const bool holds = std::all_of(splits.begin(), splits.end(), [](const TorqueSplit& t) { return t.holds(); });

  if (options.format == "table") {
    std::string text = formatTable(m, showPath(options.scene_path), results, results_phi_deg);
    if (options.split) {
      char line[320];
      // Within 100 columns: the parts on one line, whether they add up on the next.
      std::snprintf(line, sizeof line,
                    "\ndrive torque split [N m]: each part by the same engine with the other loads off\n"
                    "%-17s %7s %14s %14s %14s %14s %14s\n",
                    "engine", "phi", "gas_torque", "inertia_torque", "gravity_torque", "sum", "drive_torque");
      text += line;
      for (size_t i = 0; i < splits.size(); ++i) {
        const TorqueSplit& t = splits[i];
        std::snprintf(line, sizeof line,
                      "%-17s %7.5g %14.8g %14.8g %14.8g %14.8g %14.8g\n  sum = whole: %s (|difference| %.2e, tol %.2e)\n",
                      results[i].engine.c_str(), results_phi_deg[i], t.gas + 0.0, t.inertia + 0.0, t.gravity + 0.0,
                      t.sum() + 0.0, t.whole, t.holds() ? "holds" : "FAILS", std::fabs(t.sum() - t.whole), t.tolerance);
        text += line;
      }
    }
    return {text + describeRigidShaft(m), holds};
  }
  nlohmann::ordered_json doc;
  doc["scene"] = sceneToJson(m);
  doc["results"] = nlohmann::ordered_json::array();
  for (size_t i = 0; i < results.size(); ++i) {
    nlohmann::ordered_json r = evaluationToJson(results[i], results_phi_deg[i], m);
    if (options.split) {
      const TorqueSplit& t = splits[i];
      r["split"] = {{"gas_torque", t.gas}, {"inertia_torque", t.inertia}, {"gravity_torque", t.gravity},
                    {"sum", t.sum()}, {"sum_minus_drive_torque", t.sum() - t.whole}, {"tolerance", t.tolerance},
                    {"holds", t.holds()}};
    }
    doc["results"].push_back(r);
  }
  return {dumpJson(doc), holds};
}

}  // namespace crankcheck::app
