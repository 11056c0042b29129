// A program graded by `crankcheck grade` (docs/grade.md), written against crankcheck's own
// analytic library (crankcheck::analytic): it reads the request's scene_toml with crankcheck::parseScene, answers
// every quantity of every cylinder with the closed forms, and passes the grade.
//
//   crankcheck grade --quick -- build/bin/grade_example_analytic
//
// Reads one JSON request per line on stdin (one without --batch, many with it); writes one JSON response per line.
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "crankcheck/analytic/reactions.h"
#include "crankcheck/scene/scene_file.h"

namespace {

nlohmann::json pair(const crankcheck::Vec2& v) { return {v[0], v[1]}; }

nlohmann::json answer(const nlohmann::json& request) {
  const crankcheck::Mechanism m = crankcheck::parseScene(request.at("scene_toml").get<std::string>(), "request");
  nlohmann::json results = nlohmann::json::array();
  for (const nlohmann::json& phi_deg : request.at("phi_deg")) {
    const crankcheck::Evaluation e = crankcheck::analytic::calcEvaluation(m, crankcheck::radiansFromDegrees(phi_deg.get<double>()));
    nlohmann::json r = {{"phi_deg", phi_deg},
                        {"U", e.U},
                        {"Q", e.Q},
                        {"drive_torque", e.drive_torque},
                        {"bearing_force", pair(e.bearing_force)},
                        {"shaking_force", pair(e.shaking_force)},
                        {"shaking_moment", {e.shaking_moment[0], e.shaking_moment[1], e.shaking_moment[2]}}};
    for (const crankcheck::CylinderEvaluation& c : e.cylinders) {
      nlohmann::json cylinder = {{"x_p", c.x_p},
                                 {"v_p", c.v_p},
                                 {"a_p", c.a_p},
                                 {"crank_pin_force", pair(c.crank_pin_force)},
                                 {"wrist_pin_force", pair(c.wrist_pin_force)},
                                 {"wall_force", c.wall_force},
                                 {"rod_angle", c.rod_angle},
                                 {"rod_omega", c.rod_omega},
                                 {"rod_alpha", c.rod_alpha}};
      if (m.gas) cylinder["gas_force"] = c.gas_force;
      r["cylinders"].push_back(cylinder);
    }
    results.push_back(r);
  }
  return {{"results", results}};
}

}  // namespace

int main() {
  std::string line;
  while (std::getline(std::cin, line))
    if (line.find_first_not_of(" \t\r") != std::string::npos)
      std::cout << answer(nlohmann::json::parse(line)).dump() << "\n" << std::flush;
  return 0;
}
