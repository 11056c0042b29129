#pragma once
/// @file
/// Running a campaign (campaign.h's tasks): the workers and their rule for the tasks that measure time, the shard a
/// run takes and its manifest, the profile of where the time went, progress, and the merge of shards into the tables
/// of one run. `crankcheck validate` and `report merge`, the Python module and the tests call these; the callers
/// only parse, check and print.
///
/// The tables a run returns are the tasks' tables appended in the tasks' order; sortTables (campaign.h) makes them
/// independent of the order, the number of workers and the cut into shards.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <stop_token>
#include <string>
#include <vector>

#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/profile.h"
#include "crankcheck/validation/report.h"

namespace crankcheck::validation {

/// The most shards of one campaign (as scripts/parallel-shards.sh and scripts/slurm/submit.sh): far above its tasks.
constexpr int kMaxShards = 100000;

/// The default number of workers: one per core the machine reports (at least 1).
int getDefaultJobs();

/// Part `index` of `count` of a campaign (`validate --shard I/N`); count 1: the whole campaign.
struct ShardSelection {
  int index = 0;
  int count = 1;
};

/// Reads "I/N": digits only, each number whole, 0 <= I < N <= kMaxShards.
/// @throws std::invalid_argument "TEXT: expected I/N with 0 <= I < N <= 100000, e.g. --shard 0/4".
ShardSelection parseShard(const std::string& text);

/// The tasks of a shard: task i of `all` where i % count == index, in their order. The shards of one campaign
/// partition its tasks. @throws std::invalid_argument unless 0 <= index < count.
std::vector<Task> selectShard(const std::vector<Task>& all, const ShardSelection& shard);

/// What one task did: its wall time and, while profiling, what each engine of the registry did in it (profile.h).
struct TaskProfile {
  double seconds = 0.0;                      ///< [s] wall time of the task
  std::map<std::string, EngineUse> engines;  ///< by engine name; empty unless RunOptions::profile
};

/// A task finished (RunOptions::on_progress).
struct Progress {
  size_t done = 0;              ///< tasks finished so far, this one included
  size_t total = 0;             ///< tasks of the run
  double elapsed_seconds = 0.0; ///< [s] since the run started
  const Task* task = nullptr;   ///< the task that finished
};

struct RunOptions {
  int jobs = 0;  ///< worker threads; 0: getDefaultJobs()
  /// Count what each engine did in each task (setProfiling, profile.h) into CampaignRun::profile.
  bool profile = false;
  /// Called after each task, one call at a time (under the runner's lock), from the worker that ran it.
  std::function<void(const Progress&)> on_progress;
  /// When stop is requested, no further task starts; the run then throws CampaignCancelled once the running ones end.
  std::stop_token stop;
};

/// What a run returns.
struct CampaignRun {
  TableSet tables;                   ///< every task's tables, appended in the tasks' order (unsorted)
  std::vector<std::string> task_ids; ///< the ids of the tasks run, in order
  size_t campaign_tasks = 0;         ///< the tasks of the whole campaign (every shard's); runTasks: the tasks given
  std::vector<TaskProfile> profile;  ///< one per task, in the tasks' order (seconds always; engines when profiling)
  double seconds = 0.0;              ///< [s] wall time of the run
  int jobs = 1;                      ///< the workers it used
};

/// A run stopped through RunOptions::stop before every task ran.
class CampaignCancelled : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Runs `tasks` on options.jobs workers. The tasks that measure time (Task::measures_time) run one after the other on
/// a core of their own: when every worker has a core (jobs <= the machine's cores), on the first worker before it
/// takes other tasks, the other workers computing beside it (a busy neighbour core moves Google Benchmark's times by
/// no more than run-to-run noise, a few %: bench/README.md); with more workers than cores, alone after the others.
/// Every task runs even when some fail. @throws std::runtime_error "the campaign could not run:" and one line
/// "  ID: what" per task that threw; CampaignCancelled when options.stop was requested.
CampaignRun runTasks(const std::vector<Task>& tasks, const RunOptions& options);

/// The campaign of `campaign` (buildCampaign), the tasks of `shard`, run as runTasks. @throws as buildCampaign and
/// runTasks.
CampaignRun runCampaign(const CampaignOptions& campaign, const ShardSelection& shard, const RunOptions& options);

/// The profile as CSV: per task, one row per engine it used and one for the rest of its time (work that does not go
/// through the registry's models: the analytic batch kernels, a part's own calls into an engine, the part's own code).
/// Columns: task,engine,builds,evaluations,seconds [s],task_seconds [s].
std::string formatProfile(const CampaignRun& run);

/// A shard's manifest before its files are written: which part of which campaign it is. Its scenes are the
/// campaign's scenes (the default campaign's built-in and example scenes when campaign.scenes is empty) with the
/// checksums of their content, for the merge to refuse shards of campaigns that differ.
ShardManifest makeShardManifest(const CampaignOptions& campaign, const ShardSelection& shard, size_t campaign_tasks);

/// Writes a shard into `dir` (which must exist and be empty): the tables sorted as CSV (writeTables) and shard.json
/// with the files' records. @throws EnvironmentError when a file cannot be written.
void writeShard(TableSet tables, ShardManifest manifest, const std::filesystem::path& dir);

/// How the campaign of `shard` differs from that of `first` (read from first_dir), one phrase naming first_dir: ""
/// when both are shards of one campaign.
std::string findCampaignDifference(const ShardManifest& shard, const ShardManifest& first, const std::string& first_dir);

/// The shards merged (`crankcheck report merge`).
struct MergedShards {
  TableSet tables;      ///< every shard's tables appended, in the order given (unsorted)
  ShardManifest first;  ///< the first shard's manifest: the campaign (quick, count, parts, scenes, sat_out)
  /// The engines in play while the merged tables are read and reported: the campaign's, less first.sat_out.
  std::unique_ptr<SatOutScope> sat_out_scope;
};

/// Reads and merges the shards in `dirs`: one campaign, each shard once, all there, every data file as its shard wrote
/// it; the merge of the shards of a campaign equals a single run's tables once sorted.
/// @throws UsageError "report merge: ..." (one line naming the shard or its file) for any of those;
///         EnvironmentError as the readers.
MergedShards mergeShards(const std::vector<std::string>& dirs);

}  // namespace crankcheck::validation
