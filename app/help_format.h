#pragma once
/// @file
/// `--help` as a page that stands alone and fits a terminal: every line within kHelpWidth columns (CLI11 prints a
/// description on one line however long), and the engines named from the registry, never written in prose.

#include <CLI/CLI.hpp>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/errors.h"

namespace crankcheck::app {

/// The widest line of `--help` (and of every table crankcheck prints on a terminal).
inline constexpr size_t kHelpWidth = 100;

/// `text` with each of its lines longer than `width` broken at spaces; a broken line's continuation keeps its
/// indentation (under the text after a list marker such as "2  ", "request   " or "- ").
inline std::string wrapText(const std::string& text, size_t width) {
  std::string out;
  std::istringstream lines(text);
  std::string line;
  bool first = true;
  while (std::getline(lines, line)) {
    if (!first) out += '\n';
    first = false;
    const size_t indent = line.find_first_not_of(' ');
    if (line.size() <= width || indent == std::string::npos) {
      out += line;
      continue;
    }
    // Continuation indent: under the text after a leading marker of up to 9 characters ("- ", "0  ", "128+N  "),
    // else the line's own.
    size_t hang = indent;
    const size_t marker_end = line.find("  ", indent);
    if (line.compare(indent, 2, "- ") == 0) hang = indent + 2;
    else if (marker_end != std::string::npos && marker_end - indent <= 9) hang = line.find_first_not_of(' ', marker_end);
    if (hang == std::string::npos || hang + 20 > width) hang = indent;
    std::string prefix(indent, ' ');
    std::string rest = line.substr(indent);
    while (prefix.size() + rest.size() > width) {
      const size_t room = width > prefix.size() ? width - prefix.size() : 1;
      size_t cut = rest.rfind(' ', room);
      if (cut == std::string::npos || cut == 0) cut = rest.find(' ', room);  // a word longer than the line
      if (cut == std::string::npos) break;
      out += prefix + rest.substr(0, cut) + '\n';
      const size_t next = rest.find_first_not_of(' ', cut);
      rest = next == std::string::npos ? std::string() : rest.substr(next);
      prefix.assign(hang, ' ');
    }
    out += prefix + rest;
  }
  if (!text.empty() && text.back() == '\n') out += '\n';
  return out;
}

/// CLI11's formatter with every description and footer wrapped to kHelpWidth.
class WrappingFormatter : public CLI::Formatter {
 public:
  std::string make_option_desc(const CLI::Option* option) const override {
    return wrapText(CLI::Formatter::make_option_desc(option), kHelpWidth - get_column_width());
  }
  std::string make_subcommand(const CLI::App* sub) const override {
    std::stringstream out;
    CLI::detail::format_help(out, sub->get_display_name(), wrapText(sub->get_description(), kHelpWidth - get_column_width()),
                             get_column_width());
    return out.str();
  }
  std::string make_description(const CLI::App* app) const override {
    return wrapText(CLI::Formatter::make_description(app), kHelpWidth);
  }
  std::string make_footer(const CLI::App* app) const override {
    return wrapText(CLI::Formatter::make_footer(app), kHelpWidth);
  }
};

/// A path from the user (a scene, an output folder) as a line of output shows it: its control, line-break and
/// bidirectional characters escaped (scene/text.h: escapeControls), so that a file called "two\nlines.toml" cannot
/// split a heading or act on the terminal. Built into strings, never into a fixed buffer (no path is cut).
inline std::string showPath(const std::string& path) { return escapeControls(path); }
inline std::string showPath(const std::filesystem::path& path) { return escapeControls(path.string()); }

/// "ENGINE sat out: it cannot build scene S (reason)\n", one line per engine that sat out (validate, grade), escaped:
/// a shard's record may come from anyone.
inline std::string formatSatOut(const std::vector<validation::SatOut>& sat_out) {
  std::string out;
  for (const validation::SatOut& s : sat_out)
    out += escapeText(s.engine) + " sat out: it cannot build scene " + escapeText(s.scene) + " (" +
           escapeText(formatOneLine(s.reason)) + ")\n";
  return out;
}

/// "a", "a and b", "a, b and c".
inline std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i)
    out += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
  return out;
}

/// The engines of the registry for a help text, the closed forms under test left out: "simbody and mujoco (exact),
/// mujoco-soft and mujoco-soft-stiff (measured, never gated)"; one kind alone without the label. `keep`: only the
/// engines it accepts (e.g. those that simulate).
template <class Keep>
std::string describeEngines(Keep keep) {
  std::vector<std::string> exact, measured;
  for (const Engine& e : validation::listEngines())
    if (!e.closed_form && keep(e)) (e.gated ? exact : measured).push_back(e.name);
  if (measured.empty()) return joinNames(exact);
  if (exact.empty()) return joinNames(measured) + " (measured, never gated)";
  return joinNames(exact) + " (exact), " + joinNames(measured) + " (measured, never gated)";
}
inline std::string describeEngines() {
  return describeEngines([](const Engine&) { return true; });
}

/// The names of the engines offering `route` (validation/engines.h listEngines): for Route::kStepAtSpeed "ode,
/// ode-quickstep, bullet and box2d".
inline std::string describeEngineNames(Route route) {
  std::vector<std::string> names;
  for (const Engine& e : validation::listEngines(route)) names.push_back(e.name);
  return joinNames(names);
}

}  // namespace crankcheck::app
