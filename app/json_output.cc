#include "json_output.h"

#include <cstdio>
#include <sstream>

#include "crankcheck/analytic/kinematics.h"
#include "help_format.h"

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
  // Within 100 columns (the path on a line of its own; each cylinder's values in two tables).
  std::snprintf(line, sizeof line, ", %.6g rpm, lambda = %.6g, g = %.6g m/s^2\n", m.speed_rpm, calcCrankRatio(m),
                m.engine.gravity);
  out << "scene " << scene_path << "\n"
      << wrapText("  k = " + std::to_string(m.engine.cylinders) + ", " + toString(m.engine.cycle) + ", " +
                      toString(m.engine.acting) + "-acting, " + banks + line,
                  kHelpWidth);
  if (hasPinOffsets(m))  // the dead centres move off theta = 0 and 180 degrees and the stroke exceeds 2 r
    for (int j = 0; j < m.engine.cylinders; ++j) {
      const analytic::DeadCentres d = analytic::calcDeadCentres(m, getPinOffset(m, j));
      std::snprintf(line, sizeof line,
                    "  cylinder %d: pin offset %.6g m, stroke %.9g m, dead centres at theta =\n"
                    "    %.9g deg (outer) and %.9g deg (inner)\n",
                    j, getPinOffset(m, j), d.stroke, degreesFromRadians(d.outer), degreesFromRadians(d.inner));
      out << line;
    }
  for (size_t i = 0; i < results.size(); ++i) {
    const Evaluation& ev = results[i];
    std::snprintf(line, sizeof line, "\n%s   phi = %.10g deg\n  U = %.12g J   Q = %.12g N m   drive_torque = %.12g N m\n",
                  ev.engine.c_str(), phi_deg[i], ev.U + 0.0, ev.Q, ev.drive_torque);
    out << line;
    std::snprintf(line, sizeof line, "  bearing_force = (%.12g, %.12g) N\n  shaking_force = (%.12g, %.12g) N\n",
                  ev.bearing_force[0], ev.bearing_force[1], ev.shaking_force[0] + 0.0, ev.shaking_force[1] + 0.0);
    out << line;
    if (hasAxialPositions(m))
      std::snprintf(line, sizeof line, "  shaking_moment = (%.12g, %.12g, %.12g) N m\n", ev.shaking_moment[0] + 0.0,
                    ev.shaking_moment[1] + 0.0, ev.shaking_moment[2] + 0.0);
    else
      std::snprintf(line, sizeof line, "  shaking_moment = (-, -, %.12g) N m\n", ev.shaking_moment[2] + 0.0);
    out << line;
    std::snprintf(line, sizeof line, "  %3s %16s %16s %16s %16s%s\n", "cyl", "x_p [m]", "v_p [m/s]", "a_p [m/s^2]",
                  "wall_force [N]", m.gas ? "    gas_force [N]" : "");
    out << line;
    for (size_t j = 0; j < ev.cylinders.size(); ++j) {
      const CylinderEvaluation& c = ev.cylinders[j];
      std::snprintf(line, sizeof line, "  %3zu %16.9g %16.9g %16.9g %16.9g", j, c.x_p, c.v_p, c.a_p, c.wall_force);
      out << line;
      if (m.gas) {
        std::snprintf(line, sizeof line, " %16.9g", c.gas_force);
        out << line;
      }
      out << "\n";
    }
    std::snprintf(line, sizeof line, "  %3s %16s %16s %16s %16s\n", "cyl", "crank_pin_force", "(X, Y) [N]",
                  "wrist_pin_force", "(X, Y) [N]");
    out << line;
    for (size_t j = 0; j < ev.cylinders.size(); ++j) {
      const CylinderEvaluation& c = ev.cylinders[j];
      std::snprintf(line, sizeof line, "  %3zu %16.9g %16.9g %16.9g %16.9g\n", j, c.crank_pin_force[0],
                    c.crank_pin_force[1], c.wrist_pin_force[0], c.wrist_pin_force[1]);
      out << line;
    }
  }
  return out.str();
}

}  // namespace crankcheck::app
