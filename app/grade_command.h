#pragma once
/// @file
/// `crankcheck grade [SCENE...] [--quick] [--out DIR] [--jobs N] [--timeout S] [--batch] -- PROGRAM [ARG...]`:
/// the user's program graded against both engines (validation/grade.h, docs/grade.md).

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace crankcheck::app {

struct GradeOptions {
  std::vector<std::string> scene_paths;
  std::string out = "out/grade";
  bool quick = false;
  bool batch = false;
  int jobs = 0;                  ///< 0: one per core
  double timeout_seconds = 60.0; ///< per request
  std::vector<std::string> program;  ///< everything after `--`
};

void addGradeOptions(CLI::App& command, GradeOptions& options);

/// Splits `crankcheck grade ... -- PROGRAM ARG...` before CLI11 sees it (CLI11 would take PROGRAM for a scene):
/// moves everything after the first `--` that follows the `grade` subcommand into `program` and returns the
/// arguments before it.
std::vector<std::string> splitGradeProgram(int argc, char** argv, std::vector<std::string>& program);

/// Runs the grade and writes its report. @return 0 when every provided value agrees with both engines, 1 otherwise.
/// @throws UsageError for bad scenes or flags (2); EnvironmentError when the program cannot be run, crashes, times
/// out or breaks the protocol (3).
int runGrade(const GradeOptions& options);

}  // namespace crankcheck::app
