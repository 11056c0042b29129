#pragma once
/// @file
/// The report of a validation campaign: CSV data, gnuplot figures (reports/*.gp), a Markdown index and the same
/// index as HTML; shards and their merge; atomic installation into the output directory.

#include <filesystem>
#include <string>
#include <vector>

#include "crankcheck/validation/campaign.h"

namespace crankcheck::validation {

/// One line of the summary: a quantity over one family of cases.
struct SummaryRow {
  std::string quantity, family;
  double worst_rel_error = 0.0;  ///< worst error / scale over the family
  std::string where;             ///< case, crank angle and speed of the worst
  double tolerance_rel = 0.0;    ///< the agreement tolerance / scale at that case
  bool pass = true;              ///< every comparison of the family agreed
};

/// Groups the crosscheck table by (quantity, family).
std::vector<SummaryRow> summarize(const TableSet& tables);

/// The summary as a plain-text table for the terminal.
std::string formatSummary(const std::vector<SummaryRow>& summary);

struct ReportInfo {
  std::string title = "crankcheck validation report";
  bool quick = false;
  int shards = 1;
  double seconds = 0.0;          ///< wall time of the campaign
  int jobs = 1;
};

/// Writes tables as CSV files into dir/data.
void writeTables(const TableSet& tables, const std::filesystem::path& dir);
/// Reads every dir/data/*.csv. @throws std::runtime_error on a missing or malformed file.
TableSet readTables(const std::filesystem::path& dir);

/// Renders the complete report into `dir` (which must exist and be empty): data/*.csv, figures (*.svg, *.png) made
/// by gnuplot from reports/*.gp, index.md and index.html.
/// @throws std::runtime_error if gnuplot is missing or fails.
void renderReport(const TableSet& tables, const ReportInfo& info, const std::filesystem::path& dir);

/// A shard's manifest (shard.json): which part of which campaign the directory holds.
struct ShardManifest {
  int index = 0, count = 1;
  bool quick = false;
  std::vector<std::string> scenes;  ///< family names, to refuse merging shards of different campaigns
  int tasks = 0;
};
void writeShardManifest(const ShardManifest& manifest, const std::filesystem::path& dir);
/// @throws std::runtime_error if dir/shard.json is missing or malformed.
ShardManifest readShardManifest(const std::filesystem::path& dir);

/// Creates an empty staging directory next to `target` (same file system, so that installation is a rename).
/// @throws std::runtime_error naming `target` if it cannot be created.
std::filesystem::path createStagingDirectory(const std::filesystem::path& target);

/// Replaces `target` with the completed `staging` directory: a reader sees either the old complete report or the
/// new complete one, never a half-written one.
void installDirectory(const std::filesystem::path& staging, const std::filesystem::path& target);

}  // namespace crankcheck::validation
