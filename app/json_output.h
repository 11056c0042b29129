#pragma once
/// @file
/// JSON and table output of the CLI. JSON documents are built with nlohmann::ordered_json and written with every
/// number at 17 significant digits (round-trip exact), as the CLI promises.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "crankcheck/scene/evaluation.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::app {

/// The parsed scene in SI units, plus lambda.
nlohmann::ordered_json sceneToJson(const Mechanism& m);

/// One engine's result at one angle (phi_deg as the user gave it): {"engine", "phi_deg", "U", "Q", "drive_torque", "bearing_force",
/// "cylinders": [{"x_p", "v_p", "a_p", "crank_pin_force", "wrist_pin_force", "wall_force"}]}.
/// One result of `eval` for scene `m`: shaking_moment's X and Y are printed only when the scene places its cylinders
/// along the shaft (otherwise null); each cylinder's gas_force only when the scene has [gas].
nlohmann::ordered_json evaluationToJson(const Evaluation& ev, double phi_deg, const Mechanism& m);

/// Pretty JSON text (2-space indent) with numbers as %.17g; integers stay integers.
std::string dumpJson(const nlohmann::ordered_json& document);

/// A human-readable table of the same results.
/// phi_deg[i] is the user's angle of results[i].
std::string formatTable(const Mechanism& m, const std::string& scene_path, const std::vector<Evaluation>& results,
                        const std::vector<double>& phi_deg);

}  // namespace crankcheck::app
