// One more report part registered in this test build only (registerExtraPart): a part of one typed table, with no
// other change anywhere. The campaign runs its task, `validate --parts` accepts its key, the report numbers it after
// the others, writes data/KEY.csv from its schema and places its heading, sentence and table; a report folder read
// back (csv.h, as `report merge` reads a shard) gives its typed rows again, equal to the rows the task computed.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "crankcheck/scene/scene_file.h"
#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/csv.h"
#include "crankcheck/validation/table_schemas.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/parts.h"
#include "crankcheck/validation/report.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/runner.h"
#include "fresh_folder.h"
#include "../support/read_file.h"

namespace crankcheck::validation {
namespace {
namespace fs = std::filesystem;

const std::string kKey = "extra_typed";

// The extra part's one table: each scene's crank ratio and cylinder count.
struct ExtraRow {
  std::string scene;
  double lambda = 0.0;
  int cylinders = 0;
};
const Schema<ExtraRow> kExtraTable{kKey,
                                   {textField("scene", &ExtraRow::scene), numberField("lambda", "-", &ExtraRow::lambda),
                                    countField("cylinders", &ExtraRow::cylinders)}};

class ExtraPart final : public Part {
 public:
  std::string key() const override { return kKey; }
  std::string title() const override { return "An extra part"; }
  std::vector<Task> tasks(const PartContext& context) const override {
    return {{"extra", false, [scenes = context.scenes] {
               std::vector<ExtraRow> rows;
               for (const Mechanism& m : scenes) rows.push_back({m.name, calcCrankRatio(m), m.machine.cylinders});
               return kExtraTable.tableSet(std::move(rows));
             }}};
  }
  std::vector<const TableSchema*> schemas() const override { return {&kExtraTable}; }
  std::vector<std::string> figures() const override { return {}; }
  ReportPart describe(const TableSet& tables) const override {
    ReportPart part;
    const std::vector<ExtraRow>& rows = getRows(tables, kExtraTable);
    if (rows.empty()) return part;
    part.heading = heading();
    part.paragraphs.push_back("The first scene's lambda is " + shortNumber(rows.front().lambda, 4) + ".");
    part.header = {"scene", "lambda [-]"};
    for (const ExtraRow& row : rows) part.rows.push_back({row.scene, shortNumber(row.lambda, 4)});
    return part;
  }
};

const ExtraPart kPart;

using testing::readFile;

TEST(ExtraPartTest, IsNumberedAfterTheOthersAndChosenByItsKey) {
  const std::vector<std::string> keys = listPartKeys();
  ASSERT_FALSE(keys.empty());
  EXPECT_EQ(keys.back(), kKey);
  EXPECT_EQ(kPart.number(), static_cast<int>(keys.size()));  // the last of the numbered parts
  EXPECT_NO_THROW(checkPartKeys({kKey}));
  EXPECT_EQ(findTableSchema(kKey), &kExtraTable);
  EXPECT_THROW(registerExtraPart(kPart), std::logic_error);  // the registry is in use now
}

TEST(ExtraPartTest, ReachesTheReportAndItsCsvAndReadsBackTyped) {
  CampaignOptions options;
  options.quick = true;
  options.parts = {kKey};
  options.scenes = {loadSceneFile(std::string(CRANKCHECK_SCENES_DIR) + "/inline4_four_stroke.toml"),
                    loadSceneFile(std::string(CRANKCHECK_SCENES_DIR) + "/single_cylinder.toml")};
  RunOptions run_options;
  run_options.jobs = 2;
  const CampaignRun run = runCampaign(options, ShardSelection{}, run_options);
  ASSERT_TRUE(run.tables.count(kKey));

  const testing::FreshFolder folder;  // made for this test, removed with what the report wrote in it
  const fs::path& dir = folder.path();
  ReportInfo info;
  info.quick = true;
  renderReport(run.tables, info, dir);

  // data/KEY.csv from the schema: the header with units, one row per scene, numbers exact, sorted by scene.
  const Mechanism& four = options.scenes[0];
  const Mechanism& one = options.scenes[1];
  const std::string csv = readFile(dir / "data" / (kKey + ".csv"));
  EXPECT_EQ(csv, "scene,lambda [-],cylinders [-]\n" + four.name + "," + formatNumber(calcCrankRatio(four)) + ",4\n" +
                     one.name + "," + formatNumber(calcCrankRatio(one)) + ",1\n");
  // The report places it under its number, with its sentence; the others were not run, so they are left out.
  const std::string index = readFile(dir / "index.md");
  const std::string heading = "## " + std::to_string(kPart.number()) + ". An extra part";
  EXPECT_NE(index.find(heading), std::string::npos) << index;
  EXPECT_NE(index.find("The first scene's lambda is " + shortNumber(calcCrankRatio(four), 4) + "."), std::string::npos);
  EXPECT_EQ(index.find("## 1. "), std::string::npos);
  // Read back as `report merge` reads a shard: typed rows equal to those computed, to the last bit.
  const TableSet read = readTables(dir);
  const std::vector<ExtraRow>& rows = getRows(read, kExtraTable);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].scene, four.name);
  EXPECT_EQ(rows[0].lambda, calcCrankRatio(four));
  EXPECT_EQ(rows[0].cylinders, 4);
  EXPECT_EQ(rows[1].lambda, calcCrankRatio(one));
}

}  // namespace
}  // namespace crankcheck::validation

int main(int argc, char** argv) {
  crankcheck::validation::registerExtraPart(crankcheck::validation::kPart);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
