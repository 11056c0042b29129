#include "json_output.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace crankcheck::app {
namespace {

std::string number17(double x) {
  if (!std::isfinite(x)) return "null";  // JSON has no NaN or inf; the engines never produce them for valid scenes
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", x + 0.0);  // + 0.0 prints -0 as 0
  return buffer;
}

void write(const nlohmann::ordered_json& j, std::ostringstream& out, int indent) {
  const std::string pad(indent + 2, ' '), close(indent, ' ');
  switch (j.type()) {
    case nlohmann::ordered_json::value_t::object: {
      if (j.empty()) { out << "{}"; return; }
      out << "{\n";
      bool first = true;
      for (auto it = j.begin(); it != j.end(); ++it) {
        if (!first) out << ",\n";
        first = false;
        out << pad << nlohmann::ordered_json(it.key()).dump() << ": ";
        write(it.value(), out, indent + 2);
      }
      out << "\n" << close << "}";
      return;
    }
    case nlohmann::ordered_json::value_t::array: {
      if (j.empty()) { out << "[]"; return; }
      // Arrays of numbers (vectors such as [X, Y]) stay on one line.
      bool numbers = true;
      for (const auto& v : j) numbers = numbers && v.is_number();
      if (numbers) {
        out << "[";
        for (size_t i = 0; i < j.size(); ++i) {
          if (i) out << ", ";
          write(j[i], out, indent);
        }
        out << "]";
        return;
      }
      out << "[\n";
      for (size_t i = 0; i < j.size(); ++i) {
        if (i) out << ",\n";
        out << pad;
        write(j[i], out, indent + 2);
      }
      out << "\n" << close << "]";
      return;
    }
    case nlohmann::ordered_json::value_t::number_float:
      out << number17(j.get<double>());
      return;
    default:
      out << j.dump();
  }
}

nlohmann::ordered_json vec(const Vec2& v) { return nlohmann::ordered_json::array({v[0], v[1]}); }

}  // namespace

std::string dumpJson(const nlohmann::ordered_json& document) {
  std::ostringstream out;
  write(document, out, 0);
  out << "\n";
  return out.str();
}

nlohmann::ordered_json sceneToJson(const Mechanism& m) {
  nlohmann::ordered_json j;
  j["name"] = m.name;
  j["engine"] = {
      {"cylinders", m.engine.cylinders},
      {"cycle", toString(m.engine.cycle)},
      {"acting", toString(m.engine.acting)},
      {"crank_angles", m.engine.crank_angles},
      {"explicit_crank_angles", m.engine.explicit_crank_angles},
      {"cylinder_angle", m.engine.cylinder_angle},
      {"bank_angles", m.engine.bank_angles},
      {"axial_positions", m.engine.axial_positions},
      {"speed", m.engine.speed},
      {"gravity", m.engine.gravity},
  };
  j["crank"] = {{"radius", m.crank.radius},
                {"mass", m.crank.mass},
                {"com_radius", m.crank.com_radius},
                {"counterweight_mass", m.crank.counterweight_mass},
                {"counterweight_radius", m.crank.counterweight_radius}};
  j["rod"] = {{"length", m.rod.length},
              {"mass", m.rod.mass},
              {"com_from_wrist_pin", m.rod.com_from_wrist_pin},
              {"inertia_about_wrist_pin", m.rod.inertia_about_wrist_pin}};
  j["piston"] = {{"mass", m.piston.mass}};
  if (m.gas) {
    j["gas"] = {{"bore", m.gas->bore}, {"cycle_angles", m.gas->cycle_angles}, {"pressures", m.gas->pressures},
                {"cycle", m.gas->cycle}};
    j["engine"]["firing_angles"] = m.firing_angles;
  }
  j["flywheel"] = m.flywheel_inertia ? nlohmann::ordered_json{{"inertia", *m.flywheel_inertia}} : nlohmann::ordered_json(nullptr);
  j["lambda"] = calcCrankRatio(m);
  j["units"] = "SI: m, kg, s, rad, N, N m, J";
  return j;
}

