#include "balance_command.h"

#include <cstdio>
#include <stdexcept>

#include "crankcheck/scene/scene_writer.h"
#include "crankcheck/validation/balance.h"
#include "crankcheck/validation/engines.h"
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
  if (!s.decided)
    return "not decided (an angle is not a whole 1/8 degree, a position not a whole nanometre, the pin offsets differ, or a "
           "balance shaft turns at this harmonic: the masses decide)";
  std::string parts;
  auto add = [&](bool cancels, const char* what) {
    if (cancels) parts += std::string(parts.empty() ? "" : ", ") + what;
  };
  add(s.force_cancels, "force");
  if (axial) add(s.moment_xy_cancels, "moment X, Y");
  add(s.moment_z_cancels, "moment Z");
  return parts.empty() ? "" : parts + ": the throws' phases cancel (exact sum of roots of unity)";
}

}  // namespace

std::string runBalance(const BalanceOptions& options) {
  Mechanism m = loadScene(options.scene_path);
  // Every engine whose harmonics are shown must build the scene: refused now, naming the engine and the key.
  validation::checkEveryEngineBuilds(m, options.scene_path);
  std::vector<BalanceShaftParams> designed;
  std::vector<validation::BalanceRow> rows;
  try {
    if (options.design > 0) {
      designed = validation::designBalanceShafts(m, options.design);
      m.balance_shafts.insert(m.balance_shafts.end(), designed.begin(), designed.end());
    }
    rows = validation::calcBalance(m, std::max(options.order, options.design));
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
    doc["harmonics"] = validation::balanceToJson(rows, axial);
    for (size_t i = 0; i < rows.size(); ++i) doc["harmonics"][i]["reason"] = reasonOf(rows[i].symmetry, axial);
    return dumpJson(doc);
  }
  std::string out;
  if (options.design > 0)
    out += "balance shafts that cancel harmonic " + std::to_string(options.design) + " of the shaking force (paste into " +
           options.scene_path + "):\n\n" + tables + "\nwith them, every harmonic (the residual):\n";
  out += "balance of " + options.scene_path + " at " + formatShortest(m.speed_rpm) +
                    " rpm: amplitude of each harmonic n (closed form / Simbody DFT / MuJoCo DFT); F [N], M [N m] about O\n";
  char line[640];
  std::snprintf(line, sizeof line, "%3s %37s %37s %37s %37s  %s\n", "n", "|F_s|", "|M_X|", "|M_Y|", "|M_Z|",
                "vanishes by symmetry");
  out += line;
  // "closed form / engine / engine ..." of one amplitude
  auto all = [](double closed, const validation::BalanceRow& row, const auto& amplitude) {
    std::string text;
    char b[32];
    std::snprintf(b, sizeof b, "%11.4e", closed);
    text = b;
    for (const auto& [engine, harmonic] : row.engines) {
      std::snprintf(b, sizeof b, " / %11.4e", amplitude(harmonic));
      text += b;
    }
    return text;
  };
  for (const validation::BalanceRow& row : rows) {
    const analytic::ShakingHarmonic a = validation::withExactZeros(row.analytic, row.symmetry);
    auto moment = [](int axis) { return [axis](const analytic::ShakingHarmonic& h) { return h.calcMomentAmplitude(axis); }; };
    const std::string mx = axial ? all(a.calcMomentAmplitude(0), row, moment(0)) : "-";
    const std::string my = axial ? all(a.calcMomentAmplitude(1), row, moment(1)) : "-";
    std::snprintf(line, sizeof line, "%3d %37s %37s %37s %37s  %s\n", row.n,
                  all(a.calcForceAmplitude(), row, [](const analytic::ShakingHarmonic& h) { return h.calcForceAmplitude(); }).c_str(),
                  mx.c_str(), my.c_str(), all(a.calcMomentAmplitude(2), row, moment(2)).c_str(),
                  reasonOf(row.symmetry, axial).c_str());
    out += line;
  }
  return out;
}

}  // namespace crankcheck::app
