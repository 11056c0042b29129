#include "grade_bridge.h"

#include <fcntl.h>
#include <signal.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <nlohmann/json.hpp>
#include <stdexcept>

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

}  // namespace

// The private folder holding the socket, removed with it.
class InProcessGrade::Folder {
 public:
  Folder() {
    // A short path: a Unix socket's path has at most 107 bytes. TMPDIR when it is short enough, else /tmp.
    std::string base = "/tmp";
    if (const char* tmp = std::getenv("TMPDIR"); tmp && *tmp && std::strlen(tmp) < 64) base = tmp;
    std::string pattern = base + "/crankcheck-grade-XXXXXX";
    if (!::mkdtemp(pattern.data())) throw EnvironmentError(systemError("grade: cannot create a folder in " + base));
    folder_ = pattern;
    socket_ = folder_ + "/relay.sock";
  }
  ~Folder() {
    ::unlink(socket_.c_str());
    ::rmdir(folder_.c_str());
  }
  const std::string& socketPath() const { return socket_; }

 private:
  std::string folder_, socket_;
};

namespace {

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

// Blocks every signal that can be blocked and is not a fault's in the calling thread while it lives, so that the
// threads it starts inherit the mask: Ctrl-C and the caller's SIGALRM go to the thread running Python.
class SignalsBlocked {
 public:
  SignalsBlocked() {
    sigset_t all;
    sigfillset(&all);
    for (int fault : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGTRAP, SIGABRT}) sigdelset(&all, fault);
    pthread_sigmask(SIG_BLOCK, &all, &old_);
  }
  ~SignalsBlocked() { pthread_sigmask(SIG_SETMASK, &old_, nullptr); }
  SignalsBlocked(const SignalsBlocked&) = delete;
  SignalsBlocked& operator=(const SignalsBlocked&) = delete;

 private:
  sigset_t old_;
};

}  // namespace

// One relay's connection: its batch's request lines in, one response line each out.
struct InProcessGrade::Connection {
  explicit Connection(int descriptor) : fd(descriptor) {}
  Fd fd;  // closed with the last reference, after stop(): until then stop() may shut it down at any time
  std::vector<std::string> answers;
  size_t left = 0;  // requests without an answer
};

