// The report's verdict (always run, not numbered): the cross-checks of every family of cases and of the gate's sweep
// (crosscheck.h), and the verdict drawn from them (verdict.h): one line per engine, the closing line, the engine x
// quantity matrix.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "crankcheck/validation/crosscheck.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/validation/variants.h"
#include "crankcheck/validation/verdict.h"

namespace crankcheck::validation {
namespace {

// Every family's scene at its own lambda and, in the full campaign, with the rod changed to lambda = 0.1 .. 0.9.
void addFamilyTasks(const PartContext& context, std::vector<Task>& tasks) {
  const std::vector<double> sweep =
      context.quick ? std::vector<double>{} : std::vector<double>{0.1, 0.2, 0.3, 0.4, 0.6, 0.9};
  for (const auto& [family, m] : context.families) {
    std::vector<double> lambdas = {calcCrankRatio(m)};
    // A pin offset needs |delta| < l - r: the rod changed to lambda must still reach the crank pin at every angle.
    const double offset = calcLoopRatio(m) * m.rod.length - m.crank.radius;  // max |delta_j|
    for (double lambda : sweep)
      if (std::fabs(lambda - calcCrankRatio(m)) > 1e-3 && offset < m.crank.radius / lambda - m.crank.radius)
        lambdas.push_back(lambda);
    for (double lambda : lambdas) {
      const Mechanism variant = withLambda(m, lambda);
      char id[128];
      std::snprintf(id, sizeof id, "crosscheck %s lambda=%.3g", m.name.c_str(), lambda);
      const std::vector<double> angles = anglesDeg(context.quick ? 45.0 : 15.0);
      tasks.push_back({id, false,
                       [family = family, variant, angles] {
                         return kCrossCheckTable.tableSet(crossCheckCases(family, {variant}, angles));
                       },
                       task_cost::kCrossCheck});
    }
  }
}

// The gate's sweep (tests/gate): every k and stroke over lambda and gamma, at the gate's crank angles (both dead
// centres and quarter turns), at speed and at rest, on the base scene's parts. Only in the built-in campaign.
void addGateSweepTasks(const PartContext& context, std::vector<Task>& tasks) {
  const bool quick = context.quick;
  const std::vector<double> sweep_lambdas =
      quick ? std::vector<double>{0.3, 0.999}
            : std::vector<double>{1e-6, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.9, 0.999};
  const std::vector<double> sweep_gammas =
      quick ? std::vector<double>{90.0, 37.0} : std::vector<double>{0.0, 180.0, 90.0, -90.0, 37.0};
  const std::vector<double> gate_angles = {0.0, 17.0, 45.0, 90.0, 133.0, 180.0, 222.5, 270.0, 300.0, 359.0, -60.0};
  // The soft ways (measured, never gated) on k = 1 and 2 and the four-stroke k = 12 only, every lambda and gamma of
  // them: the full sweep puts every one of their worst errors per quantity there, at a sixth of its cost
  // (bench/README.md, "The soft ways' subset of the gate's sweep").
  auto measuresSoft = [](int k, Cycle cycle) { return k <= 2 || (k == 12 && cycle == Cycle::kFourStroke); };
  for (int k = 12; k >= 1; --k)
    for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke}) {
      const bool two = cycle == Cycle::kTwoStroke;
      const std::string family = std::string("gate sweep ") + (two ? "two" : "four") + "-stroke (k = 1..12)";
      const Mechanism kbase = withSpeed(withCylinders(context.base, k, cycle), two ? 3000.0 : 6000.0);
      tasks.push_back({"sweep k=" + std::to_string(k) + " " + toString(cycle), false,
                       [family, kbase, k, two, sweep_lambdas, sweep_gammas, gate_angles, soft = measuresSoft(k, cycle)] {
                         std::vector<CrossCheckRow> rows;
                         for (double lambda : sweep_lambdas) {
                           // The gammas of one lambda in lockstep (crossCheckCases: one assembly per angle).
                           std::vector<Mechanism> variants;
                           for (double gamma : sweep_gammas) {
                             Mechanism variant = withGamma(withLambda(kbase, lambda), gamma);
                             char name[96];
                             std::snprintf(name, sizeof name, "k%d_%s_%s", k, two ? "two" : "four", gammaTag(gamma).c_str());
                             variant.name = name;
                             variants.push_back(std::move(variant));
                           }
                           for (CrossCheckRow& row : crossCheckCases(family, variants, gate_angles, soft))
                             rows.push_back(std::move(row));
                         }
                         return kCrossCheckTable.tableSet(std::move(rows));
                       },
                       task_cost::kGateSweep});
    }
}

