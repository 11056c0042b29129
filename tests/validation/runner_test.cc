// The campaign runner (runner.h) on small fake tasks, each writing one row that names it: the shards partition the
// tasks, the merge of the shards gives the tables of a single run, one worker and two give the same tables, a task
// that throws reaches the caller (after every other task ran), the tasks that measure time never run beside each
// other, and a stop request stops the run. The tables are compared as the CSV files writeTables makes of them.

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/output_folder.h"
#include "crankcheck/validation/report.h"
#include "crankcheck/validation/runner.h"
#include "fresh_folder.h"

namespace crankcheck::validation {
namespace {

using testing::FreshFolder;

// n tasks; task i writes the row (i, i^2, its id) to table "fake" and, every third, a row to table "other".
std::vector<Task> makeTasks(int n, std::atomic<int>* runs = nullptr) {
  std::vector<Task> tasks;
  for (int i = 0; i < n; ++i) {
    Task t;
    t.id = "fake " + std::to_string(i);
    t.run = [i, id = t.id, runs] {
      if (runs) ++*runs;
      TableSet tables;
      Table fake("fake", {{"i", "-"}, {"square", "-"}, {"task", kText}});
      fake.rows.push_back({formatNumber(i), formatNumber(double(i) * i), id});
      tables["fake"] = fake;
      if (i % 3 == 0) {
        Table other("other", {{"third", "-"}});
        other.rows.push_back({formatNumber(i / 3)});
        tables["other"] = other;
      }
      return tables;
    };
    tasks.push_back(t);
  }
  return tasks;
}

// The tables as the CSV files writeTables makes of them, by file name.
std::map<std::string, std::string> toCsv(TableSet tables) {
  sortTables(tables);
  FreshFolder dir;
  const std::filesystem::path out = dir.path() / "tables";
  std::filesystem::create_directory(out);
  writeTables(tables, out);
  std::map<std::string, std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(out / "data")) {
    std::ifstream in(entry.path(), std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    files[entry.path().filename().string()] = text.str();
  }
  return files;
}

RunOptions withJobs(int jobs) {
  RunOptions options;
  options.jobs = jobs;
  return options;
}

TEST(RunnerTest, ShardsPartitionTheTasks) {
  const std::vector<Task> all = makeTasks(17);
  for (int count : {1, 2, 3, 5, 17, 20}) {
    std::map<std::string, int> seen;
    size_t total = 0;
    for (int index = 0; index < count; ++index) {
      const std::vector<Task> mine = selectShard(all, {index, count});
      total += mine.size();
      for (const Task& t : mine) ++seen[t.id];
    }
    EXPECT_EQ(total, all.size()) << count << " shards";
    for (const Task& t : all) EXPECT_EQ(seen[t.id], 1) << t.id << " in " << count << " shards";
  }
  EXPECT_THROW(selectShard(all, {2, 2}), std::invalid_argument);
  EXPECT_THROW(selectShard(all, {0, 0}), std::invalid_argument);
}

TEST(RunnerTest, ParsesShardsAndRefusesBadOnes) {
  const ShardSelection s = parseShard("3/8");
  EXPECT_EQ(s.index, 3);
  EXPECT_EQ(s.count, 8);
  EXPECT_EQ(parseShard("0/100000").count, kMaxShards);
  for (const char* bad : {"", "3", "8/8", "1/0", " 0/2", "-0/2", "0/100001", "0/2147483648", "a/b", "0/2/3"})
    EXPECT_THROW(parseShard(bad), std::invalid_argument) << '"' << bad << '"';
  try {
    parseShard("8/8");
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "8/8: expected I/N with 0 <= I < N <= 100000, e.g. --shard 0/4");
  }
}

TEST(RunnerTest, OneWorkerAndTwoGiveTheSameTables) {
  const std::vector<Task> tasks = makeTasks(23);
  const CampaignRun one = runTasks(tasks, withJobs(1));
  const CampaignRun two = runTasks(tasks, withJobs(2));
  EXPECT_EQ(one.jobs, 1);
  EXPECT_EQ(two.jobs, 2);
  EXPECT_EQ(one.task_ids.size(), tasks.size());
  // Appended in the tasks' order whatever the workers: the same before sorting too.
  EXPECT_EQ(toCsv(one.tables), toCsv(two.tables));
  const std::map<std::string, std::string> csv = toCsv(one.tables);
  ASSERT_EQ(csv.count("fake.csv"), 1u);
  ASSERT_EQ(csv.count("other.csv"), 1u);
  // One row per task, the header first: 23 tasks, 8 of them (0, 3, ..., 21) in "other".
  EXPECT_EQ(std::count(csv.at("fake.csv").begin(), csv.at("fake.csv").end(), '\n'), 24);
  EXPECT_EQ(std::count(csv.at("other.csv").begin(), csv.at("other.csv").end(), '\n'), 9);
}

TEST(RunnerTest, TheMergeOfTheShardsIsASingleRunsTables) {
  const std::vector<Task> all = makeTasks(11);
  const CampaignRun single = runTasks(all, withJobs(2));
  FreshFolder dir;
  const int count = 3;
  std::vector<std::string> shard_dirs;
  for (int index = count - 1; index >= 0; --index) {  // given in any order
    const CampaignRun run = runTasks(selectShard(all, {index, count}), withJobs(1));
    const std::string path = (dir.path() / ("shard" + std::to_string(index))).string();
    OutputFolder out(path, "--out");
    out.createStaging();
    ShardManifest manifest;  // one campaign's: the same count, tasks and version in every shard
    manifest.index = index;
    manifest.count = count;
    manifest.tasks = static_cast<int>(all.size());
    manifest.version = getCrankcheckVersion();
    writeShard(run.tables, manifest, out.getStaging());
    out.install("shard");
    shard_dirs.push_back(path);
  }
  const MergedShards merged = mergeShards(shard_dirs);
  EXPECT_EQ(merged.first.count, count);
  EXPECT_EQ(merged.first.tasks, static_cast<int>(all.size()));
  EXPECT_EQ(toCsv(merged.tables), toCsv(single.tables));

  // Every shard is needed, each once: one line naming what is wrong.
  try {
    mergeShards({shard_dirs[0], shard_dirs[1]});
    FAIL() << "a merge with a shard missing was accepted";
  } catch (const UsageError& e) {
    EXPECT_STREQ(e.what(), "report merge: shards: 2 of 3 given (missing: 0); all are needed");
  }
  try {
    mergeShards({shard_dirs[0], shard_dirs[1], shard_dirs[1]});
    FAIL() << "a shard given twice was accepted";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("shard 1 given twice"), std::string::npos) << e.what();
  }
}

