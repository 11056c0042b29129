#include "crankcheck/validation/verdict.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "crankcheck/validation/report_format.h"
#include "crankcheck/scene/quantities.h"
#include "crankcheck/validation/crosscheck.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/report_document.h"

namespace crankcheck::validation {

namespace {

// The engines in the registry's order, then any other name the table holds (a shard of another build), sorted.
std::vector<std::string> orderEngines(const std::set<std::string>& present) {
  std::vector<std::string> out;
  for (const Engine& e : listEngines())
    if (present.count(e.name)) out.push_back(e.name);
  for (const std::string& name : present)
    if (std::find(out.begin(), out.end(), name) == out.end()) out.push_back(name);
  return out;
}

// The quantities in the catalogue's order (quantities.h), then the others (e.g. "Q (virtual power)") after the one
// whose name they extend, else at the end.
std::vector<std::string> orderQuantities(const std::set<std::string>& present) {
  std::vector<std::string> out;
  for (const Quantity& quantity : getQuantityCatalogue()) {
    const std::string q = quantity.name;
    if (present.count(q)) out.push_back(q);
    for (const std::string& other : present)
      if (other != q && other.rfind(q + " ", 0) == 0) out.push_back(other);
  }
  for (const std::string& q : present)
    if (std::find(out.begin(), out.end(), q) == out.end()) out.push_back(q);
  return out;
}

}  // namespace

std::string formatWhere(const CrossCheckRow& row) {
  return row.case_name + ", phi " + formatNumber(row.where_phi_deg) + " deg, " + formatNumber(row.where_speed_rpm) + " rpm";
}

std::vector<EngineVerdict> calcVerdicts(const TableSet& tables) {
  std::map<std::string, EngineVerdict> by_engine;
  std::map<std::string, std::set<std::pair<std::string, std::string>>> cases;
  for (const CrossCheckRow& row : getRows(tables, kCrossCheckTable)) {
    EngineVerdict& v = by_engine[row.engine];
    const bool first = v.comparisons == 0;
    v.engine = row.engine;
    if (row.pass == "reported") v.gated = false;
    ++v.comparisons;
    cases[row.engine].insert({row.family, row.case_name});
    const double error = row.worst_rel_error, tolerance = row.tolerance_rel;
    const double ratio = error / tolerance;  // tolerances are never zero (scales.h: every scale is positive)
    if (row.pass == "FAIL") ++v.failed;
    // Gated engines: the worst ratio; soft ones (a ratio there is not a verdict): the largest error.
    const std::string where = formatWhere(row);
    const bool worse = first || (row.pass == "reported"
                                     ? isWorseComparison(error, where + row.quantity, v.worst_error,
                                                         v.worst_where + v.worst_quantity)
                                     : isWorseComparison(ratio, where + row.quantity, v.worst_ratio,
                                                         v.worst_where + v.worst_quantity));
    if (worse) {
      v.worst_ratio = ratio;
      v.worst_error = error;
      v.worst_quantity = row.quantity;
      v.worst_where = where;
    }
  }
  std::set<std::string> names;
  for (const auto& [name, v] : by_engine) names.insert(name);
  std::vector<EngineVerdict> out;
  for (const std::string& name : orderEngines(names)) {
    EngineVerdict v = by_engine.at(name);
    v.cases = cases[name].size();
    out.push_back(v);
  }
  return out;
}

bool allAgree(const std::vector<EngineVerdict>& verdicts) {
  return std::all_of(verdicts.begin(), verdicts.end(), [](const EngineVerdict& v) { return v.pass(); });
}

std::string formatVerdict(const std::vector<EngineVerdict>& verdicts) {
  std::ostringstream out;
  size_t width = 6;
  for (const EngineVerdict& v : verdicts) width = std::max(width, v.engine.size());
  char line[600];
  for (const EngineVerdict& v : verdicts) {
    if (v.gated) {
      // Two lines within 100 columns: the count and the verdict, then where the worst comparison is.
      std::snprintf(line, sizeof line, "  %-*s gated    %6zu cases %7zu comparisons  %s\n    worst %s of tolerance (%s: %s)\n",
                    static_cast<int>(width), v.engine.c_str(), v.cases, v.comparisons,
                    v.failed == 0 ? "pass" : ("FAIL (" + std::to_string(v.failed) + ")").c_str(),
                    shortNumber(v.worst_ratio).c_str(), v.worst_quantity.c_str(), v.worst_where.c_str());
    } else {
      std::snprintf(line, sizeof line, "  %-*s measured %6zu cases %7zu comparisons  not gated\n    largest error %s of scale (%s)\n",
                    static_cast<int>(width), v.engine.c_str(), v.cases, v.comparisons, shortNumber(v.worst_error).c_str(),
                    v.worst_quantity.c_str());
    }
    out << line;
  }
  out << formatVerdictClosing(verdicts) << "\n";
  return out.str();
}

std::string formatVerdictClosing(const std::vector<EngineVerdict>& verdicts) {
  size_t gated_comparisons = 0, failed = 0;
  std::string gated_names;
  for (const EngineVerdict& v : verdicts)
    if (v.gated) {
      gated_comparisons += v.comparisons;
      failed += v.failed;
      gated_names += (gated_names.empty() ? "" : ", ") + v.engine;
    }
  if (gated_comparisons == 0) return "No comparison of a gated engine: nothing was checked";
  // ctest's closing line: "100% tests passed, 0 tests failed out of 7". The percentage is floored, so that 100% is
  // printed only when nothing failed.
  const size_t percent = (gated_comparisons - failed) * 100 / gated_comparisons;
  return std::to_string(percent) + "% of comparisons agree, " + std::to_string(failed) + " failed out of " +
         std::to_string(gated_comparisons) + " (gated engines: " + gated_names + ")";
}

VerdictMatrix calcVerdictMatrix(const TableSet& tables) {
  VerdictMatrix m;
  std::map<std::pair<std::string, std::string>, double> worst;
  std::set<std::string> engines, quantities;
  for (const CrossCheckRow& row : getRows(tables, kCrossCheckTable)) {
    if (row.pass == "reported") continue;  // soft engines are measured in part engines, never gated
    engines.insert(row.engine);
    quantities.insert(row.quantity);
    double& w = worst.try_emplace({row.engine, row.quantity}, 0.0).first->second;
    w = std::max(w, row.worst_rel_error / row.tolerance_rel);
  }
  m.engines = orderEngines(engines);
  m.quantities = orderQuantities(quantities);
  for (const std::string& e : m.engines) {
    m.ratio.emplace_back();
    for (const std::string& q : m.quantities) {
      const auto w = worst.find({e, q});
      m.ratio.back().push_back(w == worst.end() ? -1.0 : w->second);
    }
  }
  return m;
}

std::vector<SummaryRow> summarize(const TableSet& tables) {
  std::vector<SummaryRow> out;
  std::map<std::tuple<std::string, std::string, std::string>, SummaryRow> rows;
  for (const CrossCheckRow& row : getRows(tables, kCrossCheckTable)) {
    if (row.pass == "reported") continue;  // a soft engine: measured in part engines, never gated
    SummaryRow& s = rows[{row.engine, row.quantity, row.family}];
    const bool first = s.quantity.empty();
    s.engine = row.engine;
    s.quantity = row.quantity;
    s.family = row.family;
    s.pass = s.pass && row.pass == "pass";
    const double r = row.worst_rel_error;
    const std::string where = formatWhere(row);
    if (first || isWorseComparison(r / row.tolerance_rel, where, s.worst_rel_error / s.tolerance_rel, s.where)) {
      s.worst_rel_error = r;
      s.tolerance_rel = row.tolerance_rel;
      s.where = where;
    }
  }
  for (auto& [key, row] : rows) out.push_back(row);
  return out;
}

std::string formatSummary(const std::vector<SummaryRow>& summary) {
  std::ostringstream out;
  char line[400];
  std::snprintf(line, sizeof line, "%-8s %-18s %-38s %11s  %-54s %10s  %s\n", "engine", "quantity", "family of cases",
                "worst/scale", "where", "tol/scale", "result");
  out << line;
  for (const SummaryRow& s : summary) {
    std::snprintf(line, sizeof line, "%-8s %-18s %-38s %11.2e  %-54s %10.2e  %s\n", s.engine.c_str(), s.quantity.c_str(), s.family.c_str(),
                  s.worst_rel_error, s.where.c_str(), s.tolerance_rel, s.pass ? "pass" : "FAIL");
    out << line;
  }
  return out.str();
}

std::string formatMatrixCell(double ratio) {
  if (ratio < 0.0) return "-";
  // Coloured marks that read the same in Markdown, in HTML and in a terminal: green, yellow, orange, red.
  const char* mark = kCellMarks[ratio <= 0.125 ? 0 : ratio <= 0.5 ? 1 : ratio <= 1.0 ? 2 : 3];
  return std::string(mark) + " " + shortNumber(ratio) + (ratio > 1.0 ? " FAIL" : "");
}

}  // namespace crankcheck::validation
