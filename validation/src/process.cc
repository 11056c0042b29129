#include "crankcheck/validation/process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
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

RunningProgram::RunningProgram(RunningProgram&& other) noexcept
    : pid_(other.pid_), out_fd_(other.out_fd_), err_fd_(other.err_fd_) {
  other.pid_ = -1;
  other.out_fd_ = other.err_fd_ = -1;
}

RunningProgram::~RunningProgram() {
  if (pid_ > 0) wait();
}

ProgramResult RunningProgram::wait() {
  ProgramResult result;
  struct Stream {
    int& fd;
    std::string& text;
  };
  Stream streams[2] = {{out_fd_, result.out}, {err_fd_, result.err}};
  char buffer[4096];
  while (out_fd_ >= 0 || err_fd_ >= 0) {
    pollfd fds[2];
    nfds_t n = 0;
    for (const Stream& s : streams)
      if (s.fd >= 0) fds[n++] = {s.fd, POLLIN, 0};
    if (::poll(fds, n, -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    for (nfds_t i = 0; i < n; ++i) {
      if (fds[i].revents == 0) continue;
      for (Stream& s : streams) {
        if (s.fd != fds[i].fd) continue;
        const ssize_t got = ::read(s.fd, buffer, sizeof buffer);
        if (got > 0) {
          s.text.append(buffer, static_cast<size_t>(got));
        } else if (got == 0 || errno != EINTR) {
          ::close(s.fd);
          s.fd = -1;
        }
      }
    }
  }
  for (int* fd : {&out_fd_, &err_fd_})
    if (*fd >= 0) {
      ::close(*fd);
      *fd = -1;
    }
  int status = 0;
  while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  {
    std::lock_guard<std::mutex> lock(runningMutex());
    runningPids().erase(pid_);
  }
  pid_ = -1;
  if (WIFEXITED(status)) result.exit_status = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
  return result;
}

RunningProgram startProgram(const ProgramCall& call) {
  if (call.argv.empty()) throw std::logic_error("startProgram: empty argument vector");
  const fs::path program = findOnPath(call.argv[0], pathSetting(call.environment));
  if (program.empty())
    throw EnvironmentError(call.argv[0] + ": not found (no executable of that name on PATH)");

  Pipe out, err;
  if (::pipe2(out.fd, O_CLOEXEC) != 0 || ::pipe2(err.fd, O_CLOEXEC) != 0)
    throw EnvironmentError(call.argv[0] + ": cannot create a pipe: " + std::strerror(errno));

  posix_spawn_file_actions_t actions;
  posix_spawnattr_t attributes;
  posix_spawn_file_actions_init(&actions);
  posix_spawnattr_init(&attributes);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, out.fd[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, err.fd[1], STDERR_FILENO);
  if (!call.working_dir.empty()) posix_spawn_file_actions_addchdir_np(&actions, call.working_dir.c_str());
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  for (int s : {SIGINT, SIGTERM, SIGPIPE}) sigaddset(&defaults, s);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);

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
  RunningProgram running(pid, out.fd[0], err.fd[0]);
  out.fd[0] = err.fd[0] = -1;
  return running;
}

ProgramResult runProgram(const ProgramCall& call) { return startProgram(call).wait(); }

void killRunningPrograms() {
  std::lock_guard<std::mutex> lock(runningMutex());
  for (pid_t pid : runningPids()) ::kill(pid, SIGKILL);
}

}  // namespace crankcheck::validation
