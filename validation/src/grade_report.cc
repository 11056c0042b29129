// The report of `crankcheck grade` (grade.h): the same machinery as validate's (CSV data, gnuplot figures, Markdown
// and HTML), its own page.
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <map>
#include <optional>
#include <set>

#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/grade.h"
#include "crankcheck/validation/output_folder.h"
#include "crankcheck/validation/report.h"
#include "crankcheck/validation/report_document.h"
#include "crankcheck/validation/report_format.h"

namespace crankcheck::validation {

namespace fs = std::filesystem;

namespace {

// An optional number as the report's tables write it (shortNumber); empty when there is none.
std::string shortOrEmpty(const std::optional<double>& x) { return x ? shortNumber(*x) : std::string(); }

}  // namespace

void renderGradeReport(const TableSet& tables, const std::vector<GradeCase>& cases, const GradeReportInfo& info,
                       const fs::path& dir) {
  writeTables(tables, dir);
  const std::vector<GradeSummaryRow>& summary = getRows(tables, getGradeSummarySchema());
  const std::vector<GradeFailureRow>& failures = getRows(tables, getGradeFailuresSchema());
  const std::vector<GradeLambdaRow>& by_lambda = getRows(tables, getGradeErrorVsLambdaSchema());

  std::string command;
  for (const std::string& word : info.program) command += (command.empty() ? "" : " ") + quoteShellWord(word);
  ReportDocument doc("crankcheck grade report");
  doc.showAsWritten(listSceneNames(tables));
  char line[512];
  std::snprintf(line, sizeof line,
                "crankcheck %s, %s, %s; %zu cases%s, %d job%s%s, %.1f s, timeout %.3g s per request.",
                getCrankcheckVersion(), joinEngineLibraries().c_str(), formatToday().c_str(), cases.size(),
                info.quick ? " (--quick)" : "", info.jobs, info.jobs == 1 ? "" : "s", info.batch ? ", --batch" : "",
                info.seconds, info.timeout_seconds);
  doc.addParagraph("Graded program: " + formatCodeSpan(command) + "\n\n" + line);
  const std::vector<const Engine*> judges = listGradeJudges();
  std::string names;  // "simbody / analytic / mujoco"
  for (const Engine* judge : judges) names += (names.empty() ? "" : " / ") + judge->name;
  doc.addParagraph(
      "Each value the program provided is compared with every exact engine's (" + names + ") by the gate's rule: "
      "|program - reference| <= 64 eps x scale x conditioning (docs/CONVENTIONS-crankcheck.md, \"Tolerances\"). A "
      "quantity passes when every provided value agrees with all " + std::to_string(judges.size()) + " engines. What the "
      "program left out (or sent as null) is *not provided*: never counted as wrong, never as right.");
  for (const SatOut& s : info.sat_out)
    doc.addParagraph("Engine " + s.engine + " sat out of this grade: it cannot build scene " + s.scene + " (" +
                     formatOneLine(s.reason) + "). The program is judged by the other engines.");

  doc.addHeading(2, "Summary per quantity");
  auto where = [](const std::string& case_id, const std::optional<double>& phi_deg) {
    return case_id.empty() || !phi_deg ? std::string() : case_id + " at " + formatNumber(*phi_deg) + " deg";
  };
  std::vector<std::vector<std::string>> rows;
  int passed = 0, failed = 0, absent = 0;
  for (const GradeSummaryRow& row : summary) {
    const std::string& v = row.verdict;
    const bool all = row.regime == "all";
    if (all) (v == "pass" ? passed : v == "FAIL" ? failed : absent)++;
    if (!all && row.provided == 0) continue;  // a regime of a quantity not provided
    std::string by;  // against each judge
    for (const std::optional<double>& x : row.largest_rel_error_by) by += (by.empty() ? "" : " / ") + shortOrEmpty(x);
    rows.push_back({all ? row.quantity : "", describeGradeRegime(row.regime),
                    std::to_string(row.provided) + " / " + std::to_string(row.asked), shortOrEmpty(row.largest_rel_error),
                    row.provided == 0 ? "" : by, where(row.largest_where_case, row.largest_where_phi_deg),
                    shortOrEmpty(row.rel_error_at_worst_ratio), shortOrEmpty(row.tolerance_rel),
                    where(row.where_case, row.where_phi_deg), v == "FAIL" ? "**FAIL**" : v});
  }
  doc.addParagraph(std::to_string(passed) + " quantities pass, " + std::to_string(failed) + " fail, " +
                   std::to_string(absent) + " not provided. Errors are relative to the quantity's scale. *Largest error* "
                   "is the largest |program - reference| over every provided value and every engine (then "
                   "against " + names + "); *error at worst ratio* is the error where error / tolerance is "
                   "largest, beside that tolerance (the tolerance grows near lambda = 1, so the two can be at different "
                   "cases). Each quantity is shown over all cases, then by regime: moving and at rest, lambda up to 0.4 "
                   "and beyond (a simulator's errors at rest and at speed can differ by orders of magnitude).");
  doc.addTable({"quantity", "regime", "provided / asked", "largest error / scale", "largest vs " + names,
                "where the largest (case, crank angle)", "error at worst ratio / scale", "tolerance / scale",
                "where the worst ratio (case, crank angle)", "verdict"},
               rows);

  if (!by_lambda.empty()) {
    doc.addHeading(2, "Error against lambda");
    std::set<std::string> provided;
    for (const GradeLambdaRow& row : by_lambda) provided.insert(row.quantity);
    std::string list;
    for (const std::string& q : provided) list += (list.empty() ? "" : " ") + q;
    drawFigure("grade_error_vs_lambda", dir, "quantities='" + list + "'");
    doc.addFigure("grade_error_vs_lambda",
                  "The program's largest error against " + judges[0]->name + " over each lambda, per quantity, relative "
                  "to the quantity's scale, beside the analytic engine's own largest error against " + judges[0]->name +
                  " (black) and the "
                  "gate's tolerance 64 eps x the conditioning 1 / (1 - lambda^2) x (l + r) / r (dashed)");
  }

  doc.addHeading(2, "Failing cases");
  if (failures.empty()) {
    doc.addParagraph("None.");
  } else {
    // Every failing case's scene file, so that each line below reproduces it.
    fs::create_directory(dir / "cases");
    std::map<std::string, const GradeCase*> by_id;
    for (const GradeCase& c : cases) by_id[c.id] = &c;
    std::set<std::string> written;
    std::vector<const GradeFailureRow*> worst;
    for (const GradeFailureRow& row : failures) worst.push_back(&row);
    std::stable_sort(worst.begin(), worst.end(), [](const GradeFailureRow* a, const GradeFailureRow* b) {
      return a->rel_error > b->rel_error;
    });
    for (const GradeFailureRow& row : failures)
      if (written.insert(row.case_id).second && by_id.count(row.case_id))
        writeNewFile(dir / "cases" / (row.case_id + ".toml"), by_id[row.case_id]->scene_toml);
    const size_t shown = std::min<size_t>(worst.size(), 40);
    doc.addParagraph(std::to_string(failures.size()) + " (case, quantity, cylinder) failed; the " + std::to_string(shown) +
                     " largest errors are below, all in [data/grade_failures.csv](data/grade_failures.csv). Each "
                     "command, run in this folder, shows every engine's values at that case and angle.");
    std::vector<std::vector<std::string>> table;
    for (size_t i = 0; i < shown; ++i) {
      const GradeFailureRow& r = *worst[i];
      const std::string phi = formatNumber(r.phi_deg);
      table.push_back({r.case_id, r.quantity + (r.cylinder ? " [" + std::to_string(*r.cylinder) + "]" : ""), phi,
                       formatNumber(r.program_value), formatNumber(r.judge_values.at(0)), shortNumber(r.rel_error),
                       formatCodeSpan(quoteShellWord(info.crankcheck_program) + " eval cases/" + r.case_id +
                                      ".toml --phi-deg " + phi + " --engine all")});
    }
    doc.addTable({"case", "quantity [cylinder]", "phi [deg]", "program", judges[0]->name, "error [scale]", "reproduce"}, table);
  }
  writeNewFile(dir / "index.md", doc.toMarkdown());
  writeNewFile(dir / "index.html", doc.toHtml());
}

}  // namespace crankcheck::validation
