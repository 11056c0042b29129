#pragma once
/// @file
/// A campaign shared by the tests that read it (issue 28): under ctest a fixture test runs it once
/// (tests/cli/campaign_fixture.cmake: DIR/report, and its stdout, stderr and exit status in DIR/stdout.txt,
/// DIR/stderr.txt, DIR/status.txt) and the readers get DIR from an environment variable (tests/CMakeLists.txt sets
/// it with FIXTURES_REQUIRED, so that ctest runs the fixture first, also under -R). Run without that variable (the
/// test binary on its own), a reader runs the same campaign itself, in a fresh folder of its own.

#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "run_cli.h"

namespace crankcheck::testing {

/// One run of `crankcheck ARGS... --out FOLDER/report`: what it printed and its exit status, and where its report is.
struct CampaignRun {
  std::filesystem::path folder;  ///< the report's parent: the report, and what the fixture kept beside it
  std::filesystem::path report;  ///< folder / "report"
  validation::ProgramResult result;
  std::shared_ptr<FreshFolder> own;  ///< the folder when the reader ran the campaign itself (removed with it)
};

inline std::string readWholeFile(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The campaign of the fixture whose folder the environment variable `variable` names, or, without it, the same
/// campaign (`args`, the fixture's ARGS) run here.
inline CampaignRun getCampaign(const char* variable, const std::vector<std::string>& args) {
  CampaignRun run;
  if (const char* dir = std::getenv(variable); dir != nullptr && *dir != '\0') {
    run.folder = dir;
    run.report = run.folder / "report";
    run.result.out = readWholeFile(run.folder / "stdout.txt");
    run.result.err = readWholeFile(run.folder / "stderr.txt");
    std::ifstream status(run.folder / "status.txt");
    if (!(status >> run.result.exit_status)) run.result.exit_status = -1;  // no fixture run: the readers' checks fail
    return run;
  }
  run.own = std::make_shared<FreshFolder>();
  run.folder = run.own->path();
  run.report = run.folder / "report";
  std::vector<std::string> argv = args;
  argv.insert(argv.end(), {"--out", run.report.string()});
  run.result = runCrankcheck(argv);
  return run;
}

/// The default quick campaign, `crankcheck validate --quick` (every part of the report), run once for its readers:
/// QuickRunWritesEveryPartOfTheReport, QuickReportTest and the browser test (fixture quick_campaign).
inline CampaignRun getQuickCampaign() { return getCampaign("CRANKCHECK_QUICK_CAMPAIGN", {"validate", "--quick"}); }

/// One example scene's quick campaign on one thread, `crankcheck validate --quick SCENE --jobs 1` (every part and
/// table, one family's cross-check): the one run that shards are compared with, by ShardsMergeIntoTheSameReportAsOneRun
/// and tests/distributed/shards_test.sh (fixture one_scene_campaign, SCENE scenes/inline4_four_stroke.toml).
inline CampaignRun getOneSceneCampaign(const std::string& scene) {
  return getCampaign("CRANKCHECK_ONE_SCENE_CAMPAIGN", {"validate", "--quick", scene, "--jobs", "1"});
}

}  // namespace crankcheck::testing
