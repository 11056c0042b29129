// One more engine registered in this test build only (registerExtraEngine): the analytic engine again under another
// name, gated and not the closed forms, so a reference engine like Simbody and MuJoCo. With no other change, every
// engine-comparing part of a campaign, the cross-check and the verdict must include it: the harness loops over the
// registry and names no engine (issue 27). Its numbers are the closed forms' own, so every comparison it enters is
// exact (error 0), which the test also checks where a table states an error.
#include <gtest/gtest.h>

#include "crankcheck/validation/crosscheck.h"

#include <algorithm>
#include <string>
#include <vector>

#include "crankcheck/analytic/engine.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/parts.h"
#include "crankcheck/validation/verdict.h"

namespace crankcheck::validation {
namespace {

const std::string kExtra = "analytic-again";

// The campaign on one example scene (gas, a flywheel), --quick, run as the CLI runs it: every task, the tables added
// up, sorted, and every part's derive.
const TableSet& getCampaignTables() {
  static const TableSet tables = [] {
    CampaignOptions options;
    options.quick = true;
    options.scenes = {loadSceneFile(std::string(CRANKCHECK_SCENES_DIR) + "/inline4_four_stroke.toml")};
    TableSet all;
    for (const Task& task : buildCampaign(options)) appendTables(all, task.run());
    sortTables(all);
    for (const Part* part : listParts()) part->derive(all);
    sortTables(all);
    return all;
  }();
  return tables;
}

// True when `text` appears in a header or a cell of `table`.
bool mentions(const Table& table, const std::string& text) {
  for (const std::string& name : table.names())
    if (name.find(text) != std::string::npos) return true;
  for (size_t r = 0; r < table.size(); ++r)
    for (const std::string& cell : table.formatRow(r))
      if (cell.find(text) != std::string::npos) return true;
  return false;
}

TEST(ExtraEngineTest, IsARegisteredReferenceEngine) {
  const std::vector<const Engine*> references = listReferenceEngines();
  EXPECT_TRUE(std::any_of(references.begin(), references.end(), [](const Engine* e) { return e->name == kExtra; }));
  EXPECT_EQ(getClosedFormEngine().name, "analytic");
  EXPECT_THROW(registerExtraEngine(Engine{}), std::logic_error);  // the registry is in use now
}

TEST(ExtraEngineTest, TheCrossCheckAndTheVerdictIncludeIt) {
  const TableSet& tables = getCampaignTables();
  size_t rows = 0;
  for (const CrossCheckRow& row : getRows(tables, kCrossCheckTable)) {
    if (row.engine != kExtra) continue;
    ++rows;
    EXPECT_EQ(row.worst_rel_error, 0.0) << row.quantity;  // the closed forms against themselves
    EXPECT_EQ(row.pass, "pass");
  }
  EXPECT_GT(rows, 10u);
  const std::vector<EngineVerdict> verdicts = calcVerdicts(tables);
  const auto it = std::find_if(verdicts.begin(), verdicts.end(), [](const EngineVerdict& v) { return v.engine == kExtra; });
  ASSERT_NE(it, verdicts.end());
  EXPECT_TRUE(it->gated);
  EXPECT_TRUE(it->pass());
  EXPECT_NE(formatVerdict(verdicts).find(kExtra), std::string::npos);
}

// Every part that compares the closed forms with the reference engines gains the extra engine's rows or columns.
TEST(ExtraEngineTest, EveryEngineComparingPartIncludesIt) {
  const TableSet& tables = getCampaignTables();
  for (const std::string& name : {"error_vs_lambda", "speed_vs_error", "harmonics", "gravity_significance", "errata",
                                  "balance", "torque_split", "rod_models", "pin_load_polar", "pin_load_polar_summary",
                                  "engines", "offset", "offset_thrust", "balance_shafts"}) {
    ASSERT_TRUE(tables.count(name)) << name;
    EXPECT_TRUE(mentions(tables.at(name), kExtra)) << name;
  }
  // ... and every part still describes itself from those tables.
  for (const Part* part : listParts()) EXPECT_NO_THROW(part->describe(tables)) << part->key();
}

// Where a table states the extra engine's error against the closed forms, it is 0: nothing else entered its column.
TEST(ExtraEngineTest, ItsErrorsAgainstTheClosedFormsAreZero) {
  const TableSet& tables = getCampaignTables();
  const Table& offset = tables.at("offset");
  for (const auto& row : offset.rows) EXPECT_EQ(std::stod(row[columnOf(offset, kExtra + "_max_rel_error")]), 0.0);
  const Table& lambda = tables.at("error_vs_lambda");
  int extra_rows = 0;
  for (size_t r = 0; r < lambda.size(); ++r)
    if (std::get<std::string>(lambda.cell(r, columnOf(lambda, "method"))) == "analytic_vs_" + kExtra) {
      EXPECT_EQ(std::get<double>(lambda.cell(r, columnOf(lambda, "max_abs_error"))), 0.0)
          << std::get<std::string>(lambda.cell(r, columnOf(lambda, "quantity")));
      ++extra_rows;
    }
  EXPECT_GT(extra_rows, 0);
}

}  // namespace
}  // namespace crankcheck::validation

// The extra engine is registered before anything reads the registry.
int main(int argc, char** argv) {
  crankcheck::Engine extra = crankcheck::analytic::describeEngines().front();
  extra.name = crankcheck::validation::kExtra;
  extra.closed_form = false;
  crankcheck::validation::registerExtraEngine(extra);
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
