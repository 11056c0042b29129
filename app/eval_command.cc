#include "eval_command.h"

#include <cmath>

#include "crankcheck/analytic/reactions.h"
#include "crankcheck/scene/scene_file.h"
#include "json_output.h"
#include "usage_error.h"

namespace crankcheck::app {

void addEvalOptions(CLI::App& command, EvalOptions& options) {
  command.add_option("scene", options.scene_path, "Scene file (TOML), see docs/SCENE-FORMAT.md")->required();
  command.add_option("--phi-deg", options.phi_deg, "Crank angles of cylinder 0 in degrees, comma separated")
      ->delimiter(',')
      ->capture_default_str();
  command.add_option("--engine", options.engine, "Which engine computes the results")
      ->check(CLI::IsMember({"analytic", "simbody", "both"}))
      ->capture_default_str();
  command.add_option("--format", options.format, "Output format")
      ->check(CLI::IsMember({"table", "json"}))
      ->capture_default_str();
}

std::string runEval(const EvalOptions& options) {
  Mechanism m;
  try {
    m = loadSceneFile(options.scene_path);
  } catch (const SceneError& e) {
    throw UsageError(e.what());
  }
  for (double phi : options.phi_deg)
    if (!std::isfinite(phi)) throw UsageError("--phi-deg: angles must be finite numbers");
  if (options.engine != "analytic")
    throw UsageError("--engine " + options.engine +
                     ": the Simbody engine is not built into this version yet; use --engine analytic");

  std::vector<Evaluation> results;
  std::vector<double> results_phi_deg;  // the user's angle of each result, printed as given
  for (double phi_deg : options.phi_deg) {
    const double phi = radiansFromDegrees(phi_deg);
    results.push_back(analytic::calcEvaluation(m, phi));
    results_phi_deg.push_back(phi_deg);
  }

  if (options.format == "table") return formatTable(m, options.scene_path, results, results_phi_deg);
  nlohmann::ordered_json doc;
  doc["scene"] = sceneToJson(m);
  doc["results"] = nlohmann::ordered_json::array();
  for (size_t i = 0; i < results.size(); ++i) doc["results"].push_back(evaluationToJson(results[i], results_phi_deg[i]));
  return dumpJson(doc);
}

}  // namespace crankcheck::app
