#include "grade_command.h"

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <set>

#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/errors.h"
#include "flag_checks.h"
#include "help_format.h"
#include "crankcheck/validation/grade.h"
#include "crankcheck/validation/output_folder.h"
#include "crankcheck/validation/process.h"
#include "crankcheck/validation/report.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/interrupt.h"
#include "crankcheck/validation/runner.h"
#include "scene_input.h"

namespace crankcheck::app {

void addGradeOptions(CLI::App& command, GradeOptions& options) {
  command.add_option("scene", options.scene_paths,
                     "Scene files (TOML) to grade on; none: the built-in campaign (validate's scenes)");
  command.add_option("--out", options.out, "Report folder (replaced only if missing, empty or written by crankcheck)")
      ->capture_default_str();
  command.add_flag("--quick", options.quick, "Fewer lambdas and angles (seconds, not minutes)");
  command.add_flag("--batch", options.batch,
                   "Start the program once per job and send it every request, one JSON per line; it answers one "
                   "JSON per line, in order");
  command.add_option("--jobs", options.jobs, "Programs run at once (default: one per core)")
      ->check(CLI::Range(1, 256));
  command.add_option("--timeout", options.timeout_seconds, "Seconds the program may take per request")
      ->check(FiniteRange(0.001, 1e6))
      ->capture_default_str();
  command.footer(
      "The program follows `--`: crankcheck grade [SCENE...] [options] -- PROGRAM [ARG...]. It is started without a "
      "shell, once per case (--batch: once per job, every request one line), with a time limit per request "
      "(--timeout), and speaks protocol 1, one JSON object per line:\n"
      "  request   {\"protocol\": 1, \"case\": ID, \"scene\": {...as eval --format json: SI units, radians...}, "
      "\"scene_toml\": \"...the case as a scene file...\", \"phi_deg\": [0, 45, ...], \"quantities\": [\"U\", \"Q\", "
      "...]}\n"
      "  response  {\"results\": [{\"phi_deg\": 0, \"U\": ..., \"Q\": ..., \"cylinders\": [{\"x_p\": ...}, ...]}, ...]}\n"
      "One result per angle, in order, with eval's names and SI units (`crankcheck eval SCENE --format json` shows every "
      "field; the conventions: U(0) = 0, Q = dU/dphi, reactions as the force ON the named body FROM the other, "
      "docs/CONVENTIONS.md). Leave out (or null) what the program does not compute: \"not provided\", never wrong. "
      "Each value is compared with every reference engine relative to the quantity's scale, by the gate's rule "
      "(64 eps x scale x conditioning); the report lists the failing cases with a command that reproduces each "
      "(docs/grade.md).\n"
      "Exit status 0: every value it provided agrees with every reference engine; 1: some do not (or none was "
      "provided); 2: bad usage; 3: it could not be run, crashed, timed out, wrote more than 64 MiB per request or "
      "broke the protocol (one line names the case and quotes the offending output).");
}

std::vector<std::string> splitGradeProgram(int argc, char** argv, std::vector<std::string>& program) {
  std::vector<std::string> args(argv, argv + argc);
  size_t grade = 1;
  while (grade < args.size() && !args[grade].empty() && args[grade][0] == '-') ++grade;  // global flags
  if (grade >= args.size() || args[grade] != "grade") return args;
  for (size_t i = grade + 1; i < args.size(); ++i)
    if (args[i] == "--") {
      program.assign(args.begin() + static_cast<long>(i) + 1, args.end());
      args.resize(i);
      break;
    }
  return args;
}

int runGrade(const GradeOptions& options) {
  // Everything that can be checked is checked before the first request: the program, the scenes, the output
  // folder, gnuplot.
  if (options.program.empty())
    throw UsageError("grade: no program given; put it after `--`: crankcheck grade [SCENE...] -- PROGRAM [ARG...]");
  if (options.program.front().empty())
    throw UsageError("grade: the program after `--` is an empty word; name the program to grade");
  if (validation::findProgram(options.program.front()).empty())
    throw EnvironmentError(options.program.front() + ": cannot be run (not found, or not an executable file; a name "
                           "without '/' is looked up on PATH)");
  std::vector<Mechanism> scenes;
  std::set<std::string> names;
  for (const std::string& path : options.scene_paths) {
    scenes.push_back(loadScene(path));
    if (!names.insert(scenes.back().name).second) throw UsageError(path + ": a scene named " + scenes.back().name + " is given twice");
    validation::checkEveryEngineBuilds(scenes.back(), path);  // the references grade against (and the rest)
  }
  const int jobs = options.jobs > 0 ? options.jobs : validation::getDefaultJobs();
  validation::OutputFolder out(options.out, "--out");
  validation::GradeReportInfo info;
  info.gnuplot_version = validation::checkGnuplot();
  const std::vector<validation::GradeCase> cases = validation::buildGradeCases(scenes, options.quick);
  validation::InterruptGuard interrupt(out);
  out.createStaging();

  validation::GradeProgram program;
  program.argv = options.program;
  program.timeout_seconds = options.timeout_seconds;
  program.batch = options.batch;
  const bool show_progress = ::isatty(STDERR_FILENO);
  const auto start = std::chrono::steady_clock::now();
  const validation::TableSet tables = validation::runGrade(cases, program, jobs, [&](size_t done, size_t total) {
    if (show_progress) std::fprintf(stderr, "\r\033[Kgrade: %zu of %zu cases", done, total);
  });
  if (show_progress) std::fprintf(stderr, "\r\033[K");
  info.program = options.program;
  info.quick = options.quick;
  info.batch = options.batch;
  info.jobs = jobs;
  info.timeout_seconds = options.timeout_seconds;
  std::error_code no_path;  // the report's "reproduce" commands call this program by its path
  if (const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", no_path); !no_path)
    info.crankcheck_program = self.string();
  info.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  validation::renderGradeReport(tables, cases, info, out.getStaging());
  out.install("report");

  const int status = validation::findGradeExitStatus(tables);
  // One row per quantity over all cases, then (for a provided quantity) one per regime: moving or at rest, lambda up
  // to 0.4 or beyond. Errors relative to the quantity's scale: the largest, and the one at the worst error / tolerance.
  auto brief = [](const std::optional<double>& x) { return x ? validation::shortNumber(*x) : std::string("-"); };
  // Within 100 columns: the column heads on two lines, what they mean below the table.
  std::printf("%-15s %-22s %11s %9s %9s %9s  %s\n%-15s %-22s %11s %9s %9s %9s\n", "quantity", "regime", "provided",
              "largest", "at worst", "tolerance", "verdict", "", "", "/ asked", "error", "ratio", "/ scale");
  for (const validation::GradeSummaryRow& row : validation::getRows(tables, validation::getGradeSummarySchema())) {
    const bool all = row.regime == "all";
    if (!all && row.provided == 0) continue;  // a regime of a quantity not provided
    std::printf("%-15s %-22s %11s %9s %9s %9s  %s\n", all ? row.quantity.c_str() : "",
                validation::describeGradeRegime(row.regime).c_str(),
                (std::to_string(row.provided) + " / " + std::to_string(row.asked)).c_str(),
                brief(row.largest_rel_error).c_str(), brief(row.rel_error_at_worst_ratio).c_str(),
                brief(row.tolerance_rel).c_str(), row.verdict.c_str());
  }
  std::vector<std::string> reference_names{"the analytic engine"};
  for (const Engine& e : validation::listEngines())
    if (e.gated && !e.closed_form) reference_names.push_back(e.name);
  const std::string references = joinNames(reference_names);
  std::printf("%s", wrapText("Errors relative to the quantity's scale, against " + references +
                                 ": the largest error / scale over every value, and the error at worst ratio, where "
                                 "error / tolerance is worst (beside that tolerance).\n",
                             kHelpWidth)
                        .c_str());
  std::printf("%s\nReport: %s (also index.html)\n",
              status == 0 ? ("Every provided value agrees with " + references + ".").c_str()
                          : "SOME VALUES DISAGREE, or none was provided (see the report's failing cases).",
              (out.getTarget() / "index.md").string().c_str());
  return status;
}

}  // namespace crankcheck::app
