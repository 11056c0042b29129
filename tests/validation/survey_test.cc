// The textbook survey (part survey, validation/src/parts/survey.cc): its place in the registry, its heading naming the
// first scene, its table read back through its schema, and the marks of the user's engines in the survey's parts
// (error_vs_lambda's caption, gravity_significance's column, balance's rows), present for scenes the user gave and
// absent in the default campaign (its scenes are "example"), and the captions of parts that compute at a speed or with
// a pressure table no scene gave. Every expected string is written out by hand from the rows below.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "crankcheck/validation/csv.h"
#include "crankcheck/validation/table_schemas.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/parts.h"
#include "part_fixture.h"

namespace crankcheck::validation {
namespace {

using testing::findParagraph;
using testing::readTable;

// data/your_engine.csv with one scene, `given` "user" or "example" (its schema: your_engine/topic.h).
Table makeFacts(const std::string& scene, const std::string& given, int k, const std::string& cycle, double lambda) {
  return readTable("your_engine",
                   "scene_index [-],scene,given,layout,cylinders [-],cycle,acting,speed_rpm [rpm],lambda [-],gas [-],"
                   "flywheel [-],crankshaft [-],balance_shafts [-],pin_offsets [-],max_pin_offset [m]\n"
                   "0," + scene + "," + given + ",inline," + std::to_string(k) + "," + cycle + ",single,2500," +
                       std::to_string(lambda) + ",1,1,0,0,0,0\n");
}

// data/survey_base.csv, one row.
Table makeBase(const std::string& row) {
  return readTable("survey_base", "scene,given,k [-],cycle,lambda [-],speed_rpm [rpm],single_bank [-],centric [-]\n" + row + "\n");
}

// "ENGINE" + suffix for every reference engine of the registry, each preceded by a comma.
std::string engineColumns(const std::vector<std::string>& suffixes) {
  std::string s;
  for (const Engine* e : listReferenceEngines())
    for (const std::string& suffix : suffixes) s += "," + e->name + suffix;
  return s;
}

const ReportBlock* findTable(const ReportPart& part, const std::string& first_column) {
  for (const ReportBlock& b : part.blocks)
    if (b.kind == ReportBlock::kTable && !b.header.empty() && b.header[0] == first_column) return &b;
  return nullptr;
}

TEST(SurveyTest, ComesAfterTheSceneSectionsAndTheScenesAndBeforePartOne) {
  const std::vector<const Part*>& parts = listParts();
  auto at = [&](const std::string& key) {
    return std::find(parts.begin(), parts.end(), &findPart(key)) - parts.begin();
  };
  const Part& survey = findPart("survey");
  EXPECT_TRUE(survey.always());
  EXPECT_EQ(survey.number(), 0);
  EXPECT_LT(at("your_engine"), at("survey"));
  EXPECT_EQ(at("scenes") + 1, at("survey"));
  ASSERT_LT(at("survey") + 1, static_cast<long>(parts.size()));
  EXPECT_EQ(parts[at("survey") + 1]->number(), 1);
  EXPECT_EQ(survey.tables(), std::vector<std::string>{"survey_base"});
  EXPECT_TRUE(survey.figures().empty());
}

TEST(SurveyTest, HeadingNamesTheFirstSceneAndHowTheSurveyUsesIt) {
  const Part& part = findPart("survey");
  // A V8 the user gave first: the survey uses its parts as a standing inline eight, centric.
  const ReportPart v8 = part.describe({{"survey_base", makeBase("my_v8,user,8,four-stroke,0.3,5000,0,1")},
                                       {"your_engine", makeFacts("my_v8", "user", 8, "four-stroke", 0.3)}});
  EXPECT_EQ(v8.heading, "The textbook survey on my_v8's parts");
  const std::string text = findParagraph(v8, "What follows is the textbook survey");
  EXPECT_NE(text.find("the crank, rod and piston of my_v8, the first scene you gave (as a standing inline 8-cylinder "
                      "four-stroke engine, as the paper's figures need;"), std::string::npos) << text;
  EXPECT_NE(text.find("(lambda = 0.3, 5000 rpm)"), std::string::npos) << text;
  EXPECT_NE(text.find("its caption says so"), std::string::npos) << text;
  EXPECT_NE(text.find("Your own engines, exactly as given, are in the sections above"), std::string::npos) << text;
  // The default campaign: a built-in single cylinder as given, the example engines above.
  const ReportPart built_in =
      part.describe({{"survey_base", makeBase("single_cylinder_four_gamma90,built-in,1,four-stroke,0.2966,3000,1,1")},
                     {"your_engine", makeFacts("single_cylinder", "example", 1, "four-stroke", 0.3)}});
  EXPECT_EQ(built_in.heading, "The textbook survey on single_cylinder_four_gamma90's parts");
  const std::string plain = findParagraph(built_in, "What follows is the textbook survey");
  EXPECT_NE(plain.find("of single_cylinder_four_gamma90, the default campaign's first scene (lambda = 0.2966, 3000 rpm)"),
            std::string::npos) << plain;
  EXPECT_NE(plain.find("The example engines, each exactly as given, are in the sections above."), std::string::npos);
  EXPECT_TRUE(part.describe({}).heading.empty());
}

TEST(SurveyTest, BaseTableReadsBackThroughItsSchema) {
  const Table base = makeBase("my_v8,user,8,four-stroke,0.3,5000,0,1");
  const Table again = parseTable("survey_base", parseCsv(formatCsv(base), "survey_base"), "survey_base", findTableSchema("survey_base"));
  EXPECT_EQ(formatCsv(again), formatCsv(base));
  EXPECT_EQ(formatCsv(base).substr(0, formatCsv(base).find('\n')),
            "scene,given,k [-],cycle,lambda [-],speed_rpm [rpm],single_bank [-],centric [-]");
}

// gravity_significance: two rows, k = 4 and k = 5 four-stroke.
Table makeGravity() {
  std::string csv = "cycle,k [-],max_abs_Q [N m],ratio_to_k1 [-],max_inertia_torque [N m],ratio_to_inertia [-],"
                    "first_order [-],paper_negligible,rounding_bound [N m]" +
                    engineColumns({"_max_abs_Q [N m]", "_resolved", "_ratio_to_k1 [-]"}) + "\n";
  for (int k : {4, 5}) {
    csv += "four-stroke," + std::to_string(k) + ",1,1,2,0.5,2,0,0";
    for (size_t i = 0; i < listReferenceEngines().size(); ++i) csv += ",1,yes,1";
    csv += "\n";
  }
  return readTable("gravity_significance", csv);
}

TEST(SurveyTest, GravityTableMarksTheRowsOfTheUsersK) {
  const Part& part = findPart("gravity_significance");
  const ReportPart user = part.describe({{"gravity_significance", makeGravity()},
                                         {"survey_base", makeBase("my_four,user,4,four-stroke,0.3,2500,1,1")},
                                         {"your_engine", makeFacts("my_four", "user", 4, "four-stroke", 0.3)}});
  const ReportBlock* table = findTable(user, "cycle");
  ASSERT_NE(table, nullptr);
  EXPECT_EQ(table->header.back(), "your engine(s)");
  ASSERT_EQ(table->rows.size(), 2u);
  EXPECT_EQ(table->rows[0].back(), "your engine(s): my_four");  // k = 4, four-stroke
  EXPECT_EQ(table->rows[1].back(), "");                         // k = 5
  EXPECT_NE(findParagraph(user, "marks the rows of your engines' k and cycle: my_four (k = 4, four-stroke)").size(), 0u);
  // The inertia torque's speed is named: the first scene's.
  EXPECT_EQ(user.blocks.front().kind, ReportBlock::kFigure);
  EXPECT_NE(user.blocks.front().text.find("at my_four's speed, 2500 rpm, for every k"), std::string::npos)
      << user.blocks.front().text;
  // The default campaign (example scenes): no column.
  const ReportPart example = part.describe({{"gravity_significance", makeGravity()},
                                            {"your_engine", makeFacts("inline4", "example", 4, "four-stroke", 0.3)}});
  const ReportBlock* plain = findTable(example, "cycle");
  ASSERT_NE(plain, nullptr);
  EXPECT_EQ(std::count(plain->header.begin(), plain->header.end(), "your engine(s)"), 0);
  EXPECT_EQ(plain->header.size(), table->header.size() - 1);
}

TEST(SurveyTest, BalanceTableMarksTheUsersLayout) {
  std::string summary = "layout,description,part,textbook,vanishes_exactly,analytic_amplitude [N m]" +
                        engineColumns({"_amplitude [SI]"}) + ",relative_amplitude [-],verdict\n";
  for (const std::string& row : {std::string("inline4,inline four,F2,does not vanish,no,10"),
                                  std::string("my_v8,scene my_v8,F2,no claim,yes,0")}) {
    summary += row;
    for (size_t i = 0; i < listReferenceEngines().size(); ++i) summary += ",10";
    summary += ",0.1," + std::string(row.rfind("inline4", 0) == 0 ? "agrees" : "-") + "\n";
  }
  const std::string harmonics =
      "layout_index [-],layout,n [-],force_relative [-],couple_relative [-],rocking_relative [-],force_vanishes,"
      "couple_vanishes\n0,inline4,2,0.5,0,0,0,1\n1,my_v8,2,0,0,0,1,1\n";
  const Part& part = findPart("balance");
  TableSet tables = {{"balance", readTable("balance", summary)},
                     {"balance_harmonics", readTable("balance_harmonics", harmonics)},
                     {"your_engine", makeFacts("my_v8", "user", 8, "four-stroke", 0.3)}};
  const ReportPart user = part.describe(tables);
  const ReportBlock* table = findTable(user, "layout");
  ASSERT_NE(table, nullptr);
  ASSERT_EQ(table->rows.size(), 2u);
  EXPECT_EQ(table->rows[0][0], "inline4");
  EXPECT_EQ(table->rows[1][0], "my_v8 (your engine)");
  EXPECT_NE(findParagraph(user, "Below the layouts, marked 'your engine': my_v8, each exactly as given, at its own "
                                "speed (no textbook claim).").size(), 0u);
  EXPECT_NE(findParagraph(user, "at 6000 rpm (not your scene's speed;").size(), 0u);
  // An example scene is not marked.
  tables["your_engine"] = makeFacts("my_v8", "example", 8, "four-stroke", 0.3);
  const ReportPart example = part.describe(tables);
  const ReportBlock* plain = findTable(example, "layout");
  ASSERT_NE(plain, nullptr);
  EXPECT_EQ(plain->rows[1][0], "my_v8");
}

TEST(SurveyTest, ErrorAgainstLambdaCaptionNamesTheUsersLambda) {
  const Part& part = findPart("error_vs_lambda");
  const Table errors = readTable("error_vs_lambda",
                                 "quantity,method,lambda [-],max_abs_error [SI],max_rel_error [-],resolved\n"
                                 "x_p,norton_two_term,0.3,1e-4,1e-3,1\n");
  const ReportPart user = part.describe({{"error_vs_lambda", errors},
                                         {"your_engine", makeFacts("my_four", "user", 4, "four-stroke", 0.25)}});
  EXPECT_NE(user.caption.find("The dash-dotted vertical lines mark your engines' lambda: my_four at lambda = 0.25"),
            std::string::npos) << user.caption;
  const ReportPart example = part.describe({{"error_vs_lambda", errors},
                                            {"your_engine", makeFacts("inline4", "example", 4, "four-stroke", 0.25)}});
  EXPECT_EQ(example.caption.find("your engines"), std::string::npos) << example.caption;
}

TEST(SurveyTest, CaptionsSayWhenTheSpeedOrTheGasIsNotTheScenes) {
  // torque_split: the speeds of its gravity share read from the table, the example pressure table named.
  const Table share = readTable("gravity_share",
                                "cycle,k [-],speed_rpm [rpm],mean_abs_drive_torque [N m],mean_abs_gravity_torque [N m],"
                                "share [-],resolved\nfour-stroke,1,600,10,1,0.1,1\nfour-stroke,1,6000,100,1,0.01,1\n");
  const ReportPart split = findPart("torque_split").describe({{"torque_split", readTable("torque_split",
      "engine,phi_deg [deg],drive_torque [N m],gas_torque [N m],inertia_torque [N m],gravity_torque [N m]" +
          engineColumns({"_drive_torque [N m]"}) + "\n")}, {"gravity_share", share}});
  EXPECT_NE(split.caption.find("at 600 and 6000 rpm, not your scene's speed"), std::string::npos) << split.caption;
  EXPECT_NE(split.caption.find("the example spark-ignition pressure table (validation/example_gas.h), not your "
                               "scene's [gas]"), std::string::npos) << split.caption;
  // delta_vs_k: its speeds from the table.
  const ReportPart delta = findPart("delta_vs_k").describe({{"delta_vs_k", readTable("delta_vs_k",
      "cycle,k [-],speed_rpm [rpm],delta_gravity [-],delta_no_gravity [-],delta_due_to_gravity [-]\n"
      "two-stroke,1,300,0.1,0.1,0\ntwo-stroke,1,6000,0.1,0.1,0\n")}});
  EXPECT_NE(delta.caption.find("; at 300 and 6000 rpm, not your scene's speed"), std::string::npos) << delta.caption;
}

}  // namespace
}  // namespace crankcheck::validation
