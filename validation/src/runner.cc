#include "crankcheck/validation/runner.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>

#include "crankcheck/scene/scene_writer.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/output_folder.h"

namespace crankcheck::validation {

int getDefaultJobs() { return static_cast<int>(std::max(1u, std::thread::hardware_concurrency())); }

ShardSelection parseShard(const std::string& text) {
  // Digits only, each number read whole: sscanf's %d took " 0/2", "-0/2" and an N past INT_MAX (undefined).
  const auto slash = text.find('/');
  auto isCount = [](const std::string& s) {
    return !s.empty() && s.size() <= 6 && s.find_first_not_of("0123456789") == std::string::npos;
  };
  const std::string i_text = text.substr(0, slash);
  const std::string n_text = slash == std::string::npos ? std::string() : text.substr(slash + 1);
  ShardSelection shard;
  if (isCount(i_text) && isCount(n_text)) {
    shard.index = std::stoi(i_text);
    shard.count = std::stoi(n_text);
  }
  if (!isCount(i_text) || !isCount(n_text) || shard.count < 1 || shard.count > kMaxShards || shard.index >= shard.count)
    throw std::invalid_argument(text + ": expected I/N with 0 <= I < N <= " + std::to_string(kMaxShards) +
                                ", e.g. --shard 0/4");
  return shard;
}

std::vector<Task> selectShard(const std::vector<Task>& all, const ShardSelection& shard) {
  if (shard.count < 1 || shard.index < 0 || shard.index >= shard.count)
    throw std::invalid_argument("shard " + std::to_string(shard.index) + " of " + std::to_string(shard.count) +
                                ": expected 0 <= index < count");
  std::vector<Task> mine;
  for (size_t i = 0; i < all.size(); ++i)
    if (static_cast<int>(i % static_cast<size_t>(shard.count)) == shard.index) mine.push_back(all[i]);
  return mine;
}

CampaignRun runTasks(const std::vector<Task>& tasks, const RunOptions& options) {
  CampaignRun run;
  run.jobs = options.jobs > 0 ? options.jobs : getDefaultJobs();
  run.campaign_tasks = tasks.size();
  for (const Task& t : tasks) run.task_ids.push_back(t.id);
  run.profile.assign(tasks.size(), {});
  setProfiling(options.profile);
  const auto start = std::chrono::steady_clock::now();
  std::vector<TableSet> results(tasks.size());
  std::vector<std::string> errors;
  std::mutex mutex;
  std::atomic<size_t> next{0}, done{0};
  std::atomic<bool> stopped{false};
  auto runOne = [&](size_t i) {
    if (options.stop.stop_requested()) {
      stopped = true;
      return;
    }
    try {
      if (options.profile) getThreadEngineUse().clear();
      const auto task_start = std::chrono::steady_clock::now();
      results[i] = tasks[i].run();
      run.profile[i].seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - task_start).count();
      if (options.profile) run.profile[i].engines = getThreadEngineUse();
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(mutex);
      errors.push_back(tasks[i].id + ": " + e.what());
    }
    // Counted and reported under one lock: the calls come one at a time, their counts in order.
    std::lock_guard<std::mutex> lock(mutex);
    const size_t finished = ++done;
    if (options.on_progress)
      options.on_progress({finished, tasks.size(),
                           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), &tasks[i]});
  };
  std::vector<size_t> parallel, timed;
  for (size_t i = 0; i < tasks.size(); ++i) (tasks[i].measures_time ? timed : parallel).push_back(i);
  const bool beside = run.jobs <= getDefaultJobs();  // each worker on a core of its own
  std::vector<std::thread> workers;
  for (int w = 0; w < run.jobs; ++w)
    workers.emplace_back([&, w] {
      if (beside && w == 0)
        for (size_t i : timed) runOne(i);
      for (size_t n; (n = next++) < parallel.size();) runOne(parallel[n]);
    });
  for (auto& worker : workers) worker.join();
  if (!beside)
    for (size_t i : timed) runOne(i);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (stopped) throw CampaignCancelled("the campaign was stopped after " + std::to_string(done.load()) + " of " +
                                       std::to_string(tasks.size()) + " tasks");
  if (!errors.empty()) {
    std::string message = "the campaign could not run:";
    for (const auto& e : errors) message += "\n  " + e;
    throw std::runtime_error(message);
  }
  for (const TableSet& r : results) appendTables(run.tables, r);
  return run;
}

