#pragma once
/// @file
/// Checks every command's flags share (docs/safety.md, "What is refused"): a number's range that NaN cannot slip through, and
/// no empty value taken as "not given".

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "crankcheck/validation/errors.h"

namespace crankcheck::app {

/// A number in [lo, hi]. CLI::Range lets NaN through (both of its comparisons are false for NaN: `--timeout nan`
/// reached the grade and `--accuracy nan` Simbody's assertion); this one refuses NaN, infinities and text.
inline CLI::Validator FiniteRange(double lo, double hi) {
  const std::string range = "[" + CLI::detail::to_string(lo) + " - " + CLI::detail::to_string(hi) + "]";
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        char* end = nullptr;
        errno = 0;
        const double x = std::strtod(text.c_str(), &end);
        if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(x))
          return "Value " + text + " is not a finite number";
        if (!(x >= lo && x <= hi)) return "Value " + text + " not in range " + range;
        return std::string();
      },
      "FLOAT in " + range);
}

/// Refuses an empty value of any flag or argument of the commands that were parsed (`--shard ''`, `--profile ''`,
/// `--out=`) and an empty item in a list (`--parts offset,,torsion`, which CLI11 would drop): an empty string read as
/// "not given" would run another job than the one asked for. `args`: crankcheck's own words as parsed (the program's
/// words after `grade ... --` never reach CLI11 and may be empty).
/// @throws UsageError "FLAG: an empty value (give one, or leave the flag out)".
inline void checkNoEmptyValues(const CLI::App& app, const std::vector<std::string>& args) {
  auto refuse = [](const std::string& flag, bool list) {
    throw UsageError(flag + (list ? ": an empty list or an empty item in it" : ": an empty value") +
                     " (give one, or leave the flag out)");
  };
  for (const CLI::App* command : app.get_subcommands()) {
    for (const CLI::Option* option : command->get_options()) {
      if (option->get_type_size() == 0) continue;  // a flag: no value
      const char delimiter = option->get_delimiter();
      for (const std::string& value : option->results())
        if (value.empty()) refuse(option->get_name(), delimiter != '\0');
      // CLI11 splits a list at its delimiter and drops the empty items: the words as given are read here.
      if (delimiter == '\0' || option->get_lnames().empty()) continue;
      for (size_t i = 0; i < args.size(); ++i)
        for (const std::string& name : option->get_lnames()) {
          const std::string flag = "--" + name;
          std::string value;
          if (args[i] == flag && i + 1 < args.size()) value = args[i + 1];
          else if (args[i].rfind(flag + "=", 0) == 0) value = args[i].substr(flag.size() + 1);
          else continue;
          const std::string twice(2, delimiter);
          if (value.empty() || value.front() == delimiter || value.back() == delimiter ||
              value.find(twice) != std::string::npos)
            refuse(flag, true);
        }
    }
    checkNoEmptyValues(*command, args);
  }
  // `--flag=` with nothing after the sign: CLI11 takes the next word as its value instead.
  for (const std::string& arg : args)
    if (arg.size() > 3 && arg.rfind("--", 0) == 0 && arg.back() == '=' && arg.find('=') == arg.size() - 1)
      refuse(arg.substr(0, arg.size() - 1), false);
}

}  // namespace crankcheck::app
