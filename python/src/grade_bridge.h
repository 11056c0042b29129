#pragma once
/// @file
/// `crankcheck.grade(function)`: a function of this process graded by `crankcheck grade`'s own code. The grade
/// (validation::runGrade: its cases, the protocol's checks, the rule, the tables) starts programs and talks to them
/// through pipes; here the program it starts is a relay (grade_relay.cc, installed beside the module) that passes the
/// requests to this process over a Unix socket and the answers back. So the cases, the rule, the summary, the failures
/// and the report are those of `crankcheck grade --batch`, line for line; nothing of the rule is restated here.
///
/// runGrade runs in a thread of its own; the requests the relays pass wait in a queue until the caller's thread takes
/// them (next) and answers them (answer). So the user's function runs in the thread that called crankcheck.grade,
/// where Python can interrupt it (Ctrl-C, the per-request timeout) and where the locks it holds (an import lock) are its
/// own; no thread of this bridge calls into Python.

#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/grade.h"

namespace crankcheck::python {

struct GradeSettings {
  std::filesystem::path relay;   ///< the relay program (grade_relay.cc)
  int jobs = 1;                  ///< relays at once; the references of each job's cases are computed in parallel
  /// [s] per request of a relay, as `crankcheck grade --timeout` (batch: times the requests of its batch); the caller
  /// holds each answer to its own limit, this one ends the grade when the caller does not answer at all.
  double relay_timeout_seconds = 60.0;
};

/// A grade under way: validation::runGrade on `cases` in batch mode with the relay as the program, in a thread of its
/// own. Every signal that can be blocked is blocked in the threads it starts, so Ctrl-C and SIGALRM reach the caller.
/// The destructor stops it (stop).
class InProcessGrade {
 public:
  struct Request {
    size_t id;                            ///< to give to answer
    const validation::GradeCase* grade_case;
  };

  /// Starts the grade. @throws EnvironmentError if the socket cannot be set up.
  InProcessGrade(std::vector<validation::GradeCase> cases, const GradeSettings& settings);
  ~InProcessGrade();
  InProcessGrade(const InProcessGrade&) = delete;
  InProcessGrade& operator=(const InProcessGrade&) = delete;

  /// The next request, waiting at most `wait` for one; none when none came or the grade is over (finished).
  std::optional<Request> next(std::chrono::milliseconds wait);
  /// The response line (protocol 1, without newline) to request `id`; its relay gets its batch's answers once every
  /// request of the batch has one.
  void answer(size_t id, std::string response);
  /// The case of request `id` while it waits for its answer; null once the grade has stopped.
  const validation::GradeCase* caseOf(size_t id);
  /// runGrade has returned: no request will come.
  bool finished();
  /// Ends the grade now (idempotent): no more connections, every relay's connection shut (a relay exits when its
  /// connection ends, and runGrade ends with it), every thread joined, the socket's folder removed. Takes at most
  /// what runGrade's jobs take to finish the case they are grading.
  void stop();
  /// After finished(): stops and returns runGrade's tables. @throws what runGrade threw (EnvironmentError for a relay
  /// that did not answer in time or an answer that is not the protocol), or a logic_error of the bridge.
  validation::TableSet result();
  const std::vector<validation::GradeCase>& cases() const { return cases_; }

 private:
  struct Connection;
  struct Pending {
    std::shared_ptr<Connection> connection;
    size_t slot;
    const validation::GradeCase* grade_case;
  };
  class Folder;

  void acceptLoop();
  void handle(const std::shared_ptr<Connection>& connection);

  std::vector<validation::GradeCase> cases_;
  std::map<std::string, const validation::GradeCase*> by_id_;
  GradeSettings settings_;
  std::unique_ptr<Folder> folder_;
  int listener_ = -1, stop_read_ = -1, stop_write_ = -1;

  std::mutex mutex_;  // guards everything below
  std::condition_variable changed_;
  bool stopping_ = false, grade_done_ = false, stopped_ = false;
  std::vector<std::shared_ptr<Connection>> connections_;
  std::vector<std::thread> handlers_;
  std::deque<size_t> queue_;
  std::map<size_t, Pending> pending_;
  size_t next_id_ = 0;
  validation::TableSet tables_;
  std::exception_ptr grade_error_, bridge_error_;

  std::thread acceptor_, grader_;
};

}  // namespace crankcheck::python
