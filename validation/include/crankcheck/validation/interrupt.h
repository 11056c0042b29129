#pragma once
/// @file
/// SIGINT, SIGTERM and SIGHUP: every program crankcheck started is ended with it, during `validate`, `report merge` and
/// `grade` the partial folder is removed and the previous report stays as it was, and crankcheck exits with status
/// 128 + the signal number. The library owns the watcher thread (the CLI starts none): the CLI calls watchInterrupts
/// first thing in main.

#include "crankcheck/validation/output_folder.h"

namespace crankcheck::validation {

/// Blocks SIGINT, SIGTERM and SIGHUP in the calling thread (and so in every thread it starts later) and starts the
/// one watcher thread that receives them: it kills every external program crankcheck is running (gnuplot, a graded
/// program), abandons the output folder of a live InterruptGuard, and exits with 128 + the signal number. Call it
/// first thing in main, before any other thread and any child. Idempotent.
void watchInterrupts();

/// Returns at once, unless an interrupt is being handled: then it waits for the watcher to end the process (128 + the
/// signal), so that what failed because the interrupt killed a child (a wait on gnuplot) is not reported as a
/// failure of its own with another status. The CLI calls it before it reports an error.
void yieldToInterrupt();

/// While a guard lives, SIGINT or SIGTERM kills the external programs crankcheck is running (gnuplot), abandons
/// `folder` (OutputFolder::abandon) and exits with 128 + the signal number. The signals are blocked in every thread
/// and received by one watcher thread, so construct the first guard before any other thread starts. After the
/// guard, the signals still end the process with 128 + the signal number.
class InterruptGuard {
 public:
  explicit InterruptGuard(OutputFolder& folder);
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
};

}  // namespace crankcheck::validation
