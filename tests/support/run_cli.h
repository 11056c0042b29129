#pragma once
/// @file
/// Runs the crankcheck program as a user would, without a shell (an argument vector: paths with quotes, `$(...)`
/// or newlines are passed as they are). The including target defines CRANKCHECK_BINARY.

#include <filesystem>
#include <string>
#include <vector>

#include "crankcheck/validation/process.h"

#ifndef CRANKCHECK_BINARY
#error "CRANKCHECK_BINARY (the crankcheck program under test) must be defined by the build"
#endif

namespace crankcheck::testing {

/// Runs `crankcheck ARGS...` in `working_dir` (empty: the test's) with `environment` changes ("NAME=VALUE",
/// "NAME" to remove); returns its exit status, stdout and stderr.
inline validation::ProgramResult runCrankcheck(const std::vector<std::string>& args,
                                               const std::vector<std::string>& environment = {},
                                               const std::filesystem::path& working_dir = {}) {
  validation::ProgramCall call{{CRANKCHECK_BINARY}, working_dir, environment};
  call.argv.insert(call.argv.end(), args.begin(), args.end());
  return validation::runProgram(call);
}

/// Starts `crankcheck ARGS...` and returns at once (to send it a signal, then wait()).
inline validation::RunningProgram startCrankcheck(const std::vector<std::string>& args) {
  validation::ProgramCall call{{CRANKCHECK_BINARY}};
  call.argv.insert(call.argv.end(), args.begin(), args.end());
  return validation::startProgram(call);
}

}  // namespace crankcheck::testing
