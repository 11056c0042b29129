#pragma once
/// @file
/// The verdict of a campaign, read from its crosscheck table: what a person or a CI log reads first. One line per
/// engine compared with the analytic engine (cases, comparisons, the worst error against its tolerance, pass or
/// FAIL; soft engines: measured, never gated), one closing line in ctest's style, and the engine x quantity matrix
/// of worst error / tolerance the report opens with (docs/validate.md).
///
/// A comparison is one row of the crosscheck table: one quantity (of one cylinder or of the whole mechanism) of one
/// case, the worst over the case's crank angles and speeds; a case is one scene at one lambda.

#include <cstddef>
#include <string>
#include <vector>

#include "crankcheck/validation/crosscheck.h"
#include "crankcheck/validation/table.h"

namespace crankcheck::validation {

/// One engine's verdict over every case of the campaign.
struct EngineVerdict {
  std::string engine;            ///< the engine compared with the analytic one
  bool gated = true;             ///< false: a soft engine, measured and reported, never gated
  size_t cases = 0;              ///< distinct (family, case) pairs
  size_t comparisons = 0;        ///< rows of the crosscheck table
  size_t failed = 0;             ///< comparisons beyond their tolerance (gated engines only)
  double worst_ratio = 0.0;      ///< max worst error / tolerance [-] (gated: <= 1 passes)
  double worst_error = 0.0;      ///< worst error / scale [-] of that comparison (soft engines: the largest one)
  std::string worst_quantity;    ///< the quantity of that comparison
  std::string worst_where;       ///< its case, crank angle and speed
  bool pass() const { return !gated || failed == 0; }
};

/// The one rule for the worst comparison everywhere (the terminal's verdict, the report's verdict and summary): the
/// larger value; of equal values (an exact tie) the smaller `where` (its case, crank angle and speed, and quantity, as
/// text), whatever order the rows come in.
inline bool isWorseComparison(double value, const std::string& where, double worst, const std::string& worst_where) {
  return value > worst || (value == worst && where < worst_where);
}

/// One verdict per engine of the crosscheck table, in the engines' registry order (listEngines()); none when the
/// campaign has no crosscheck table (a part's own shard, say). The worst comparison by isWorseComparison.
std::vector<EngineVerdict> calcVerdicts(const TableSet& tables);

/// Where a cross-check row's worst comparison is: "CASE, phi PHI deg, RPM rpm".
std::string formatWhere(const CrossCheckRow& row);

/// The closing lines for the terminal: one per engine and the ctest-style last line, e.g.
///   simbody      gated     624 cases   7488 comparisons  worst 0.15 of tolerance (x_p, ...)  pass
///   100% of comparisons agree, 0 failed out of 14976 (gated engines: simbody, mujoco)
/// @return the lines, each ended by '\n'.
std::string formatVerdict(const std::vector<EngineVerdict>& verdicts);

/// The verdict's closing line alone, without a line break (formatVerdict's last line): ctest's style, "100% of
/// comparisons agree, 0 failed out of N (gated engines: ...)", or that no gated engine was compared.
std::string formatVerdictClosing(const std::vector<EngineVerdict>& verdicts);

/// True when every gated engine's comparisons all agree (true for a table without comparisons: a shard may hold none).
bool allAgree(const std::vector<EngineVerdict>& verdicts);

/// The engine x quantity matrix: for each gated engine (rows) and quantity (columns), the worst error / tolerance
/// over every case; negative where the engine has no comparison of that quantity.
struct VerdictMatrix {
  std::vector<std::string> engines, quantities;
  std::vector<std::vector<double>> ratio;  ///< [engine][quantity]
};
VerdictMatrix calcVerdictMatrix(const TableSet& tables);

/// A matrix cell as the report shows it: a coloured mark from pass to fail and the ratio to two digits: green below
/// 1/8 of the tolerance, yellow up to 1/2, orange up to the tolerance, red beyond (FAIL); "-" without comparisons.
std::string formatMatrixCell(double ratio);

/// One line of the summary: a quantity over one family of cases, the analytic engine against one exact engine.
struct SummaryRow {
  std::string engine;            ///< the engine compared with the analytic one (simbody, mujoco, ...)
  std::string quantity, family;
  double worst_rel_error = 0.0;  ///< worst error / scale over the family
  std::string where;             ///< case, crank angle and speed of the worst
  double tolerance_rel = 0.0;    ///< the agreement tolerance / scale at that case
  bool pass = true;              ///< every comparison of the family agreed
};

/// Groups the crosscheck table by (engine, quantity, family), the gated engines only (soft engines are reported in
/// part engines, never gated). The worst of each by isWorseComparison (verdict.h).
std::vector<SummaryRow> summarize(const TableSet& tables);

/// The summary as a plain-text table for the terminal.
std::string formatSummary(const std::vector<SummaryRow>& summary);

}  // namespace crankcheck::validation
