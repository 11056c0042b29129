// `crankcheck validate --profile FILE` (issue 28, "measure first"): one row per task and engine with its model
// builds, evaluations and seconds, and a "(rest)" row per task; the counts are held against the campaign's own
// definition (docs/validate.md: the quick gate sweep), the seconds against the identity engines + rest = task.
// A shard keeps it short: the same code path, a few tasks.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "run_cli.h"

namespace crankcheck {
namespace {
namespace fs = std::filesystem;

std::vector<std::vector<std::string>> readCsv(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> fields;
    std::stringstream s(line);
    for (std::string f; std::getline(s, f, ',');) fields.push_back(f);
    rows.push_back(fields);
  }
  return rows;
}

TEST(ProfileTest, CountsEachTasksEngineWorkAndItsTime) {
  testing::FreshFolder folder;
  const fs::path profile = folder.path() / "profile.csv";
  // Shard 1 of 6 of the quick campaign: tasks 1, 7, 13, ...; the gate sweep's 24 tasks (k = 12..1, both strokes)
  // follow each other, so at least four of them are here.
  const validation::ProgramResult r = testing::runCrankcheck(
      {"validate", "--quick", "--shard", "1/6", "--profile", profile.string(), "--out", (folder.path() / "s").string()});
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const auto rows = readCsv(profile);
  ASSERT_FALSE(rows.empty());
  EXPECT_EQ(rows[0], (std::vector<std::string>{"task", "engine", "builds", "evaluations", "seconds [s]", "task_seconds [s]"}));
  std::map<std::string, double> engine_seconds, task_seconds;
  std::set<std::string> with_rest;
  int sweeps = 0;
  for (size_t i = 1; i < rows.size(); ++i) {
    const auto& row = rows[i];
    ASSERT_EQ(row.size(), 6u) << i;
    const std::string& task = row[0];
    engine_seconds[task] += std::stod(row[4]);
    task_seconds[task] = std::stod(row[5]);
    if (row[1] == "(rest)") with_rest.insert(task);
    // The quick gate sweep of one k and stroke: lambda 0.3 and 0.999, gamma 90 and 37: 4 mechanisms, each model
    // built once (speed is a state) and evaluated at the gate's 11 angles at speed and at rest (campaign.cc).
    if (task.rfind("sweep k=", 0) == 0 && row[1] == "mujoco") {
      ++sweeps;
      EXPECT_EQ(row[2], "4") << task;
      EXPECT_EQ(row[3], "88") << task;
    }
  }
  EXPECT_GE(sweeps, 4);
  const size_t tasks = task_seconds.size();
  EXPECT_NE(r.out.find("(" + std::to_string(tasks) + " of "), std::string::npos) << "every task of the shard: " << r.out;
  EXPECT_EQ(with_rest.size(), tasks);
  // Engines + rest = the task: the CSV prints every number in its shortest round-trip form (exact), the rest is the
  // task's seconds less the engines' (one rounding), and the test adds the rows again in another order (one rounding
  // per row, at most six rows: five engines and the rest): within 8 eps of the task's seconds, its own scale; 16 eps
  // keeps a margin of two.
  for (const auto& [task, seconds] : task_seconds) {
    ASSERT_GT(seconds, 0.0) << task;
    EXPECT_NEAR(engine_seconds[task], seconds, 16 * std::numeric_limits<double>::epsilon() * seconds) << task;
  }
}

TEST(ProfileTest, NeverOverwritesAFile) {
  testing::FreshFolder folder;
  const fs::path profile = folder.path() / "mine.csv";
  std::ofstream(profile) << "my data\n";
  const validation::ProgramResult r = testing::runCrankcheck(
      {"validate", "--quick", "--profile", profile.string(), "--out", (folder.path() / "report").string()});
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_EQ(r.err, "crankcheck: --profile: \"" + profile.string() + "\": exists; crankcheck never overwrites a file\n");
  EXPECT_FALSE(fs::exists(folder.path() / "report"));
  std::ifstream in(profile);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "my data\n");
  // A link, dangling or not, is named as a link (a dangling one was said to "exist"): nothing is written through it.
  const fs::path dangling = folder.path() / "dangling.csv";
  fs::create_symlink(folder.path() / "nowhere" / "x.csv", dangling);
  const validation::ProgramResult link = testing::runCrankcheck(
      {"validate", "--quick", "--profile", dangling.string(), "--out", (folder.path() / "report").string()});
  EXPECT_EQ(link.exit_status, 2);
  EXPECT_EQ(link.err, "crankcheck: --profile: \"" + dangling.string() +
                          "\": is a symbolic link (to a file or not); crankcheck never writes through a link\n");
  EXPECT_FALSE(fs::exists(folder.path() / "nowhere"));
}

}  // namespace
}  // namespace crankcheck
