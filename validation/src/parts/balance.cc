// Report part `balance` (9): the balance of engine layouts, computed (calcBalance, balance.h) beside the textbook's claims, what
// the two-term rules miss, and the figure of every harmonic.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "crankcheck/validation/balance.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/layouts.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/validation/part.h"

namespace crankcheck::validation {
namespace {

// The report's balance tables for every layout of layouts.h, built on `parts` (its crank, rod and piston) at
// 6000 rpm, and for each of `scenes` as it is (the user's scenes: harmonics only, no textbook claim), harmonics 1..8
// from the closed forms and each reference engine:
//   balance            layout,description,part,textbook,vanishes_exactly,analytic_amplitude,simbody_amplitude,
//                      mujoco_amplitude,relative_amplitude,verdict (one <engine>_amplitude per reference engine)
//                      (part F1, F2: primary and secondary force [N]; M1, M2: couples about X, Y [N m]; textbook
//                      "vanishes" | "does not vanish" | "no claim"; relative to the force or moment scale of
//                      scales.h; verdict "agrees" | "DIFFERS" | "-")
//   balance_harmonics  layout_index,layout,n,force_relative,couple_relative,rocking_relative,force_vanishes,
//                      couple_vanishes (amplitudes relative to the force and moment scales; exact zeros as 0)
TableSet calcBalanceTables(const Mechanism& parts, const std::vector<Mechanism>& scenes) {
  constexpr int kOrder = 8;
  std::vector<Column> summary_columns = {{"layout", kText},   {"description", kText},      {"part", kText},
                                         {"textbook", kText}, {"vanishes_exactly", kText}, {"analytic_amplitude", "N m"}};
  // each reference engine's amplitude: a force (N) or a couple (N m), as the row's part says
  for (const Engine* engine : listReferenceEngines()) summary_columns.push_back({engine->name + "_amplitude", "SI"});
  summary_columns.insert(summary_columns.end(), {{"relative_amplitude", "-"}, {"verdict", kText}});
  Table summary("balance", std::move(summary_columns));
  Table harmonics("balance_harmonics", {{"layout_index", "-"}, {"layout", kText}, {"n", "-"}, {"force_relative", "-"},
                                        {"couple_relative", "-"}, {"rocking_relative", "-"}, {"force_vanishes", kText},
                                        {"couple_vanishes", kText}});
  Mechanism base = parts;
  base.speed_rpm = 6000.0;
  base.engine.speed = 6000.0 * (M_PI / 30.0);
  std::vector<Layout> layouts = getBalanceLayouts();
  std::vector<Mechanism> mechanisms;
  for (const Layout& layout : layouts) mechanisms.push_back(makeLayoutMechanism(layout, base));
  for (const Mechanism& scene : scenes) {
    layouts.push_back({scene.name, "scene " + scene.name, {}, {}});  // a user's scene: no textbook claim
    mechanisms.push_back(scene);
  }
  for (size_t index = 0; index < layouts.size(); ++index) {
    const Layout& layout = layouts[index];
    const Mechanism& m = mechanisms[index];
    const Scales sc = calcScales(m);
    const std::vector<BalanceRow> rows = calcBalance(m, kOrder);
    for (const BalanceRow& row : rows) {
      const analytic::HarmonicSymmetry& s = row.symmetry;
      const double force = s.force_cancels ? 0.0 : row.analytic.calcForceAmplitude();
      const double couple = s.moment_xy_cancels ? 0.0
                                                : std::hypot(row.analytic.calcMomentAmplitude(0), row.analytic.calcMomentAmplitude(1));
      const double rocking = s.moment_z_cancels ? 0.0 : row.analytic.calcMomentAmplitude(2);
      harmonics.rows.push_back({std::to_string(index), layout.name, std::to_string(row.n), formatNumber(force / sc.force),
                                formatNumber(couple / sc.moment), formatNumber(rocking / sc.moment),
                                s.force_cancels ? "1" : "0", s.moment_xy_cancels ? "1" : "0"});
      if (row.n > 2 || index >= mechanisms.size() - scenes.size()) continue;  // the summary: the balance layouts
      const std::optional<bool> claims[2] = {row.n == 1 ? layout.textbook.F1 : layout.textbook.F2,
                                             row.n == 1 ? layout.textbook.M1 : layout.textbook.M2};
      for (int part = 0; part < 2; ++part) {
        const bool vanishes = part == 0 ? s.force_cancels : s.moment_xy_cancels;
        const double analytic = part == 0 ? force : couple;
        const std::optional<bool>& claim = claims[part];
        std::vector<std::string> fields = {layout.name, layout.description, (part == 0 ? "F" : "M") + std::to_string(row.n),
                                           !claim ? "no claim" : *claim ? "vanishes" : "does not vanish",
                                           vanishes ? "yes" : "no", formatNumber(analytic)};
        for (const auto& [name, h] : row.engines)
          fields.push_back(formatNumber(part == 0 ? h.calcForceAmplitude()
                                                  : std::hypot(h.calcMomentAmplitude(0), h.calcMomentAmplitude(1))));
        fields.push_back(formatNumber(analytic / (part == 0 ? sc.force : sc.moment)));
        fields.push_back(!claim ? "-" : *claim == vanishes ? "agrees" : "DIFFERS");
        summary.rows.push_back(fields);
      }
    }
  }
  return {{"balance", summary}, {"balance_harmonics", harmonics}};
}


// A field as a number; an empty one as 0.
double toDouble(const std::string& s) { return std::strtod(s.c_str(), nullptr); }

// Part 9: the balance table (computed, beside the textbook's claims), what the two-term rules miss, the figure.
void addBalancePart(ReportPart& part, const TableSet& tables, const std::string& caption) {
  part.blocks.push_back({ReportBlock::kParagraph,
                 "Each layout is built on the base scene's crank, rod and piston at 6000 rpm, cylinders spaced along "
                 "the shaft (throws 0.1 m apart, the two cylinders of a shared pin 0.02 m apart, O in the middle). F1, F2: "
                 "primary and secondary shaking force [N]; M1, M2: primary and secondary couple about X and Y [N m]. "
                 "'Vanishes exactly' is decided in integers (sums of roots of unity over the throws), not read off a "
                 "small number; the amplitudes are the closed form's and each reference engine's (a DFT of each engine's own "
                 "shaking force and moment over one revolution). The textbook column is the claim of the standard balance tables "
                 "(two-term piston motion, both cylinders of a pin in one plane). A DIFFERS is a finding, not a failure "
                 "of the engines (they agree, see the summary): for example the 0.02 m between the two cylinders of a "
                 "shared pin, which the tables ignore, gives a flat-plane V8 a secondary couple."});
  {
    std::vector<std::string> headings = {"layout", "part", "textbook", "vanishes exactly", "amplitude (closed form)"};
    std::vector<std::string> names = {"layout", "part", "textbook", "vanishes_exactly", "analytic_amplitude"};
    std::vector<bool> numeric = {false, false, false, false, true};
    for (const Engine* e : listReferenceEngines()) {  // each reference engine's DFT
      headings.push_back("amplitude (" + e->name + ")");
      names.push_back(e->name + "_amplitude");
      numeric.push_back(true);
    }
    headings.insert(headings.end(), {"relative", "verdict"});
    names.insert(names.end(), {"relative_amplitude", "verdict"});
    numeric.insert(numeric.end(), {true, false});
    part.blocks.push_back({ReportBlock::kTable, "", headings, formatRows(tables, "balance", names, numeric)});
  }
  // Beyond the two-term rules: the largest harmonic above 2 that the exact motion leaves, per layout.
  const auto it = tables.find("balance_harmonics");
  if (it != tables.end()) {
    const Table& t = it->second;
    const size_t layout = columnOf(t, "layout"), n = columnOf(t, "n"), force = columnOf(t, "force_relative"),
                 couple = columnOf(t, "couple_relative");
    std::map<std::string, std::pair<std::string, double>> worst_force, worst_couple;
    std::vector<std::string> order;
    for (const auto& row : t.rows) {
      if (!worst_force.count(row[layout])) order.push_back(row[layout]);
      auto& wf = worst_force[row[layout]];
      auto& wc = worst_couple[row[layout]];
      if (std::stoi(row[n]) <= 2) continue;
      if (toDouble(row[force]) > wf.second) wf = {row[n], toDouble(row[force])};
      if (toDouble(row[couple]) > wc.second) wc = {row[n], toDouble(row[couple])};
    }
    ReportBlock beyond{ReportBlock::kTable, "", {"layout", "largest force harmonic above 2", "relative [-]", "largest couple harmonic above 2", "relative [-]"}};
    for (const std::string& name : order) {
      const auto& f = worst_force[name];
      const auto& c = worst_couple[name];
      beyond.rows.push_back({name, f.first.empty() ? "none up to 8" : "n = " + f.first, shortNumber(f.second, 3),
                             c.first.empty() ? "none up to 8" : "n = " + c.first, shortNumber(c.second, 3)});
    }
    part.blocks.push_back({ReportBlock::kParagraph,
                   "Where the textbook rules hold only for the two-term approximation: the exact piston motion has "
                   "harmonics 4, 6, 8, ... (and the rod's swing odd ones in the couples), which the tables do not "
                   "consider. The largest that survives each layout's symmetry, relative to the force (moment) scale:"});
    part.blocks.push_back(beyond);
  }
  part.blocks.push_back({ReportBlock::kFigure, caption, {}, {}, "balance_harmonics"});
}

class BalancePart final : public Part {
 public:
  std::string key() const override { return "balance"; }
  std::string title() const override { return "Balance of engine layouts"; }
  // The layouts on the first scene's parts, and the user's scenes.
  std::vector<Task> tasks(const PartContext& context) const override {
    return {{"balance", false,
             [first = context.first, user = context.user_scenes] { return calcBalanceTables(first, user); }}};
  }
  ReportPart describe(const TableSet& tables) const override {
    ReportPart part;
    if (!tables.count("balance_harmonics")) return part;
    part.heading = heading();
    addBalancePart(part, tables,
                   "The shaking force and the couple about X and Y of every layout of the balance table (and of the "
                   "campaign's own scenes, below the layouts, when scene files were given), harmonics 1-8, relative "
                   "to the force and moment scales: closed form from the exact Fourier coefficients (Simbody's DFT "
                   "agrees, see the summary); white with a dot where the harmonic vanishes exactly by the layout's "
                   "symmetry");
    return part;
  }
  std::vector<std::string> tables() const override { return {"balance", "balance_harmonics"}; }
  std::vector<std::string> figures() const override { return {"balance_harmonics"}; }
};

}  // namespace

namespace parts {
const Part& balance() {
  static const BalancePart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
