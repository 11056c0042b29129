#pragma once
/// @file
/// SIGINT and SIGTERM during `validate` and `report merge`: the partial folder is removed, the previous report
/// stays as it was, and crankcheck exits with status 128 + the signal number.

#include "crankcheck/validation/output_folder.h"

namespace crankcheck::app {

/// While a guard lives, SIGINT or SIGTERM kills the external programs crankcheck is running (gnuplot), abandons
/// `folder` (OutputFolder::abandon) and exits with 128 + the signal number. The signals are blocked in every thread
/// and received by one watcher thread, so construct the first guard before any other thread starts. After the
/// guard, the signals still end the process with 128 + the signal number.
class InterruptGuard {
 public:
  explicit InterruptGuard(validation::OutputFolder& folder);
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
};

}  // namespace crankcheck::app
