#include "validate_command.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <mutex>
#include <set>
#include <thread>

#include "crankcheck/analytic/torsion_domain.h"
#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/output_folder.h"
#include "crankcheck/validation/parts.h"
#include "crankcheck/validation/report.h"
#include "crankcheck/validation/profile.h"
#include "crankcheck/validation/verdict.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/scene/scene_writer.h"
#include "help_format.h"
#include "interrupt.h"
#include "scene_input.h"

namespace crankcheck::app {
namespace fs = std::filesystem;
using validation::TableSet;
using validation::Task;

void addValidateOptions(CLI::App& command, ValidateOptions& options) {
  std::vector<std::string> keys;
  for (const validation::Part* part : validation::listParts()) keys.push_back(part->key());
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

// The most shards of one campaign (as scripts/parallel-shards.sh and scripts/slurm/submit.sh): far above its tasks.
constexpr int kMaxShards = 100000;

// A duration for the progress line: "42s", "3m07s", "1h05m".
std::string formatDuration(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char text[32];
  if (s < 60) std::snprintf(text, sizeof text, "%lds", s);
  else if (s < 3600) std::snprintf(text, sizeof text, "%ldm%02lds", s / 60, s % 60);
  else std::snprintf(text, sizeof text, "%ldh%02ldm", s / 3600, s % 3600 / 60);
  return text;
}

// Runs the tasks; shows progress when stderr is a terminal: tasks done, the elapsed time and an estimate of the time
// left (the mean time per task so far times the tasks left; the tasks differ in cost, so it settles as the run goes on).
// The tasks that measure time (Task::measures_time) run one after the other on a core of their own: when every worker
// has a core (jobs <= the machine's cores), on the first worker before it takes other tasks, the other workers
// computing beside it (on this project's 2-core VM a busy neighbour core moves Google Benchmark's times by no more than
// run-to-run noise, a few %: bench/README.md, "Seventh session"); with more workers than cores, alone after the others.
// With `profile`, each task's seconds and what each engine did in it (profile.h) go to profile->at(i).
struct TaskProfile {
  double seconds = 0.0;
  std::map<std::string, validation::EngineUse> engines;
};

TableSet runTasks(const std::vector<Task>& tasks, int jobs, std::vector<TaskProfile>* profile = nullptr) {
  const bool progress = ::isatty(STDERR_FILENO);
  const auto start = std::chrono::steady_clock::now();
  std::vector<TableSet> results(tasks.size());
  if (profile) profile->assign(tasks.size(), {});
  std::vector<std::string> errors;
  std::mutex mutex;
  std::atomic<size_t> next{0}, done{0};
  auto runOne = [&](size_t i) {
    try {
      if (profile) validation::getThreadEngineUse().clear();
      const auto task_start = std::chrono::steady_clock::now();
      results[i] = tasks[i].run();
      if (profile) {
        (*profile)[i].seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - task_start).count();
        (*profile)[i].engines = validation::getThreadEngineUse();
      }
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(mutex);
      errors.push_back(tasks[i].id + ": " + e.what());
    }
    const size_t finished = ++done;
    if (progress) {
      std::lock_guard<std::mutex> lock(mutex);
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const double left = elapsed / static_cast<double>(finished) * static_cast<double>(tasks.size() - finished);
      std::fprintf(stderr, "\r\033[K[%3zu/%zu] %s elapsed, about %s left: %s", finished, tasks.size(),
                   formatDuration(elapsed).c_str(), formatDuration(left).c_str(), tasks[i].id.c_str());
      std::fflush(stderr);
    }
  };
  std::vector<size_t> parallel, timed;
  for (size_t i = 0; i < tasks.size(); ++i) (tasks[i].measures_time ? timed : parallel).push_back(i);
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const bool beside = jobs <= cores;  // each worker on a core of its own
  std::vector<std::thread> workers;
  for (int w = 0; w < jobs; ++w)
    workers.emplace_back([&, w] {
      if (beside && w == 0)
        for (size_t i : timed) runOne(i);
      for (size_t n; (n = next++) < parallel.size();) runOne(parallel[n]);
    });
  for (auto& worker : workers) worker.join();
  if (!beside)
    for (size_t i : timed) runOne(i);
  if (progress) std::fprintf(stderr, "\r\033[K");
  if (!errors.empty()) {
    std::string message = "the campaign could not run:";
    for (const auto& e : errors) message += "\n  " + e;
    throw std::runtime_error(message);
  }
  TableSet merged;
  for (const TableSet& r : results) validation::appendTables(merged, r);
  return merged;
}

// The profile as CSV: per task, one row per engine it used and one for the rest of its time (work that does not go
// through the registry's models: the analytic batch kernels, a part's own calls into an engine, the part's own code).
std::string formatProfile(const std::vector<Task>& tasks, const std::vector<TaskProfile>& profile) {
  std::string csv = "task,engine,builds,evaluations,seconds [s],task_seconds [s]\n";
  auto field = [](const std::string& s) { return s.find_first_of(",\"\n") == std::string::npos ? s : "\"" + s + "\""; };
  for (size_t i = 0; i < tasks.size(); ++i) {
    double engines = 0.0;
    for (const auto& [name, use] : profile[i].engines) {
      csv += field(tasks[i].id) + "," + name + "," + std::to_string(use.builds) + "," + std::to_string(use.evaluations) + "," +
             validation::formatNumber(use.build_seconds + use.evaluate_seconds) + "," +
             validation::formatNumber(profile[i].seconds) + "\n";
      engines += use.build_seconds + use.evaluate_seconds;
    }
    csv += field(tasks[i].id) + ",(rest),0,0," + validation::formatNumber(std::max(0.0, profile[i].seconds - engines)) + "," +
           validation::formatNumber(profile[i].seconds) + "\n";
  }
  return csv;
}

bool allPass(const TableSet& tables) { return validation::allAgree(validation::calcVerdicts(tables)); }

// The terminal's end: the families' table (all of it with --verbose, else only the families that failed), the
// verdict (one line per engine, the ctest-style closing line) and where the report is.
int reportAndInstall(const TableSet& unsorted, validation::ReportInfo& info, validation::OutputFolder& out, bool verbose) {
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
            << validation::formatVerdict(verdicts)
            << "Report: " << (out.getTarget() / "index.md").string() << " (also index.html)\n";
  return pass ? 0 : 1;
}

}  // namespace

