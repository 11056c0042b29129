#pragma once
/// @file
/// `crankcheck grade [SCENE...] [--quick] [--out DIR] [--jobs N] [--timeout S] [--batch] -- PROGRAM [ARG...]`:
/// the user's program graded against the exact engines (validation/grade.h, docs/grade.md); with `--free-run`, its
/// time-stepped runs (validation/free_run_grade.h).

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "crankcheck/validation/free_run_grade.h"

namespace crankcheck::app {

struct GradeOptions {
  std::vector<std::string> scene_paths;
  std::string out;  ///< empty: out/grade (--free-run: out/grade-free-run)
  bool quick = false;
  bool batch = false;
  int jobs = 0;                  ///< 0: one per core
  double timeout_seconds = 60.0; ///< per request
  std::vector<std::string> program;  ///< everything after `--`
  // --free-run: a time-stepped run (validation/free_run_grade.h, docs/grade.md "Time-stepped runs")
  bool free_run = false;
  std::string drive = "free";        ///< free, held
  int revolutions = 10;              ///< the horizon
  std::string dt;                    ///< a step [s], "own", or empty: 1/720 of a revolution
  int dt_sweep = 1;                  ///< steps dt, dt/2, ...
  double output_interval = 0.0;      ///< [s] 0: every step
  validation::RunTolerances tolerances;  ///< --energy-tolerance ... --values-tolerance (defaults: RunTolerances's)
  double work_limit = 600.0;         ///< [s] --work-limit: the longest estimated work of crankcheck's own runs
};

void addGradeOptions(CLI::App& command, GradeOptions& options);

/// Splits `crankcheck grade ... -- PROGRAM ARG...` before CLI11 sees it (CLI11 would take PROGRAM for a scene):
/// moves everything after the first `--` that follows the `grade` subcommand into `program` and returns the
/// arguments before it.
std::vector<std::string> splitGradeProgram(int argc, char** argv, std::vector<std::string>& program);

/// Runs the grade and writes its report. @return 0 when every provided value agrees with every reference engine, 1 otherwise.
/// @throws UsageError for bad scenes or flags (2); EnvironmentError when the program cannot be run, crashes, times
/// out or breaks the protocol (3).
int runGrade(const GradeOptions& options);

/// `grade --free-run`: the program's time-stepped runs graded and reported. @return 0 when every measure of the asked
/// step passes, 1 otherwise. @throws UsageError (2), EnvironmentError (3) as runGrade.
int runFreeRunGrade(const GradeOptions& options);

}  // namespace crankcheck::app
