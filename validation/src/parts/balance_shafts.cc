// Report part `balance_shafts`: what balance shafts designed by `crankcheck balance --design N` cancel, by every
// exact engine.
//
// The cases: the base scene's parts at 6000 rpm as a standing single cylinder with the shafts that cancel its primary
// force (design 1: a shaft turning with the crank and one against it, the second the primary balancer, ratio -1),
// as an inline four with the pair that cancels its secondary force (design 2: a Lanchester pair, ratios 2 and -2),
// and each campaign scene that carries `[[balance_shaft]]` tables as it is (the example offset four with its pair),
// each beside the same engine without shafts.

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>

#include "crankcheck/validation/balance.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/variants.h"
#include "survey.h"

namespace crankcheck::validation {
namespace {

constexpr int kOrder = 6;

// balance_shafts: per case, with and without its shafts ("none" | "with"), engine and harmonic n = 1..6, the amplitude
// of harmonic n of the shaking force and that amplitude relative to the force scale (scales.h) of the engine without
// shafts. Engine "analytic": the closed form, its exact zeros as 0; each other exact engine: a DFT of its own shaking
// force over a revolution. Each series together, in n.
struct BalanceShaftRow {
  std::string case_name, shafts, engine;
  int n = 1;
  double force_amplitude = 0.0;  ///< [N]
  double force_relative = 0.0;
};
const Schema<BalanceShaftRow> kBalanceShaftsTable{
    "balance_shafts",
    {textField("case", &BalanceShaftRow::case_name), textField("shafts", &BalanceShaftRow::shafts),
     textField("engine", &BalanceShaftRow::engine), countField("n", &BalanceShaftRow::n),
     numberField("force_amplitude", "N", &BalanceShaftRow::force_amplitude),
     numberField("force_relative", "-", &BalanceShaftRow::force_relative)}};

// The rows of one engine (with or without its shafts): every harmonic from the closed form (its exact zeros as 0) and
// from each other exact engine's DFT, relative to `force_scale`.
void addShaftRows(std::vector<BalanceShaftRow>& t, const std::string& kase, const std::string& shafts, const Mechanism& m, double force_scale) {
  for (const BalanceRow& row : calcBalance(m, kOrder)) {
    std::vector<std::pair<std::string, double>> amplitudes = {
        {getClosedFormEngine().name, withExactZeros(row.analytic, row.symmetry).calcForceAmplitude()}};
    for (const auto& [name, h] : row.engines) amplitudes.emplace_back(name, h.calcForceAmplitude());
    for (const auto& [engine, a] : amplitudes)
      t.push_back({kase, shafts, engine, row.n, a, a / force_scale});
  }
}

// The part's table on `parts` (its crank, rod and piston) and the `scenes` with balance shafts.
// @throws std::runtime_error if an engine fails.
TableSet calcBalanceShaftTables(const Mechanism& parts, const std::vector<Mechanism>& scenes) {
  std::vector<BalanceShaftRow> t;
  Mechanism base = withSpeed(withGamma(parts, 90.0), 6000.0);
  base.balance_shafts.clear();
  base.machine.pin_offsets.clear();
  base.gas.reset();
  struct Case {
    std::string name;
    Mechanism without, with;
  };
  std::vector<Case> cases;
  for (const auto& [k, n, what] : {std::tuple{1, 1, "single cylinder: shafts for n = 1"},
                                   std::tuple{4, 2, "inline four: Lanchester pair for n = 2"}}) {
    Case c{what, withCylinders(base, k, Cycle::kFourStroke), {}};
    c.with = c.without;
    c.with.balance_shafts = designBalanceShafts(c.without, n);
    cases.push_back(std::move(c));
  }
  for (const Mechanism& scene : scenes) {
    if (scene.balance_shafts.empty()) continue;
    Case c{"scene " + scene.name, scene, scene};
    c.without.balance_shafts.clear();
    cases.push_back(std::move(c));
  }
  for (const Case& c : cases) {
    const double force_scale = calcScales(c.without).force;
    addShaftRows(t, c.name, "none", c.without, force_scale);
    addShaftRows(t, c.name, "with", c.with, force_scale);
  }
  return kBalanceShaftsTable.tableSet(std::move(t));
}

// The part as the report shows it under `heading`: figure caption, sentences read from the data; an empty heading
// without data.
ReportPart describeBalanceShaftPart(const TableSet& tables, const std::string& heading) {
  ReportPart part;
  const std::vector<BalanceShaftRow>& rows = getRows(tables, kBalanceShaftsTable);
  if (rows.empty()) return part;
  part.heading = heading;
  part.caption =
      "The amplitude of each harmonic n of the shaking force relative to the force scale, without balance shafts "
      "(grey) and with them (colours: the closed form as a line, each other exact engine's DFT as points): "
      "the base scene's parts at 6000 rpm (" + std::string(survey::kNotSceneSpeed) + ", without gas) as a single "
      "cylinder with the shafts crankcheck balance --design 1 gives and as an inline four with the Lanchester pair of "
      "--design 2, and each campaign scene with [[balance_shaft]] tables as given, at its own speed. "
      "Exact zeros and amplitudes below 1e-17 are drawn at 1e-17";
  // case -> n -> (analytic without, analytic with, worst engine with (relative), its engine)
  struct Harmonic {
    double without = 0.0, with = 0.0, engine_worst = 0.0, without_rel = 0.0;
    std::string engine;
  };
  std::map<std::string, std::map<int, Harmonic>> cases;
  std::map<std::string, double> force_scale;  // [N] of each case's engine without shafts
  std::vector<std::string> order;
  for (const BalanceShaftRow& row : rows) {
    if (!cases.count(row.case_name)) order.push_back(row.case_name);
    Harmonic& h = cases[row.case_name][row.n];
    const double a = row.force_amplitude, r = row.force_relative;
    if (r > 0.0) force_scale[row.case_name] = a / r;
    if (row.engine == getClosedFormEngine().name) {
      (row.shafts == "none" ? h.without : h.with) = a;
      if (row.shafts == "none") h.without_rel = r;
    } else if (row.shafts == "with" && r >= h.engine_worst) {
      h.engine_worst = r;
      h.engine = row.engine;
    }
  }
  for (const std::string& name : order) {
    // The harmonic the shafts cancel: the one whose closed-form amplitude fell the most.
    int cancelled = 0;
    double best = 1.0;
    for (const auto& [k, h] : cases[name]) {
      if (h.without <= 0.0) continue;
      const double left = h.with / h.without;
      if (left < best) best = left, cancelled = k;
    }
    if (cancelled == 0) {
      part.paragraphs.push_back(name + ": the shafts cancel no harmonic of the shaking force.");
      continue;
    }
    const Harmonic& h = cases[name][cancelled];
    double others = 0.0;  // the largest change the shafts make to any other harmonic, relative to the force scale
    for (const auto& [k, o] : cases[name])
      if (k != cancelled) others = std::max(others, std::fabs(o.with - o.without) / force_scale[name]);
    part.paragraphs.push_back(name + ": harmonic " + std::to_string(cancelled) + " of the shaking force falls from " +
                              shortNumber(h.without, 4) + " N (" + shortNumber(h.without_rel, 3) +
                              " of the force scale) to " + shortNumber(h.with, 2) + " N in closed form; the largest "
                              "residual of the other exact engines is " + shortNumber(h.engine_worst, 2) +
                              " of the force scale (" + h.engine + "); " +
                              (others == 0.0 ? std::string("the closed form of every other harmonic is unchanged.")
                                             : "the other harmonics change by at most " + shortNumber(others, 2) +
                                                   " of the force scale."));
  }
  return part;
}

class BalanceShaftsPart final : public Part {
 public:
  std::string key() const override { return "balance_shafts"; }
  std::string title() const override { return "Balance shafts: what a designed set cancels, by every engine"; }
  // Designed sets on the base's parts, and the scenes that carry shafts.
  std::vector<Task> tasks(const PartContext& context) const override {
    return {{"balance_shafts", false,
             [base = context.base, scenes = context.scenes] { return calcBalanceShaftTables(base, scenes); }}};
  }
  ReportPart describe(const TableSet& tables) const override { return describeBalanceShaftPart(tables, heading()); }
  std::vector<const TableSchema*> schemas() const override { return {&kBalanceShaftsTable}; }
};

}  // namespace

namespace parts {
const Part& balanceShafts() {
  static const BalanceShaftsPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