int runValidate(const ValidateOptions& options) {
  // Everything that can be checked is checked before the campaign: scenes, flags, the output folder, gnuplot.
  validation::CampaignOptions campaign;
  campaign.quick = options.quick;
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
    // Every engine must be able to build the scene (a massless rod for Simbody, a massless piston for MuJoCo, ...):
    // refused now, naming the engine and the key, not after minutes of work.
    validation::checkEveryEngineBuilds(campaign.scenes.back(), path);
    if (campaign.scenes.back().crankshaft) {  // part 17's domain (analytic/torsion_domain.h), before any work
      try {
        analytic::checkTorsionDomain(campaign.scenes.back());
      } catch (const std::invalid_argument& e) {
        throw UsageError(path + ": " + e.what());
      }
    }
  }
  int shard_index = 0, shard_count = 1;
  if (!options.shard.empty()) {
    // Digits only, each number read whole: sscanf's %d took " 0/2", "-0/2" and an N past INT_MAX (undefined).
    const auto slash = options.shard.find('/');
    auto isCount = [](const std::string& s) {
      return !s.empty() && s.size() <= 6 && s.find_first_not_of("0123456789") == std::string::npos;
    };
    const std::string i_text = options.shard.substr(0, slash);
    const std::string n_text = slash == std::string::npos ? std::string() : options.shard.substr(slash + 1);
    if (isCount(i_text) && isCount(n_text)) {
      shard_index = std::stoi(i_text);
      shard_count = std::stoi(n_text);
    }
    if (!isCount(i_text) || !isCount(n_text) || shard_count < 1 || shard_count > kMaxShards || shard_index >= shard_count)
      throw UsageError("--shard: " + options.shard + ": expected I/N with 0 <= I < N <= " + std::to_string(kMaxShards) +
                       ", e.g. --shard 0/4");
  }
  const bool shard = shard_count > 1;
  // A new file, in a folder that exists, outside the report: checked before the campaign.
  if (!options.profile.empty()) validation::checkNewFile(options.profile, "--profile", {options.out});
  const int jobs = options.jobs > 0 ? options.jobs : std::max(1u, std::thread::hardware_concurrency());
  validation::OutputFolder out(options.out, "--out");
  validation::ReportInfo info;
  if (!shard) info.gnuplot_version = validation::checkGnuplot();  // a shard draws no figures
  InterruptGuard interrupt(out);
  out.createStaging();

  const std::vector<Task> all = validation::buildCampaign(campaign);
  // A shard's campaign is its scenes' content (the default campaign's built-in and example scenes too), --quick,
  // N and crankcheck's version: the merge refuses shards of campaigns that differ in any.
  validation::ShardManifest manifest{shard_index, shard_count, options.quick, {}, options.parts, static_cast<int>(all.size()),
                                     validation::getCrankcheckVersion(), {}};
  if (shard) {
    std::vector<Mechanism> scenes = campaign.scenes;
    if (scenes.empty()) {
      scenes = validation::buildDefaultScenes();
      for (Mechanism& m : validation::loadExampleScenes()) scenes.push_back(std::move(m));
    }
    for (const Mechanism& m : scenes) manifest.scenes.push_back({m.name, validation::calcChecksum(formatSceneToml(m))});
  }
  std::vector<Task> mine;
  for (size_t i = 0; i < all.size(); ++i)
    if (static_cast<int>(i % shard_count) == shard_index) mine.push_back(all[i]);
  const auto start = std::chrono::steady_clock::now();
  TableSet tables;
  std::vector<TaskProfile> profile;
  validation::setProfiling(!options.profile.empty());
  try {
    tables = runTasks(mine, jobs, options.profile.empty() ? nullptr : &profile);
  } catch (const std::runtime_error& e) {
    std::cerr << "crankcheck: " << formatOneLine(e.what()) << "\n";
    return 1;
  }
  if (!options.profile.empty()) validation::writeNewFile(options.profile, formatProfile(mine, profile));
  info.quick = options.quick;
  info.jobs = jobs;
  info.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (shard) {
    validation::sortTables(tables);
    manifest.files = validation::writeTables(tables, out.getStaging());
    validation::writeShardManifest(manifest, out.getStaging());
    out.install("shard");
    const bool pass = allPass(tables);
    std::cout << "Shard " << shard_index << "/" << shard_count << " (" << mine.size() << " of " << all.size()
              << " tasks) written to " << options.out << (pass ? "" : "; SOME COMPARISONS FAIL")
              << ". Merge the shards with: crankcheck report merge SHARD_DIR... --out DIR\n";
    return pass ? 0 : 1;
  }
  return reportAndInstall(tables, info, out, options.verbose);
}

