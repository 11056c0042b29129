#pragma once
/// @file
/// The two kinds of failure every crankcheck command tells apart, each with its own exit status
/// (README, "Exit status"): bad input or usage (2, nothing written) and a failed environment (3: a tool missing,
/// a disk full, a write refused). A comparison that should hold and fails is not an exception: it is exit status 1.

#include <filesystem>
#include <stdexcept>
#include <string>

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

/// A path as it appears in messages: in double quotes, with backslash, quote and control characters (a newline
/// in a folder name) escaped, so that every message stays one line and shows exactly which path is meant.
std::string quotePath(const std::filesystem::path& path);

}  // namespace crankcheck
