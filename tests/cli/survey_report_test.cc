// The textbook survey in a real report (part survey, validation/src/parts/survey.cc): its heading after the scene
// sections and before part 1, naming the first scene; the marks of the user's engine in a user campaign (the example
// scene scenes/inline4_four_stroke.toml given on the command line: the ctest fixture one_scene_campaign) and none in
// the default campaign (fixture quick_campaign); and every numbered part that computes at a speed or with a pressure
// table that no scene gave says so, read from its describe() on the campaign's own tables.

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "crankcheck/validation/parts.h"
#include "crankcheck/validation/report.h"
#include "campaign_fixture.h"

namespace crankcheck {
namespace {
namespace fs = std::filesystem;

// Every paragraph, caption and table cell of a described part, one after the other.
std::string collectText(const validation::ReportPart& part) {
  std::string text = part.caption + "\n";
  for (const std::string& p : part.paragraphs) text += p + "\n";
  for (const auto& row : part.rows)
    for (const std::string& cell : row) text += cell + "\n";
  for (const validation::ReportBlock& b : part.blocks) {
    text += b.text + "\n";
    for (const std::string& h : b.header) text += h + "\n";
    for (const auto& row : b.rows)
      for (const std::string& cell : row) text += cell + "\n";
  }
  return text;
}

TEST(SurveyReportTest, UserCampaignPlacesTheSurveyAndMarksYourEngine) {
  const std::string scene = std::string(CRANKCHECK_SCENES_DIR) + "/inline4_four_stroke.toml";
  const testing::CampaignRun run = testing::getOneSceneCampaign(scene);
  ASSERT_EQ(run.result.exit_status, 0) << run.result.err;
  const std::string index = testing::readWholeFile(run.report / "index.md");
  const size_t sections = index.find("\n## Your engine\n");
  const size_t survey = index.find("\n## The textbook survey on inline4_four_stroke's parts\n");
  const size_t first = index.find("\n## 1. " + validation::findPart("error_vs_lambda").title() + "\n");
  ASSERT_NE(sections, std::string::npos);
  ASSERT_NE(survey, std::string::npos);
  ASSERT_NE(first, std::string::npos);
  EXPECT_LT(sections, survey);
  EXPECT_LT(survey, first);
  EXPECT_NE(index.find("Your own engines, exactly as given, are in the sections above"), std::string::npos);
  // The marks: its lambda on the error-against-lambda figure, its k in the gravity table, its layout in the balance table.
  EXPECT_NE(index.find("mark your engines' lambda: inline4_four_stroke at lambda = "), std::string::npos);
  EXPECT_NE(index.find("your engine(s): inline4_four_stroke"), std::string::npos);
  EXPECT_NE(index.find("inline4_four_stroke (your engine)"), std::string::npos);

  // Every numbered part that computes at a speed or with a pressure table that no scene gave says so.
  const validation::TableSet tables = validation::readTables(run.report);
  const std::set<std::string> own_speed_only = {"error_vs_lambda", "speed_vs_error", "harmonics", "gravity_significance",
                                                "norton_fig13_8", "errata", "pin_load_polar", "engines",
                                                "stepped_engines"};
  const std::set<std::string> example_gas = {"torque_split", "offset", "flywheel"};
  for (const validation::Part* part : validation::listParts()) {
    if (part->always()) continue;
    SCOPED_TRACE(part->key());
    const validation::ReportPart described = part->describe(tables);
    ASSERT_FALSE(described.heading.empty()) << "the quick user campaign runs every part";
    const std::string text = collectText(described);
    if (!own_speed_only.count(part->key())) {
      EXPECT_NE(text.find("not your scene's speed"), std::string::npos) << text;
    }
    const bool names_example_gas = text.find("example spark-ignition") != std::string::npos ||
                                   text.find("example pressure") != std::string::npos;
    EXPECT_EQ(names_example_gas, example_gas.count(part->key()) > 0) << text;
    if (names_example_gas) {
      EXPECT_NE(text.find("not your scene's [gas]"), std::string::npos) << text;
    }
  }
}

TEST(SurveyReportTest, DefaultCampaignNamesTheBuiltInBaseAndMarksNothing) {
  const testing::CampaignRun run = testing::getQuickCampaign();
  ASSERT_EQ(run.result.exit_status, 0) << run.result.err;
  const std::string index = testing::readWholeFile(run.report / "index.md");
  const size_t survey = index.find("\n## The textbook survey on single_cylinder_four_gamma90's parts\n");
  ASSERT_NE(survey, std::string::npos);
  EXPECT_LT(index.find("\n## The example engines\n"), survey);
  EXPECT_LT(survey, index.find("\n## 1. "));
  EXPECT_NE(index.find("The example engines, each exactly as given, are in the sections above."), std::string::npos);
  for (const char* mark : {"your engines' lambda", "your engine(s)", "(your engine)"})
    EXPECT_EQ(index.find(mark), std::string::npos) << mark;
}

}  // namespace
}  // namespace crankcheck