class VerdictPart final : public Part {
 public:
  std::string key() const override { return "verdict"; }
  std::string title() const override { return "Verdict"; }
  bool always() const override { return true; }
  std::vector<Task> tasks(const PartContext& context) const override {
    std::vector<Task> out;
    addFamilyTasks(context, out);
    if (context.user_scenes.empty()) addGateSweepTasks(context, out);
    return out;
  }
  std::vector<const TableSchema*> schemas() const override { return {&kCrossCheckTable}; }
  std::vector<std::string> figures() const override { return {}; }
  ReportPart describe(const TableSet& tables) const override {
    ReportPart part;
    if (!tables.count(kCrossCheckTable.name())) return part;  // not run: left out
    const std::vector<EngineVerdict> verdicts = calcVerdicts(tables);
    part.heading = heading();
    const std::string closing = formatVerdictClosing(verdicts);
    part.blocks.push_back({ReportBlock::kParagraph,
                           std::string(allAgree(verdicts) ? "**Pass.** " : "**FAIL.** ") + closing + "."});
    ReportBlock verdict_table{ReportBlock::kTable, "", {"engine", "gated", "cases", "comparisons",
                                                        "worst error / tolerance [-]", "worst error / scale [-]", "of",
                                                        "result"}};
    std::string where;  // each engine's worst comparison, for the sentence under the matrix
    for (const EngineVerdict& v : verdicts) {
      verdict_table.rows.push_back({v.engine, v.gated ? "gated" : "measured", std::to_string(v.cases),
                                    std::to_string(v.comparisons), v.gated ? formatMatrixCell(v.worst_ratio) : "-",
                                    shortNumber(v.worst_error), v.worst_quantity,
                                    !v.gated ? "reported" : v.failed == 0 ? "pass" : "FAIL (" + std::to_string(v.failed) + ")"});
      where += (where.empty() ? "" : "; ") + v.engine + ": " + v.worst_quantity + " at " + v.worst_where;
    }
    part.blocks.push_back(verdict_table);
    const VerdictMatrix matrix = calcVerdictMatrix(tables);
    part.blocks.push_back({ReportBlock::kParagraph,
                           "Worst error / tolerance by quantity and gated engine (green up to 1/8, yellow up to 1/2, "
                           "orange up to 1, red beyond: FAIL):"});
    ReportBlock matrix_table{ReportBlock::kTable, "", {"quantity"}};
    for (const std::string& e : matrix.engines) matrix_table.header.push_back(e + " [-]");
    for (size_t q = 0; q < matrix.quantities.size(); ++q) {
      std::vector<std::string> row = {matrix.quantities[q]};
      for (size_t e = 0; e < matrix.engines.size(); ++e) row.push_back(formatMatrixCell(matrix.ratio[e][q]));
      matrix_table.rows.push_back(row);
    }
    part.blocks.push_back(matrix_table);
    part.blocks.push_back({ReportBlock::kParagraph,
                           "A comparison is one quantity of one case (a scene at one lambda), the worst over its crank "
                           "angles and speeds, judged by the gate's rule |analytic - engine| <= 64 eps x scale x "
                           "conditioning (docs/CONVENTIONS-crankcheck.md); soft engines are measured, never gated. The "
                           "worst comparisons: " + where + "."});
    return part;
  }
};

}  // namespace

namespace parts {
const Part& verdict() {
  static const VerdictPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
