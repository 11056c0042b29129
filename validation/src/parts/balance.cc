// Report part `balance`: the balance of engine layouts, computed (calcBalance, balance.h) beside the textbook's claims, what
// the two-term rules miss, and the figure of every harmonic.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "crankcheck/validation/balance.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/layouts.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/validation/part.h"
#include "engine_fields.h"
#include "survey.h"

namespace crankcheck::validation {
namespace {

// balance: the summary beside the textbook's claims, per balance layout and part (F1, F2: primary and secondary
// shaking force [N]; M1, M2: couples about X, Y [N m]): the textbook's claim, whether it vanishes exactly, the closed
// form's amplitude and each reference engine's (a DFT of its own), the amplitude relative to the force or moment scale
// (scales.h), and the verdict.
struct BalanceSummaryRow {
  std::string layout, description, part;
  std::string textbook;          ///< "vanishes" | "does not vanish" | "no claim"
  std::string vanishes_exactly;  ///< "yes" | "no"
  double analytic_amplitude = 0.0;        ///< [N] or [N m], as the part says
  std::vector<double> engine_amplitudes;  ///< per reference engine (listReferenceEngines' order)
  double relative_amplitude = 0.0;
  std::string verdict;  ///< "agrees" | "DIFFERS" | "-"
};
std::vector<Field<BalanceSummaryRow>> makeBalanceSummaryFields() {
  using R = BalanceSummaryRow;
  std::vector<Field<R>> fields = {textField("layout", &R::layout), textField("description", &R::description),
                                  textField("part", &R::part), textField("textbook", &R::textbook),
                                  textField("vanishes_exactly", &R::vanishes_exactly),
                                  numberField("analytic_amplitude", "N m", &R::analytic_amplitude)};
  // each reference engine's amplitude: a force (N) or a couple (N m), as the row's part says
  addEngineNumberFields(fields, "_amplitude", "SI", &R::engine_amplitudes);
  fields.push_back(numberField("relative_amplitude", "-", &R::relative_amplitude));
  fields.push_back(textField("verdict", &R::verdict));
  return fields;
}
const Schema<BalanceSummaryRow>& balanceSummaryTable() {
  return getEngineSchema<BalanceSummaryRow, makeBalanceSummaryFields>("balance");
}

// balance_harmonics: per layout (its index in the figure) and harmonic n = 1..8, the amplitudes relative to the force
// and moment scales (exact zeros as 0), and whether the force and the couple vanish exactly ("1" | "0").
struct BalanceHarmonicRow {
  int layout_index = 0;
  std::string layout;
  int n = 1;
  double force_relative = 0.0, couple_relative = 0.0, rocking_relative = 0.0;
  std::string force_vanishes, couple_vanishes;
};
const Schema<BalanceHarmonicRow> kBalanceHarmonicsTable{
    "balance_harmonics",
    {countField("layout_index", &BalanceHarmonicRow::layout_index), textField("layout", &BalanceHarmonicRow::layout),
     countField("n", &BalanceHarmonicRow::n), numberField("force_relative", "-", &BalanceHarmonicRow::force_relative),
     numberField("couple_relative", "-", &BalanceHarmonicRow::couple_relative),
     numberField("rocking_relative", "-", &BalanceHarmonicRow::rocking_relative),
     textField("force_vanishes", &BalanceHarmonicRow::force_vanishes),
     textField("couple_vanishes", &BalanceHarmonicRow::couple_vanishes)}};

// The report's balance tables for every layout of layouts.h, built on `parts` (its crank, rod and piston) at
// 6000 rpm, and for each of `scenes` as it is (the user's scenes, at their own speed: no textbook claim), harmonics 1..8
// from the closed forms and each reference engine.
TableSet calcBalanceTables(const Mechanism& parts, const std::vector<Mechanism>& scenes) {
  constexpr int kOrder = 8;
  std::vector<BalanceSummaryRow> summary;
  std::vector<BalanceHarmonicRow> harmonics;
  Mechanism base = parts;
  base.speed_rpm = 6000.0;
  base.machine.speed = 6000.0 * (M_PI / 30.0);
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
      harmonics.push_back({static_cast<int>(index), layout.name, row.n, force / sc.force, couple / sc.moment,
                           rocking / sc.moment, s.force_cancels ? "1" : "0", s.moment_xy_cancels ? "1" : "0"});
      if (row.n > 2) continue;  // the summary: the balance layouts, then the user's scenes (no textbook claim)
      const std::optional<bool> claims[2] = {row.n == 1 ? layout.textbook.F1 : layout.textbook.F2,
                                             row.n == 1 ? layout.textbook.M1 : layout.textbook.M2};
      for (int part = 0; part < 2; ++part) {
        const bool vanishes = part == 0 ? s.force_cancels : s.moment_xy_cancels;
        const double analytic = part == 0 ? force : couple;
        const std::optional<bool>& claim = claims[part];
        BalanceSummaryRow fields{layout.name, layout.description, std::string(part == 0 ? "F" : "M").append(std::to_string(row.n)),
                                 !claim ? "no claim" : *claim ? "vanishes" : "does not vanish", vanishes ? "yes" : "no",
                                 analytic, {}, analytic / (part == 0 ? sc.force : sc.moment),
                                 !claim ? "-" : *claim == vanishes ? "agrees" : "DIFFERS"};
        for (const auto& [name, h] : row.engines)
          fields.engine_amplitudes.push_back(part == 0 ? h.calcForceAmplitude()
                                                       : std::hypot(h.calcMomentAmplitude(0), h.calcMomentAmplitude(1)));
        summary.push_back(std::move(fields));
      }
    }
  }
  return {{balanceSummaryTable().name(), balanceSummaryTable().table(std::move(summary))},
          {kBalanceHarmonicsTable.name(), kBalanceHarmonicsTable.table(std::move(harmonics))}};
}

