// The pieces of `crankcheck grade`'s protocols that protocol 1 (grade.cc) and protocol 2 (free_run_grade.cc) share:
// case ids, quoting a program's output, running it under the process rules, reading its values.
#include "grade_protocol.h"

#include <algorithm>
#include <set>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "crankcheck/scene/quantities.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/process.h"
#include "crankcheck/validation/table.h"

namespace crankcheck::validation {

using Json = nlohmann::json;

// "0.3" -> "0p3", "-90" -> "m90": a number in a case id.
std::string numberTag(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", x);
  std::string text = buffer;
  for (char& c : text) {
    if (c == '.') c = 'p';
    if (c == '-') c = 'm';
    if (c == '+') c = '_';
  }
  return text;
}

std::string safeStem(const std::string& name) {
  std::string out;
  for (char c : name) out += std::isalnum(static_cast<unsigned char>(c)) || c == '_' ? c : '_';
  return out.empty() ? std::string("scene") : out;
}

// The first line of `text` that holds byte `at` (or the first line), at most 160 bytes, for a message: quoted, its
// control bytes escaped (an ESC never reaches the terminal, a NUL never cuts the message), the quote closed.
std::string quoteLine(const std::string& text, size_t at, size_t first_line) {
  at = std::min(at, text.empty() ? size_t{0} : text.size() - 1);
  size_t begin = text.rfind('\n', at == 0 ? 0 : at - (text[at] == '\n' ? 1 : 0));
  begin = begin == std::string::npos || begin > at ? 0 : begin + 1;
  if (at == 0) begin = 0;
  size_t end = text.find('\n', begin);
  if (end == std::string::npos) end = text.size();
  const std::string line = text.substr(begin, std::min<size_t>(end - begin, 160));
  const size_t line_number =
      static_cast<size_t>(std::count(text.begin(), text.begin() + static_cast<long>(begin), '\n')) + first_line;
  return "line " + std::to_string(line_number) + ": " + quoteText(line) + (end - begin > 160 ? "..." : "");
}

std::string describeSignal(int signal) {
  const char* name = ::strsignal(signal);
  return "signal " + std::to_string(signal) + (name ? std::string(" (") + name + ")" : std::string());
}

// True when `out` holds `requests` complete JSON responses (one per line in batch; one document otherwise), whatever
// they say: the program answered, even if it did not exit.
bool isCompleteAnswer(const std::string& out, size_t requests, bool batch) {
  if (!batch) return out.find_first_not_of(" \t\r\n") != std::string::npos && Json::accept(out);
  size_t complete = 0;
  for (size_t begin = 0; begin < out.size();) {
    size_t end = out.find('\n', begin);
    if (end == std::string::npos) end = out.size();
    const std::string line = out.substr(begin, end - begin);
    if (line.find_first_not_of(" \t\r") != std::string::npos) {
      if (!Json::accept(line)) return false;
      ++complete;
    }
    begin = end + 1;
  }
  return complete == requests;
}

std::string runOnce(const GradeProgram& program, const std::string& input, size_t requests, const std::string& what) {
  ProgramCall call{program.argv};
  call.input = input;
  call.timeout_seconds = program.timeout_seconds * static_cast<double>(requests);
  call.output_limit = program.output_limit * requests;
  const ProgramResult r = runProgram(call);
  const std::string name = program.argv.front();
  auto stderrLine = [&] {  // its last 3 lines (where a traceback says what failed), quoted with control bytes escaped
    std::vector<std::string> lines;
    for (size_t at = 0; at < r.err.size();) {
      const size_t end = std::min(r.err.find('\n', at), r.err.size());
      lines.push_back(r.err.substr(at, end - at));
      at = end + 1;
    }
    while (!lines.empty() && (lines.back().empty() || lines.back() == "\r")) lines.pop_back();
    if (lines.empty()) return std::string();
    const size_t first = lines.size() > 3 ? lines.size() - 3 : 0;
    std::string end;
    for (size_t i = first; i < lines.size(); ++i) end += (i > first ? "\n" : "") + lines[i];
    const bool cut = first > 0 || end.size() > 300;
    if (end.size() > 300) end = end.substr(end.size() - 300);
    return cut ? "; the end of its stderr: " + quoteText("...\n" + end) : "; its stderr: " + quoteText(end);
  };
  if (r.left_output_open)
    throw EnvironmentError(name + ": " + what + ": exited" +
                           (r.exit_status >= 0 ? " with status " + std::to_string(r.exit_status) : std::string()) +
                           ", but its output was still open " + formatNumber(call.timeout_seconds) +
                           " s after it started: held by a process it left running" +
                           (r.left_behind > 0 ? std::string(" outside its process group (a setsid child), which crankcheck ended")
                            : isReapingLeftBehindProcesses() ? std::string(", which crankcheck ended")
                                                             : std::string(" (ended if in its process group; a setsid child is "
                                                                           "out of reach from Python)")) +
                           "; a program must end every process it starts");
  if (r.left_behind > 0)
    throw EnvironmentError(name + ": " + what + ": exited" +
                           (r.exit_status >= 0 ? " with status " + std::to_string(r.exit_status) : std::string()) +
                           " but left " + std::to_string(r.left_behind) + (r.left_behind == 1 ? " process" : " processes") +
                           " running outside its process group (a setsid child or a daemon; crankcheck ended " +
                           (r.left_behind == 1 ? "it" : "them") + "); a program must end every process it starts");
  if (r.timed_out && isCompleteAnswer(r.out, requests, program.batch))
    throw EnvironmentError(name + ": " + what + ": answered completely but did not exit within " +
                           formatNumber(call.timeout_seconds) + " s (killed; the program must exit when its stdin ends)");
  if (r.timed_out)
    throw EnvironmentError(name + ": " + what + ": no complete answer within " + formatNumber(call.timeout_seconds) +
                           " s (killed; --timeout sets the time per request)");
  if (r.output_limit_exceeded)
    throw EnvironmentError(name + ": " + what + ": wrote more than " + std::to_string(call.output_limit) +
                           " bytes to stdout (killed)");
  if (r.signal != 0) throw EnvironmentError(name + ": " + what + ": ended by " + describeSignal(r.signal) + stderrLine());
  if (r.exit_status != 0)
    throw EnvironmentError(name + ": " + what + ": exited with status " + std::to_string(r.exit_status) + stderrLine());
  return r.out;
}

void throwProtocolError(const std::string& where, const std::string& what, const std::string& response, size_t at,
                        size_t first_line) {
  throw EnvironmentError(where + what + "; " +
                         (response.empty() ? std::string("no output at all") : quoteLine(response, at, first_line)));
}

Json parseResponseObject(const std::string& response, const std::string& key, const std::string& where,
                         size_t first_line) {
  if (response.find_first_not_of(" \t\r\n") == std::string::npos)
    throwProtocolError(where, "no response on stdout", response, 0, first_line);
  Json doc;
  // A key given twice in one object is not the protocol: JSON leaves which one counts to the reader (nlohmann keeps
  // the last), and an answer "U": 12345, "U": <right value> passed. Found while parsing, each object's keys kept.
  std::vector<std::set<std::string>> keys;
  std::string twice;
  const auto watch = [&](int, Json::parse_event_t event, Json& parsed) {
    if (event == Json::parse_event_t::object_start) keys.emplace_back();
    if (event == Json::parse_event_t::object_end && !keys.empty()) keys.pop_back();
    if (event == Json::parse_event_t::key && !keys.empty() && !keys.back().insert(parsed.get<std::string>()).second &&
        twice.empty())
      twice = parsed.get<std::string>();
    return true;
  };
  try {
    doc = Json::parse(response, watch);
  } catch (const Json::parse_error& e) {
    throwProtocolError(where, "the response is not JSON (" + escapeText(e.what()) + ")", response,
                       e.byte > 0 ? e.byte - 1 : 0, first_line);
  } catch (const Json::out_of_range& e) {
    // A number past a double's range (1e400): the reader names the number, not where it stands; it is found in the
    // response to quote its line.
    const std::string what = e.what();
    const size_t open = what.find(" parsing '"), close = what.rfind('\'');
    const std::string number = open != std::string::npos && close > open + 10 ? what.substr(open + 10, close - open - 10)
                                                                                : std::string();
    const size_t at = number.empty() ? std::string::npos : response.find(number);
    throwProtocolError(where, "a number beyond the range of a double" + (number.empty() ? std::string() : " (" + escapeText(number) + ")"),
                       response, at == std::string::npos ? 0 : at, first_line);
  } catch (const Json::exception& e) {
    throwProtocolError(where, "the response cannot be read (" + escapeText(e.what()) + ")", response, 0,
                       first_line);
  }
  if (!twice.empty()) {
    const std::string quoted = "\"" + twice + "\"";
    const size_t first = response.find(quoted), second = first == std::string::npos ? first : response.find(quoted, first + 1);
    throwProtocolError(where, "the key " + quoteText(twice) + " is given twice in one object (which one counts is not "
                              "defined)", response, second == std::string::npos ? 0 : second, first_line);
  }
  if (!doc.is_object() || !doc.contains(key) || !doc[key].is_array())
    throwProtocolError(where, "the response must be an object {\"" + key + "\": [...]}", response, 0, first_line);
  // Beside it, nothing: a key the protocol does not know (a misspelled "result", a quantity put at the top) is named,
  // as inside the results, not passed over.
  for (const auto& item : doc.items())
    if (item.key() != key) {
      const size_t at = response.find("\"" + item.key() + "\"");
      throwProtocolError(where, "the key " + quoteText(item.key()) + " is not the protocol (a response is {\"" + key +
                                "\": [...]} and nothing beside it)", response, at == std::string::npos ? 0 : at, first_line);
    }
  return doc;
}

Evaluation readProgramValues(const Json& r, const std::string& at, const Mechanism& m,
                             const std::function<void(const std::string&)>& fail,
                             const std::vector<std::string>& protocol_keys) {
  const int k = m.machine.cylinders;
  const double kNotProvided = std::nan("");
  if (!r.is_object() && !r.is_null()) fail(at + " must be an object or null");
  // Every key is one the protocol knows: a misspelled quantity (x_P, Uu) was not provided without a word, and the
  // program passed with what it meant to send never looked at.
  auto names = [](bool per_cylinder) {
    std::string all;
    for (const Quantity& q : getQuantityCatalogue())
      if (q.per_cylinder == per_cylinder) all += (all.empty() ? "" : ", ") + std::string(q.name);
    return all;
  };
  auto checkKeys = [&](const Json& object, const std::string& path, bool per_cylinder) {
    for (const auto& item : object.items()) {
      const std::string& name = item.key();
      if (!per_cylinder && (name == "cylinders" ||
                            std::find(protocol_keys.begin(), protocol_keys.end(), name) != protocol_keys.end()))
        continue;
      const Quantity* q = findQuantity(name);
      if (q && q->per_cylinder == per_cylinder) continue;
      fail(path + ": " + quoteText(name) + (q ? (per_cylinder ? " is not a cylinder's quantity (it goes at the top)"
                                                               : " is a cylinder's quantity (it goes under \"cylinders\")")
                                              : " is not a quantity of eval (one of " + names(per_cylinder) + ")"));
    }
  };
  if (r.is_object()) checkKeys(r, at, false);
  // A number, or null / absent for "not provided"; anything else is not the protocol.
  auto number = [&](const Json& parent, const std::string& key, const std::string& path) -> double {
    if (!parent.is_object() || !parent.contains(key) || parent[key].is_null()) return kNotProvided;
    const Json& v = parent[key];
    if (!v.is_number()) fail(path + "." + key + " must be a number or null");
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(path + "." + key + " is not a finite number");
    return x;
  };
  auto vector = [&](const Json& parent, const std::string& key, const std::string& path, double* into, size_t n) {
    for (size_t e = 0; e < n; ++e) into[e] = kNotProvided;
    if (!parent.is_object() || !parent.contains(key) || parent[key].is_null()) return;
    const Json& v = parent[key];
    if (!v.is_array() || v.size() != n) fail(path + "." + key + " must be an array of " + std::to_string(n) + " numbers (or null)");
    for (size_t e = 0; e < n; ++e) {
      if (v[e].is_null()) continue;
      if (!v[e].is_number()) fail(path + "." + key + "[" + std::to_string(e) + "] must be a number or null");
      into[e] = v[e].get<double>();
      if (!std::isfinite(into[e])) fail(path + "." + key + "[" + std::to_string(e) + "] is not a finite number");
    }
  };
  Evaluation e;
  e.engine = "program";
  e.cylinders.assign(static_cast<size_t>(k), CylinderEvaluation{});
  // Every value "not provided" until read; a quantity the scene does not define is never read (gas_force without
  // [gas]), a component it does not define is not provided whatever the program says (shaking_moment X and Y
  // without axial positions).
  auto read = [&](const Quantity& q, const Json& parent, const std::string& path, int cylinder) {
    double* values = accessQuantity(q, e, cylinder);
    if (!isQuantityDefined(q, m)) {
      for (int n = 0; n < q.components; ++n) values[n] = kNotProvided;
      return;
    }
    if (q.components == 1)
      values[0] = number(parent, q.name, path);
    else
      vector(parent, q.name, path, values, static_cast<size_t>(q.components));
    for (int n = 0; n < q.components; ++n)
      if (!isComponentDefined(q, n, m)) values[n] = kNotProvided;
  };
  for (const Quantity& q : getQuantityCatalogue()) {
    if (!q.per_cylinder) read(q, r, at, -1);
    for (int j = 0; j < k && q.per_cylinder; ++j)
      for (int n = 0; n < q.components; ++n) accessQuantity(q, e, j)[n] = kNotProvided;
  }
  if (r.is_object() && r.contains("cylinders") && !r["cylinders"].is_null()) {
    const Json& cylinders = r["cylinders"];
    if (!cylinders.is_array() || cylinders.size() > static_cast<size_t>(k))
      fail(at + ".cylinders must be an array of at most " + std::to_string(k) + " objects (one per cylinder, in order)");
    for (size_t j = 0; j < cylinders.size(); ++j) {
      const Json& cj = cylinders[j];
      if (cj.is_null()) continue;
      const std::string cat = at + ".cylinders[" + std::to_string(j) + "]";
      if (!cj.is_object()) fail(cat + " must be an object or null");
      checkKeys(cj, cat, true);
      for (const Quantity& q : getQuantityCatalogue())
        if (q.per_cylinder) read(q, cj, cat, static_cast<int>(j));
    }
  }
  return e;
}

}  // namespace crankcheck::validation
