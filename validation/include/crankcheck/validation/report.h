#pragma once
/// @file
/// The report of a validation campaign: CSV data, gnuplot figures (reports/*.gp), a Markdown index and the same
/// index as HTML; shards and their merge. Where and how it is written safely: output_folder.h.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/table.h"
#include "crankcheck/validation/verdict.h"

namespace crankcheck::validation {


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

/// Finds gnuplot on PATH and asks its version, and finds the figures' scripts (findReportsDir): the check made before
/// a campaign that ends in figures (well under a second). @return gnuplot's version line. @throws EnvironmentError
/// when gnuplot is missing, does not run or does not answer within kGnuplotVersionSeconds, or the scripts are not
/// found; UsageError as findReportsDir.
std::string checkGnuplot();

/// The checksum of a file's or a scene's bytes: FNV-1a 64 as 16 hex digits. It finds a changed, truncated or
/// replaced file, not a forged one.
std::string calcChecksum(std::string_view bytes);

/// What a shard records of one data file it wrote, for the merge to check.
struct DataFileRecord {
  std::string path;      ///< relative to the shard's folder: data/NAME.csv
  std::string header;    ///< the first line, without its line break
  size_t rows = 0;       ///< CSV records after the header
  std::string checksum;  ///< calcChecksum of the whole file
};

/// Writes tables as CSV files (RFC 4180) into dir/data, which must not exist yet; each header is "name [unit]"
/// (the unit its Column declares), a text column's the bare name. @return a record of each file written, by name. @throws EnvironmentError when a file cannot be
/// written.
std::vector<DataFileRecord> writeTables(const TableSet& tables, const std::filesystem::path& dir);
/// Reads every dir/data/*.csv; each column's name and unit from its header ("name [unit]", a bare name: kText). @throws std::runtime_error on a missing or
/// malformed file.
TableSet readTables(const std::filesystem::path& dir);

/// Renders the complete report into `dir` (which must exist and be empty): data/*.csv, figures (*.svg, *.png) made
/// by gnuplot from reports/*.gp, index.md and index.html.
/// gnuplot runs in `dir` without a shell. @throws EnvironmentError if gnuplot fails or a file cannot be written.
void renderReport(const TableSet& tables, const ReportInfo& info, const std::filesystem::path& dir);

/// A scene of a shard's campaign: its name and its content (calcChecksum of the scene as formatSceneToml writes it).
struct ShardScene {
  std::string name, checksum;
};

/// A shard's manifest (shard.json): which part of which campaign the folder holds, and what it wrote. Two shards
/// are of one campaign when version, count, quick, scenes, parts and tasks are the same.
struct ShardManifest {
  int index = 0, count = 1;
  bool quick = false;
  std::vector<ShardScene> scenes;    ///< every scene the campaign uses (the default campaign's too), in order
  std::vector<std::string> parts;    ///< validate --parts; empty: every part
  std::vector<SatOut> sat_out;       ///< the engines that sat out of the campaign (CampaignOptions::sat_out)
  int tasks = 0;
  std::string version;               ///< the crankcheck that wrote it (getCrankcheckVersion)
  std::vector<DataFileRecord> files;  ///< every data file, by path
};
void writeShardManifest(const ShardManifest& manifest, const std::filesystem::path& dir);
/// @throws std::runtime_error naming dir/shard.json if it is missing, malformed or of another format.
ShardManifest readShardManifest(const std::filesystem::path& dir);
/// Reads a shard's data for the merge, after checking it against both its manifests: every file
/// crankcheck-manifest.json lists is there, every data file is in shard.json and no other is in data/, and each has
/// the header, row count and checksum shard.json records. @throws std::runtime_error, one line naming the file.
TableSet readShardTables(const std::filesystem::path& dir, const ShardManifest& manifest);

}  // namespace crankcheck::validation
