#include "json_output.h"

#include <cstdio>
#include <sstream>

#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/scene/quantities.h"
#include "help_format.h"

namespace crankcheck::app {

std::string dumpJson(const nlohmann::ordered_json& document) {
  // nlohmann-json writes each number in its shortest form that reads back to the same double, NaN and infinity
  // as null.
  return document.dump(2) + "\n";
}

namespace {

// A whole-mechanism value as the table prints it: U and the shaking force and moment with a negative zero shown as
// 0 (the others keep the sign they were computed with, as the table has always printed them).
double wholeValue(const Quantity& q, double x) {
  const bool fold = q.id == QuantityId::kU || q.id == QuantityId::kShakingForce || q.id == QuantityId::kShakingMoment;
  return fold ? x + 0.0 : x;
}

}  // namespace

std::string formatTable(const Mechanism& m, const std::string& scene_path, const std::vector<Evaluation>& results,
                        const std::vector<double>& phi_deg) {
  std::ostringstream out;
  char line[512];
  std::string banks;  // one bank: its gamma; a layout: every cylinder's bank and throw
  char part[96];
  if (isSingleBank(m)) {
    std::snprintf(part, sizeof part, "gamma = %.6g deg", degreesFromRadians(m.machine.cylinder_angle));
    banks = part;
  } else {
    banks = "(bank, throw) deg =";
    for (int j = 0; j < m.machine.cylinders; ++j) {
      std::snprintf(part, sizeof part, " (%.6g, %.6g)", degreesFromRadians(getBankAngle(m, j)),
                    degreesFromRadians(getThrowAngle(m, j)));
      banks += part;
    }
  }
  // Within 100 columns (the path on a line of its own; each cylinder's values in two tables).
  std::snprintf(line, sizeof line, ", %.6g rpm, lambda = %.6g, g = %.6g m/s^2\n", m.speed_rpm, calcCrankRatio(m),
                m.machine.gravity);
  out << "scene " << scene_path << "\n"
      << wrapText("  k = " + std::to_string(m.machine.cylinders) + ", " + toString(m.machine.cycle) + ", " +
                      toString(m.machine.acting) + "-acting, " + banks + line,
                  kHelpWidth);
  if (hasPinOffsets(m))  // the dead centres move off theta = 0 and 180 degrees and the stroke exceeds 2 r
    for (int j = 0; j < m.machine.cylinders; ++j) {
      const analytic::DeadCentres d = analytic::calcDeadCentres(m, getPinOffset(m, j));
      std::snprintf(line, sizeof line,
                    "  cylinder %d: pin offset %.6g m, stroke %.9g m, dead centres at theta =\n"
                    "    %.9g deg (outer) and %.9g deg (inner)\n",
                    j, getPinOffset(m, j), d.stroke, degreesFromRadians(d.outer), degreesFromRadians(d.inner));
      out << line;
    }
  // The catalogue's quantities (quantities.h): the whole mechanism's numbers on one line, each of its vectors on a
  // line of its own, then each cylinder's numbers in one table and its vectors in another (those in_table).
  const std::vector<Quantity>& catalogue = getQuantityCatalogue();
  auto shown = [&](const Quantity& q, bool per_cylinder, bool vector) {
    return q.per_cylinder == per_cylinder && (q.components > 1) == vector && q.in_table && isQuantityDefined(q, m);
  };
  for (size_t i = 0; i < results.size(); ++i) {
    const Evaluation& ev = results[i];
    std::snprintf(line, sizeof line, "\n%s   phi = %.10g deg\n  ", ev.engine.c_str(), phi_deg[i]);
    out << line;
    const char* separator = "";
    for (const Quantity& q : catalogue)
      if (shown(q, false, false)) {
        std::snprintf(line, sizeof line, "%s%s = %.12g %s", separator, q.name, wholeValue(q, readQuantity(q, ev)[0]), q.unit);
        out << line;
        separator = "   ";
      }
    out << "\n";
    for (const Quantity& q : catalogue)
      if (shown(q, false, true)) {
        out << "  " << q.name << " = (";
        for (int c = 0; c < q.components; ++c) {
          if (isComponentDefined(q, c, m))
            std::snprintf(line, sizeof line, "%s%.12g", c ? ", " : "", wholeValue(q, readQuantity(q, ev)[c]));
          else
            std::snprintf(line, sizeof line, "%s-", c ? ", " : "");
          out << line;
        }
        out << ") " << q.unit << "\n";
      }
    std::snprintf(line, sizeof line, "  %3s", "cyl");
    out << line;
    for (const Quantity& q : catalogue)
      if (shown(q, true, false)) {
        std::snprintf(line, sizeof line, " %16s", (std::string(q.name) + " [" + q.unit + "]").c_str());
        out << line;
      }
    out << "\n";
    for (size_t j = 0; j < ev.cylinders.size(); ++j) {
      std::snprintf(line, sizeof line, "  %3zu", j);
      out << line;
      for (const Quantity& q : catalogue)
        if (shown(q, true, false)) {
          std::snprintf(line, sizeof line, " %16.9g", readQuantity(q, ev, static_cast<int>(j))[0]);
          out << line;
        }
      out << "\n";
    }
    std::snprintf(line, sizeof line, "  %3s", "cyl");
    out << line;
    for (const Quantity& q : catalogue)
      if (shown(q, true, true)) {
        std::snprintf(line, sizeof line, " %16s %16s", q.name,
                      (std::string(q.components == 2 ? "(X, Y)" : "(X, Y, Z)") + " [" + q.unit + "]").c_str());
        out << line;
      }
    out << "\n";
    for (size_t j = 0; j < ev.cylinders.size(); ++j) {
      std::snprintf(line, sizeof line, "  %3zu", j);
      out << line;
      for (const Quantity& q : catalogue)
        if (shown(q, true, true))
          for (int c = 0; c < q.components; ++c) {
            std::snprintf(line, sizeof line, " %16.9g", readQuantity(q, ev, static_cast<int>(j))[c]);
            out << line;
          }
      out << "\n";
    }
  }
  return out.str();
}

}  // namespace crankcheck::app