nlohmann::ordered_json evaluationToJson(const Evaluation& ev, double phi_deg, const Mechanism& m) {
  const bool moment_xy_defined = hasAxialPositions(m);
  nlohmann::ordered_json j;
  j["engine"] = ev.engine;
  j["phi_deg"] = phi_deg;
  j["U"] = ev.U;
  j["Q"] = ev.Q;
  j["drive_torque"] = ev.drive_torque;
  // The paper's dimensionless values (divided by I_w omega^2): only with a flywheel and a speed.
  const bool dimensionless = m.flywheel_inertia && m.engine.speed > 0.0;
  const double unit = dimensionless ? *m.flywheel_inertia * m.engine.speed * m.engine.speed : 1.0;
  j["U_star"] = dimensionless ? nlohmann::ordered_json(ev.U / unit) : nlohmann::ordered_json(nullptr);
  j["Q_star"] = dimensionless ? nlohmann::ordered_json(ev.Q / unit) : nlohmann::ordered_json(nullptr);
  j["bearing_force"] = vec(ev.bearing_force);
  j["shaking_force"] = vec(ev.shaking_force);
  // Without axial positions the X and Y moments are not defined: null, never 0.
  j["shaking_moment"] = nlohmann::ordered_json::array(
      {moment_xy_defined ? nlohmann::ordered_json(ev.shaking_moment[0]) : nlohmann::ordered_json(nullptr),
       moment_xy_defined ? nlohmann::ordered_json(ev.shaking_moment[1]) : nlohmann::ordered_json(nullptr),
       ev.shaking_moment[2]});
  nlohmann::ordered_json cylinders = nlohmann::ordered_json::array();
  for (const CylinderEvaluation& c : ev.cylinders) {
    nlohmann::ordered_json cylinder = {{"x_p", c.x_p},
                                       {"v_p", c.v_p},
                                       {"a_p", c.a_p},
                                       {"crank_pin_force", vec(c.crank_pin_force)},
                                       {"wrist_pin_force", vec(c.wrist_pin_force)},
                                       {"wall_force", c.wall_force}};
    if (m.gas) cylinder["gas_force"] = c.gas_force;  // absent without [gas]
    cylinder["rod_angle"] = c.rod_angle;
    cylinder["rod_omega"] = c.rod_omega;
    cylinder["rod_alpha"] = c.rod_alpha;
    cylinders.push_back(cylinder);
  }
  j["cylinders"] = cylinders;
  return j;
}

std::string formatTable(const Mechanism& m, const std::string& scene_path, const std::vector<Evaluation>& results,
                        const std::vector<double>& phi_deg) {
  std::ostringstream out;
  char line[512];
  std::string banks;  // one bank: its gamma; a layout: every cylinder's bank and throw
  char part[96];
  if (isSingleBank(m)) {
    std::snprintf(part, sizeof part, "gamma = %.6g deg", degreesFromRadians(m.engine.cylinder_angle));
    banks = part;
  } else {
    banks = "(bank, throw) deg =";
    for (int j = 0; j < m.engine.cylinders; ++j) {
      std::snprintf(part, sizeof part, " (%.6g, %.6g)", degreesFromRadians(getBankAngle(m, j)),
                    degreesFromRadians(getThrowAngle(m, j)));
      banks += part;
    }
  }
  out << "scene " << scene_path << ": k = " << m.engine.cylinders << ", " << toString(m.engine.cycle) << ", "
      << toString(m.engine.acting) << "-acting, " << banks;
  std::snprintf(line, sizeof line, ", %.6g rpm, lambda = %.6g, g = %.6g m/s^2\n", m.speed_rpm, calcCrankRatio(m),
                m.engine.gravity);
  out << line;
  for (size_t i = 0; i < results.size(); ++i) {
    const Evaluation& ev = results[i];
    std::snprintf(line, sizeof line,
                  "\n%-9s phi = %.10g deg   U = %.12g J   Q = %.12g N m   drive_torque = %.12g N m   "
                  "bearing_force = (%.12g, %.12g) N\n",
                  ev.engine.c_str(), phi_deg[i], ev.U + 0.0, ev.Q, ev.drive_torque, ev.bearing_force[0],
                  ev.bearing_force[1]);
    out << line;
    if (hasAxialPositions(m))
      std::snprintf(line, sizeof line, "          shaking_force = (%.12g, %.12g) N   shaking_moment = (%.12g, %.12g, %.12g) N m\n",
                    ev.shaking_force[0] + 0.0, ev.shaking_force[1] + 0.0, ev.shaking_moment[0] + 0.0,
                    ev.shaking_moment[1] + 0.0, ev.shaking_moment[2] + 0.0);
    else
      std::snprintf(line, sizeof line, "          shaking_force = (%.12g, %.12g) N   shaking_moment = (-, -, %.12g) N m\n",
                    ev.shaking_force[0] + 0.0, ev.shaking_force[1] + 0.0, ev.shaking_moment[2] + 0.0);
    out << line;
    std::snprintf(line, sizeof line, "  %3s %15s %15s %15s %33s %33s %15s%s\n", "cyl", "x_p [m]", "v_p [m/s]",
                  "a_p [m/s^2]", "crank_pin_force (X, Y) [N]", "wrist_pin_force (X, Y) [N]", "wall_force [N]",
                  m.gas ? "  gas_force [N]" : "");
    out << line;
    for (size_t j = 0; j < ev.cylinders.size(); ++j) {
      const CylinderEvaluation& c = ev.cylinders[j];
      std::snprintf(line, sizeof line, "  %3zu %15.9g %15.9g %15.9g %16.9g %16.9g %16.9g %16.9g %15.9g\n", j, c.x_p,
                    c.v_p, c.a_p, c.crank_pin_force[0], c.crank_pin_force[1], c.wrist_pin_force[0],
                    c.wrist_pin_force[1], c.wall_force);
      out << line;
      if (m.gas) {
        out.seekp(-1, std::ios_base::cur);  // the gas force on the same line
        std::snprintf(line, sizeof line, " %14.9g\n", c.gas_force);
        out << line;
      }
    }
  }
  return out.str();
}

}  // namespace crankcheck::app