CampaignRun runCampaign(const CampaignOptions& campaign, const ShardSelection& shard, const RunOptions& options) {
  const std::vector<Task> all = buildCampaign(campaign);
  CampaignRun run = runTasks(selectShard(all, shard), options);
  run.campaign_tasks = all.size();
  return run;
}

std::string formatProfile(const CampaignRun& run) {
  std::string csv = "task,engine,builds,evaluations,seconds [s],task_seconds [s]\n";
  auto field = [](const std::string& s) { return s.find_first_of(",\"\n") == std::string::npos ? s : "\"" + s + "\""; };
  for (size_t i = 0; i < run.task_ids.size() && i < run.profile.size(); ++i) {
    const TaskProfile& p = run.profile[i];
    double engines = 0.0;
    for (const auto& [name, use] : p.engines) {
      csv += field(run.task_ids[i]) + "," + name + "," + std::to_string(use.builds) + "," + std::to_string(use.evaluations) +
             "," + formatNumber(use.build_seconds + use.evaluate_seconds) + "," + formatNumber(p.seconds) + "\n";
      engines += use.build_seconds + use.evaluate_seconds;
    }
    csv += field(run.task_ids[i]) + ",(rest),0,0," + formatNumber(std::max(0.0, p.seconds - engines)) + "," +
           formatNumber(p.seconds) + "\n";
  }
  return csv;
}

ShardManifest makeShardManifest(const CampaignOptions& campaign, const ShardSelection& shard, size_t campaign_tasks) {
  // A shard's campaign is its scenes' content (the default campaign's built-in and example scenes too), --quick, the
  // parts, N and crankcheck's version: the merge refuses shards of campaigns that differ in any.
  ShardManifest manifest{shard.index, shard.count, campaign.quick, {}, campaign.parts, campaign.sat_out,
                         static_cast<int>(campaign_tasks), getCrankcheckVersion(), {}};
  std::vector<Mechanism> scenes = campaign.scenes;
  if (scenes.empty()) {
    scenes = buildDefaultScenes();
    for (Mechanism& m : loadExampleScenes()) scenes.push_back(std::move(m));
  }
  for (const Mechanism& m : scenes) manifest.scenes.push_back({m.name, calcChecksum(formatSceneToml(m))});
  return manifest;
}

void writeShard(TableSet tables, ShardManifest manifest, const std::filesystem::path& dir) {
  sortTables(tables);
  manifest.files = writeTables(tables, dir);
  writeShardManifest(manifest, dir);
}

namespace {

// The scenes' names, for a message: "a, b, c".
std::string listNames(const std::vector<ShardScene>& scenes) {
  std::string names;
  for (const auto& scene : scenes) names += (names.empty() ? "" : ", ") + scene.name;
  return names.empty() ? "none" : names;
}

}  // namespace

std::string findCampaignDifference(const ShardManifest& shard, const ShardManifest& first, const std::string& first_dir) {
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
  auto listSatOut = [](const std::vector<SatOut>& sat_out) {
    std::string s;
    for (const SatOut& e : sat_out) s += (s.empty() ? "" : ", ") + e.engine;
    return sat_out.empty() ? std::string("no engine") : s;
  };
  const auto sameSatOut = [](const SatOut& a, const SatOut& b) {
    return a.engine == b.engine && a.scene == b.scene && a.reason == b.reason;
  };
  if (!std::equal(shard.sat_out.begin(), shard.sat_out.end(), first.sat_out.begin(), first.sat_out.end(), sameSatOut))
    return listSatOut(shard.sat_out) + " sat out, in " + there + " " + listSatOut(first.sat_out);
  if (shard.tasks != first.tasks)
    return std::to_string(shard.tasks) + " tasks, " + there + " " + std::to_string(first.tasks) +
           ": a shard of another campaign";
  return "";
}

