#pragma once
/// @file
/// Runs the crankcheck program as a user would, without a shell (an argument vector: paths with quotes, `$(...)`
/// or newlines are passed as they are). The including target defines CRANKCHECK_BINARY.

#include <stdlib.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "crankcheck/validation/process.h"
#include "fresh_folder.h"

#ifndef CRANKCHECK_BINARY
#error "CRANKCHECK_BINARY (the crankcheck program under test) must be defined by the build"
#endif

namespace crankcheck::testing {

/// [s] The limit on one crankcheck run in a test (every child has one): the longest, a full campaign, takes about
/// two minutes on two cores; ctest's own timeout (1500 s) is the test's.
constexpr double kCliRunSeconds = 1200.0;

/// Runs `crankcheck ARGS...` in `working_dir` (empty: the test's) with `environment` changes ("NAME=VALUE",
/// "NAME" to remove); returns its exit status, stdout and stderr.
inline validation::ProgramResult runCrankcheck(const std::vector<std::string>& args,
                                               const std::vector<std::string>& environment = {},
                                               const std::filesystem::path& working_dir = {}) {
  validation::ProgramCall call{{CRANKCHECK_BINARY}, working_dir, environment};
  call.argv.insert(call.argv.end(), args.begin(), args.end());
  call.timeout_seconds = kCliRunSeconds;
  return validation::runProgram(call);
}

/// Starts `crankcheck ARGS...` and returns at once (to send it a signal, then wait()).
inline validation::RunningProgram startCrankcheck(const std::vector<std::string>& args) {
  validation::ProgramCall call{{CRANKCHECK_BINARY}};
  call.argv.insert(call.argv.end(), args.begin(), args.end());
  call.timeout_seconds = kCliRunSeconds;
  return validation::startProgram(call);
}

}  // namespace crankcheck::testing

