#pragma once
/// @file
/// The kinds of failure every crankcheck command tells apart, each with its own exit status (docs/safety.md, "Exit
/// status"): bad input or usage (2, nothing written), a result that cannot be computed to its accuracy (1, refused)
/// and a failed environment (3: a tool missing, a disk full, a write refused). A comparison that should hold and fails is not an exception: it is exit status 1.

#include <filesystem>
#include <stdexcept>
#include <string>

#include "crankcheck/scene/text.h"  // escapeText, quoteText, formatOneLine: text from outside in messages

namespace crankcheck {

/// Bad input or usage: a bad scene, flag or output folder. The message is "FILE: KEY: rule" or "--flag: rule";
/// the CLI prints it after "crankcheck: " and exits with status 2, having written nothing.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The environment failed: a program crankcheck needs is missing or failed, a file could not be written (disk
/// full, write refused). The CLI prints the message after "crankcheck: " and exits with status 3.
class EnvironmentError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A result that cannot be computed to its promised accuracy for this input (a Simbody run too stiff to finish, a
/// harmonic analysis that does not reach rounding, a sizing whose root does not converge): refused, never printed.
/// Neither the user's mistake nor the environment's: the CLI prints the message after "crankcheck: " and exits with
/// status 1, as for a case an engine could not compute.
class UncomputableError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A path as it appears in messages: quoteText of it (in double quotes, backslash, quote, control and bidirectional
/// characters escaped), so that every message stays one line and shows exactly which path is meant.
std::string quotePath(const std::filesystem::path& path);

}  // namespace crankcheck