namespace {

// The scenes' names, for a message: "a, b, c".
std::string listNames(const std::vector<validation::ShardScene>& scenes) {
  std::string names;
  for (const auto& scene : scenes) names += (names.empty() ? "" : ", ") + scene.name;
  return names.empty() ? "none" : names;
}

// How the campaign of `shard` differs from that of `first` (read from first_dir): "" when it is the same one.
std::string findCampaignDifference(const validation::ShardManifest& shard, const validation::ShardManifest& first,
                                   const std::string& first_dir) {
  const std::string there = quotePath(first_dir);
  if (shard.version != first.version)
    return "written by crankcheck " + shard.version + ", " + there + " by crankcheck " + first.version;
  if (shard.count != first.count)
    return "shard " + std::to_string(shard.index) + " of " + std::to_string(shard.count) + ", not of " +
           std::to_string(first.count) + " as " + there;
  if (shard.quick != first.quick)
    return std::string("a ") + (shard.quick ? "--quick" : "full") + " campaign, " + there + " a " +
           (first.quick ? "--quick" : "full") + " one";
  if (shard.scenes.size() != first.scenes.size())
    return "scenes " + listNames(shard.scenes) + ", " + there + " has " + listNames(first.scenes);
  for (size_t i = 0; i < shard.scenes.size(); ++i) {
    if (shard.scenes[i].name != first.scenes[i].name)
      return "scenes " + listNames(shard.scenes) + ", " + there + " has " + listNames(first.scenes);
    if (shard.scenes[i].checksum != first.scenes[i].checksum)
      return "scene " + shard.scenes[i].name + ": another scene than in " + there + " (the same name, other content)";
  }
  if (shard.parts != first.parts) {
    auto list = [](const std::vector<std::string>& parts) {
      std::string s;
      for (const std::string& p : parts) s += (s.empty() ? "" : ",") + p;
      return parts.empty() ? std::string("every part") : "--parts " + s;
    };
    return list(shard.parts) + ", " + there + " " + list(first.parts);
  }
  if (shard.tasks != first.tasks)
    return std::to_string(shard.tasks) + " tasks, " + there + " " + std::to_string(first.tasks) +
           ": a shard of another campaign";
  return "";
}

}  // namespace

