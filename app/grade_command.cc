#include "grade_command.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
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
#include "crankcheck/validation/free_run_grade.h"
#include "crankcheck/validation/work_limit.h"
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
  command.add_option("--out", options.out,
                     "Report folder (replaced only if missing, empty or written by crankcheck); default out/grade, "
                     "with --free-run out/grade-free-run");
  command.add_flag("--quick", options.quick, "Fewer lambdas and angles (seconds, not minutes); --free-run: the engines' "
                   "reference runs at their default accuracy or step only");
  command.add_flag("--batch", options.batch,
                   "Start the program once per job and send it every request, one JSON per line; it answers one "
                   "JSON per line, in order");
  command.add_option("--jobs", options.jobs, "Programs run at once (default: one per core)")
      ->check(CLI::Range(1, 256));
  command.add_option("--timeout", options.timeout_seconds, "Seconds the program may take per request (--free-run: per run at its scene's largest step, doubled at each halving of --dt-sweep)")
      ->check(FiniteRange(0.001, 1e6))
      ->capture_default_str();
  command.add_flag("--free-run", options.free_run,
                   "Grade a time-stepped run (protocol 2): the program steps the crank train through time and answers "
                   "its trajectory; the energy's trend, the speed fluctuation and the phase are measured against the "
                   "exact run (one scene at least; docs/grade.md, \"Time-stepped runs\")");
  command.add_option("--drive", options.drive, "--free-run: free (no drive, no load, gravity alone), held (the crank "
                     "held at the scene's speed; the program reports the torque it takes) or loaded (the scene's gas "
                     "against a constant load, the gas torque's cycle mean: the working cycle's steady run)")
      ->check(CLI::IsMember({"free", "held", "loaded"}))
      ->capture_default_str();
  command.add_option("--revolutions", options.revolutions, "--free-run: the horizon, in revolutions of the exact run")
      ->check(CLI::Range(2, 100000))
      ->capture_default_str();
  command.add_option("--dt", options.dt, "--free-run: the step [s] the program must take, or `own` (its own choice); "
                     "default 1/720 of a revolution");
  command.add_option("--dt-sweep", options.dt_sweep, "--free-run: N runs at dt, dt/2, ... dt/2^(N-1): the largest step "
                     "meeting each tolerance and each measure's observed order")
      ->check(CLI::Range(1, 20))
      ->capture_default_str();
  command.add_option("--output-interval", options.output_interval,
                     "--free-run: seconds between the samples the program reports (default: every step; with --dt own, 1/720 of a revolution)")
      ->check(FiniteRange(1e-12, 1e6));
  command.add_option("--energy-tolerance", options.tolerances.energy_trend,
                     "--free-run: the energy's trend per revolution, relative to its start")
      ->check(FiniteRange(0.0, 1e6))
      ->capture_default_str();
  command.add_option("--delta-tolerance", options.tolerances.delta,
                     "--free-run: the speed fluctuation delta's error, relative to the exact delta")
      ->check(FiniteRange(0.0, 1e6))
      ->capture_default_str();
  command.add_option("--extreme-phase-tolerance", options.tolerances.extreme_phase,
                     "--free-run: [deg] the crank angles of the largest and smallest speed against the exact run's")
      ->check(FiniteRange(0.0, 360.0))
      ->capture_default_str();
  command.add_option("--phase-tolerance", options.tolerances.phase, "--free-run: [rad] the crank angle at the horizon")
      ->check(FiniteRange(0.0, 1e6))
      ->capture_default_str();
  command.add_option("--values-tolerance", options.tolerances.values,
                     "--free-run: a value's error at the program's own state, relative to the quantity's scale")
      ->check(FiniteRange(0.0, 1e6))
      ->capture_default_str();
  command.add_option(validation::kWorkLimitFlag, options.work_limit,
                     "--free-run: the longest work [s] of crankcheck's own runs (the engines' reference runs over the "
                     "horizon), estimated before the program is started and refused past it")
      ->check(FiniteRange(1.0, 1e7))
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
      "broke the protocol (one line names the case and quotes the offending output).\n"
      "--free-run: protocol 2, one request per step (JSON, one line): {\"protocol\": 2, \"case\": ID, \"scene\": {...}, "
      "\"scene_toml\": \"...\", \"drive\": \"free\"|\"held\"|\"loaded\", \"gas\": BOOL, \"load_torque\": N M, "
      "\"gravity\": true, \"phi0\": 0, \"omega0\": RAD/S, \"dt\": S|\"own\", "
      "\"t_end\": S, \"output_interval\": S, \"quantities\": [...]}; the response: {\"samples\": [{\"t\": S, \"phi\": RAD, "
      "\"omega\": RAD/S, \"omega_t\": S, \"values_t\": S, \"drive_torque\": ..., \"cylinders\": [...]}, ...]}, a sample at "
      "t = 0, one every output_interval, the last at t_end; phi unwrapped; omega_t and values_t (optional, default t) "
      "the instants omega and the other values stand at (a backward-difference velocity: t - dt/2). Exit status 0: every "
      "measure of the asked step within its tolerance; 1: some are not; 3: a broken run (not the protocol, NaN, time "
      "or phi not increasing, fewer than 8 samples, stopping before t_end, no answer in time).");
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

