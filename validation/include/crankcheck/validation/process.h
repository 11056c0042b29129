#pragma once
/// @file
/// Starting external programs (gnuplot, a graded program) without a shell: the program gets its arguments as a
/// vector, so no character of a path (quotes, `$(...)`, backticks, semicolons, newlines) is ever interpreted.

#include <sys/types.h>

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace crankcheck::validation {

/// What to start.
struct ProgramCall {
  std::vector<std::string> argv;          ///< argv[0]: a path with a '/', or a name looked up on PATH
  std::filesystem::path working_dir = {}; ///< the child's working folder; empty: the caller's
  /// Changes to the child's environment: "NAME=VALUE" sets NAME, "NAME" alone removes it.
  std::vector<std::string> environment = {};
  /// What the program reads on stdin (written through a pipe, then closed); none: stdin is /dev/null.
  std::optional<std::string> input = std::nullopt;
  /// [s] The program (and every process of its process group) is killed with SIGKILL after this long. Required:
  /// crankcheck never waits on a child without a limit (startProgram refuses a call without one).
  double timeout_seconds = 0.0;
  /// [bytes] The program is killed with SIGKILL when its stdout grows past this; 0: no limit.
  size_t output_limit = 0;
};

/// [bytes] How much of a program's stderr is kept: its last 256 KiB (a message is read from its end: grade quotes the
/// last three lines), so that a program writing stderr at full speed until its timeout costs crankcheck no more memory.
inline constexpr size_t kErrorTailBytes = 256 * 1024;

/// How a program ended, and what it printed.
struct ProgramResult {
  int exit_status = -1;  ///< the exit status, or -1 when a signal ended it
  int signal = 0;        ///< the signal that ended it, or 0
  std::string out;       ///< everything it wrote to stdout (cut at the call's output_limit)
  std::string err;       ///< the end of what it wrote to stderr: at most kErrorTailBytes (err_cut: its start dropped)
  bool err_cut = false;  ///< stderr was longer than kErrorTailBytes
  bool timed_out = false;              ///< killed at the call's timeout_seconds
  bool output_limit_exceeded = false;  ///< killed because stdout passed the call's output_limit
  bool input_refused = false;          ///< it closed its stdin (or ended) before reading all of the input
  /// It had exited by the timeout, but its stdout or stderr was still open: held by a process it left behind outside
  /// its process group (a setsid child). timed_out is set too.
  bool left_output_open = false;
  /// Processes still running when the call returned, outside the program's process group, that crankcheck ended
  /// (SIGKILL) as left behind by it: a setsid child or a daemon. (What crankcheck killed in the group does not count.) Counted only where reapLeftBehindProcesses
  /// was called (the CLI); a call that runs beside others may count what another call's program left.
  int left_behind = 0;
};

/// Makes this process the reaper of whatever its programs leave behind (Linux PR_SET_CHILD_SUBREAPER): a process a
/// program started and did not end (a setsid child, a daemon) becomes this process's child when the program ends, and
/// every wait() ends such processes (SIGKILL, then reaped) before it returns, counting them in
/// ProgramResult::left_behind; an interrupt ends them too (endLeftBehindProcesses). The CLI calls it once at start. A library user (the
/// Python module, in the user's interpreter) does not: there such a process outlives the call, out of reach.
/// @return false when the kernel refuses (before Linux 3.4): then nothing is reaped, as in a library.
bool reapLeftBehindProcesses();

/// Whether reapLeftBehindProcesses was called (and took effect): a process a program leaves behind is then ended.
bool isReapingLeftBehindProcesses();

/// The full path of the executable file `name` on PATH (or `name` itself when it contains a '/' and is
/// executable); empty when there is none. Reads only the file system: takes microseconds.
std::filesystem::path findProgram(const std::string& name);

/// A program started by startProgram: wait() collects its output and its end.
class RunningProgram {
 public:
  RunningProgram(pid_t pid, int out_fd, int err_fd, int in_fd = -1, const ProgramCall* call = nullptr);
  RunningProgram(RunningProgram&& other) noexcept;
  RunningProgram(const RunningProgram&) = delete;
  RunningProgram& operator=(const RunningProgram&) = delete;
  RunningProgram& operator=(RunningProgram&&) = delete;
  /// Waits for the program if wait() was not called (its output is discarded).
  ~RunningProgram();

  pid_t pid() const { return pid_; }
  /// Writes the call's input, reads stdout and stderr until the program closes them (or the call's timeout or
  /// output limit ends it: SIGKILL to its process group), then waits for it to end.
  ProgramResult wait();

 private:
  pid_t pid_ = -1;
  int out_fd_ = -1, err_fd_ = -1, in_fd_ = -1;
  std::string input_;
  double timeout_seconds_ = 0.0;
  size_t output_limit_ = 0;
};

/// Starts a program with posix_spawn in a process group of its own: stdin is the call's input or /dev/null, stdout
/// and stderr are captured, the signal mask and the dispositions of SIGINT, SIGTERM, SIGPIPE and SIGXFSZ are reset to
/// the defaults whatever the caller's are. Writing the input never raises SIGPIPE in the caller.
/// @throws EnvironmentError naming the program when it is not found or cannot be started.
/// @throws std::logic_error when the call has no time limit (timeout_seconds <= 0): a caller's mistake.
RunningProgram startProgram(const ProgramCall& call);

/// startProgram, then wait. While it runs the child is listed for killRunningPrograms().
ProgramResult runProgram(const ProgramCall& call);

/// Sends SIGKILL to every program that runProgram is waiting for (used when crankcheck is interrupted).
void killRunningPrograms();

/// Ends (SIGKILL) and reaps every process the programs left behind that came to this process as their reaper
/// (reapLeftBehindProcesses); nothing where it was not called. An interrupted crankcheck calls it as it exits.
void endLeftBehindProcesses();

}  // namespace crankcheck::validation
