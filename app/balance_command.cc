#include "balance_command.h"

#include <cstdio>
#include <stdexcept>

#include "crankcheck/scene/scene_writer.h"
#include "crankcheck/validation/balance.h"
#include "crankcheck/validation/engines.h"
#include "help_format.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/evaluation_json.h"
#include "json_output.h"
#include "scene_input.h"

namespace crankcheck::app {

void addBalanceOptions(CLI::App& command, BalanceOptions& options) {
  command.add_option("scene", options.scene_path, "Scene file (TOML), see docs/SCENE-FORMAT.md")->required();
  command.add_option("--order", options.order, "Highest harmonic n (n times the crank speed)")->check(CLI::Range(1, 64))->capture_default_str();
  command.add_option("--format", options.format, "Output format")
      ->check(CLI::IsMember({"table", "json"}))
      ->capture_default_str();
  command.add_option("--design", options.design,
                     "Design the balance shafts that cancel harmonic N of the shaking force, print them as "
                     "[[balance_shaft]] tables and every harmonic with them")
      ->check(CLI::Range(1, 64));
}

namespace {

// What vanishes by symmetry, in words ("" when nothing does, "undecided" when angles are not whole degrees).
std::string reasonOf(const analytic::HarmonicSymmetry& s, bool axial) {
  // What no centric cylinder carries at this order (whatever the phases), then what the phases cancel.
  std::string absent;
  if (s.force_order_absent) absent = axial ? "force, moment X, Y" : "force";
  if (s.moment_z_order_absent) absent = "moment Z";
  std::string reason;
  if (!absent.empty())
    reason = absent + (s.force_order_absent ? ": a centric cylinder's has orders 1 and even only"
                                            : ": a centric cylinder's has odd orders only");
  if (axial && !s.force_order_absent && (s.moment_x_direction_absent || s.moment_y_direction_absent))
    reason += std::string(reason.empty() ? "" : "; ") + (s.moment_x_direction_absent ? "moment X" : "moment Y") +
              ": from order 2 on each cylinder's force lies along its axis, and every axis along " +
              (s.moment_x_direction_absent ? "X" : "Y");
  if (!s.decided) {
    if (!reason.empty()) return reason;
    return "not decided (an angle is not a whole 1/8 degree, a position not a whole nanometre, the pin offsets differ, "
           "or a balance shaft turns at this harmonic: the masses decide)";
  }
  std::string parts;
  auto add = [&](bool cancels, bool order_absent, const char* what) {
    if (cancels && !order_absent) parts += std::string(parts.empty() ? "" : ", ") + what;
  };
  add(s.force_cancels, s.force_order_absent, "force");
  if (axial) add(s.moment_xy_cancels, s.force_order_absent, "moment X, Y");
  add(s.moment_z_cancels, s.moment_z_order_absent, "moment Z");
  if (!parts.empty()) reason += (reason.empty() ? "" : "; ") + parts + ": the throws' phases cancel";
  return reason;
}

}  // namespace

std::string runBalance(const BalanceOptions& options) {
  Mechanism m = loadScene(options.scene_path);
  // The closed forms must take the scene; a reference engine that cannot build it, or hold its accuracy on it, sits
  // out, named with its reason, and the others answer (none left: refused, naming the first).
  try {
    validation::getClosedFormEngine().build(m);
  } catch (const std::invalid_argument& e) {
    throw UsageError(options.scene_path + ": " + e.what());
  }
  std::vector<validation::SatOut> sat_out;
  std::vector<BalanceShaftParams> designed;
  std::vector<validation::BalanceRow> rows;
  try {
    if (options.design > 0) {
      designed = validation::designBalanceShafts(m, options.design);
      m.balance_shafts.insert(m.balance_shafts.end(), designed.begin(), designed.end());
    }
    rows = validation::calcBalance(m, std::max(options.order, options.design), 0, &sat_out);
  } catch (const std::invalid_argument& e) {
    throw UsageError(options.scene_path + ": " + e.what());
  } catch (const std::runtime_error& e) {  // a harmonic analysis that does not reach rounding: refused
    throw UncomputableError(options.scene_path + ": balance: " + e.what());
  }
  // The designed shafts as the scene file writes them (degrees at the edge).
  std::string tables;
  for (const BalanceShaftParams& b : designed)
    tables += "[[balance_shaft]]\nratio = " + formatShortest(b.ratio) + "\nmass = " + formatShortest(b.mass) +
              "   # [kg]\nradius = " + formatShortest(b.radius) + "   # [m]\nphase_deg = " +
              formatShortest(degreesFromRadians(b.phase)) + "\nposition = [" + formatShortest(b.position[0]) + ", " +
              formatShortest(b.position[1]) + ", " + formatShortest(b.position[2]) + "]   # [m]\n";
  const bool axial = hasAxialPositions(m);
  const validation::BalanceResolution resolution = validation::calcBalanceResolution(m);
  if (options.format == "json") {
    nlohmann::ordered_json doc;
    doc["scene"] = sceneToJson(m);
    if (options.design > 0) {
      nlohmann::ordered_json shafts = nlohmann::ordered_json::array();
      for (const BalanceShaftParams& b : designed)
        shafts.push_back({{"ratio", b.ratio}, {"mass", b.mass}, {"radius", b.radius}, {"phase_deg", degreesFromRadians(b.phase)},
                          {"position", {b.position[0], b.position[1], b.position[2]}}});
      doc["design"] = {{"harmonic", options.design}, {"balance_shafts", shafts}, {"toml", tables}};
    }
    doc["order"] = options.order;
    doc["samples"] = std::max(64, 4 * options.order);
    doc["resolution"] = validation::balanceResolutionToJson(resolution);
    doc["harmonics"] = validation::balanceToJson(rows, axial);
    for (size_t i = 0; i < rows.size(); ++i) doc["harmonics"][i]["reason"] = reasonOf(rows[i].symmetry, axial);
    doc["sat_out"] = validation::satOutToJson(sat_out);
    return dumpJson(doc);
  }
  std::string out;
  if (options.design > 0)
    out += "balance shafts that cancel harmonic " + std::to_string(options.design) + " of the shaking force; paste into\n" +
           showPath(options.scene_path) + ":\n\n" + tables + "\nwith them, every harmonic (the residual):\n";
  char line[640];
  // One block per harmonic, a row per amplitude (within 100 columns for any number of engines up to four).
  out += "balance of " + showPath(options.scene_path) + " at " + formatShortest(m.speed_rpm) + " rpm\n";
  out += "amplitude of each harmonic n (n times the crank speed) by the closed form and each engine's DFT;\n"
         "F [N], M [N m] about O" +
         std::string(axial ? "" : "; no moments X, Y: the scene gives no axial positions") + "\n";
  std::snprintf(line, sizeof line,
                "each DFT resolves %.2g N, %.2g N m (2 x 64 eps x scale x conditioning);\n"
                "an engine's amplitude below that is its rounding, shown as <\n",
                resolution.force, resolution.moment);
  out += line;
  std::string header = "  n  amplitude     closed form";
  if (!rows.empty())
    for (const auto& [engine, harmonic] : rows.front().engines) {
      std::snprintf(line, sizeof line, " %15s", (engine + " DFT").c_str());
      header += line;
    }
  out += header + "\n";
  for (const validation::SatOut& s : sat_out) out += wrapText(s.engine + " sat out: " + s.reason, kHelpWidth) + "\n";
  for (const validation::BalanceRow& row : rows) {
    const analytic::ShakingHarmonic a = validation::withExactZeros(row.analytic, row.symmetry);
    auto print = [&](bool first, const char* name, double closed, double floor, const auto& amplitude) {
      std::snprintf(line, sizeof line, "%3s  %-9s %15.4e", first ? std::to_string(row.n).c_str() : "", name, closed);
      out += line;
      for (const auto& [engine, harmonic] : row.engines) {
        const double value = amplitude(harmonic);
        if (value < floor) {
          char below[40];
          std::snprintf(below, sizeof below, "<%.2g", floor);
          std::snprintf(line, sizeof line, " %15s", below);
        } else {
          std::snprintf(line, sizeof line, " %15.4e", value);
        }
        out += line;
      }
      out += "\n";
    };
    print(true, "|F_s|", a.calcForceAmplitude(), resolution.force,
          [](const analytic::ShakingHarmonic& h) { return h.calcForceAmplitude(); });
    for (int axis = axial ? 0 : 2; axis < 3; ++axis)
      print(false, axis == 0 ? "|M_X|" : axis == 1 ? "|M_Y|" : "|M_Z|", a.calcMomentAmplitude(axis), resolution.moment,
            [axis](const analytic::ShakingHarmonic& h) { return h.calcMomentAmplitude(axis); });
    const std::string reason = reasonOf(row.symmetry, axial);
    if (!reason.empty()) {  // its continuation lines under the reason's first word
      const std::string text = wrapText("vanishes: " + reason, kHelpWidth - 15);
      for (size_t at = 0, next; at < text.size(); at = next + 1) {
        next = text.find('\n', at);
        if (next == std::string::npos) next = text.size();
        out += std::string(at == 0 ? 5 : 15, ' ') + text.substr(at, next - at) + "\n";
      }
    }
  }
  return out;
}

}  // namespace crankcheck::app
