// The report's figures drawn by one gnuplot for several (drawFigures) against one gnuplot each (drawFigure), on the
// data of a real report: the one-scene quick campaign's (fixture one_scene_campaign, every part's tables).

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/report_document.h"
#include "campaign_fixture.h"
#include "fresh_folder.h"

namespace crankcheck {
namespace {
namespace fs = std::filesystem;

std::string readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// An SVG without the one attribute a gnuplot that drew another SVG before writes differently: the stroke of the empty
// group gnuplot opens for the background (`stroke="black"` after an earlier SVG, `stroke="currentColor"` in a fresh
// gnuplot), which draws nothing.
std::string withoutEmptyGroupStroke(std::string svg) {
  const std::string fresh = "<g fill=\"none\" color=\"#FFFFFF\" stroke=\"currentColor\"";
  const std::string after = "<g fill=\"none\" color=\"#FFFFFF\" stroke=\"black\"";
  for (size_t at; (at = svg.find(after)) != std::string::npos;) svg.replace(at, after.size(), fresh);
  return svg;
}

class FiguresTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // The scripts from the source tree, as the CLI finds them beside its own build (install_paths.h).
    ::setenv("CRANKCHECK_REPORTS_DIR", (fs::path(CRANKCHECK_SCENES_DIR).parent_path() / "reports").c_str(), 1);
    const testing::CampaignRun one =
        testing::getOneSceneCampaign(std::string(CRANKCHECK_SCENES_DIR) + "/inline4_four_stroke.toml");
    ASSERT_EQ(one.result.exit_status, 0) << one.result.err;
    for (const fs::directory_entry& e : fs::directory_iterator(one.report))
      if (e.path().extension() == ".png") figures_.push_back(e.path().stem().string());
    ASSERT_GE(figures_.size(), 16u) << "every part's figure";
    for (const char* name : {"each", "together"}) {
      fs::create_directories(folder_.path() / name);
      fs::copy(one.report / "data", folder_.path() / name / "data");
    }
  }
  fs::path at(const char* name) const { return folder_.path() / name; }

  testing::FreshFolder folder_;
  std::vector<std::string> figures_;
};

TEST_F(FiguresTest, OneGnuplotDrawsEveryFigureAsAGnuplotOfItsOwnDoes) {
  for (const std::string& name : figures_) validation::drawFigure(name, at("each"));
  // One gnuplot, not a fallback to one each: no script leaves a setting behind that breaks the next (`reset session`
  // keeps `set datafile columnheaders`).
  EXPECT_TRUE(validation::drawFigures(figures_, at("together")));
  for (const std::string& name : figures_) {
    SCOPED_TRACE(name);
    // PNG byte for byte: the same pixels, the same encoder.
    EXPECT_EQ(readBytes(at("together") / (name + ".png")), readBytes(at("each") / (name + ".png")));
    EXPECT_EQ(withoutEmptyGroupStroke(readBytes(at("together") / (name + ".svg"))),
              withoutEmptyGroupStroke(readBytes(at("each") / (name + ".svg"))));
  }
}

TEST_F(FiguresTest, AFailingScriptAmongSeveralIsNamed) {
  std::ofstream(at("together") / "data/torsion.csv", std::ios::trunc).close();  // empty: torsion.gp stops with status 1
  try {
    validation::drawFigures({"rod_models", "torsion", "engines"}, at("together"));
    FAIL() << "drawn without torsion's data";
  } catch (const EnvironmentError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("gnuplot failed on"), std::string::npos) << what;
    EXPECT_NE(what.find("torsion.gp"), std::string::npos) << what;
    EXPECT_EQ(what.find("rod_models.gp"), std::string::npos) << what;
  }
  EXPECT_TRUE(fs::exists(at("together") / "rod_models.png"));  // the figure before it, drawn again on its own
}

}  // namespace
}  // namespace crankcheck
