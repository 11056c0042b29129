#pragma once
// The pieces of `crankcheck grade`'s two protocols (grade.h: states, free_run_grade.h: time-stepped runs) that both
// use: internal to the validation library.

#include <cstddef>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "crankcheck/scene/evaluation.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/grade_program.h"

namespace crankcheck::validation {

/// "0.3" -> "0p3", "-90" -> "m90": a number in a case id.
std::string numberTag(double x);
/// `name` with every character but [A-Za-z0-9_] replaced by '_' ("scene" when empty): a case id, a file stem.
std::string safeStem(const std::string& name);
/// The first line of `text` that holds byte `at` (or the first line), at most 160 bytes, for a message: quoted, its
/// control bytes escaped (an ESC never reaches the terminal, a NUL never cuts the message), the quote closed. Lines
/// are numbered from `first_line`: the line of the program's output where `text` begins (a batch's response line).
std::string quoteLine(const std::string& text, size_t at = 0, size_t first_line = 1);
/// "signal 9 (Killed)".
std::string describeSignal(int signal);
/// True when `out` holds `requests` complete JSON responses (one per line in batch; one document otherwise), whatever
/// they say: the program answered, even if it did not exit.
bool isCompleteAnswer(const std::string& out, size_t requests, bool batch);
/// Runs the program on `input` (`requests` requests: the time limit and the output limit are per request); returns
/// its stdout. `what` names the request in messages ("case ID").
/// @throws EnvironmentError on anything but a clean exit: not started, killed at the time or output limit, ended by
/// a signal, a non-zero exit status (with the first line of its stderr, quoted).
std::string runOnce(const GradeProgram& program, const std::string& input, size_t requests, const std::string& what);

/// Throws EnvironmentError "WHERE WHAT; line N: "..."": a response that is not the protocol, `at` a byte of it on the
/// offending line ("no output at all" when it is empty).
[[noreturn]] void throwProtocolError(const std::string& where, const std::string& what, const std::string& response,
                                     size_t at = 0, size_t first_line = 1);

/// A response line as JSON: an object holding the array `key` ("results", "samples"). `where` begins every message
/// ("PROGRAM: case ID: "). @throws EnvironmentError (throwProtocolError) when it is empty, not JSON, or not such an
/// object.
nlohmann::json parseResponseObject(const std::string& response, const std::string& key, const std::string& where,
                                   size_t first_line = 1);

/// The values a program gave in one JSON object `r` (a result of protocol 1, a sample of protocol 2): every quantity of
/// the catalogue at the top and per cylinder under "cylinders", NaN where not provided (left out or null) or not
/// defined for m; engine "program". `at` names the object in messages ("results[3]").
/// `fail(what)` is called (and must throw) on anything that is not the protocol: a string where a number belongs, a
/// number that is not finite, an array of the wrong size, more cylinders than m has.
/// Every key must be one the protocol knows: a quantity (at its level), "cylinders", or one of `protocol_keys` at the
/// top (a sample's "t", "phi", ...); another is not the protocol either.
Evaluation readProgramValues(const nlohmann::json& r, const std::string& at, const Mechanism& m,
                             const std::function<void(const std::string&)>& fail,
                             const std::vector<std::string>& protocol_keys = {});

}  // namespace crankcheck::validation
