#include "crankcheck/validation/process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <dirent.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <pthread.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <set>

#include "crankcheck/validation/errors.h"

extern char** environ;

namespace crankcheck::validation {
namespace fs = std::filesystem;

namespace {

std::mutex& runningMutex() {
  static std::mutex mutex;
  return mutex;
}
std::set<pid_t>& runningPids() {
  static std::set<pid_t> pids;
  return pids;
}

std::atomic<bool>& reaping() {
  static std::atomic<bool> on{false};
  return on;
}

// A process left behind: its pid, and whether it counts against the program (alive, and outside `group`, the
// program's own process group, which crankcheck ends itself: its members killed there come here only to be reaped).
struct LeftBehind {
  pid_t pid;
  bool counts;
};

// This process's children that no call started (their pids not in runningPids): what programs left behind, handed
// to this process as their reaper. Read from /proc/PID/stat (after the name, which is in parentheses and may hold
// anything, so read after the last ')': the state, the parent's pid, the process group). Under runningMutex, so that
// a child being spawned is already listed.
std::vector<LeftBehind> findLeftBehind(pid_t group) {
  std::vector<LeftBehind> found;
  const pid_t self = ::getpid();
  DIR* proc = ::opendir("/proc");
  if (proc == nullptr) return found;
  while (const dirent* entry = ::readdir(proc)) {
    char* end = nullptr;
    const long pid = std::strtol(entry->d_name, &end, 10);
    if (pid <= 0 || *end != '\0' || runningPids().count(static_cast<pid_t>(pid))) continue;
    std::ifstream in(std::string("/proc/") + entry->d_name + "/stat");
    std::string stat;
    std::getline(in, stat);
    const size_t close = stat.rfind(')');
    if (close == std::string::npos) continue;
    char state = 0;
    long parent = 0, process_group = 0;
    if (std::sscanf(stat.c_str() + close + 1, " %c %ld %ld", &state, &parent, &process_group) == 3 && parent == self)
      found.push_back({static_cast<pid_t>(pid), state != 'Z' && state != 'X' && process_group != group});
  }
  ::closedir(proc);
  return found;
}

// Ends (SIGKILL to the process and to its group: a setsid child leads one) and reaps every process left behind;
// what they started in turn comes to this process as they end, so the scan repeats until it finds none (at most 64
// rounds: a fork bomb is not waited on without a limit). Returns how many counted (findLeftBehind) against the
// program whose process group is `group`.
int endLeftBehind(pid_t group) {
  int ended = 0;
  for (int round = 0; round < 64; ++round) {
    std::vector<LeftBehind> found;
    {
      std::lock_guard<std::mutex> lock(runningMutex());
      found = findLeftBehind(group);
      for (const LeftBehind& p : found) {
        ::kill(p.pid, SIGKILL);
        ::kill(-p.pid, SIGKILL);
      }
    }
    if (found.empty()) break;
    for (const LeftBehind& p : found) {
      while (::waitpid(p.pid, nullptr, 0) < 0 && errno == EINTR) {
      }
      ended += p.counts ? 1 : 0;
    }
  }
  return ended;
}

bool isExecutableFile(const fs::path& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

// The caller's environment with the call's changes applied, as "NAME=VALUE" strings.
std::vector<std::string> childEnvironment(const std::vector<std::string>& changes) {
  std::map<std::string, std::string> env;
  for (char** e = environ; e != nullptr && *e != nullptr; ++e) {
    const std::string entry = *e;
    const size_t eq = entry.find('=');
    if (eq != std::string::npos) env[entry.substr(0, eq)] = entry;
  }
  for (const std::string& change : changes) {
    const size_t eq = change.find('=');
    if (eq == std::string::npos) env.erase(change);
    else env[change.substr(0, eq)] = change;
  }
  std::vector<std::string> out;
  for (auto& [name, entry] : env) out.push_back(std::move(entry));
  return out;
}

std::string pathSetting(const std::vector<std::string>& changes) {
  for (auto it = changes.rbegin(); it != changes.rend(); ++it)
    if (it->rfind("PATH=", 0) == 0) return it->substr(5);
  const char* path = std::getenv("PATH");
  return path != nullptr ? path : "/usr/local/bin:/usr/bin:/bin";
}

fs::path findOnPath(const std::string& name, const std::string& path) {
  if (name.empty()) return {};
  if (name.find('/') != std::string::npos) return isExecutableFile(name) ? fs::path(name) : fs::path();
  size_t begin = 0;
  while (begin <= path.size()) {
    size_t end = path.find(':', begin);
    if (end == std::string::npos) end = path.size();
    const fs::path candidate = fs::path(end > begin ? path.substr(begin, end - begin) : ".") / name;
    if (isExecutableFile(candidate)) return candidate;
    begin = end + 1;
  }
  return {};
}

// Closes the descriptors of a pipe on scope exit unless released.
struct Pipe {
  int fd[2] = {-1, -1};
  ~Pipe() {
    for (int f : fd)
      if (f >= 0) ::close(f);
  }
};

}  // namespace

fs::path findProgram(const std::string& name) { return findOnPath(name, pathSetting({})); }

RunningProgram::RunningProgram(pid_t pid, int out_fd, int err_fd, int in_fd, const ProgramCall* call)
    : pid_(pid), out_fd_(out_fd), err_fd_(err_fd), in_fd_(in_fd) {
  if (call != nullptr) {
    if (call->input) input_ = *call->input;
    timeout_seconds_ = call->timeout_seconds;
    output_limit_ = call->output_limit;
  }
}

RunningProgram::RunningProgram(RunningProgram&& other) noexcept
    : pid_(other.pid_), out_fd_(other.out_fd_), err_fd_(other.err_fd_), in_fd_(other.in_fd_),
      input_(std::move(other.input_)), timeout_seconds_(other.timeout_seconds_), output_limit_(other.output_limit_) {
  other.pid_ = -1;
  other.out_fd_ = other.err_fd_ = other.in_fd_ = -1;
}

RunningProgram::~RunningProgram() {
  if (pid_ > 0) wait();
}

namespace {

// write() to a pipe whose reader is gone raises SIGPIPE; block it in this thread around the write and consume a
// SIGPIPE the write left pending, so the caller sees EPIPE and nothing else (the signal is per thread here).
ssize_t writeWithoutSigpipe(int fd, const char* data, size_t size) {
  sigset_t pipe_only, old_mask;
  sigemptyset(&pipe_only);
  sigaddset(&pipe_only, SIGPIPE);
  sigset_t pending;
  sigpending(&pending);
  const bool was_pending = sigismember(&pending, SIGPIPE) == 1;
  pthread_sigmask(SIG_BLOCK, &pipe_only, &old_mask);
  const ssize_t written = ::write(fd, data, size);
  const int saved_errno = errno;
  if (written < 0 && saved_errno == EPIPE && !was_pending) {
    const timespec zero{0, 0};
    while (sigtimedwait(&pipe_only, nullptr, &zero) < 0 && errno == EINTR) {
    }
  }
  pthread_sigmask(SIG_SETMASK, &old_mask, nullptr);
  errno = saved_errno;
  return written;
}

}  // namespace

ProgramResult RunningProgram::wait() {
  using Clock = std::chrono::steady_clock;
  ProgramResult result;
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(timeout_seconds_));
  size_t input_done = 0;
  if (in_fd_ >= 0 && input_.empty()) {
    ::close(in_fd_);
    in_fd_ = -1;
  }
  bool killed = false, reaped = false;
  int status = 0;
  auto killGroup = [&] {
    if (!killed) ::kill(-pid_, SIGKILL);
    killed = true;
  };
  char buffer[65536];
  while (out_fd_ >= 0 || err_fd_ >= 0 || in_fd_ >= 0) {
    pollfd fds[3];
    nfds_t n = 0;
    if (out_fd_ >= 0) fds[n++] = {out_fd_, POLLIN, 0};
    if (err_fd_ >= 0) fds[n++] = {err_fd_, POLLIN, 0};
    if (in_fd_ >= 0) fds[n++] = {in_fd_, POLLOUT, 0};
    int wait_ms = -1;
    if (timeout_seconds_ > 0.0 && !killed) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
      if (left <= 0) {
        result.timed_out = true;
        // Ended already (reaped here, its status kept) while its output stays open: a process it left behind holds it.
        if (::waitpid(pid_, &status, WNOHANG) == pid_) reaped = result.left_output_open = true;
        killGroup();
        // The pipes may stay open in a grandchild that escaped the group: stop reading them.
        break;
      }
      wait_ms = static_cast<int>(std::min<long long>(left, 1000));
    }
    const int ready = ::poll(fds, n, wait_ms);
    if (ready < 0) {
      if (errno == EINTR) continue;
      break;
    }
    for (nfds_t i = 0; i < n; ++i) {
      if (fds[i].revents == 0) continue;
      if (fds[i].fd == in_fd_) {
        const ssize_t put = writeWithoutSigpipe(in_fd_, input_.data() + input_done, input_.size() - input_done);
        if (put > 0) input_done += static_cast<size_t>(put);
        if ((put < 0 && errno != EINTR && errno != EAGAIN) || input_done == input_.size()) {
          if (input_done < input_.size()) result.input_refused = true;
          ::close(in_fd_);
          in_fd_ = -1;
        }
        continue;
      }
      const bool is_out = fds[i].fd == out_fd_;
      int& fd = is_out ? out_fd_ : err_fd_;
      std::string& text = is_out ? result.out : result.err;
      const ssize_t got = ::read(fd, buffer, sizeof buffer);
      if (got > 0) {
        text.append(buffer, static_cast<size_t>(got));
        if (!is_out && text.size() > 2 * kErrorTailBytes) {  // keep the tail; erase once per kErrorTailBytes read
          text.erase(0, text.size() - kErrorTailBytes);
          result.err_cut = true;
        }
        if (is_out && output_limit_ > 0 && text.size() > output_limit_) {
          text.resize(output_limit_);
          result.output_limit_exceeded = true;
          killGroup();
          ::close(fd);
          fd = -1;
        }
      } else if (got == 0 || errno != EINTR) {
        ::close(fd);
        fd = -1;
      }
    }
  }
  for (int* fd : {&out_fd_, &err_fd_, &in_fd_})
    if (*fd >= 0) {
      ::close(*fd);
      *fd = -1;
    }
  if (result.err.size() > kErrorTailBytes) {
    result.err.erase(0, result.err.size() - kErrorTailBytes);
    result.err_cut = true;
  }
  // A program that closed its output but does not end is still held to the timeout.
  while (timeout_seconds_ > 0.0 && !killed) {
    const pid_t done = ::waitpid(pid_, &status, WNOHANG);
    if (done == pid_ || (done < 0 && errno != EINTR)) break;
    if (Clock::now() >= deadline) {
      result.timed_out = true;
      killGroup();
      break;
    }
    ::usleep(2000);
  }
  if ((killed || timeout_seconds_ <= 0.0) && !reaped)
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
  {
    std::lock_guard<std::mutex> lock(runningMutex());
    runningPids().erase(pid_);
  }
  if (reaping()) result.left_behind = endLeftBehind(pid_);  // its own group is pid_ (posix_spawnattr_setpgroup 0)
  pid_ = -1;
  if (WIFEXITED(status)) result.exit_status = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
  return result;
}