namespace {

// The program's words checked before anything runs (both protocols).
void checkProgram(const std::vector<std::string>& program, const char* usage) {
  if (program.empty())
    throw UsageError(std::string("grade: no program given; put it after `--`: ") + usage);
  if (program.front().empty())
    throw UsageError("grade: the program after `--` is an empty word; name the program to grade");
  if (validation::findProgram(program.front()).empty())
    throw EnvironmentError(program.front() + ": cannot be run (not found, or not an executable file; a name "
                           "without '/' is looked up on PATH)");
}

}  // namespace

int runGrade(const GradeOptions& options) {
  if (options.free_run) return runFreeRunGrade(options);
  const GradeOptions d;  // a flag of the time-stepped run given without --free-run
  for (const auto& [flag, given] : std::vector<std::pair<const char*, bool>>{
           {"--drive", options.drive != d.drive},
           {"--revolutions", options.revolutions != d.revolutions},
           {"--dt", options.dt != d.dt},
           {"--dt-sweep", options.dt_sweep != d.dt_sweep},
           {"--output-interval", options.output_interval != d.output_interval},
           {"--energy-tolerance", options.tolerances.energy_trend != d.tolerances.energy_trend},
           {"--delta-tolerance", options.tolerances.delta != d.tolerances.delta},
           {"--extreme-phase-tolerance", options.tolerances.extreme_phase != d.tolerances.extreme_phase},
           {"--phase-tolerance", options.tolerances.phase != d.tolerances.phase},
           {"--values-tolerance", options.tolerances.values != d.tolerances.values},
           {validation::kWorkLimitFlag, options.work_limit != d.work_limit}})
    if (given) throw UsageError(std::string(flag) + ": applies to a time-stepped run only; add --free-run");
  // Everything that can be checked is checked before the first request: the program, the scenes, the output
  // folder, gnuplot.
  checkProgram(options.program, "crankcheck grade [SCENE...] -- PROGRAM [ARG...]");
  std::vector<Mechanism> scenes;
  std::set<std::string> names;
  for (const std::string& path : options.scene_paths) {
    scenes.push_back(loadScene(path));
    if (!names.insert(scenes.back().name).second) throw UsageError(path + ": a scene named " + scenes.back().name + " is given twice");
  }
  // Every engine builds every scene now: one that cannot sits out, and the program is judged by the others (refused,
  // status 2, when no exact engine is left; docs/grade.md).
  validation::GradeReportInfo info;
  info.sat_out = validation::findSatOut(scenes, options.scene_paths);
  const validation::SatOutScope sat_out_scope(info.sat_out);
  const int jobs = options.jobs > 0 ? options.jobs : validation::getDefaultJobs();
  validation::OutputFolder out(options.out.empty() ? std::string("out/grade") : options.out, "--out");
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
  for (const validation::SatOut& s : info.sat_out) std::printf("%s", wrapText(formatSatOut({s}), kHelpWidth).c_str());
  std::printf("%s\nReport: %s (also index.html)\n",
              status == 0 ? ("Every provided value agrees with " + references + ".").c_str()
                          : "SOME VALUES DISAGREE, or none was provided (see the report's failing cases).",
              showPath(out.getTarget() / "index.md").c_str());
  return status;
}