// shard.json's record of the engines that sat out is held to the campaign's scenes and to the data (a round of
// attacks: a hand-edited record naming mujoco-soft merged, its rows and all, and was printed as having sat out).
TEST(RunnerTest, AMergeRefusesARecordOfEnginesThatSatOutWhichItsDataContradict) {
  FreshFolder dir;
  auto writeShards = [&](const std::string& name, const std::vector<SatOut>& sat_out) {
    std::vector<std::string> shard_dirs;
    for (int index = 0; index < 2; ++index) {
      TableSet tables;
      Table rows("by_engine", {{"engine", kText}, {"value", "-"}});
      rows.rows.push_back({"mujoco-soft", formatNumber(index)});
      tables["by_engine"] = rows;
      const std::string path = (dir.path() / (name + std::to_string(index))).string();
      OutputFolder out(path, "--out");
      out.createStaging();
      ShardManifest manifest;
      manifest.index = index;
      manifest.count = 2;
      manifest.tasks = 2;
      manifest.version = getCrankcheckVersion();
      manifest.scenes = {{"light", "0123456789abcdef"}};
      manifest.sat_out = sat_out;
      writeShard(tables, manifest, out.getStaging());
      out.install("shard");
      shard_dirs.push_back(path);
    }
    return shard_dirs;
  };
  auto refusal = [](const std::vector<std::string>& shard_dirs) {
    try {
      mergeShards(shard_dirs);
    } catch (const UsageError& e) {
      return std::string(e.what());
    }
    return std::string("merged");
  };
  EXPECT_EQ(refusal(writeShards("ok", {})), "merged");
  EXPECT_NE(refusal(writeShards("rows", {{"mujoco-soft", "light", "-"}})).find(
                "sat_out: names engine \"mujoco-soft\", but the shards' table by_engine holds its values"),
            std::string::npos);
  EXPECT_NE(refusal(writeShards("scene", {{"mujoco-soft-stiff", "heavy", "-"}})).find(
                "sat_out: scene \"heavy\" is none of the campaign's scenes (light)"),
            std::string::npos);
  EXPECT_NE(refusal(writeShards("twice", {{"mujoco-soft-stiff", "light", "-"}, {"mujoco-soft-stiff", "light", "-"}}))
                .find("sat_out: engine \"mujoco-soft-stiff\" twice"),
            std::string::npos);
  EXPECT_EQ(refusal(writeShards("other", {{"mujoco-soft-stiff", "light", "-"}})), "merged");  // no row of it
}