InProcessGrade::InProcessGrade(std::vector<validation::GradeCase> cases, const GradeSettings& settings)
    : cases_(std::move(cases)), settings_(settings), folder_(std::make_unique<Folder>()) {
  for (const validation::GradeCase& c : cases_) by_id_[c.id] = &c;
  listener_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (listener_ < 0) throw EnvironmentError(systemError("grade: cannot create a Unix socket"));
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::strncpy(address.sun_path, folder_->socketPath().c_str(), sizeof address.sun_path - 1);
  // A backlog above the most relays at once (jobs <= 256): a relay never waits in connect.
  if (::bind(listener_, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0 || ::listen(listener_, 1024) != 0) {
    const std::string error = systemError("grade: cannot listen on " + folder_->socketPath());
    ::close(listener_);
    throw EnvironmentError(error);
  }
  int stop_pipe[2];
  if (::pipe2(stop_pipe, O_CLOEXEC) != 0) {
    const std::string error = systemError("grade: cannot create a pipe");
    ::close(listener_);
    throw EnvironmentError(error);
  }
  stop_read_ = stop_pipe[0];
  stop_write_ = stop_pipe[1];

  validation::GradeProgram program;
  program.argv = {settings_.relay.string(), folder_->socketPath()};
  program.timeout_seconds = settings_.relay_timeout_seconds;
  program.batch = true;
  const SignalsBlocked blocked;
  acceptor_ = std::thread([this] { acceptLoop(); });
  grader_ = std::thread([this, program] {
    validation::TableSet tables;
    std::exception_ptr error;
    try {
      tables = validation::runGrade(cases_, program, settings_.jobs);
    } catch (...) {
      error = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(mutex_);
    tables_ = std::move(tables);
    grade_error_ = error;
    grade_done_ = true;
    changed_.notify_all();
  });
}

InProcessGrade::~InProcessGrade() { stop(); }

void InProcessGrade::acceptLoop() {
  for (;;) {
    pollfd fds[2] = {{listener_, POLLIN, 0}, {stop_read_, POLLIN, 0}};
    if (::poll(fds, 2, -1) < 0) {  // stop() ends the wait
      if (errno == EINTR) continue;
      return;
    }
    if (fds[1].revents) return;
    const int fd = ::accept4(listener_, nullptr, nullptr, SOCK_CLOEXEC);
    if (fd < 0) continue;
    const auto connection = std::make_shared<Connection>(fd);
    std::lock_guard<std::mutex> lock(mutex_);
    if (stopping_) {
      ::shutdown(fd, SHUT_RDWR);  // its relay exits; the descriptor closes with `connection`
      continue;
    }
    connections_.push_back(connection);
    handlers_.emplace_back([this, connection] { handle(connection); });
  }
}

void InProcessGrade::handle(const std::shared_ptr<Connection>& connection) {
  const int fd = connection->fd.get();
  std::string input;
  // The relay sends its batch, then shuts its side; stop() shuts the connection, which ends the read too.
  const bool read = readAll(fd, input);
  std::vector<const validation::GradeCase*> requests;
  try {
    for (size_t begin = 0; read && begin < input.size();) {
      size_t end = input.find('\n', begin);
      if (end == std::string::npos) end = input.size();
      const std::string line = input.substr(begin, end - begin);
      begin = end + 1;
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      const std::string id = nlohmann::json::parse(line).at("case").get<std::string>();
      const auto it = by_id_.find(id);
      if (it == by_id_.end()) throw std::logic_error("grade: a request for unknown case " + id);
      requests.push_back(it->second);
    }
  } catch (...) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!bridge_error_) bridge_error_ = std::current_exception();
    requests.clear();
  }
  std::string output;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    if (!stopping_ && !requests.empty()) {
      connection->answers.resize(requests.size());
      connection->left = requests.size();
      for (size_t slot = 0; slot < requests.size(); ++slot) {
        const size_t id = next_id_++;
        pending_[id] = {connection, slot, requests[slot]};
        queue_.push_back(id);
      }
      changed_.notify_all();
      // Until the caller has answered every request of the batch, or stop() (which every ending of the grade calls).
      changed_.wait(lock, [&] { return connection->left == 0 || stopping_; });
      if (!stopping_)
        for (const std::string& answer : connection->answers) output += answer + '\n';
    }
  }
  // Nothing sent when the grade stops or a request was not understood: the relay prints nothing and runGrade ends.
  if (!output.empty()) sendAll(fd, output);
  ::shutdown(fd, SHUT_RDWR);  // the relay reads to the end of the answers and exits
}

std::optional<InProcessGrade::Request> InProcessGrade::next(std::chrono::milliseconds wait) {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait_for(lock, wait, [&] { return !queue_.empty() || grade_done_ || stopping_; });
  if (queue_.empty() || grade_done_ || stopping_) return std::nullopt;
  const size_t id = queue_.front();
  queue_.pop_front();
  return Request{id, pending_.at(id).grade_case};
}

void InProcessGrade::answer(size_t id, std::string response) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = pending_.find(id);
  if (it == pending_.end()) return;
  Connection& connection = *it->second.connection;
  connection.answers[it->second.slot] = std::move(response);
  --connection.left;
  pending_.erase(it);
  changed_.notify_all();
}

const validation::GradeCase* InProcessGrade::caseOf(size_t id) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = pending_.find(id);
  return it == pending_.end() || stopping_ ? nullptr : it->second.grade_case;
}

bool InProcessGrade::finished() {
  std::lock_guard<std::mutex> lock(mutex_);
  return grade_done_;
}

void InProcessGrade::stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (stopped_) return;
    stopping_ = true;
    for (const std::shared_ptr<Connection>& c : connections_) ::shutdown(c->fd.get(), SHUT_RDWR);
    changed_.notify_all();
  }
  const char stop = 1;
  while (::write(stop_write_, &stop, 1) < 0 && errno == EINTR) {
  }
  acceptor_.join();
  // A relay not yet accepted finds its connection reset, one not yet connected finds no socket: it exits either way.
  ::close(listener_);
  // No thread adds to handlers_ now. Each returns at stopping_ (a read ends at the shutdown).
  for (std::thread& t : handlers_) t.join();
  // Every relay exits once its connection ends; runGrade then ends after the case each job is grading.
  grader_.join();
  ::close(stop_read_);
  ::close(stop_write_);
  folder_.reset();
  std::lock_guard<std::mutex> lock(mutex_);
  stopped_ = true;
}

validation::TableSet InProcessGrade::result() {
  stop();
  if (bridge_error_) std::rethrow_exception(bridge_error_);
  if (grade_error_) std::rethrow_exception(grade_error_);
  return std::move(tables_);
}

}  // namespace crankcheck::python