int runFreeRunGrade(const GradeOptions& options) {
  const char* usage = "crankcheck grade --free-run SCENE... [options] -- PROGRAM [ARG...]";
  checkProgram(options.program, usage);
  if (options.batch) throw UsageError("--batch: does not apply to --free-run (one program per run)");
  if (options.jobs != 0) throw UsageError("--jobs: does not apply to --free-run (the runs go one at a time)");
  if (options.scene_paths.empty())
    throw UsageError("grade --free-run: give the scene file(s) to run (a scene with [flywheel] for a free run): " +
                     std::string(usage));
  validation::RunSettings settings;
  settings.drive = options.drive == "held"     ? validation::RunDrive::kHeld
                   : options.drive == "loaded" ? validation::RunDrive::kLoaded
                                               : validation::RunDrive::kFree;
  settings.revolutions = options.revolutions;
  settings.dt_sweep = options.dt_sweep;
  settings.own_step = options.dt == "own";
  if (!options.dt.empty() && options.dt != "own") {
    char* end = nullptr;
    const double dt = std::strtod(options.dt.c_str(), &end);
    if (end != options.dt.c_str() + options.dt.size() || !std::isfinite(dt) || !(dt > 0.0))
      throw UsageError("--dt: " + options.dt + " is neither a step > 0 [s] nor `own`");
    settings.dt = dt;
  }
  if (options.dt == "own" && options.dt_sweep != 1)
    throw UsageError("--dt-sweep: needs a step to halve; give --dt S (the program's own step cannot be swept)");
  if (options.output_interval > 0.0) settings.output_interval = options.output_interval;
  settings.tolerances = options.tolerances;
  std::vector<validation::RunCase> cases;
  std::set<std::string> names;
  for (const std::string& path : options.scene_paths) {
    Mechanism m = loadScene(path);
    if (!names.insert(m.name).second) throw UsageError(path + ": a scene named " + m.name + " is given twice");
    try {
      for (validation::RunCase& c : validation::buildRunCases(m, settings)) cases.push_back(std::move(c));
    } catch (const UsageError& e) {
      throw UsageError(path + ": " + e.what());
    }
  }
  validation::OutputFolder out(options.out.empty() ? std::string("out/grade-free-run") : options.out, "--out");
  validation::RunGradeReportInfo info;
  info.gnuplot_version = validation::checkGnuplot();
  validation::checkRunGradeWork(cases, options.quick, options.work_limit);  // before the program is started
  validation::InterruptGuard interrupt(out);
  out.createStaging();

  validation::GradeProgram program;
  program.argv = options.program;
  program.timeout_seconds = options.timeout_seconds;
  const bool show_progress = ::isatty(STDERR_FILENO);
  const auto start = std::chrono::steady_clock::now();
  validation::TableSet tables =
      validation::runRunGrade(cases, program, settings.tolerances, [&](size_t done, size_t total) {
        if (show_progress) std::fprintf(stderr, "\r\033[Kgrade --free-run: %zu of %zu runs", done, total);
      });
  if (show_progress) std::fprintf(stderr, "\r\033[Kgrade --free-run: the engines' own runs");
  validation::addEngineRuns(tables, cases, options.quick);
  if (show_progress) std::fprintf(stderr, "\r\033[K");
  info.program = options.program;
  info.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  info.timeout_seconds = options.timeout_seconds;
  info.tolerances = settings.tolerances;
  validation::renderRunGradeReport(tables, cases, info, out.getStaging());
  out.install("report");

  const int status = validation::findRunGradeExitStatus(tables);
  std::printf("%s", validation::formatRunGradeSummary(tables, cases).c_str());
  std::printf("%s\nReport: %s (also index.html)\n",
              status == 0 ? "Every measure of the asked step is within its tolerance."
                          : "SOME MEASURES ARE OUT OF TOLERANCE at the asked step (or none was graded).",
              showPath(out.getTarget() / "index.md").c_str());
  return status;
}

}  // namespace crankcheck::app
