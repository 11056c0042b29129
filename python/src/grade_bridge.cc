#include "grade_bridge.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "crankcheck/validation/errors.h"

namespace crankcheck::python {
namespace {

std::string systemError(const std::string& what) { return what + ": " + std::strerror(errno); }

// A file descriptor closed once.
class Fd {
 public:
  explicit Fd(int fd = -1) : fd_(fd) {}
  ~Fd() { reset(); }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return fd_; }
  void reset() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }

 private:
  int fd_;
};

// The private folder holding the socket, removed with it.
class SocketFolder {
 public:
  SocketFolder() {
    // A short path: a Unix socket's path has at most 107 bytes. TMPDIR when it is short enough, else /tmp.
    std::string base = "/tmp";
    if (const char* tmp = std::getenv("TMPDIR"); tmp && *tmp && std::strlen(tmp) < 64) base = tmp;
    std::string pattern = base + "/crankcheck-grade-XXXXXX";
    if (!::mkdtemp(pattern.data())) throw EnvironmentError(systemError("grade: cannot create a folder in " + base));
    folder_ = pattern;
    socket_ = folder_ + "/relay.sock";
  }
  ~SocketFolder() {
    ::unlink(socket_.c_str());
    ::rmdir(folder_.c_str());
  }
  const std::string& socketPath() const { return socket_; }

 private:
  std::string folder_, socket_;
};

bool readAll(int fd, std::string& into) {
  char buffer[65536];
  for (;;) {
    const ssize_t got = ::read(fd, buffer, sizeof buffer);
    if (got == 0) return true;
    if (got < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    into.append(buffer, static_cast<size_t>(got));
  }
}

void sendAll(int fd, const std::string& text) {
  size_t sent = 0;
  while (sent < text.size()) {
    const ssize_t n = ::send(fd, text.data() + sent, text.size() - sent, MSG_NOSIGNAL);
    if (n < 0) {
      if (errno == EINTR) continue;
      return;  // the relay is gone (killed at its timeout): runGrade reports that
    }
    sent += static_cast<size_t>(n);
  }
}

}  // namespace

validation::TableSet gradeInProcess(const std::vector<validation::GradeCase>& cases, const GradeAnswer& answer,
                                    const InProcessGrade& settings) {
  std::map<std::string, const validation::GradeCase*> by_id;
  for (const validation::GradeCase& c : cases) by_id[c.id] = &c;

  SocketFolder folder;
  Fd listener(::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0));
  if (listener.get() < 0) throw EnvironmentError(systemError("grade: cannot create a Unix socket"));
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::strncpy(address.sun_path, folder.socketPath().c_str(), sizeof address.sun_path - 1);
  if (::bind(listener.get(), reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0 ||
      ::listen(listener.get(), 64) != 0)
    throw EnvironmentError(systemError("grade: cannot listen on " + folder.socketPath()));
  int stop_pipe[2];
  if (::pipe2(stop_pipe, O_CLOEXEC) != 0) throw EnvironmentError(systemError("grade: cannot create a pipe"));
  Fd stop_read(stop_pipe[0]), stop_write(stop_pipe[1]);

  std::atomic<bool> failed{false};
  std::mutex mutex;  // guards answer_error and handlers
  std::exception_ptr answer_error;
  std::vector<std::thread> handlers;

  // One relay's connection: every request line of its batch in, one response line each out.
  auto handle = [&](int fd) {
    Fd connection(fd);
    std::string input, output;
    if (!readAll(fd, input)) return;
    size_t begin = 0;
    try {
      while (begin < input.size() && !failed) {
        size_t end = input.find('\n', begin);
        if (end == std::string::npos) end = input.size();
        const std::string line = input.substr(begin, end - begin);
        begin = end + 1;
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        const std::string id = nlohmann::json::parse(line).at("case").get<std::string>();
        const auto it = by_id.find(id);
        if (it == by_id.end()) throw std::logic_error("grade: a request for unknown case " + id);
        output += answer(*it->second, line);
        output += '\n';
      }
    } catch (...) {
      failed = true;
      std::lock_guard<std::mutex> lock(mutex);
      if (!answer_error) answer_error = std::current_exception();
      return;  // no answer: the relay prints nothing and runGrade stops; the error above is what the caller sees
    }
    sendAll(fd, output);
  };
  std::thread acceptor([&] {
    for (;;) {
      pollfd fds[2] = {{listener.get(), POLLIN, 0}, {stop_read.get(), POLLIN, 0}};
      if (::poll(fds, 2, -1) < 0) {
        if (errno == EINTR) continue;
        return;
      }
      if (fds[1].revents) return;
      const int fd = ::accept4(listener.get(), nullptr, nullptr, SOCK_CLOEXEC);
      if (fd < 0) continue;
      std::lock_guard<std::mutex> lock(mutex);
      handlers.emplace_back(handle, fd);
    }
  });

  validation::GradeProgram program;
  program.argv = {settings.relay.string(), folder.socketPath()};
  program.timeout_seconds = settings.timeout_seconds;
  program.batch = true;
  validation::TableSet tables;
  std::exception_ptr grade_error;
  try {
    tables = validation::runGrade(cases, program, settings.jobs);
  } catch (...) {
    grade_error = std::current_exception();
  }
  // The grade is over (or ended by a timeout, which killed the relays): a handler still answering stops after the
  // answer it is computing, which cannot be interrupted (the function runs in this process).
  failed = true;
  const char stop = 1;
  while (::write(stop_write.get(), &stop, 1) < 0 && errno == EINTR) {
  }
  acceptor.join();
  for (std::thread& t : handlers) t.join();  // a handler still in `answer` (its relay timed out) finishes it first
  if (answer_error) std::rethrow_exception(answer_error);
  if (grade_error) std::rethrow_exception(grade_error);
  return tables;
}

}  // namespace crankcheck::python
