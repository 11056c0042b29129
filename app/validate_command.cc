#include "validate_command.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <set>

#include "crankcheck/analytic/torsion_domain.h"
#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/output_folder.h"
#include "crankcheck/validation/parts.h"
#include "crankcheck/validation/report.h"
#include "crankcheck/validation/interrupt.h"
#include "crankcheck/validation/runner.h"
#include "crankcheck/validation/scene_sections.h"
#include "crankcheck/validation/verdict.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/work_limit.h"
#include "flag_checks.h"
#include "help_format.h"
#include "scene_input.h"

namespace crankcheck::app {
namespace fs = std::filesystem;
using validation::TableSet;

void addValidateOptions(CLI::App& command, ValidateOptions& options) {
  const std::vector<std::string> keys = validation::listPartKeys();
  command.add_option("scenes", options.scene_paths,
                     "Scene files (TOML) to cross-check; none: the built-in default campaign");
  command.add_option("--out", options.out, "Report folder: created, or replaced when the run completes if it is empty or a report crankcheck wrote; any "
                     "other folder or file is refused")
      ->capture_default_str();
  command.add_flag("--quick", options.quick, "A fast smoke run: fewer lambdas, angles and methods");
  command.add_flag("--verbose", options.verbose,
                   "Print the table of every family of cases on the terminal (without it: only the families that failed; "
                   "the report always has all of it)");
  command.add_option("--profile", options.profile,
                     "Write where the time goes to FILE (a new CSV file, never an existing one): per task and engine, "
                     "model builds, evaluations and seconds");
  command.add_option("--parts", options.parts,
                     "Run only these report parts, by key, comma-separated (" + joinNames(keys) +
                         "); the cross-checks and the verdict always run")
      ->delimiter(',')
      ->allow_extra_args(false);  // one comma-separated value: the scene files after it stay scene files
  command.add_option("--jobs", options.jobs, "Worker threads (default: one per core)")->check(CLI::Range(1, 1024));
  command.add_option(validation::kWorkLimitFlag, options.work_limit,
                     "The longest work a part may start [s]: a part whose runs grow with the scene (the stepped "
                     "engines' steps at a low speed) is estimated before the campaign and refused past it")
      ->check(FiniteRange(1.0, 1e7))
      ->capture_default_str();
  command.add_flag("--check", options.check,
                   "Check everything that is checked before the work (the scenes, the flags, the output folder, "
                   "gnuplot unless --shard, each part's estimated work), print one line and stop: nothing is created "
                   "or run (the shard scripts check OUT so before any shard runs)");
  command.add_option("--shard", options.shard,
                     "Run only part I of N (0 <= I < N <= 100000) of the campaign and write its data for 'crankcheck "
                     "report merge' (docs: shards and clusters)");
}

void addMergeOptions(CLI::App& command, MergeOptions& options) {
  command.add_option("shards", options.shard_dirs, "Shard folders written by 'crankcheck validate --shard I/N'")
      ->required();
  command.add_option("--out", options.out, "Report folder (the same rule as validate --out)")->capture_default_str();
  command.add_flag("--verbose", options.verbose, "Print the table of every family of cases (as validate --verbose)");
}

namespace {

// A duration for the progress line: "42s", "3m07s", "1h05m".
std::string formatDuration(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char text[32];
  if (s < 60) std::snprintf(text, sizeof text, "%lds", s);
  else if (s < 3600) std::snprintf(text, sizeof text, "%ldm%02lds", s / 60, s % 60);
  else std::snprintf(text, sizeof text, "%ldh%02ldm", s / 3600, s % 3600 / 60);
  return text;
}

// The progress line on stderr, when it is a terminal: tasks done, the elapsed time and an estimate of the time left
// (the mean time per task so far times the tasks left; the tasks differ in cost, so it settles as the run goes on).
void printProgress(const validation::Progress& p) {
  const double left = p.elapsed_seconds / static_cast<double>(p.done) * static_cast<double>(p.total - p.done);
  std::fprintf(stderr, "\r\033[K[%3zu/%zu] %s elapsed, about %s left: %s", p.done, p.total,
               formatDuration(p.elapsed_seconds).c_str(), formatDuration(left).c_str(), p.task->id.c_str());
  std::fflush(stderr);
}

bool allPass(const TableSet& tables) { return validation::allAgree(validation::calcVerdicts(tables)); }

// The terminal's end: the families' table (all of it with --verbose, else only the families that failed), the
// verdict (one line per engine, the ctest-style closing line), the engines that sat out and where the report is.
int reportAndInstall(const TableSet& unsorted, const std::vector<validation::SatOut>& sat_out,
                     validation::ReportInfo& info, validation::OutputFolder& out, bool verbose) {
  // Sorted as the report writes them (the ties' rule itself is order-free: isWorseComparison, verdict.h).
  TableSet tables = unsorted;
  validation::sortTables(tables);
  validation::renderReport(tables, info, out.getStaging());
  out.install("report");
  const std::vector<validation::EngineVerdict> verdicts = validation::calcVerdicts(tables);
  const bool pass = validation::allAgree(verdicts);
  std::vector<validation::SummaryRow> families = validation::summarize(tables);
  if (!verbose) std::erase_if(families, [](const validation::SummaryRow& s) { return s.pass; });
  if (!families.empty())
    std::cout << (verbose ? "Every family of cases:\n" : "The families of cases that FAIL:\n") << validation::formatSummary(families)
              << "\n";
  std::cout << "crankcheck validate" << (info.quick ? " --quick" : "") << ": the analytic engine against " << verdicts.size()
            << " engine(s)"
            << (info.shards > 1 ? ", merged from " + std::to_string(info.shards) + " shards"
                                : ", in " + validation::shortNumber(info.seconds, 3) + " s")
            << "\n"
            << validation::formatVerdict(verdicts) << formatSatOut(sat_out) << validation::formatSceneHeadlines(tables)
            << "Report: " << showPath(out.getTarget() / "index.md") << " (also index.html)\n";
  return pass ? 0 : 1;
}

}  // namespace

int runValidate(const ValidateOptions& options) {
  // Everything that can be checked is checked before the campaign: scenes, flags, the output folder, gnuplot.
  validation::CampaignOptions campaign;
  campaign.quick = options.quick;
  campaign.work_limit = options.work_limit;
  try {
    validation::checkPartKeys(options.parts);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--parts: ") + e.what());
  }
  campaign.parts = options.parts;
  std::set<std::string> names;
  for (const std::string& path : options.scene_paths) {
    campaign.scenes.push_back(loadScene(path));
    if (!names.insert(campaign.scenes.back().name).second)
      throw UsageError(path + ": a scene named " + campaign.scenes.back().name + " is given twice");
    if (campaign.scenes.back().crankshaft) {  // the torsion part's domain (analytic/torsion_domain.h), before any work
      try {
        analytic::checkTorsionDomain(campaign.scenes.back());
      } catch (const std::invalid_argument& e) {
        throw UsageError(path + ": " + e.what());
      }
    }
  }
  // Every engine builds every scene now, not after minutes of work: an engine that cannot (a rule of its own, an
  // accuracy it cannot hold there) sits out of the campaign, and the others go on; the closed forms, or every exact
  // engine, unable to: refused, naming the engine and the reason.
  campaign.sat_out = validation::findSatOut(campaign.scenes, options.scene_paths);
  const validation::SatOutScope sat_out_scope(campaign.sat_out);
  validation::ShardSelection selection;
  if (!options.shard.empty()) {
    try {
      selection = validation::parseShard(options.shard);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--shard: ") + e.what());
    }
  }
  // Any --shard writes a shard, --shard 0/1 too (a job array of one): it merges as any other (it wrote a report,
  // which report merge then called "not a shard").
  const bool shard = !options.shard.empty();
  // A new file, in a folder that exists, outside the report: checked before the campaign.
  if (!options.profile.empty()) validation::checkNewFile(options.profile, "--profile", {options.out});
  validation::OutputFolder out(options.out, "--out");
  validation::ReportInfo info;
  if (!shard) info.gnuplot_version = validation::checkGnuplot();  // a shard draws no figures
  // Every part's work, estimated before any of it starts (Part::checkWork): refused with status 2, nothing written.
  const std::vector<validation::Task> all = validation::buildCampaign(campaign);
  if (options.check) {
    std::cout << "validate --check: " << all.size() << " tasks" << (shard ? " (shard " + options.shard + ")" : "")
              << " would be run and written to " << showPath(options.out) << "; every check before the work holds\n";
    return 0;
  }
  validation::InterruptGuard interrupt(out);
  out.createStaging();

  validation::RunOptions run_options;
  run_options.jobs = options.jobs;
  run_options.profile = !options.profile.empty();
  const bool progress = ::isatty(STDERR_FILENO);
  if (progress) run_options.on_progress = printProgress;
  // The shard's manifest before the work: a scene of the default campaign that does not load stops it now.
  const validation::ShardManifest manifest =
      shard ? validation::makeShardManifest(campaign, selection, all.size()) : validation::ShardManifest{};
  validation::CampaignRun run;
  try {
    run = validation::runTasks(validation::selectShard(all, selection), run_options);
  } catch (const std::runtime_error& e) {
    validation::yieldToInterrupt();  // a task that failed because an interrupt killed its child: the interrupt's
    if (progress) std::fprintf(stderr, "\r\033[K");
    std::cerr << "crankcheck: " << formatOneLine(e.what()) << "\n";
    return 1;
  }
  if (progress) std::fprintf(stderr, "\r\033[K");
  if (!options.profile.empty()) validation::writeNewFile(options.profile, validation::formatProfile(run));
  info.quick = options.quick;
  info.jobs = run.jobs;
  info.seconds = run.seconds;

  if (shard) {
    validation::writeShard(run.tables, manifest, out.getStaging());
    out.install("shard");
    const bool pass = allPass(run.tables);
    std::cout << formatSatOut(campaign.sat_out) << "Shard " << selection.index << "/" << selection.count << " (" << run.task_ids.size() << " of " << all.size() << " tasks) written to " << showPath(options.out) << (pass ? "" : "; SOME COMPARISONS FAIL")
              << ". Merge the shards with: crankcheck report merge SHARD_DIR... --out DIR\n";
    return pass ? 0 : 1;
  }
  return reportAndInstall(run.tables, campaign.sat_out, info, out, options.verbose);
}

int runMerge(const MergeOptions& options) {
  // Every shard is checked before anything is written: one campaign, each shard once, all there, every data file
  // as its shard wrote it. A refusal is one line naming the shard or its file ("report merge: ..."), status 2.
  const validation::MergedShards merged = validation::mergeShards(options.shard_dirs);
  std::error_code ec;
  for (const std::string& dir : options.shard_dirs)
    if (fs::equivalent(dir, options.out, ec))
      throw UsageError("--out: " + quotePath(options.out) + ": is a shard being merged (" + quotePath(dir) +
                       "); choose another folder");
  validation::OutputFolder out(options.out, "--out");
  validation::ReportInfo info;
  info.gnuplot_version = validation::checkGnuplot();
  info.quick = merged.first.quick;
  info.shards = merged.first.count;
  validation::InterruptGuard interrupt(out);
  out.createStaging();
  return reportAndInstall(merged.tables, merged.first.sat_out, info, out, options.verbose);
}

}  // namespace crankcheck::app
