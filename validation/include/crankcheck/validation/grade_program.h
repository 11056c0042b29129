#pragma once
/// @file
/// How `crankcheck grade` runs the graded program, in both protocols (grade.h: states; free_run_grade.h: time-stepped
/// runs). Plain values.

#include <cstddef>
#include <string>
#include <vector>

namespace crankcheck::validation {

/// How to run the graded program.
struct GradeProgram {
  std::vector<std::string> argv;          ///< the program and its arguments (argv[0]: a path or a name on PATH)
  double timeout_seconds = 60.0;          ///< [s] per request (batch: per request times the requests sent)
  size_t output_limit = size_t{64} << 20; ///< [bytes] of stdout per request (batch: times the requests)
  bool batch = false;
};

}  // namespace crankcheck::validation