// The part: the balance table (computed, beside the textbook's claims), what the two-term rules miss, the figure.
void addBalancePart(ReportPart& part, const TableSet& tables, const std::string& caption) {
  std::vector<std::string> yours;  // the user's scenes: their rows follow the layouts'
  for (const your_engine::SceneFactsRow& f : survey::listUserScenes(tables)) yours.push_back(f.scene);
  auto isYours = [&yours](const std::string& layout) { return std::find(yours.begin(), yours.end(), layout) != yours.end(); };
  std::string about = "Each layout is built on the base scene's crank, rod and piston at 6000 rpm (";
  about += survey::kNotSceneSpeed;
  about += "; the relative amplitudes do not depend on it), cylinders spaced along "
           "the shaft (throws 0.1 m apart, the two cylinders of a shared pin 0.02 m apart, O in the middle). F1, F2: "
           "primary and secondary shaking force [N]; M1, M2: primary and secondary couple about X and Y [N m]. "
           "'Vanishes exactly' is decided in integers (sums of roots of unity over the throws), not read off a "
           "small number; the amplitudes are the closed form's and each reference engine's (a DFT of each engine's own "
           "shaking force and moment over one revolution). The textbook column is the claim of the standard balance tables "
           "(two-term piston motion, both cylinders of a pin in one plane). A DIFFERS is a finding, not a failure "
           "of the engines (they agree, see the summary): for example the 0.02 m between the two cylinders of a "
           "shared pin, which the tables ignore, gives a flat-plane V8 a secondary couple.";
  if (!yours.empty())
    about += " Below the layouts, marked 'your engine': " + survey::joinNames(yours) +
             ", each exactly as given, at its own speed (no textbook claim).";
  part.blocks.push_back({ReportBlock::kParagraph, about});
  {
    std::vector<std::string> headings = {"layout", "part", "textbook", "vanishes exactly", "amplitude (closed form)"};
    for (const Engine* e : listReferenceEngines()) headings.push_back("amplitude (" + e->name + ")");  // each one's DFT
    headings.insert(headings.end(), {"relative", "verdict"});
    std::vector<std::vector<std::string>> rows;
    for (const BalanceSummaryRow& r : getRows(tables, balanceSummaryTable())) {
      std::vector<std::string> row = {isYours(r.layout) ? r.layout + " (your engine)" : r.layout, r.part, r.textbook,
                                      r.vanishes_exactly, shortNumber(r.analytic_amplitude, 4)};
      for (double a : r.engine_amplitudes) row.push_back(shortNumber(a, 4));
      row.insert(row.end(), {shortNumber(r.relative_amplitude, 4), r.verdict});
      rows.push_back(std::move(row));
    }
    part.blocks.push_back({ReportBlock::kTable, "", headings, std::move(rows)});
  }
  // Beyond the two-term rules: the largest harmonic above 2 that the exact motion leaves, per layout.
  if (tables.count(kBalanceHarmonicsTable.name())) {
    struct Largest {
      int n = 0;  ///< 0: none above 2
      double relative = 0.0;
    };
    std::map<std::string, Largest> worst_force, worst_couple;
    std::vector<std::string> order;
    for (const BalanceHarmonicRow& row : getRows(tables, kBalanceHarmonicsTable)) {
      if (!worst_force.count(row.layout)) order.push_back(row.layout);
      Largest& wf = worst_force[row.layout];
      Largest& wc = worst_couple[row.layout];
      if (row.n <= 2) continue;
      if (row.force_relative > wf.relative) wf = {row.n, row.force_relative};
      if (row.couple_relative > wc.relative) wc = {row.n, row.couple_relative};
    }
    ReportBlock beyond{ReportBlock::kTable, "", {"layout", "largest force harmonic above 2", "relative [-]", "largest couple harmonic above 2", "relative [-]"}};
    for (const std::string& name : order) {
      const auto& f = worst_force[name];
      const auto& c = worst_couple[name];
      beyond.rows.push_back({isYours(name) ? name + " (your engine)" : name, f.n == 0 ? "none up to 8" : "n = " + std::to_string(f.n), shortNumber(f.relative, 3),
                             c.n == 0 ? "none up to 8" : "n = " + std::to_string(c.n), shortNumber(c.relative, 3)});
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
    if (!tables.count(kBalanceHarmonicsTable.name())) return part;
    part.heading = heading();
    addBalancePart(part, tables,
                   "The shaking force and the couple about X and Y of every layout of the balance table (at 6000 rpm, "
                   "not your scene's speed; and of the campaign's own scenes as given, below the layouts, when scene "
                   "files were given), harmonics 1-8, relative "
                   "to the force and moment scales: closed form from the exact Fourier coefficients (" +
                       getReferenceName() + "'s DFT agrees, see the summary); white with a dot where the harmonic vanishes exactly by the layout's "
                   "symmetry");
    return part;
  }
  std::vector<const TableSchema*> schemas() const override { return {&balanceSummaryTable(), &kBalanceHarmonicsTable}; }
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
