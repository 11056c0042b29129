#pragma once
/// @file
/// `crankcheck.grade(function)`: a function of this process graded by `crankcheck grade`'s own code. The grade
/// (validation::runGrade: its cases, the protocol's checks, the rule, the tables) starts programs and talks to them
/// through pipes; here the program it starts is a relay (grade_relay.cc, installed beside the module) that passes the
/// requests to this process over a Unix socket and the answers back. The answers are computed in this process by
/// `answer` (the Python module calls the user's function there). So the cases, the rule, the summary, the failures and
/// the report are those of `crankcheck grade --batch`, line for line; nothing of the rule is restated here.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/grade.h"

namespace crankcheck::python {

/// The response line (protocol 1, without newline) to one request line of case `c`. May be called from several
/// threads at once (one per job); it may throw, which ends the grade with that exception.
using GradeAnswer = std::function<std::string(const validation::GradeCase& c, const std::string& request)>;

struct InProcessGrade {
  std::filesystem::path relay;   ///< the relay program (grade_relay.cc)
  int jobs = 1;                  ///< relays at once; the references of each job's cases are computed in parallel
  double timeout_seconds = 60.0; ///< per request, as `crankcheck grade --timeout`
};

/// Runs validation::runGrade on `cases` in batch mode with the relay as the program, answering each request with
/// `answer`. Returns runGrade's tables. @throws the first exception `answer` threw, if any (in preference to
/// runGrade's complaint about the relay's missing answer); otherwise what runGrade throws (EnvironmentError for a
/// timeout or an answer that is not the protocol); EnvironmentError if the socket cannot be set up.
validation::TableSet gradeInProcess(const std::vector<validation::GradeCase>& cases, const GradeAnswer& answer,
                                    const InProcessGrade& settings);

}  // namespace crankcheck::python
