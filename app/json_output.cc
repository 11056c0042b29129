#include "json_output.h"

#include <cstdio>
#include <sstream>

#include "crankcheck/analytic/kinematics.h"

namespace crankcheck::app {

std::string dumpJson(const nlohmann::ordered_json& document) {
  // nlohmann-json writes each number in its shortest form that reads back to the same double, NaN and infinity
  // as null.
  return document.dump(2) + "\n";
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
  if (hasPinOffsets(m))  // the dead centres move off theta = 0 and 180 degrees and the stroke exceeds 2 r
    for (int j = 0; j < m.engine.cylinders; ++j) {
      const analytic::DeadCentres d = analytic::calcDeadCentres(m, getPinOffset(m, j));
      std::snprintf(line, sizeof line,
                    "  cylinder %d: pin offset %.6g m, dead centres at theta = %.9g deg (outer) and %.9g deg (inner), "
                    "stroke %.9g m\n",
                    j, getPinOffset(m, j), degreesFromRadians(d.outer), degreesFromRadians(d.inner), d.stroke);
      out << line;
    }
  for (size_t i = 0; i < results.size(); ++i) {
    const Evaluation& ev = results[i];
    std::snprintf(line, sizeof line,
                  "\n%-17s phi = %.10g deg   U = %.12g J   Q = %.12g N m   drive_torque = %.12g N m   "
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
