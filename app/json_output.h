#pragma once
/// @file
/// JSON and table output of the CLI. JSON documents are built with nlohmann::ordered_json (the scene and result
/// objects: crankcheck/validation/evaluation_json.h) and written by nlohmann-json, every number round-trip exact.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "crankcheck/scene/evaluation.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/evaluation_json.h"

namespace crankcheck::app {

using validation::evaluationToJson;
using validation::sceneToJson;

/// Pretty JSON text (2-space indent, nlohmann-json's dump): numbers in their shortest round-trip form.
std::string dumpJson(const nlohmann::ordered_json& document);

/// A human-readable table of the same results.
/// phi_deg[i] is the user's angle of results[i].
std::string formatTable(const Mechanism& m, const std::string& scene_path, const std::vector<Evaluation>& results,
                        const std::vector<double>& phi_deg);

}  // namespace crankcheck::app
