// `crankcheck validate` and `crankcheck report merge` as a user runs them: every part of the report, shards that
// merge into the same data as one run, refusals with exit status 2, and a good report never replaced by a failed run.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <unistd.h>

#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/parts.h"
#include "crankcheck/validation/scales.h"
#include "campaign_fixture.h"
#include "run_cli.h"
#include "train_report.h"
#include "../support/read_file.h"

namespace crankcheck {
namespace {
namespace fs = std::filesystem;

using testing::readFile;

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

// Every figure and table of a quick campaign: those of the parts (parts.h), and the campaign's own tables.
std::vector<std::string> listFigures() {
  std::vector<std::string> figures;
  for (const validation::Part* part : validation::listParts())
    for (const std::string& figure : part->figures()) figures.push_back(figure);
  return figures;
}
std::vector<std::string> listTables() {
  std::vector<std::string> tables = {"crosscheck", "scenes"};
  for (const validation::Part* part : validation::listParts())
    for (const std::string& table : part->tables()) tables.push_back(table);
  return tables;
}
// "Part N": the torsion part as the report's notes name it, its number from the registry.
std::string torsionPart() { return "Part " + std::to_string(validation::findPart("torsion").number()); }

// The default quick campaign, run once for its readers (campaign_fixture.h: under ctest the fixture quick_campaign,
// also read by QuickReportTest and the browser test): every check here reads its report and what it printed.
TEST_F(ValidateTest, QuickRunWritesEveryPartOfTheReport) {
  const testing::CampaignRun campaign = testing::getQuickCampaign();
  const fs::path report = campaign.report;
  const RunResult& r = campaign.result;
  ASSERT_EQ(r.exit_status, 0) << r.err << r.out;
  // The verdict first (verdict.h): a passing run ends with one line per engine and ctest's closing line, no table.
  EXPECT_NE(r.out.find("\n100% of comparisons agree, 0 failed out of "), std::string::npos) << r.out;
  EXPECT_LE(std::count(r.out.begin(), r.out.end(), '\n'), 15) << r.out;
  EXPECT_EQ(r.out.find("family of cases"), std::string::npos) << r.out;
  EXPECT_EQ(r.err, "");
  const std::string index = readFile(report / "index.md");
  for (const std::string& figure : listFigures()) {
    SCOPED_TRACE(figure);
    EXPECT_GT(fs::file_size(report / (std::string(figure) + ".svg")), 1000u);
    EXPECT_GT(fs::file_size(report / (std::string(figure) + ".png")), 1000u);
    EXPECT_NE(index.find(std::string("](") + figure + ".png)"), std::string::npos);
    EXPECT_NE(index.find(std::string("data/") + figure + ".csv"), std::string::npos);
  }
  for (const std::string& table : listTables()) EXPECT_TRUE(fs::exists(report / "data" / (std::string(table) + ".csv"))) << table;
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
  // balance_shafts: the Lanchester pair designed for the inline four takes its secondary force to rounding in every engine.
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
  // torsion: each gated engine's own elastic train against the analytic steady state (train_report.h).
  testing::expectGatedTrainsAgree(report);
  // Nothing but the report next to it (and the fixture's record of the run): no staging folder left behind.
  for (const auto& entry : fs::directory_iterator(campaign.folder))
    EXPECT_EQ(entry.path().filename().string().find("partial"), std::string::npos) << entry.path();
}

// Two shards merged give the same data as one run (timings excepted: they are measurements). The campaign of one
// example scene: every part and every table, the cross-check of one family (the default campaign's many families
// merge by the same rule, and take several times as long). The one run (on one thread) is the one the shard recipes'
// test compares with too (tests/distributed/shards_test.sh): under ctest the fixture one_scene_campaign, run once for
// both (campaign_fixture.h); the shards and the merge are this test's own.
TEST_F(ValidateTest, ShardsMergeIntoTheSameReportAsOneRun) {
  const std::string scene = std::string(CRANKCHECK_SCENES_DIR) + "/inline4_four_stroke.toml";
  const testing::CampaignRun one = testing::getOneSceneCampaign(scene);
  ASSERT_EQ(one.result.exit_status, 0) << one.result.err;
  const fs::path whole = one.report;
  const std::string campaign = "validate --quick " + scene + " ";
  const RunResult s0 = run(campaign + "--shard 0/2 --out " + (dir_ / "s0").string());
  const RunResult s1 = run(campaign + "--shard 1/2 --out " + (dir_ / "s1").string());
  ASSERT_EQ(s0.exit_status, 0) << s0.err;
  ASSERT_EQ(s1.exit_status, 0) << s1.err;
  EXPECT_TRUE(fs::exists(dir_ / "s0" / "shard.json"));
  const RunResult merged = run("report merge " + (dir_ / "s0").string() + " " + (dir_ / "s1").string() + " --out " +
                               (dir_ / "merged").string() + " --verbose");
  ASSERT_EQ(merged.exit_status, 0) << merged.err;
  // --verbose: the families' table in full before the verdict.
  EXPECT_NE(merged.out.find("Every family of cases:\n"), std::string::npos) << merged.out;
  EXPECT_NE(merged.out.find("merged from 2 shards\n"), std::string::npos) << merged.out;
  for (const std::string& table : listTables()) {
    const std::string name = table;
    if (name == "speed_vs_error" || name == "integrator_pareto" || name == "engine_cost" || name == "engines" ||
        name == "engines_league" || name == "torsion_cost" || name == "stepped_cost")
      continue;  // timings (the errors of the engines part come from crosscheck, compared here)
    EXPECT_EQ(readFile(dir_ / "merged/data" / (std::string(table) + ".csv")),
              readFile(whole / "data" / (std::string(table) + ".csv")))
        << table;
  }
  for (const std::string& figure : listFigures()) EXPECT_TRUE(fs::exists(dir_ / "merged" / (std::string(figure) + ".png")));
  const RunResult incomplete = run("report merge " + (dir_ / "s0").string() + " --out " + (dir_ / "m2").string());
  EXPECT_EQ(incomplete.exit_status, 2);
  EXPECT_NE(incomplete.err.find("1 of 2 given"), std::string::npos) << incomplete.err;
}

// Shards of one scene file, for the merge's refusals: a small campaign (the user's scene alone, --quick).
class MergeRefusalTest : public ValidateTest {
 protected:
  // Writes the example single cylinder to dir_/FOLDER/one.toml with its crank radius replaced by `radius` (empty:
  // as it is); returns the path.
  fs::path writeScene(const std::string& folder, const std::string& radius = "") {
    std::string text = readFile(fs::path(CRANKCHECK_SCENES_DIR) / "single_cylinder.toml");
    if (!radius.empty()) {
      const size_t at = text.find("radius = 0.043");
      EXPECT_NE(at, std::string::npos);
      text.replace(at, std::string("radius = 0.043").size(), "radius = " + radius);
    }
    fs::create_directories(dir_ / folder);
    std::ofstream(dir_ / folder / "one.toml") << text;
    return dir_ / folder / "one.toml";
  }
  // `crankcheck validate --quick --parts pin_load_polar,offset --shard I/N SCENE --out dir_/NAME` (two parts: enough
  // tables for each shard to hold some of its own); expects it to succeed.
  fs::path shard(const std::string& name, const std::string& part, const fs::path& scene) {
    const RunResult r = run("validate --quick --parts pin_load_polar,offset --jobs 2 --shard " + part + " " +
                            scene.string() + " --out " + (dir_ / name).string());
    EXPECT_EQ(r.exit_status, 0) << r.err << r.out;
    return dir_ / name;
  }
  // `crankcheck report merge SHARDS... --out dir_/merged`; expects a refusal: status 2, one line on stderr naming
  // `what`, nothing on stdout, no --out folder and nothing left beside it.
  void expectRefused(const std::vector<fs::path>& shards, const std::string& what) {
    std::string args = "report merge";
    for (const fs::path& s : shards) args.append(" ").append(s.string());
    const RunResult r = run(args + " --out " + (dir_ / "merged").string());
    EXPECT_EQ(r.exit_status, 2) << r.err << r.out;
    EXPECT_EQ(r.err.rfind("crankcheck: report merge: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(what), std::string::npos) << "expected " << what << " in: " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_FALSE(fs::exists(dir_ / "merged"));
    for (const auto& entry : fs::directory_iterator(dir_))
      EXPECT_EQ(entry.path().filename().string().find("partial"), std::string::npos) << entry.path();
  }
  // A data file of `shard` (data/NAME.csv) that the other shard does not have: its rows come from `shard` alone.
  // A table in `shard` alone; `unquoted`: one whose first row does not begin with a quoted field (a test that changes
  // that row's first character must not break the quoting instead). The folder's order is the file system's.
  std::string onlyIn(const fs::path& shard, const fs::path& other, bool unquoted = false) {
    for (const auto& entry : fs::directory_iterator(shard / "data")) {
      if (fs::exists(other / "data" / entry.path().filename())) continue;
      const std::string text = readFile(entry.path());
      const size_t row = text.find('\n') + 1;
      if (unquoted && row < text.size() && text[row] == '"') continue;
      return entry.path().filename().string();
    }
    ADD_FAILURE() << "every table of " << shard << " is also in " << other;
    return "";
  }
};

// (a) Two scene files of the same name but other content (another crank radius): not one campaign.
TEST_F(MergeRefusalTest, ShardsOfDifferentScenesOfTheSameNameAreRefused) {
  const fs::path s0 = shard("s0", "0/2", writeScene("a")), s1 = shard("s1", "1/2", writeScene("b", "0.05"));
  ASSERT_FALSE(HasFailure());
  expectRefused({s0, s1}, "\"" + s1.string() + "\": scene one: another scene than in \"" + s0.string() + "\"");
  // The same campaign with another N, or other options, is refused too; the same shard twice, or one missing.
  const fs::path other_n = shard("s1of3", "1/3", writeScene("a"));
  ASSERT_FALSE(HasFailure());
  expectRefused({s0, other_n}, "\"" + other_n.string() + "\": shard 1 of 3, not of 2 as \"" + s0.string() + "\"");
  expectRefused({s0, s0}, "\"" + s0.string() + "\": shard 0 given twice");
  expectRefused({s0}, "1 of 2 given (missing: 1)");
}

// (b) A shard that lacks a file its manifest lists: refused, naming the file, not merged without its rows.
TEST_F(MergeRefusalTest, ShardWithoutAFileItsManifestListsIsRefused) {
  const fs::path scene = writeScene("a");
  const fs::path s0 = shard("s0", "0/2", scene), s1 = shard("s1", "1/2", scene);
  ASSERT_FALSE(HasFailure());
  const std::string name = onlyIn(s1, s0);
  const fs::path file = s1 / "data" / name;
  const std::string good = readFile(file);
  fs::remove(file);
  expectRefused({s0, s1}, "\"" + file.string() + "\": missing");
  // A data file the manifest does not list (one more table) is refused too.
  std::ofstream(file) << good;
  std::ofstream(s1 / "data" / "extra.csv") << good;
  expectRefused({s0, s1}, "\"" + (s1 / "data" / "extra.csv").string() + "\": not listed");
}

// (c) A CSV replaced by other content: garbage with no rows, the same header with rows left out, the same rows
// changed: refused, naming the file (the merge would draw a figure from nothing, or from other data).
TEST_F(MergeRefusalTest, ShardWithAChangedDataFileIsRefused) {
  const fs::path scene = writeScene("a");
  const fs::path s0 = shard("s0", "0/2", scene), s1 = shard("s1", "1/2", scene);
  ASSERT_FALSE(HasFailure());
  const std::string name = onlyIn(s0, s1, true);
  const fs::path file = s0 / "data" / name;
  const std::string good = readFile(file);
  const std::string header = good.substr(0, good.find('\n') + 1);
  const size_t rows = static_cast<size_t>(std::count(good.begin(), good.end(), '\n')) - 1;
  ASSERT_GE(rows, 1u) << good;
  auto replace = [&](const std::string& text) {
    fs::remove(file);
    std::ofstream(file) << text;
  };
  replace("garbage\n");
  expectRefused({s0, s1}, "\"" + file.string() + "\": header");
  replace(header);
  expectRefused({s0, s1}, "\"" + file.string() + "\": 0 rows, the shard wrote " + std::to_string(rows));
  std::string changed = good;
  changed[header.size()] = changed[header.size()] == '9' ? '8' : '9';
  replace(changed);
  expectRefused({s0, s1}, "\"" + file.string() + "\": not the content the shard wrote");
  replace(good);  // as written: merged, but never into one of the shards
  const RunResult into_shard = run("report merge " + s0.string() + " " + s1.string() + " --out " + s1.string());
  EXPECT_EQ(into_shard.exit_status, 2);
  EXPECT_NE(into_shard.err.find("--out: \"" + s1.string() + "\": is a shard being merged"), std::string::npos)
      << into_shard.err;
  EXPECT_TRUE(fs::exists(s1 / "shard.json"));
  const RunResult r = run("report merge " + s0.string() + " " + s1.string() + " --out " + (dir_ / "merged").string());
  EXPECT_EQ(r.exit_status, 0) << r.err;
}

// A run that fails (here: the figure scripts cannot be found) leaves the previous good report exactly as it was.
// One scene and one part with a figure: the rule is the output folder's, whatever the campaign.
TEST_F(ValidateTest, FailedRunNeverReplacesAGoodReport) {
  const fs::path report = dir_ / "report";
  const std::string campaign =
      "validate --quick " + std::string(CRANKCHECK_SCENES_DIR) + "/single_cylinder.toml --parts pin_load_polar --out ";
  ASSERT_EQ(run(campaign + report.string()).exit_status, 0);
  const std::string before = readFile(report / "index.md");
  // A folder without the figures' scripts: the run fails when it draws them, after the campaign. (A variable naming
  // no folder at all is refused before any work: Cli.DataFolderVariablesThatNameNoFolderAreRefused.)
  fs::create_directories(dir_ / "no_scripts");
  const RunResult failed = run(campaign + report.string(), {"CRANKCHECK_REPORTS_DIR=" + (dir_ / "no_scripts").string()});
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

// A scene Simbody builds whose lambda variants it does not all build: the inline four with its pressures scaled to a
// 1e9 Pa peak (the format's largest), where the gas force is 8e5 times the piston's mass times r omega^2 + g at
// Simbody's probe and its loops' residual passes at the scene's lambda but not at 0.01, 0.0249, 0.0618 and 0.95. The
// campaign stopped ("could not run", status 1); now part error_vs_lambda leaves Simbody out at those lambdas and the
// notes say so, the rest of the campaign stands.
TEST_F(ValidateTest, AnEngineThatCannotBuildALambdaVariantIsLeftOutThere) {
  std::ifstream in(fs::path(CRANKCHECK_SCENES_DIR) / "inline4_four_stroke.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string scene = text.str();
  const std::string from = "pressure_pa = [";
  const size_t begin = scene.find(from) + from.size(), end = scene.find(']', begin);
  std::stringstream values(scene.substr(begin, end - begin));
  std::string scaled, item;
  while (std::getline(values, item, ',')) {
    const double p = std::max(-101325.0, std::stod(item) * (1e9 / 5.6e6));
    char number[32];
    std::snprintf(number, sizeof number, "%.9g", p);
    scaled += (scaled.empty() ? "" : ", ") + std::string(number);
  }
  scene.replace(begin, end - begin, scaled);
  const fs::path path = dir_ / "high_gas.toml";
  std::ofstream(path) << scene;
  const RunResult r = run("validate " + path.string() + " --quick --parts error_vs_lambda --out " + (dir_ / "r").string());
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const std::string index = readFile(dir_ / "r" / "index.md");
  EXPECT_NE(index.find("(error_vs_lambda): simbody is left out at lambda = 0.01, where it cannot build the scene: "
                       "cannot hold its accuracy on this scene"), std::string::npos) << index;
  const std::string data = readFile(dir_ / "r" / "data" / "error_vs_lambda.csv");
  EXPECT_NE(data.find("analytic_vs_mujoco"), std::string::npos);
  EXPECT_NE(data.find("analytic_vs_simbody"), std::string::npos);  // at the lambdas where it builds the scene
}

// --shard 0/1 (a job array of one) writes a shard, which merges as any other: it wrote a report, which report merge
// then called "not a shard".
TEST_F(ValidateTest, AShardOfOneMerges) {
  const std::string scene = std::string(CRANKCHECK_SCENES_DIR) + "/single_cylinder.toml";
  const fs::path shard = dir_ / "shard", merged = dir_ / "merged";
  const RunResult r = run("validate " + scene + " --quick --parts pin_load_polar --shard 0/1 --out " + shard.string());
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_TRUE(fs::is_regular_file(shard / "shard.json"));
  EXPECT_FALSE(fs::exists(shard / "index.md"));
  const RunResult m = run("report merge " + shard.string() + " --out " + merged.string());
  EXPECT_EQ(m.exit_status, 0) << m.err;
  EXPECT_TRUE(fs::is_regular_file(merged / "index.md"));
}

// A damaged or hand-edited shard.json says where it is wrong, by the key's path, not by the JSON library's message
// ("[json.exception.type_error.304] cannot use at() with array"); status 2, nothing written.
TEST_F(ValidateTest, AMalformedShardRecordIsNamedByItsKey) {
  const std::string good = R"({"crankcheck_shard": 4, "version": "0", "index": 0, "count": 2, "quick": true,
      "scenes": [{"name": "a", "fnv1a64": "0"}], "tasks": 1, "parts": [], "sat_out": [], "files": []})";
  const std::vector<std::pair<std::string, std::string>> cases{
      {"[1, 2]", "malformed: the record: must be an object (got array)"},
      {"{\"crankcheck_shard\": 4,", "malformed: not JSON (parse error at line 1, column"},
      {std::string(good).replace(good.find("\"index\": 0"), 10, "\"index\": \"0\""),
       "malformed: index: must be a whole number from 0 to 2^40 (got string)"},
      {std::string(good).replace(good.find("\"name\": \"a\", "), 13, ""), "malformed: scenes[0].name: missing"},
      {std::string(good).replace(good.find("\"sat_out\": []"), 13, "\"sat_out\": {}"),
       "malformed: sat_out: must be a list (got object)"},
      {std::string(good).replace(good.find("\"quick\": true"), 13, "\"quick\": 1"),
       "malformed: quick: must be true or false (got number)"}};
  for (size_t i = 0; i < cases.size(); ++i) {
    const auto& [text, expected] = cases[i];
    const fs::path shard = dir_ / ("shard_" + std::to_string(i));  // a folder of its own: nothing is deleted
    fs::create_directories(shard);
    std::ofstream(shard / "shard.json") << text;
    const RunResult r = run("report merge " + shard.string() + " --out " + (dir_ / "x").string());
    EXPECT_EQ(r.exit_status, 2) << text << ": " << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << text << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "x"));
  }
}

// --parts runs those parts alone, with every cross-check: their tables, figures and headings and no other part's; the
// report says so. An unknown or repeated key is refused before any work.
// Three scenes of a user (issue 49): the verdict with one line per scene under it, still within 15 lines; each scene's
// section in the report, after the verdict and before the survey, with a line for each table the scene lacks.
TEST_F(ValidateTest, ThreeUserScenesGetTheirSectionsAndAVerdictOf15Lines) {
  std::string scenes;
  for (const char* stem : {"v8_cross_plane", "inline4_pin_offset", "inline3_lying_two_stroke"})
    scenes += std::string(CRANKCHECK_SCENES_DIR) + "/" + stem + ".toml ";
  const fs::path report = dir_ / "report";
  const RunResult r = run("validate --quick " + scenes + "--parts offset --out " + report.string());
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_LE(std::count(r.out.begin(), r.out.end(), '\n'), 15) << r.out;
  for (const char* stem : {"v8_cross_plane", "inline4_pin_offset", "inline3_lying_two_stroke"})
    EXPECT_NE(r.out.find(std::string("\n  ") + stem + ": Norton's a_p "), std::string::npos) << r.out;
  const std::string index = readFile(report / "index.md");
  const size_t verdict = index.find("## Verdict"), survey = index.find("## The textbook survey on v8_cross_plane's parts");
  for (const char* stem : {"v8_cross_plane", "inline4_pin_offset", "inline3_lying_two_stroke"}) {
    const size_t section = index.find(std::string("### ") + stem + ": your engine");
    EXPECT_TRUE(section != std::string::npos && verdict < section && section < survey) << stem;
  }
  // None of the three has a [crankshaft]; the lying inline three has no [gas] either: one line each, never a gap.
  auto count = [&index](const std::string& text) {
    size_t n = 0;
    for (size_t at = index.find(text); at != std::string::npos; at = index.find(text, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("No [crankshaft] table: add one"), 3u);
  EXPECT_EQ(count("No [gas] table:"), 1u);
}

// The marine example as the one scene: the balance-shaft part designs shafts of tens of tonnes on its parts, which
// Simbody refused to build (a point mass's central inertia came out at -1 ulp; simbody_models/src/model_support.h).
TEST_F(ValidateTest, TheMarineSceneValidatesAlone) {
  const std::string scene = std::string(CRANKCHECK_SCENES_DIR) + "/inline6_two_stroke_marine.toml";
  const RunResult r = run("validate --quick " + scene + " --parts balance_shafts --out " + (dir_ / "report").string());
  EXPECT_EQ(r.exit_status, 0) << r.err << r.out;
  EXPECT_EQ(r.err, "");
}

TEST_F(ValidateTest, PartsRunsOnlyThoseParts) {
  const std::string scene = std::string(CRANKCHECK_SCENES_DIR) + "/single_cylinder.toml";
  const fs::path report = dir_ / "report";
  const RunResult r = run("validate --quick " + scene + " --parts pin_load_polar,offset --out " + report.string());
  ASSERT_EQ(r.exit_status, 0) << r.err;
  std::set<std::string> written;
  for (const auto& entry : fs::directory_iterator(report / "data")) written.insert(entry.path().stem().string());
  std::set<std::string> expected = {"crosscheck", "scenes", "notes"};
  for (const validation::Part* part : validation::listParts())
    if (part->key() == "pin_load_polar" || part->key() == "offset" || part->always())
      for (const std::string& table : part->tables()) expected.insert(table);
  EXPECT_EQ(written, expected);
  EXPECT_TRUE(fs::exists(report / "pin_load_polar.png"));
  EXPECT_TRUE(fs::exists(report / "offset.png"));
  EXPECT_FALSE(fs::exists(report / "harmonics.png"));
  const std::string index = readFile(report / "index.md");
  EXPECT_NE(index.find("Only the report parts pin_load_polar, offset were run"), std::string::npos);
  for (const validation::Part* part : validation::listParts())
    EXPECT_EQ(index.find("## " + part->heading()) != std::string::npos,
              part->always() || part->key() == "pin_load_polar" || part->key() == "offset")
        << part->heading();
  for (const std::string& bad : {"nonsense", "offset,offset"}) {
    const RunResult refused = run("validate --quick " + scene + " --parts " + bad + " --out " + (dir_ / "x").string());
    EXPECT_EQ(refused.exit_status, 2) << refused.err;
    EXPECT_EQ(refused.err.rfind("crankcheck: --parts: ", 0), 0u) << refused.err;
    EXPECT_EQ(std::count(refused.err.begin(), refused.err.end(), '\n'), 1) << refused.err;
    EXPECT_EQ(refused.out, "");
    EXPECT_FALSE(fs::exists(dir_ / "x"));
  }
  // Shards of campaigns with other parts are not one campaign.
  const fs::path s0 = dir_ / "s0", s1 = dir_ / "s1";
  ASSERT_EQ(run("validate --quick " + scene + " --parts norton_fig13_8 --shard 0/2 --out " + s0.string()).exit_status, 0);
  ASSERT_EQ(run("validate --quick " + scene + " --parts offset --shard 1/2 --out " + s1.string()).exit_status, 0);
  const RunResult merge = run("report merge " + s0.string() + " " + s1.string() + " --out " + (dir_ / "m").string());
  EXPECT_EQ(merge.exit_status, 2) << merge.err;
  EXPECT_NE(merge.err.find("--parts offset, \"" + s0.string() + "\" --parts norton_fig13_8"), std::string::npos)
      << merge.err;
  EXPECT_FALSE(fs::exists(dir_ / "m"));
}

// Issue 46: a part with nothing to show for the scenes given is never left out without a word: `--parts torsion` on a
// scene without [crankshaft] exited 0 with no torsion section and no reason (a full run dropped the torsion part the same way).
TEST_F(ValidateTest, APartLeftOutForItsScenesSaysWhy) {
  const std::string scene = std::string(CRANKCHECK_SCENES_DIR) + "/single_cylinder.toml";
  const fs::path report = dir_ / "report";
  const RunResult r = run("validate --quick " + scene + " --parts torsion --out " + report.string());
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const std::string index = readFile(report / "index.md");
  EXPECT_NE(index.find(torsionPart() + " (torsion) is left out: no scene (single_cylinder) has a [crankshaft] table"),
            std::string::npos)
      << index;
  EXPECT_FALSE(fs::exists(report / "data" / "torsion.csv"));
}

// A scene inside the small-twist domain up front (its mean torque) but beyond it at the torsion part's sweep speeds (every
// section at 3000 N m/rad, the example four: 0.11 rad at 3000 and 6000 rpm) ended the whole campaign ("could not run",
// status 1, no report). Now the refused routes are named in the notes and the torsion part is left out, saying so; the report
// is written.
TEST_F(ValidateTest, APartWhoseRoutesAreRefusedIsLeftOutWithItsReasons) {
  std::string text = readFile(fs::path(CRANKCHECK_SCENES_DIR) / "inline4_four_stroke.toml");
  const size_t at = text.find("stiffness = [");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, text.find(']', at) + 1 - at, "stiffness = [3000, 3000, 3000, 3000, 3000]");
  const fs::path scene = dir_ / "soft.toml";
  std::ofstream(scene) << text;
  const fs::path report = dir_ / "report";
  const RunResult r = run("validate --quick --parts torsion " + scene.string() + " --out " + report.string());
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const std::string index = readFile(report / "index.md");
  EXPECT_NE(index.find(torsionPart() + " (torsion): soft at 3000 rpm not computed: torsion: at 3e+03 rpm Holzer's linear "
                       "response twists section 1 by"),
            std::string::npos)
      << index;
  EXPECT_NE(index.find(torsionPart() + " (torsion) is left out"), std::string::npos);
  EXPECT_FALSE(fs::exists(report / "torsion.png"));
  EXPECT_FALSE(fs::exists(report / "data" / "torsion.csv"));
}

TEST_F(ValidateTest, SceneFilesAreTheirOwnFamilies) {
  const std::string scenes = CRANKCHECK_SCENES_DIR;
  // One part beside the cross-checks: the families are the cross-checks' (and the scenes table's).
  const RunResult r = run("validate --quick --parts pin_load_polar " + scenes + "/single_cylinder.toml " + scenes +
                          "/compressor2_explicit_angles.toml --out " + (dir_ / "report").string());
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_NE(r.out.find("compressor2_explicit_angles"), std::string::npos) << r.out;
  EXPECT_NE(readFile(dir_ / "report/data/scenes.csv").find("single_cylinder"), std::string::npos);
}

}  // namespace
}  // namespace crankcheck
