// The terminal summary and the report of `crankcheck grade --free-run` (free_run_grade.h): the same machinery as
// grade's report (CSV data, gnuplot figures, Markdown and HTML), its own page.
#include <cstdio>
#include <ctime>
#include <map>
#include <set>

#include "crankcheck/validation/engine_runs.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/free_run_grade.h"
#include "crankcheck/validation/output_folder.h"
#include "crankcheck/validation/report.h"
#include "crankcheck/validation/report_document.h"
#include "crankcheck/validation/report_format.h"

namespace crankcheck::validation {

namespace fs = std::filesystem;

namespace {

std::string orDash(const std::optional<double>& x, int digits = 2) { return x ? shortNumber(*x, digits) : std::string("-"); }

std::string describeStep(const std::optional<double>& dt) { return dt ? shortNumber(*dt) + " s" : "its own"; }

// The rows of one case, in the table's order.
std::vector<const RunMeasureRow*> rowsOf(const std::vector<RunMeasureRow>& rows, const std::string& id) {
  std::vector<const RunMeasureRow*> out;
  for (const RunMeasureRow& r : rows)
    if (r.case_id == id) out.push_back(&r);
  return out;
}

// What the run is, in one line: "inline4_four_stroke: free run, 10 revolutions (0.2 s), step 2.8e-05 s".
std::string describeCase(const RunCase& c) {
  const char* what = c.drive == RunDrive::kFree   ? "free run"
                     : c.drive == RunDrive::kHeld ? "crank held at its speed"
                                                  : "loaded run (gas against its cycle-mean load)";
  return c.family + ": " + what + ", " +
         std::to_string(c.revolutions) + " revolutions (" + shortNumber(c.t_end) + " s), step " + describeStep(c.dt);
}

}  // namespace

std::string formatRunGradeSummary(const TableSet& tables, const std::vector<RunCase>& cases) {
  const std::vector<RunMeasureRow>& rows = getRows(tables, getRunMeasuresSchema());
  std::string out;
  char line[256];
  for (const RunCase& c : cases) {
    out += describeCase(c) + "\n";
    std::snprintf(line, sizeof line, "  %-26s %12s %12s %10s %10s  %s\n", "measure [unit]", "program", "exact", "error",
                  "tolerance", "verdict");
    out += line;
    for (const RunMeasureRow* r : rowsOf(rows, c.id)) {
      std::snprintf(line, sizeof line, "  %-26s %12s %12s %10s %10s  %s\n", (r->measure + " [" + r->unit + "]").c_str(),
                    orDash(r->program, 5).c_str(), orDash(r->exact, 5).c_str(), orDash(r->error).c_str(),
                    shortNumber(r->tolerance).c_str(), r->verdict.c_str());
      out += line;
      if (r->verdict == "FAIL") out += "      where: " + r->where + "\n";  // the failing error's place
    }
  }
  const std::vector<RunConvergenceRow>& convergence = getRows(tables, getRunConvergenceSchema());
  if (!convergence.empty()) {
    std::snprintf(line, sizeof line, "%-26s %-20s %9s %18s\n", "scene", "measure", "order", "largest step passing");
    out += line;
    for (const RunConvergenceRow& r : convergence) {
      std::snprintf(line, sizeof line, "%-26s %-20s %9s %18s\n", r.scene.c_str(), r.measure.c_str(),
                    r.observed_order ? shortNumber(*r.observed_order, 3).c_str() : "-",
                    r.largest_step ? (shortNumber(*r.largest_step) + " s").c_str() : "none");
      out += line;
    }
  }
  return out;
}

void renderRunGradeReport(const TableSet& tables, const std::vector<RunCase>& cases, const RunGradeReportInfo& info,
                          const fs::path& dir) {
  writeTables(tables, dir);
  const std::vector<RunMeasureRow>& measures = getRows(tables, getRunMeasuresSchema());
  const std::vector<RunConvergenceRow>& convergence = getRows(tables, getRunConvergenceSchema());

  std::string command;
  for (const std::string& word : info.program) command += (command.empty() ? "" : " ") + quoteShellWord(word);
  ReportDocument doc("crankcheck grade --free-run report");
  doc.showAsWritten(listSceneNames(tables));
  char line[512];
  std::snprintf(line, sizeof line, "crankcheck %s, %s, %s; %zu runs, %.1f s, timeout %.3g s per run.",
                getCrankcheckVersion(), joinEngineLibraries().c_str(), formatToday().c_str(), cases.size(), info.seconds,
                info.timeout_seconds);
  doc.addParagraph("Graded program: " + formatCodeSpan(command) + "\n\n" + line);
  const RunTolerances& t = info.tolerances;
  doc.addParagraph(
      "Each run starts at phi = 0 with the scene's speed. A *free* run (no drive, no load, no gas; gravity on) is "
      "measured against the exact free run, the energy integral (1/2) J(phi) omega^2 + U(phi) = E: "
      "**energy_trend**, the least-squares slope of E at each crossing of phi = 2 pi k against k, relative to E_0 "
      "(tolerance " + shortNumber(t.energy_trend) + " per revolution; read at a fixed phase, a velocity half a step "
      "behind its angle does not show as an oscillation); **delta**, the speed fluctuation (omega_max - omega_min) / "
      "omega_mean over the first revolution against the exact run's with the run's own speed at phi = 0 (relative "
      "error, tolerance " + shortNumber(t.delta) + "); **phi_at_omega_max**, **phi_at_omega_min**, where the speed "
      "peaks (tolerance " + shortNumber(t.extreme_phase) + " deg); **phase**, phi_run - phi_exact at the horizon "
      "t_end (tolerance " + shortNumber(t.phase) + " rad at that horizon: a run that loses energy slows, and its "
      "phase error grows about as t^2). A *held* run (the crank at the constant speed) is measured by its phase "
      "against phi0 + omega0 t. Every value the program reports beyond phi and omega (drive torque, forces, x_p, ...) "
      "is compared with the exact value at the program's own state at the instant it says the value stands at "
      "(values_t): its phi and omega there and, in a free run, the crank's acceleration from the equation of motion "
      "(error relative to the quantity's scale, tolerance " + shortNumber(t.values) + "): a wrong formula and a "
      "wrong trajectory are told apart. The run is read between its samples by local Lagrange interpolation of "
      "degree 5, at omega's own instants (omega_t).");

  doc.addHeading(2, "Measures of each run");
  for (const RunCase& c : cases) {
    std::vector<std::vector<std::string>> table;
    for (const RunMeasureRow* r : rowsOf(measures, c.id))
      table.push_back({r->measure, r->unit, orDash(r->program, 6), orDash(r->exact, 6), orDash(r->error),
                       shortNumber(r->tolerance), shortNumber(r->resolution), r->where,
                       r->verdict == "FAIL" ? "**FAIL**" : r->verdict});
    doc.addParagraph("**" + describeCase(c) + "**");
    doc.addTable({"measure", "unit", "program", "exact", "error", "tolerance", "resolution", "where", "verdict"}, table);
  }

  if (!convergence.empty()) {
    doc.addHeading(2, "Error against step size");
    std::vector<std::vector<std::string>> table;
    for (const RunConvergenceRow& r : convergence)
      table.push_back({r.scene, r.measure, r.observed_order ? shortNumber(*r.observed_order, 3) : "-",
                       r.largest_step ? shortNumber(*r.largest_step) + " s" : "none of the steps",
                       shortNumber(r.tolerance)});
    doc.addParagraph("Each measure over the sweep of steps: its observed order of convergence (the least-squares slope "
                     "of log error against log dt over the steps whose error is above 10 times the measure's resolution, the smallest error it resolves: data/free_run_measures.csv) and the largest step "
                     "that meets its tolerance together with every smaller step of the sweep. Different measures of "
                     "one run converge at different orders.");
    doc.addTable({"scene", "measure", "observed order", "largest step meeting the tolerance", "tolerance"}, table);
    std::set<std::string> scenes;
    for (const RunConvergenceRow& r : convergence) scenes.insert(r.scene);
    std::string names;
    std::set<std::string> seen;
    for (const RunConvergenceRow& r : convergence)
      if (r.scene == *scenes.begin() && seen.insert(r.measure).second) names += (names.empty() ? "" : " ") + r.measure;
    // Scene names come from the user's files: only a safe name reaches gnuplot's command line.
    const std::string& scene = *scenes.begin();
    if (scene.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-.") ==
        std::string::npos) {
      drawFigure("free_run_error_vs_step", dir, "measures='" + names + "'; scene='" + scene + "'");
      doc.addFigure("free_run_error_vs_step", "Each measure's error over its tolerance against the step, on " + scene +
                                                  " (below the dashed line: within tolerance; the slope: the order)");
    }
  }

  const std::vector<EngineRunRow>& engines = getRows(tables, getFreeRunEnginesSchema());
  if (!engines.empty()) {
    doc.addHeading(2, "Beside the engines' own runs");
    doc.addParagraph(
        "The same run (each scene from phi = 0 at the run's speed, over the same revolutions: free under gravity "
        "alone, or loaded under its gas and mean load by the engines that take them) stepped by every engine that "
        "simulates, through the same measures: Simbody's integrators at a relative accuracy, MuJoCo's soft constraint "
        "solver (as its users run it) at a fixed step given as a fraction of a revolution. Energy trend per period (a "
        "revolution; a loaded four-stroke's working cycle) relative to E_0; delta's error relative to the exact delta; the phase error at the "
        "horizon; the processor time per simulated revolution. *omega read*: where the engine's recorded speed stands "
        "(a semi-implicit Euler's is a backward difference, half a step behind its angle; found by that identity at "
        "every step).");
    std::vector<std::vector<std::string>> table;
    for (const EngineRunRow& r : engines)
      table.push_back({r.scene, r.engine, r.integrator, shortNumber(r.accuracy), shortNumber(r.energy_trend_per_revolution),
                       shortNumber(r.delta_error_rel), shortNumber(r.phase_error_at_horizon),
                       shortNumber(r.cpu_seconds_per_revolution) + " s", r.omega_reading});
    doc.addTable({"scene", "engine", "integrator", "accuracy or step", "energy trend / period", "delta error",
                  "phase error [rad]", "cost / revolution", "omega read"},
                 table);
  }

  doc.addHeading(2, "Error against time");
  std::string runs;
  for (const RunCase& c : cases) runs += (runs.empty() ? "" : " ") + c.id;  // ids are [A-Za-z0-9_]
  bool free = false;
  for (const RunCase& c : cases) free = free || c.drive == RunDrive::kFree;
  drawFigure("free_run_error_vs_time", dir, "runs='" + runs + "'; energy=" + (free ? "1" : "0"));
  doc.addFigure("free_run_error_vs_time",
                free ? "Top: the phase error |phi_run - phi_exact| of each run against time. Bottom: the energy's error "
                       "at each crossing of phi = 2 pi k (free runs): the trend the energy_trend measure fits"
                     : "The phase error |phi_run - (phi0 + omega0 t)| of each run against time");
  writeNewFile(dir / "index.md", doc.toMarkdown());
  writeNewFile(dir / "index.html", doc.toHtml());
}

}  // namespace crankcheck::validation
