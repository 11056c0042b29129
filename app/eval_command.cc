#include "eval_command.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "crankcheck/analytic/reactions.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/simbody_models/k_crank_model.h"
#include "json_output.h"
#include "crankcheck/validation/errors.h"

namespace crankcheck::app {

void addEvalOptions(CLI::App& command, EvalOptions& options) {
  command.add_option("scene", options.scene_path, "Scene file (TOML), see docs/SCENE-FORMAT.md")->required();
  command.add_option("--phi-deg", options.phi_deg, "Crank angles of cylinder 0 in degrees, comma separated")
      ->capture_default_str();
  command.add_option("--engine", options.engine, "Which engine computes the results")
      ->check(CLI::IsMember({"analytic", "simbody", "both"}))
      ->capture_default_str();
  command.add_option("--format", options.format, "Output format")
      ->check(CLI::IsMember({"table", "json"}))
      ->capture_default_str();
}

std::vector<double> parseAngleList(const std::string& text, const std::string& flag) {
  if (text.empty()) throw UsageError(flag + ": empty; give at least one angle, e.g. " + flag + " 0,90");
  std::vector<double> angles;
  size_t begin = 0;
  for (int item = 1;; ++item) {
    const size_t end = std::min(text.find(',', begin), text.size());
    const std::string field = text.substr(begin, end - begin);
    const std::string where = flag + ": item " + std::to_string(item) + " of \"" + text + "\"";
    if (field.empty()) throw UsageError(where + ": empty (nothing is assumed in its place)");
    size_t used = 0;
    double value = 0.0;
    try {
      value = std::stod(field, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != field.size()) throw UsageError(where + ": \"" + field + "\" is not a number");
    if (!std::isfinite(value)) throw UsageError(where + ": must be a finite number of degrees");
    angles.push_back(value);
    if (end == text.size()) break;
    begin = end + 1;
  }
  return angles;
}

std::string runEval(const EvalOptions& options) {
  const std::vector<double> angles_deg = parseAngleList(options.phi_deg, "--phi-deg");
  Mechanism m;
  try {
    m = loadSceneFile(options.scene_path);
  } catch (const SceneError& e) {
    throw UsageError(e.what());
  }
  const bool use_analytic = options.engine != "simbody";
  const bool use_simbody = options.engine != "analytic";
  std::unique_ptr<simbody_models::KCrankModel> model;
  if (use_simbody) {
    try {
      model = std::make_unique<simbody_models::KCrankModel>(m);
    } catch (const std::invalid_argument& e) {
      throw UsageError(options.scene_path + ": --engine " + options.engine + ": " + e.what());
    }
  }

  // One row per angle and engine; for --engine both the analytic row comes first.
  std::vector<Evaluation> results;
  std::vector<double> results_phi_deg;  // the user's angle of each result, printed as given
  for (double phi_deg : angles_deg) {
    const double phi = radiansFromDegrees(phi_deg);
    if (use_analytic) {
      results.push_back(analytic::calcEvaluation(m, phi));
      results_phi_deg.push_back(phi_deg);
    }
    if (use_simbody) {
      try {
        results.push_back(model->evaluate(phi));
      } catch (const std::runtime_error& e) {
        throw UsageError(options.scene_path + ": --engine " + options.engine + ": Simbody could not evaluate phi = " +
                         std::to_string(phi_deg) + " deg: " + e.what());
      }
      results_phi_deg.push_back(phi_deg);
    }
  }

  if (options.format == "table") return formatTable(m, options.scene_path, results, results_phi_deg);
  nlohmann::ordered_json doc;
  doc["scene"] = sceneToJson(m);
  doc["results"] = nlohmann::ordered_json::array();
  for (size_t i = 0; i < results.size(); ++i) doc["results"].push_back(evaluationToJson(results[i], results_phi_deg[i], m));
  return dumpJson(doc);
}

}  // namespace crankcheck::app
