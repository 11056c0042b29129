#include "balance_command.h"

#include <cstdio>
#include <stdexcept>

#include "crankcheck/scene/scene_writer.h"
#include "crankcheck/validation/balance.h"
#include "crankcheck/validation/errors.h"
#include "json_output.h"
#include "scene_input.h"

namespace crankcheck::app {

void addBalanceOptions(CLI::App& command, BalanceOptions& options) {
  command.add_option("scene", options.scene_path, "Scene file (TOML), see docs/SCENE-FORMAT.md")->required();
  command.add_option("--order", options.order, "Highest harmonic n")->check(CLI::Range(1, 64))->capture_default_str();
  command.add_option("--format", options.format, "Output format")
      ->check(CLI::IsMember({"table", "json"}))
      ->capture_default_str();
  command.add_option("--design", options.design,
                     "Design the balance shafts that cancel harmonic N of the shaking force, print them as "
                     "[[balance_shaft]] tables and every harmonic with them")
      ->check(CLI::Range(1, 64));
}

namespace {

const char* kAxes[3] = {"X", "Y", "Z"};

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

// The closed form with exactly-cancelling parts set to 0 (they are rounding otherwise).
analytic::ShakingHarmonic withExactZeros(analytic::ShakingHarmonic h, const analytic::HarmonicSymmetry& s) {
  if (!s.decided) return h;
  if (s.force_cancels) h.force_cos = h.force_sin = Vec2{0.0, 0.0};
  for (int k = 0; k < 2; ++k)
    if (s.moment_xy_cancels) h.moment_cos[k] = h.moment_sin[k] = 0.0;
  if (s.moment_z_cancels) h.moment_cos[2] = h.moment_sin[2] = 0.0;
  return h;
}

nlohmann::ordered_json harmonicToJson(const analytic::ShakingHarmonic& h, bool axial) {
  nlohmann::ordered_json j;
  j["shaking_force"] = {{"amplitude", h.calcForceAmplitude()},
                        {"cos", nlohmann::ordered_json::array({h.force_cos[0], h.force_cos[1]})},
                        {"sin", nlohmann::ordered_json::array({h.force_sin[0], h.force_sin[1]})}};
  nlohmann::ordered_json moment;
  for (int k = 0; k < 3; ++k) {
    if (k < 2 && !axial) {
      moment[kAxes[k]] = nullptr;  // no axial positions: not defined
      continue;
    }
    moment[kAxes[k]] = {{"amplitude", h.calcMomentAmplitude(k)}, {"cos", h.moment_cos[k]}, {"sin", h.moment_sin[k]}};
  }
  j["shaking_moment"] = moment;
  return j;
}

}  // namespace

std::string runBalance(const BalanceOptions& options) {
  Mechanism m = loadScene(options.scene_path);
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
    doc["harmonics"] = nlohmann::ordered_json::array();
    for (const validation::BalanceRow& row : rows) {
      nlohmann::ordered_json h;
      h["n"] = row.n;
      h["analytic"] = harmonicToJson(withExactZeros(row.analytic, row.symmetry), axial);
      for (const auto& [engine, harmonic] : row.engines) h[engine] = harmonicToJson(harmonic, axial);
      const auto& s = row.symmetry;
      auto decided = [&](bool v) { return s.decided ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr); };
      h["vanishes_by_symmetry"] = {{"force", decided(s.force_cancels)},
                                   {"moment_xy", axial ? decided(s.moment_xy_cancels) : nlohmann::ordered_json(nullptr)},
                                   {"moment_z", decided(s.moment_z_cancels)}};
      h["reason"] = reasonOf(s, axial);
      doc["harmonics"].push_back(h);
    }
    return dumpJson(doc);
  }
  std::string out;
  if (options.design > 0)
    out += "balance shafts that cancel harmonic " + std::to_string(options.design) + " of the shaking force (paste into " +
           options.scene_path + "):\n\n" + tables + "\nwith them, every harmonic (the residual):\n";
  out += "balance of " + options.scene_path + " at " + std::to_string(m.speed_rpm) +
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
    const analytic::ShakingHarmonic a = withExactZeros(row.analytic, row.symmetry);
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