int runMerge(const MergeOptions& options) {
  // Every shard is checked before anything is written: one campaign, each shard once, all there, every data file
  // as its shard wrote it. A refusal is one line naming the shard or its file ("report merge: ..."), status 2.
  auto refuse = [](const std::string& why) { return UsageError("report merge: " + why); };
  TableSet tables;
  std::set<int> seen;
  validation::ShardManifest first;
  for (size_t i = 0; i < options.shard_dirs.size(); ++i) {
    const std::string& dir = options.shard_dirs[i];
    try {
      const validation::ShardManifest manifest = validation::readShardManifest(dir);
      if (i == 0) first = manifest;
      const std::string difference = findCampaignDifference(manifest, first, options.shard_dirs[0]);
      if (!difference.empty()) throw refuse(quotePath(dir) + ": " + difference);
      if (!seen.insert(manifest.index).second)
        throw refuse(quotePath(dir) + ": shard " + std::to_string(manifest.index) + " given twice");
      validation::appendTables(tables, validation::readShardTables(dir, manifest));
    } catch (const UsageError&) {
      throw;
    } catch (const EnvironmentError&) {
      throw;
    } catch (const std::runtime_error& e) {
      throw refuse(e.what());
    }
  }
  if (static_cast<int>(seen.size()) != first.count) {
    std::string missing;
    for (int index = 0; index < first.count; ++index)
      if (!seen.count(index)) missing += (missing.empty() ? "" : ", ") + std::to_string(index);
    throw refuse("shards: " + std::to_string(seen.size()) + " of " + std::to_string(first.count) + " given (missing: " +
                 missing + "); all are needed");
  }
  std::error_code ec;
  for (const std::string& dir : options.shard_dirs)
    if (fs::equivalent(dir, options.out, ec))
      throw UsageError("--out: " + quotePath(options.out) + ": is a shard being merged (" + quotePath(dir) +
                       "); choose another folder");
  validation::OutputFolder out(options.out, "--out");
  validation::ReportInfo info;
  info.gnuplot_version = validation::checkGnuplot();
  info.quick = first.quick;
  info.shards = first.count;
  InterruptGuard interrupt(out);
  out.createStaging();
  return reportAndInstall(tables, info, out, options.verbose);
}

}  // namespace crankcheck::app