RunningProgram startProgram(const ProgramCall& call) {
  if (call.argv.empty()) throw std::logic_error("startProgram: empty argument vector");
  if (!(call.timeout_seconds > 0.0))
    throw std::logic_error("startProgram: " + call.argv[0] + ": no time limit (every child has one)");
  const fs::path program = findOnPath(call.argv[0], pathSetting(call.environment));
  if (program.empty())
    throw EnvironmentError(call.argv[0] + ": not found (no executable of that name on PATH)");

  Pipe out, err, in;
  if (::pipe2(out.fd, O_CLOEXEC) != 0 || ::pipe2(err.fd, O_CLOEXEC) != 0 ||
      (call.input && ::pipe2(in.fd, O_CLOEXEC) != 0))
    throw EnvironmentError(call.argv[0] + ": cannot create a pipe: " + std::strerror(errno));

  posix_spawn_file_actions_t actions;
  posix_spawnattr_t attributes;
  posix_spawn_file_actions_init(&actions);
  posix_spawnattr_init(&attributes);
  if (call.input) posix_spawn_file_actions_adddup2(&actions, in.fd[0], STDIN_FILENO);
  else posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, out.fd[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, err.fd[1], STDERR_FILENO);
  if (!call.working_dir.empty()) posix_spawn_file_actions_addchdir_np(&actions, call.working_dir.c_str());
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  for (int s : {SIGINT, SIGTERM, SIGPIPE, SIGXFSZ}) sigaddset(&defaults, s);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setpgroup(&attributes, 0);  // a group of its own: a timeout kills whatever it started too
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETPGROUP);

  std::vector<char*> argv;
  for (const std::string& a : call.argv) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const std::vector<std::string> env_strings = childEnvironment(call.environment);
  std::vector<char*> envp;
  for (const std::string& e : env_strings) envp.push_back(const_cast<char*>(e.c_str()));
  envp.push_back(nullptr);

  pid_t pid = -1;
  int rc = 0;
  {
    std::lock_guard<std::mutex> lock(runningMutex());
    rc = ::posix_spawn(&pid, program.c_str(), &actions, &attributes, argv.data(), envp.data());
    if (rc == 0) runningPids().insert(pid);
  }
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  if (rc != 0) throw EnvironmentError(program.string() + ": cannot be started: " + std::strerror(rc));
  ::close(out.fd[1]);
  ::close(err.fd[1]);
  out.fd[1] = err.fd[1] = -1;
  if (call.input) {
    ::close(in.fd[0]);
    in.fd[0] = -1;
    ::fcntl(in.fd[1], F_SETFL, ::fcntl(in.fd[1], F_GETFL) | O_NONBLOCK);
  }
  RunningProgram running(pid, out.fd[0], err.fd[0], in.fd[1], &call);
  out.fd[0] = err.fd[0] = in.fd[1] = -1;
  return running;
}

ProgramResult runProgram(const ProgramCall& call) { return startProgram(call).wait(); }

void killRunningPrograms() {
  std::lock_guard<std::mutex> lock(runningMutex());
  for (pid_t pid : runningPids()) ::kill(-pid, SIGKILL);  // each runs in a process group of its own
}

void endLeftBehindProcesses() {
  if (reaping()) endLeftBehind(0);
}

bool isReapingLeftBehindProcesses() { return reaping(); }

bool reapLeftBehindProcesses() {
  if (::prctl(PR_SET_CHILD_SUBREAPER, 1) != 0) return false;
  reaping() = true;
  return true;
}

}  // namespace crankcheck::validation
