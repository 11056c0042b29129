// `crankcheck validate` and `crankcheck report merge` as a user runs them: every part of the report, shards that
// merge into the same data as one run, refusals with exit status 2, and a good report never replaced by a failed run.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

#include "crankcheck/validation/scales.h"
#include "run_cli.h"

namespace crankcheck {
namespace {
namespace fs = std::filesystem;

std::string readFile(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

using RunResult = validation::ProgramResult;

class ValidateTest : public ::testing::Test {
 protected:

  // Runs the CLI with the arguments of `args` (split at spaces; no argument here holds one), without a shell.
  RunResult run(const std::string& args, const std::vector<std::string>& env = {}) {
    std::vector<std::string> argv;
    std::stringstream words(args);
    for (std::string word; words >> word;) argv.push_back(word);
    return testing::runCrankcheck(argv, env);
  }

  testing::FreshFolder folder_;
  const fs::path dir_ = folder_.path();
};

const char* kFigures[] = {"error_vs_lambda", "speed_vs_error", "harmonics", "gravity_significance", "norton_fig13_8", "engines", "offset", "flywheel",
                          "balance_shafts", "delta_vs_k", "integrator_pareto", "balance_harmonics", "torque_split", "rod_models",
                          "pin_load_polar"};
const char* kTables[] = {"crosscheck", "error_vs_lambda", "speed_vs_error", "harmonics", "gravity_significance",
                         "norton_fig13_8", "errata", "scenes", "delta_vs_k", "integrator_pareto", "balance",
                         "balance_harmonics", "torque_split", "gravity_share", "rod_models", "eq5_layouts",
                         "eq15_coefficients", "eq15_engines", "pin_load_polar", "pin_load_polar_summary", "engine_cost",
                         "engines", "engines_league", "offset", "offset_thrust", "flywheel", "flywheel_sizing",
                         "flywheel_norton", "balance_shafts"};

TEST_F(ValidateTest, QuickRunWritesEveryPartOfTheReport) {
  const fs::path report = dir_ / "report";
  const RunResult r = run("validate --quick --out " + report.string());
  ASSERT_EQ(r.exit_status, 0) << r.err << r.out;
  // The verdict first (verdict.h): a passing run ends with one line per engine and ctest's closing line, no table.
  EXPECT_NE(r.out.find("\n100% of comparisons agree, 0 failed out of "), std::string::npos) << r.out;
  EXPECT_LE(std::count(r.out.begin(), r.out.end(), '\n'), 15) << r.out;
  EXPECT_EQ(r.out.find("family of cases"), std::string::npos) << r.out;
  EXPECT_EQ(r.err, "");
  const std::string index = readFile(report / "index.md");
  for (const char* figure : kFigures) {
    SCOPED_TRACE(figure);
    EXPECT_GT(fs::file_size(report / (std::string(figure) + ".svg")), 1000u);
    EXPECT_GT(fs::file_size(report / (std::string(figure) + ".png")), 1000u);
    EXPECT_NE(index.find(std::string("](") + figure + ".png)"), std::string::npos);
    EXPECT_NE(index.find(std::string("data/") + figure + ".csv"), std::string::npos);
  }
  for (const char* table : kTables) EXPECT_TRUE(fs::exists(report / "data" / (std::string(table) + ".csv"))) << table;
  EXPECT_NE(index.find("Errata"), std::string::npos);
  EXPECT_NE(index.find("Simbody 3.7"), std::string::npos);
  EXPECT_NE(readFile(report / "index.html").find("<img src=\"harmonics.png\""), std::string::npos);
  // Every header names its unit (text columns stay bare).
  EXPECT_EQ(readFile(report / "data/error_vs_lambda.csv")
                .rfind("quantity,method,lambda [-],max_abs_error [SI],max_rel_error [-],resolved\n", 0), 0u);
  const std::string speed = readFile(report / "data/speed_vs_error.csv");
  EXPECT_EQ(speed.rfind("method,ns_per_eval [ns],max_rel_error [-],resolved\n", 0), 0u);
  EXPECT_GE(std::count(speed.begin(), speed.end(), '\n'), 6) << "every method timed:\n" << speed;
  EXPECT_NE(speed.find("simbody_tol_1e-12,"), std::string::npos) << speed;
  // Part 16: the Lanchester pair designed for the inline four takes its secondary force to rounding in every engine.
  // 64 eps of the force scale: the gate's multiple for a force (docs/CONVENTIONS-crankcheck.md); the secondary force
  // without the pair is about lambda / 4 of the primary, itself about 1/8 of the scale (0.02 at the base scene's lambda).
  const std::string shafts = readFile(report / "data/balance_shafts.csv");
  std::stringstream lines(shafts);
  int checked = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("inline four: Lanchester pair for n = 2,", 0) != 0) continue;
    std::vector<std::string> f;
    std::stringstream fields(line);
    for (std::string x; std::getline(fields, x, ',');) f.push_back(x);
    ASSERT_EQ(f.size(), 6u) << line;  // case,shafts,engine,n,force_amplitude,force_relative
    if (f[3] != "2") continue;
    const double rel = std::stod(f[5]);
    if (f[1] == "none") {
      EXPECT_GT(rel, 1e-3) << line;
    } else {
      EXPECT_LT(rel, validation::kAgreementMultiple * validation::kEps) << line;
    }
    ++checked;
  }
  EXPECT_EQ(checked, 6) << "analytic, simbody and mujoco, without and with the pair:\n" << shafts;
  // Nothing but the report next to it: no staging folder left behind.
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_EQ(entry.path().filename().string().find("partial"), std::string::npos) << entry.path();
}

// Two shards merged give the same data as one run (timings excepted: they are measurements).
TEST_F(ValidateTest, ShardsMergeIntoTheSameReportAsOneRun) {
  ASSERT_EQ(run("validate --quick --jobs 1 --out " + (dir_ / "whole").string()).exit_status, 0);
  const RunResult s0 = run("validate --quick --shard 0/2 --out " + (dir_ / "s0").string());
  const RunResult s1 = run("validate --quick --shard 1/2 --out " + (dir_ / "s1").string());
  ASSERT_EQ(s0.exit_status, 0) << s0.err;
  ASSERT_EQ(s1.exit_status, 0) << s1.err;
  EXPECT_TRUE(fs::exists(dir_ / "s0" / "shard.json"));
  const RunResult merged = run("report merge " + (dir_ / "s0").string() + " " + (dir_ / "s1").string() + " --out " +
                               (dir_ / "merged").string() + " --verbose");
  ASSERT_EQ(merged.exit_status, 0) << merged.err;
  // --verbose: the families' table in full before the verdict.
  EXPECT_NE(merged.out.find("Every family of cases:\n"), std::string::npos) << merged.out;
  EXPECT_NE(merged.out.find("merged from 2 shards\n"), std::string::npos) << merged.out;
  for (const char* table : kTables) {
    const std::string name = table;
    if (name == "speed_vs_error" || name == "integrator_pareto" || name == "engine_cost" || name == "engines" ||
        name == "engines_league")
      continue;  // timings (the errors of part 13 come from crosscheck, compared here)
    EXPECT_EQ(readFile(dir_ / "merged/data" / (std::string(table) + ".csv")),
              readFile(dir_ / "whole/data" / (std::string(table) + ".csv")))
        << table;
  }
  for (const char* figure : kFigures) EXPECT_TRUE(fs::exists(dir_ / "merged" / (std::string(figure) + ".png")));
  const RunResult incomplete = run("report merge " + (dir_ / "s0").string() + " --out " + (dir_ / "m2").string());
  EXPECT_EQ(incomplete.exit_status, 2);
  EXPECT_NE(incomplete.err.find("1 of 2 given"), std::string::npos) << incomplete.err;
}

// A run that fails (here: the figure scripts cannot be found) leaves the previous good report exactly as it was.
TEST_F(ValidateTest, FailedRunNeverReplacesAGoodReport) {
  const fs::path report = dir_ / "report";
  ASSERT_EQ(run("validate --quick --out " + report.string()).exit_status, 0);
  const std::string before = readFile(report / "index.md");
  const RunResult failed = run("validate --quick --out " + report.string(), {"CRANKCHECK_REPORTS_DIR=/nonexistent"});
  EXPECT_EQ(failed.exit_status, 3) << "a missing tool is the environment's failure";
  EXPECT_NE(failed.err.find("gnuplot script not found"), std::string::npos) << failed.err;
  EXPECT_EQ(readFile(report / "index.md"), before);
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_EQ(entry.path().filename().string().find("partial"), std::string::npos) << entry.path();
}

TEST_F(ValidateTest, BadInputIsRefusedWithStatus2) {
  const RunResult bad_out = run("validate --quick --out /proc/crankcheck/report");
  EXPECT_EQ(bad_out.exit_status, 3) << "a folder that cannot be created: a write refused";
  EXPECT_NE(bad_out.err.find("--out: \"/proc/crankcheck\": cannot create the folder"), std::string::npos) << bad_out.err;
  EXPECT_EQ(bad_out.out, "");
  const RunResult bad_shard = run("validate --quick --shard 2/2 --out " + (dir_ / "x").string());
  EXPECT_EQ(bad_shard.exit_status, 2);
  EXPECT_NE(bad_shard.err.find("--shard: 2/2"), std::string::npos) << bad_shard.err;
  const RunResult bad_scene = run("validate " + (dir_ / "missing.toml").string() + " --out " + (dir_ / "x").string());
  EXPECT_EQ(bad_scene.exit_status, 2);
  EXPECT_NE(bad_scene.err.find("missing.toml: file"), std::string::npos) << bad_scene.err;
  EXPECT_FALSE(fs::exists(dir_ / "x"));
  const RunResult not_a_shard = run("report merge " + dir_.string() + " --out " + (dir_ / "x").string());
  EXPECT_EQ(not_a_shard.exit_status, 2);
  EXPECT_NE(not_a_shard.err.find("shard.json"), std::string::npos) << not_a_shard.err;
}

TEST_F(ValidateTest, SceneFilesAreTheirOwnFamilies) {
  const std::string scenes = CRANKCHECK_SCENES_DIR;
  const RunResult r = run("validate --quick " + scenes + "/single_cylinder.toml " + scenes +
                          "/compressor2_explicit_angles.toml --out " + (dir_ / "report").string());
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_NE(r.out.find("compressor2_explicit_angles"), std::string::npos) << r.out;
  EXPECT_NE(readFile(dir_ / "report/data/scenes.csv").find("single_cylinder"), std::string::npos);
}

}  // namespace
}  // namespace crankcheck
