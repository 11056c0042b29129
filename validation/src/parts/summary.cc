// The report's summary of the families of cases (always run, not numbered): the analytic engine against every exact
// engine, the worst comparison of each (engine, quantity, family) from the cross-checks the verdict part runs.
#include <string>
#include <vector>

#include "crankcheck/validation/crosscheck.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/parts.h"
#include "crankcheck/validation/verdict.h"
#include "crankcheck/validation/report_format.h"

namespace crankcheck::validation {
namespace {

// The exact engines in play, by their libraries: "Simbody, MuJoCo".
std::string listExactNames() {
  std::string names;
  for (const Engine* e : listReferenceEngines()) names += (names.empty() ? "" : ", ") + getLibraryName(*e);
  return names;
}

class SummaryPart final : public Part {
 public:
  std::string key() const override { return "summary"; }
  std::string title() const override { return "Summary: the analytic engine against every exact engine"; }
  bool always() const override { return true; }
  std::vector<Task> tasks(const PartContext&) const override { return {}; }
  std::vector<std::string> figures() const override { return {}; }
  ReportPart describe(const TableSet& tables) const override {
    ReportPart part;
    if (!tables.count(kCrossCheckTable.name())) return part;  // not run: left out
    part.heading = heading();
    const std::vector<SummaryRow> summary = summarize(tables);
    bool all_pass = true;
    for (const SummaryRow& s : summary) all_pass = all_pass && s.pass;
    std::string soft;  // the parts that measure the soft engines
    for (const Part* p : listParts())
      if (p->key() == "engines") soft = " MuJoCo's soft solver is measured in part " + std::to_string(p->number()) + ", not gated.";
    part.blocks.push_back({ReportBlock::kParagraph,
                           std::string(all_pass ? "Every comparison agrees" : "SOME COMPARISONS FAIL") +
                               " within the gate's rule: |analytic - engine| <= 64 eps x scale x conditioning "
                               "(docs/CONVENTIONS-crankcheck.md), for each exact engine (" + listExactNames() + "). "
                               "Errors are relative to the quantity's physical scale." + soft});
    ReportBlock table{ReportBlock::kTable, "", {"engine", "quantity", "family", "worst error / scale [-]", "where",
                                                "tolerance / scale [-]", "result"}};
    for (const SummaryRow& s : summary)
      table.rows.push_back({s.engine, s.quantity, s.family, shortNumber(s.worst_rel_error), s.where,
                            shortNumber(s.tolerance_rel), s.pass ? "pass" : "FAIL"});
    part.blocks.push_back(table);
    return part;
  }
};

}  // namespace

namespace parts {
const Part& summary() {
  static const SummaryPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
