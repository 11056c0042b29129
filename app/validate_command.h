#pragma once
/// @file
/// `crankcheck validate [SCENE...] [--out DIR] [--quick] [--jobs N] [--shard I/N]` and
/// `crankcheck report merge SHARD_DIR... --out DIR`.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace crankcheck::app {

struct ValidateOptions {
  std::vector<std::string> scene_paths;
  std::string out = "out/report";
  bool quick = false;
  int jobs = 0;            ///< 0: one per core
  std::string shard;       ///< "I/N", empty = the whole campaign
  bool verbose = false;    ///< the families' table in full on the terminal (else only the families that failed)
  std::string profile;     ///< --profile FILE: where each task's time goes, by engine (a new CSV file); empty: none
  std::vector<std::string> parts;  ///< --parts KEY,...: only these report parts (the cross-checks always); empty: all
  double work_limit = 600.0;       ///< [s] --work-limit: the longest estimated work a part may start
  bool check = false;              ///< --check: every check before the work, then stop (nothing created, nothing run)
};

struct MergeOptions {
  std::vector<std::string> shard_dirs;
  std::string out = "out/report";
  bool verbose = false;    ///< as ValidateOptions::verbose
};

void addValidateOptions(CLI::App& command, ValidateOptions& options);
void addMergeOptions(CLI::App& command, MergeOptions& options);

/// Runs the campaign and writes the report (or the shard). Returns the exit status: 0 when every comparison that
/// should hold holds, 1 otherwise. @throws UsageError for bad scenes or flags (exit status 2).
int runValidate(const ValidateOptions& options);
/// Merges shards into one report; same exit statuses.
int runMerge(const MergeOptions& options);

}  // namespace crankcheck::app
