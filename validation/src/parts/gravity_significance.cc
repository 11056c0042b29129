// Report part `gravity_significance`: when gravity matters, max |Q| against k, and the paper's claims about
// it tested.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "../part_math.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/balance.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/campaign_scenes.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/table.h"
#include "crankcheck/validation/task.h"
#include "crankcheck/validation/extremum.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/validation/variants.h"
#include "engine_fields.h"
#include "survey.h"

namespace crankcheck::validation {
namespace {

// gravity_significance: max |Q| against k, relative to k = 1 and to the inertia torque at the scene's speed. The
// analytic maximum is that of Q's exact harmonics (no cancellation: exact however small); each reference engine's is
// found on the same grid, refined the same way (extremum.h); below the agreement tolerance it is a bound, not a value.
struct GravityEngineMaximum {
  double max_abs_Q = 0.0;   ///< [N m]
  std::string resolved;     ///< "yes" | "no": max_abs_Q is above the rounding bound (else it is a bound)
  double ratio_to_k1 = 0.0; ///< max_abs_Q (the bound where not resolved) over the engine's own at k = 1
};
struct GravitySignificanceRow {
  std::string cycle;
  int k = 1;
  double max_abs_Q = 0.0, ratio_to_k1 = 0.0, max_inertia_torque = 0.0, ratio_to_inertia = 0.0;  ///< [N m], -, [N m], -
  int first_order = 0;           ///< the first surviving harmonic of Q
  std::string paper_negligible;  ///< "1": k = 7, 9, 11 (Stanczak section 7), else "0"
  double rounding_bound = 0.0;   ///< [N m]
  std::vector<GravityEngineMaximum> engines;  ///< per reference engine (listReferenceEngines' order)
};
std::vector<Field<GravitySignificanceRow>> makeGravitySignificanceFields() {
  using R = GravitySignificanceRow;
  std::vector<Field<R>> fields = {
      textField("cycle", &R::cycle), countField("k", &R::k), numberField("max_abs_Q", "N m", &R::max_abs_Q),
      numberField("ratio_to_k1", "-", &R::ratio_to_k1), numberField("max_inertia_torque", "N m", &R::max_inertia_torque),
      numberField("ratio_to_inertia", "-", &R::ratio_to_inertia), countField("first_order", &R::first_order),
      textField("paper_negligible", &R::paper_negligible), numberField("rounding_bound", "N m", &R::rounding_bound)};
  const std::vector<const Engine*> references = listReferenceEngines();
  for (size_t i = 0; i < references.size(); ++i) {
    const std::string& e = references[i]->name;
    fields.push_back(engineElementField(e + "_max_abs_Q", "N m", &R::engines, i, &GravityEngineMaximum::max_abs_Q));
    fields.push_back(engineElementField(e + "_resolved", "", &R::engines, i, &GravityEngineMaximum::resolved));
    fields.push_back(engineElementField(e + "_ratio_to_k1", "-", &R::engines, i, &GravityEngineMaximum::ratio_to_k1));
  }
  return fields;
}
const Schema<GravitySignificanceRow>& gravitySignificanceTable() {
  return getEngineSchema<GravitySignificanceRow, makeGravitySignificanceFields>("gravity_significance");
}

TableSet calcGravitySignificanceTables(const Mechanism& base, Cycle cycle, bool quick) {
  const std::vector<const Engine*> references = listReferenceEngines();
  std::vector<GravitySignificanceRow> rows;
  double q1 = 0.0;
  std::vector<double> q1_engine(references.size(), 0.0);
  for (int k = 1; k <= 12; ++k) {
    const Mechanism m = withGamma(withCylinders(base, k, cycle), 90.0);
    const auto harmonics = exactHarmonics(m);
    const int first = harmonics.empty() ? 0 : harmonics.front().n;
    const int samples = samplesForOrder(first);
    const double max_q = maxAbsOfHarmonics(harmonics);
    const double max_inertia = findMaxAbsOverTurn([&](double phi) {
      return analytic::calcReactions(m, phi).drive_torque - analytic::calcGravityTorque(m, phi); }, samples).value;
    if (k == 1) q1 = max_q;
    // Below the agreement tolerance an engine's Q(phi) is rounding, not physics (CONVENTIONS.md: tiny values are
    // compared absolutely against the scale): the engine then shows only that |Q| is below the bound.
    const double bound = kAgreementMultiple * kEps * calcEnergyScale(m);
    const bool paper_negligible = k == 7 || k == 9 || k == 11;  // Stanczak section 7
    GravitySignificanceRow row{toString(cycle), k, max_q, max_q / q1, max_inertia,
                               max_inertia > 0 ? max_q / max_inertia : 0.0, first, paper_negligible ? "1" : "0", bound, {}};
    for (size_t i = 0; i < references.size(); ++i) {
      const std::unique_ptr<EngineModel> model = buildGravityModel(*references[i], m);
      // Every hump of |Q| is the same height to rounding (the first surviving harmonic dominates by 1 / lambda^2), so
      // two refinements find the maximum.
      const double max_q_engine =
          findMaxAbsOverTurn([&](double phi) { return model->calcQ(phi); }, samples, 2, getAngleTolerance(quick)).value;
      if (k == 1) q1_engine[i] = max_q_engine;
      const bool resolved = max_q_engine > bound;
      row.engines.push_back({max_q_engine, resolved ? "yes" : "no",
                             resolved ? max_q_engine / q1_engine[i] : bound / q1_engine[i]});
    }
    rows.push_back(std::move(row));
  }
  return gravitySignificanceTable().tableSet(std::move(rows));
}

// The part's claims: the paper's dividing line and its practical list, tested with stated thresholds on max |Q|
// relative to the single cylinder of the same cycle (the exact harmonics' maxima, gravity_significance).
void addGravityClaims(ReportPart& part, const TableSet& tables) {
  std::map<std::string, std::map<int, double>> ratio;  // cycle -> k -> max |Q| / max |Q|(k = 1)
  for (const GravitySignificanceRow& r : getRows(tables, gravitySignificanceTable())) ratio[r.cycle][r.k] = r.ratio_to_k1;
  if (ratio.empty()) return;
  const std::vector<int> matters = {1, 2, 3, 4, 5, 6, 8, 10, 12}, negligible = {7, 9, 11};
  auto list = [](const std::vector<int>& ks) {
    std::string s;
    for (int k : ks) s += (s.empty() ? "" : ", ") + std::to_string(k);
    return "{" + s + "}";
  };
  ReportBlock claims{ReportBlock::kTable, "", {"claim (Stanczak section 7)", "cycle", "test", "paper", "data", "deciding ratios", "verdict"}};
  std::string sentence;
  for (const auto& [cycle, by_k] : ratio) {
    if (by_k.size() < 12) continue;
    // The dividing line holds when every k it says matters has a larger max |Q| than every k it says is negligible.
    int k_low = matters.front(), k_high = negligible.front();
    for (int k : matters) if (by_k.at(k) < by_k.at(k_low)) k_low = k;
    for (int k : negligible) if (by_k.at(k) > by_k.at(k_high)) k_high = k;
    const double margin = by_k.at(k_low) / by_k.at(k_high);
    claims.rows.push_back({"gravity matters for k = 1..6, 8, 10, 12, negligible for 7, 9, 11", cycle,
                           "some threshold separates the two sets (min of the first / max of the second > 1)",
                           list(negligible) + " below all others", "smallest of the first: k = " + std::to_string(k_low) +
                               ", largest of the second: k = " + std::to_string(k_high),
                           "k = " + std::to_string(k_low) + ": " + shortNumber(by_k.at(k_low), 2) + ", k = " +
                               std::to_string(k_high) + ": " + shortNumber(by_k.at(k_high), 2) + " (ratio " +
                               shortNumber(margin, 2) + ")",
                           margin > 1.0 ? "holds, by a factor " + shortNumber(margin, 2) : "does not hold"});
    sentence += (sentence.empty() ? "" : " ") + cycle + ": the weakest engine the paper says gravity matters for (k = " +
                std::to_string(k_low) + ") has " + shortNumber(margin, 2) + " times the max |Q| of the strongest it calls " +
                "negligible (k = " + std::to_string(k_high) + ")" +
                (margin > 1.0 ? ", so the line holds for any threshold between " + shortNumber(by_k.at(k_high), 2) + " and " +
                                    shortNumber(by_k.at(k_low), 2) + " of the single cylinder's max |Q|, far below the "
                                    "thresholds at which the practical list is tested"
                              : ", so no threshold separates them") + ".";
    // The practical list: k = 1, 2, 4 (perhaps 3 and 6), at stated thresholds.
    for (const auto& [threshold, paper] : {std::pair<double, std::vector<int>>{1e-3, {1, 2, 4}},
                                           std::pair<double, std::vector<int>>{1e-5, {1, 2, 3, 4, 6}}}) {
      std::vector<int> data;
      std::string deciding;
      for (const auto& [k, x] : by_k) {
        if (x >= threshold) data.push_back(k);
        const bool in_paper = std::find(paper.begin(), paper.end(), k) != paper.end();
        if ((x >= threshold) != in_paper) deciding += (deciding.empty() ? "" : ", ") + ("k = " + std::to_string(k) + ": " + shortNumber(x, 2));
      }
      claims.rows.push_back({threshold == 1e-3 ? "gravity may matter for k = 1, 2, 4" : "... perhaps also for k = 3, 6", cycle,
                             "max |Q| >= " + shortNumber(threshold, 1) + " of the single cylinder's", list(paper), list(data),
                             deciding.empty() ? "-" : deciding, data == paper ? "holds" : "does not hold"});
    }
  }
  part.blocks.push_back({ReportBlock::kParagraph,
                 "The paper (section 7): 'For k = 7, 9, 11 the influence of gravity on the motion can be neglected as "
                 "negligibly small, since, for example, for k = 7 a non-zero value of formula (16) was obtained only at "
                 "Lambda_14.' And its practical list: gravity 'may be significant in particular for heavy, medium- or "
                 "high-speed mechanisms with k = 1, 2, 4 (possibly also k = 3, 6)'. Both tested as claims, on max |Q| "
                 "relative to the single cylinder of the same cycle (the thresholds are stated in each row):"});
  part.blocks.push_back(claims);
  if (!sentence.empty()) part.blocks.push_back({ReportBlock::kParagraph, sentence});
}

class GravitySignificancePart final : public Part {
 public:
  std::string key() const override { return "gravity_significance"; }
  std::string title() const override { return "When gravity matters"; }
  // One task per cycle.
  std::vector<Task> tasks(const PartContext& context) const override {
    std::vector<Task> out;
    for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke})
      out.push_back({"gravity_significance " + toString(cycle), false,
                     [base = context.base, cycle, quick = context.quick] {
                       return calcGravitySignificanceTables(base, cycle, quick);
                     }});
    return out;
  }
  ReportPart describe(const TableSet& tables) const override {
    ReportPart part;
    if (!tables.count(key())) return part;
    part.heading = heading();
    // The speed of the inertia torque: the survey's base's (the first scene's), said by name where the table has it.
    const std::optional<survey::SurveyBaseRow> base = survey::findSurveyBase(tables);
    const std::string speed = base ? base->scene + "'s speed, " + shortNumber(base->speed_rpm, 4) + " rpm, for every k"
                                   : "the base scene's speed";
    const std::vector<your_engine::SceneFactsRow> users = survey::listUserScenes(tables);
    part.blocks.push_back({ReportBlock::kFigure,
                           "Max |Q| against k (standing inline engines on the base scene's parts), relative to k = 1 "
                           "and relative to the inertia torque at " + speed,
                           {}, {}, key()});
    part.blocks.push_back({ReportBlock::kParagraph,
                           "max |Q| is the maximum over the turn of Q's exact harmonics (no cancellation, so it is exact however "
                           "small); each reference engine's is found on the same grid (6 samples per period of the first surviving "
                           "harmonic, at least 48) and refined the same way (Brent's method). Where an engine's max |Q| is below "
                           "the rounding bound (64 eps of the energy scale) it shows only that |Q| is below the bound: 'resolves' "
                           "= no, and the figure draws the first reference engine's bound as an arrow down."});
    std::vector<std::string> headings = {"cycle", "k", "first order", "max |Q| [N m]", "/ k = 1", "max inertia torque [N m]",
                                         "max |Q| / inertia", "rounding bound [N m]"};
    for (const Engine* e : listReferenceEngines())
      headings.insert(headings.end(), {e->name + " max |Q| [N m]", e->name + " resolves"});
    // Where the user's engines sit: the rows of their k and cycle (the scenes given; none in the default campaign).
    if (!users.empty()) headings.push_back("your engine(s)");
    auto yours = [&users](const GravitySignificanceRow& r) {
      std::vector<std::string> names;
      for (const your_engine::SceneFactsRow& f : users)
        if (f.cylinders == r.k && f.cycle == r.cycle) names.push_back(f.scene);
      return names.empty() ? std::string() : "your engine(s): " + survey::joinNames(names);
    };
    std::vector<std::vector<std::string>> rows;
    for (const GravitySignificanceRow& r : getRows(tables, gravitySignificanceTable())) {
      std::vector<std::string> row = {r.cycle, std::to_string(r.k), std::to_string(r.first_order), shortNumber(r.max_abs_Q, 4),
                                      shortNumber(r.ratio_to_k1, 4), shortNumber(r.max_inertia_torque, 4),
                                      shortNumber(r.ratio_to_inertia, 4), shortNumber(r.rounding_bound, 4)};
      for (const GravityEngineMaximum& e : r.engines) row.insert(row.end(), {shortNumber(e.max_abs_Q, 4), e.resolved});
      if (!users.empty()) row.push_back(yours(r));
      rows.push_back(std::move(row));
    }
    part.blocks.push_back({ReportBlock::kTable, "", headings, std::move(rows)});
    if (!users.empty()) {
      std::vector<std::string> names;
      for (const your_engine::SceneFactsRow& f : users)
        names.push_back(f.scene + " (k = " + std::to_string(f.cylinders) + ", " + f.cycle + ")");
      part.blocks.push_back({ReportBlock::kParagraph,
                             "The column 'your engine(s)' marks the rows of your engines' k and cycle: " +
                                 survey::joinNames(names) + ". Those rows are standing inline engines on the base "
                                 "scene's parts; each engine's own gravity, in its layout at its speed, is in its "
                                 "section above."});
    }
    addGravityClaims(part, tables);
    return part;
  }
  std::vector<const TableSchema*> schemas() const override { return {&gravitySignificanceTable()}; }
  std::vector<ReportedMaximum> maxima() const override {
    std::vector<ReportedMaximum> out = {
        {"gravity_significance", {"cycle", "k"}, {"max_abs_Q", "ratio_to_k1", "max_inertia_torque", "ratio_to_inertia"}, "", ""}};
    for (const Engine* e : listReferenceEngines())  // an engine's max |Q| below its rounding bound is a bound
      out.push_back({"gravity_significance", {"cycle", "k"}, {e->name + "_max_abs_Q"}, e->name + "_resolved", "no"});
    return out;
  }
};

}  // namespace

namespace parts {
const Part& gravitySignificance() {
  static const GravitySignificancePart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
