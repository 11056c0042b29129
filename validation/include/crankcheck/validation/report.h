#pragma once
/// @file
/// The report of a validation campaign: CSV data, gnuplot figures (reports/*.gp), a Markdown index and the same
/// index as HTML; shards and their merge. Where and how it is written safely: output_folder.h.

#include <filesystem>
#include <string>
#include <vector>

#include "crankcheck/validation/campaign.h"

namespace crankcheck::validation {

/// One line of the summary: a quantity over one family of cases, the analytic engine against one exact engine.
struct SummaryRow {
  std::string engine;            ///< the engine compared with the analytic one (simbody, mujoco, ...)
  std::string quantity, family;
  double worst_rel_error = 0.0;  ///< worst error / scale over the family
  std::string where;             ///< case, crank angle and speed of the worst
  double tolerance_rel = 0.0;    ///< the agreement tolerance / scale at that case
  bool pass = true;              ///< every comparison of the family agreed
};

/// Groups the crosscheck table by (engine, quantity, family), the gated engines only (soft engines are reported in
/// part engines, never gated).
std::vector<SummaryRow> summarize(const TableSet& tables);

/// The summary as a plain-text table for the terminal.
std::string formatSummary(const std::vector<SummaryRow>& summary);

struct ReportInfo {
  std::string title = "crankcheck validation report";
  bool quick = false;
  int shards = 1;
  double seconds = 0.0;          ///< wall time of the campaign
  int jobs = 1;
  std::string gnuplot_version;   ///< from checkGnuplot()
};

/// [s] How long `gnuplot --version` may take: it answers in milliseconds; a gnuplot that has not answered in 10 s
/// (a wrapper waiting on a display, a hung install) is ended and crankcheck stops before the campaign.
constexpr double kGnuplotVersionSeconds = 10.0;

/// Finds gnuplot on PATH and asks its version: the check made before a campaign that ends in figures (well under
/// a second). @return gnuplot's version line. @throws EnvironmentError when gnuplot is missing, does not run or
/// does not answer within kGnuplotVersionSeconds.
std::string checkGnuplot();

/// The unit of a column of table `table` as its CSV header shows it: "" (text), "-" (dimensionless), "N m", ...,
/// "SI" (the unit of the row's quantity). @throws std::logic_error for a column without one (column_units.cc).
std::string getColumnUnit(const std::string& table, const std::string& column);

/// Writes tables as CSV files (RFC 4180) into dir/data, which must not exist yet; each header is "name [unit]"
/// (getColumnUnit). @throws EnvironmentError when a file cannot be written.
void writeTables(const TableSet& tables, const std::filesystem::path& dir);
/// Reads every dir/data/*.csv; the columns are named without their units. @throws std::runtime_error on a missing or
/// malformed file.
TableSet readTables(const std::filesystem::path& dir);

/// Renders the complete report into `dir` (which must exist and be empty): data/*.csv, figures (*.svg, *.png) made
/// by gnuplot from reports/*.gp, index.md and index.html.
/// gnuplot runs in `dir` without a shell. @throws EnvironmentError if gnuplot fails or a file cannot be written.
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

}  // namespace crankcheck::validation
