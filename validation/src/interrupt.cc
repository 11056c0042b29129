#include "crankcheck/validation/interrupt.h"

#include <pthread.h>
#include <signal.h>
#include <string.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <thread>

#include "crankcheck/validation/process.h"

namespace crankcheck::validation {
namespace {

std::mutex g_mutex;
OutputFolder* g_folder = nullptr;  // guarded by g_mutex
std::atomic<bool> g_interrupting{false};  // set by the watcher, holding g_mutex, before it kills anything

sigset_t interruptSignals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGHUP);  // the terminal closed
  return set;
}

void watch() {
  const sigset_t set = interruptSignals();
  int signal_number = 0;
  while (sigwait(&set, &signal_number) != 0) {
  }
  {
    // The lock first, then the mark, then the kill: whatever fails because of the kill (a wait on gnuplot) finds the
    // mark set in yieldToInterrupt and waits on this lock, which is never released (the process ends holding it).
    std::lock_guard<std::mutex> lock(g_mutex);
    g_interrupting = true;
    killRunningPrograms();
    const char* name = signal_number == SIGINT ? "SIGINT" : signal_number == SIGTERM ? "SIGTERM" : "SIGHUP";
    // On a terminal the message starts on a line of its own (after the ^C the terminal echoed); in a file or a pipe,
    // where nothing else was written, it is the one line.
    const char* start = ::isatty(STDERR_FILENO) ? "\n" : "";
    if (g_folder != nullptr) {
      g_folder->abandon();
      std::fprintf(stderr, "%scrankcheck: interrupted by %s; the partial output was removed, the previous report is as it was\n",
                   start, name);
    } else {
      std::fprintf(stderr, "%scrankcheck: interrupted by %s; nothing was written\n", start, name);
    }
    std::fflush(stderr);
    endLeftBehindProcesses();  // after the message: a program's setsid child does not outlive crankcheck either
    std::_Exit(128 + signal_number);  // with the lock held: no install starts after this point
  }
}

}  // namespace

void yieldToInterrupt() {
  if (g_interrupting) std::lock_guard<std::mutex> wait(g_mutex);  // never taken: the watcher exits holding it
}

void watchInterrupts() {
  static const bool started = [] {
    const sigset_t set = interruptSignals();
    pthread_sigmask(SIG_BLOCK, &set, nullptr);
    std::thread(watch).detach();
    return true;
  }();
  (void)started;
}

InterruptGuard::InterruptGuard(OutputFolder& folder) {
  watchInterrupts();
  std::lock_guard<std::mutex> lock(g_mutex);
  g_folder = &folder;
}

InterruptGuard::~InterruptGuard() {
  std::lock_guard<std::mutex> lock(g_mutex);
  g_folder = nullptr;
}

}  // namespace crankcheck::validation
