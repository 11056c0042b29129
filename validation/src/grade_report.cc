// The report of `crankcheck grade` (grade.h): the same machinery as validate's (CSV data, gnuplot figures, Markdown
// and HTML), its own page.
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <map>
#include <set>

#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/grade.h"
#include "crankcheck/validation/output_folder.h"
#include "crankcheck/validation/report.h"
#include "crankcheck/validation/report_document.h"

namespace crankcheck::validation {

namespace fs = std::filesystem;

namespace {

// A word as a POSIX shell reads it back: as it is when it holds only safe characters, else in single quotes.
std::string quoteShellWord(const std::string& word) {
  if (!word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-./+:=@%") ==
                           std::string::npos)
    return word;
  std::string out = "'";
  for (const char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}


std::string shortNumber(const std::string& text) {
  if (text.empty()) return text;
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2g", std::strtod(text.c_str(), nullptr));
  return buffer;
}

// An argument as a POSIX shell would need it quoted to be read back as the same word (for the commands the report
// prints for the user to copy; crankcheck itself never runs them through a shell).
std::string shellWord(const std::string& word) {
  if (!word.empty() && word.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-./=:,+") ==
                           std::string::npos)
    return word;
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string today() {
  const std::time_t now = std::time(nullptr);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%d", std::gmtime(&now));
  return buffer;
}

}  // namespace

void renderGradeReport(const TableSet& tables, const std::vector<GradeCase>& cases, const GradeReportInfo& info,
                       const fs::path& dir) {
  writeTables(tables, dir);
  const Table& summary = tables.at("grade_summary");
  const Table& failures = tables.at("grade_failures");

  std::string command;
  for (const std::string& word : info.program) command += (command.empty() ? "" : " ") + shellWord(word);
  ReportDocument doc("crankcheck grade report");
  char line[512];
  std::snprintf(line, sizeof line,
                "crankcheck %s, %s, %s; %zu cases%s, %d job%s%s, %.1f s, timeout %.3g s per request.",
                getCrankcheckVersion(), joinEngineLibraries().c_str(), today().c_str(), cases.size(),
                info.quick ? " (--quick)" : "", info.jobs, info.jobs == 1 ? "" : "s", info.batch ? ", --batch" : "",
                info.seconds, info.timeout_seconds);
  doc.addParagraph("Graded program: `" + command + "`\n\n" + line);
  const std::vector<const Engine*> judges = listGradeJudges();
  std::string names;  // "simbody / analytic / mujoco"
  for (const Engine* judge : judges) names += (names.empty() ? "" : " / ") + judge->name;
  doc.addParagraph(
      "Each value the program provided is compared with every exact engine's (" + names + ") by the gate's rule: "
      "|program - reference| <= 64 eps x scale x conditioning (docs/CONVENTIONS-crankcheck.md, \"Tolerances\"). A "
      "quantity passes when every provided value agrees with all " + std::to_string(judges.size()) + " engines. What the "
      "program left out (or sent as null) is *not provided*: never counted as wrong, never as right.");

  doc.addHeading(2, "Summary per quantity");
  const size_t regime = columnOf(summary, "regime"), verdict = columnOf(summary, "verdict");
  auto cell = [&summary](const std::vector<std::string>& row, const char* column) { return row[columnOf(summary, column)]; };
  auto where = [&](const std::vector<std::string>& row, const char* case_column, const char* phi_column) {
    return cell(row, case_column).empty() ? std::string() : cell(row, case_column) + " at " + cell(row, phi_column) + " deg";
  };
  std::vector<std::vector<std::string>> rows;
  int passed = 0, failed = 0, absent = 0;
  for (const auto& row : summary.rows) {
    const std::string& v = row[verdict];
    if (row[regime] == "all") (v == "pass" ? passed : v == "FAIL" ? failed : absent)++;
    if (row[regime] != "all" && cell(row, "provided") == "0") continue;  // a regime of a quantity not provided
    rows.push_back({row[regime] == "all" ? row[0] : "", describeGradeRegime(row[regime]),
                    cell(row, "provided") + " / " + cell(row, "asked"), shortNumber(cell(row, "largest_rel_error")),
                    [&] {
                      std::string by;
                      for (const Engine* judge : judges)
                        by += (by.empty() ? "" : " / ") + shortNumber(cell(row, ("largest_rel_error_" + judge->name).c_str()));
                      return by;
                    }(),
                    where(row, "largest_where_case", "largest_where_phi_deg"), shortNumber(cell(row, "rel_error_at_worst_ratio")),
                    shortNumber(cell(row, "tolerance_rel")), where(row, "where_case", "where_phi_deg"),
                    v == "FAIL" ? "**FAIL**" : v});
    if (cell(row, "provided") == "0") rows.back()[4] = "";
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

  if (!tables.at("grade_error_vs_lambda").rows.empty()) {
    doc.addHeading(2, "Error against lambda");
    std::set<std::string> provided;
    for (const auto& row : tables.at("grade_error_vs_lambda").rows) provided.insert(row[0]);
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
  if (failures.rows.empty()) {
    doc.addParagraph("None.");
  } else {
    // Every failing case's scene file, so that each line below reproduces it.
    fs::create_directory(dir / "cases");
    std::map<std::string, const GradeCase*> by_id;
    for (const GradeCase& c : cases) by_id[c.id] = &c;
    std::set<std::string> written;
    std::vector<std::vector<std::string>> worst = failures.rows;
    const size_t rel = columnOf(failures, "rel_error");
    std::stable_sort(worst.begin(), worst.end(), [rel](const auto& a, const auto& b) {
      return std::strtod(a[rel].c_str(), nullptr) > std::strtod(b[rel].c_str(), nullptr);
    });
    for (const auto& row : failures.rows)
      if (written.insert(row[0]).second && by_id.count(row[0]))
        writeNewFile(dir / "cases" / (row[0] + ".toml"), by_id[row[0]]->scene_toml);
    const size_t shown = std::min<size_t>(worst.size(), 40);
    doc.addParagraph(std::to_string(failures.rows.size()) + " (case, quantity, cylinder) failed; the " + std::to_string(shown) +
                     " largest errors are below, all in [data/grade_failures.csv](data/grade_failures.csv). Each "
                     "command, run in this folder, shows every engine's values at that case and angle.");
    std::vector<std::vector<std::string>> table;
    for (size_t i = 0; i < shown; ++i) {
      const auto& r = worst[i];
      table.push_back({r[0], r[3] + (r[4].empty() ? "" : " [" + r[4] + "]"), r[5], r[7], r[8], shortNumber(r[10]),
                       "`" + quoteShellWord(info.crankcheck_program) + " eval cases/" + r[0] + ".toml --phi-deg " + r[5] +
                           " --engine all`"});
    }
    doc.addTable({"case", "quantity [cylinder]", "phi [deg]", "program", judges[0]->name, "error [scale]", "reproduce"}, table);
  }
  writeNewFile(dir / "index.md", doc.toMarkdown());
  writeNewFile(dir / "index.html", doc.toHtml());
}

}  // namespace crankcheck::validation