TEST(RunnerTest, AThrowingTaskReachesTheCallerAfterTheOthersRan) {
  std::atomic<int> runs{0};
  std::vector<Task> tasks = makeTasks(9, &runs);
  tasks[4].run = [] () -> TableSet { throw std::runtime_error("no convergence at phi = 1"); };
  for (int jobs : {1, 2}) {
    runs = 0;
    try {
      runTasks(tasks, withJobs(jobs));
      FAIL() << "a task threw and the run returned";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "the campaign could not run:\n  fake 4: no convergence at phi = 1");
    }
    EXPECT_EQ(runs, 8) << jobs << " workers";
  }
}

TEST(RunnerTest, TasksThatMeasureTimeNeverRunBesideEachOther) {
  std::atomic<int> timing{0}, most{0};
  std::vector<Task> tasks = makeTasks(12);
  for (size_t i = 0; i < tasks.size(); i += 2) {
    tasks[i].measures_time = true;
    const auto run = tasks[i].run;
    tasks[i].run = [run, &timing, &most] {
      const int now = ++timing;
      for (int seen = most; now > seen && !most.compare_exchange_weak(seen, now);) {
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));  // long enough for a second worker to start one
      --timing;
      return run();
    };
  }
  for (int jobs : {1, 2, 3, 64}) {  // 64: more workers than cores, the timed ones after the others
    most = 0;
    const CampaignRun run = runTasks(tasks, withJobs(jobs));
    EXPECT_EQ(most, 1) << jobs << " workers";
    EXPECT_EQ(toCsv(run.tables), toCsv(runTasks(makeTasks(12), withJobs(1)).tables));
  }
}

TEST(RunnerTest, ReportsProgressOncePerTask) {
  const std::vector<Task> tasks = makeTasks(7);
  RunOptions options = withJobs(2);
  std::vector<size_t> done;
  options.on_progress = [&](const Progress& p) {
    EXPECT_EQ(p.total, tasks.size());
    ASSERT_NE(p.task, nullptr);
    done.push_back(p.done);
  };
  runTasks(tasks, options);
  ASSERT_EQ(done.size(), tasks.size());
  for (size_t i = 0; i < done.size(); ++i) EXPECT_EQ(done[i], i + 1);  // one call at a time, counting up
}

TEST(RunnerTest, AStopRequestStopsTheRun) {
  std::atomic<int> runs{0};
  std::stop_source stop;
  stop.request_stop();
  RunOptions options = withJobs(2);
  options.stop = stop.get_token();
  EXPECT_THROW(runTasks(makeTasks(5, &runs), options), CampaignCancelled);
  EXPECT_EQ(runs, 0);
}

TEST(RunnerTest, ProfilesEachTask) {
  const std::vector<Task> tasks = makeTasks(3);
  RunOptions options = withJobs(1);
  options.profile = true;
  const CampaignRun run = runTasks(tasks, options);
  setProfiling(false);
  // No engine in a fake task: one "(rest)" row per task, its seconds the task's.
  const std::string csv = formatProfile(run);
  EXPECT_EQ(csv.rfind("task,engine,builds,evaluations,seconds [s],task_seconds [s]\n", 0), 0u) << csv;
  for (const Task& t : tasks) EXPECT_NE(csv.find(t.id + ",(rest),0,0,"), std::string::npos) << csv;
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4);
}

}  // namespace
}  // namespace crankcheck::validation