MergedShards mergeShards(const std::vector<std::string>& dirs) {
  // Every shard is checked before its tables are taken: one campaign, each shard once, all there, every data file as
  // its shard wrote it. A refusal is one line naming the shard or its file ("report merge: ...").
  auto refuse = [](const std::string& why) { return UsageError("report merge: " + why); };
  auto guarded = [&](const std::function<void()>& read) {
    try {
      read();
    } catch (const UsageError&) {
      throw;
    } catch (const EnvironmentError&) {
      throw;
    } catch (const std::runtime_error& e) {
      throw refuse(e.what());
    }
  };
  MergedShards merged;
  std::set<int> seen;
  std::vector<ShardManifest> manifests;
  for (const std::string& dir : dirs)
    guarded([&] {
      ShardManifest manifest = readShardManifest(dir);
      if (manifests.empty()) merged.first = manifest;
      const std::string difference = findCampaignDifference(manifest, merged.first, dirs[0]);
      if (!difference.empty()) throw refuse(quotePath(dir) + ": " + difference);
      if (!seen.insert(manifest.index).second)
        throw refuse(quotePath(dir) + ": shard " + std::to_string(manifest.index) + " given twice");
      manifests.push_back(std::move(manifest));
    });
  if (static_cast<int>(seen.size()) != merged.first.count) {
    std::string missing;
    for (int index = 0; index < merged.first.count; ++index)
      if (!seen.count(index)) missing += (missing.empty() ? "" : ", ") + std::to_string(index);
    throw refuse("shards: " + std::to_string(seen.size()) + " of " + std::to_string(merged.first.count) +
                 " given (missing: " + missing + "); all are needed");
  }
  // The tables are read with the engines the campaign ran: its schemas have a column per engine in play. What
  // shard.json says sat out must be one of the campaign's scenes, each engine once, and hold no row of the data.
  const std::string record = quotePath(std::filesystem::path(dirs[0]) / "shard.json") + ": sat_out: ";
  std::set<std::string> sat_engines;
  for (const SatOut& s : merged.first.sat_out) {
    if (!sat_engines.insert(s.engine).second) throw refuse(record + "engine " + quoteText(s.engine) + " twice");
    if (std::none_of(merged.first.scenes.begin(), merged.first.scenes.end(), [&](const ShardScene& c) { return c.name == s.scene; }))
      throw refuse(record + "scene " + quoteText(s.scene) + " is none of the campaign's scenes (" + listNames(merged.first.scenes) + ")");
  }
  try {
    merged.sat_out_scope = std::make_unique<SatOutScope>(merged.first.sat_out);
  } catch (const std::invalid_argument& e) {
    throw refuse(record + e.what());
  }
  for (size_t i = 0; i < dirs.size(); ++i)
    guarded([&] { appendTables(merged.tables, readShardTables(dirs[i], manifests[i])); });
  for (const auto& [name, table] : merged.tables) {
    const std::vector<std::string> columns = table.names();
    const auto engine = std::find(columns.begin(), columns.end(), "engine");
    if (engine == columns.end()) continue;
    const size_t column = static_cast<size_t>(engine - columns.begin());
    for (size_t row = 0; row < table.size(); ++row) {
      const Cell cell = table.cell(row, column);
      const auto* value = std::get_if<std::string>(&cell);
      if (value && sat_engines.count(*value))
        throw refuse(record + "names engine " + quoteText(*value) + ", but the shards' table " + name +
                     " holds its values: a record that does not match its data");
    }
  }
  return merged;
}

}  // namespace crankcheck::validation
