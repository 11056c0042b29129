// One more engine registered in this test build only (registerExtraEngine): the analytic engine again under another
// name, gated and not the closed forms, so a reference engine like Simbody and MuJoCo. With no other change, every
// engine-comparing part of a campaign, the cross-check and the verdict must include it: the harness loops over the
// registry and names no engine (issue 27). Its numbers are the closed forms' own, so every comparison it enters is
// exact (error 0), which the test also checks where a table states an error.
// A second one offers a stepped route alone (no build, no free run): the closed forms read at each step's start, so
// the stepped part includes it with errors of 0, and no part that evaluates sees it (one registry, filtered by route).
#include <gtest/gtest.h>

#include "crankcheck/validation/crosscheck.h"

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "crankcheck/analytic/engine.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/commands/stepped.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/parts.h"
#include "crankcheck/validation/verdict.h"

namespace crankcheck::validation {
namespace {

const std::string kExtra = "analytic-again";
const std::string kStepOnly = "closed-forms-stepped";

// A step-only engine: held at the scene's speed, each step's x_p and drive torque are the closed forms' at the step's
// start (stated instant 0), the loop closed exactly. The crank angle after step i is phi0 + omega (i + 1) dt.
Engine makeStepOnlyEngine() {
  Engine e;
  e.name = kStepOnly;
  e.library = "crankcheck's closed forms";
  e.method = "the closed forms read at each step's start";
  e.gated = false;
  e.settings = {"defaults"};
  e.settings_meaning = {"the only one"};
  e.step_at_speed = [](const Mechanism& m, const ConstantSpeedRunOptions& o) {
    const std::unique_ptr<EngineModel> exact = analytic::describeEngines().front().build(m);
    Trajectory run;
    run.reported = {{QuantityId::kPistonPosition, 0.0}, {QuantityId::kDriveTorque, 0.0}};
    double phi_start = o.start.phi;
    for (long i = 0; i < o.steps; ++i) {
      run.time.push_back(static_cast<double>(i + 1) * o.dt);
      run.phi.push_back(o.start.phi + m.machine.speed * static_cast<double>(i + 1) * o.dt);
      run.omega.push_back(m.machine.speed);
      run.values.push_back(exact->evaluate(phi_start));
      run.loop_error.push_back(0.0);
      phi_start = run.phi.back();
    }
    return run;
  };
  return e;
}

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
  for (const char* name : {"error_vs_lambda", "speed_vs_error", "harmonics", "gravity_significance", "errata",
                                  "balance", "torque_split", "rod_models", "pin_load_polar", "pin_load_polar_summary",
                                  "engines", "offset", "offset_thrust", "balance_shafts"}) {
    ASSERT_TRUE(tables.count(name)) << name;
    EXPECT_TRUE(mentions(tables.at(name), kExtra)) << name;
  }
  // ... and every part still describes itself from those tables.
  for (const Part* part : listParts()) EXPECT_NO_THROW(part->describe(tables)) << part->key();
}

// The step-only engine is in the lists of the route it offers and no other; the stepped part measures it (errors 0:
// the values are the closed forms' at the very angle the measure reads them), and the evaluating parts never see it.
TEST(ExtraEngineTest, AStepOnlyEngineJoinsItsRouteAlone) {
  auto names = [](Route route) {
    std::vector<std::string> out;
    for (const Engine& e : listEngines(route)) out.push_back(e.name);
    return out;
  };
  auto has = [](const std::vector<std::string>& v, const std::string& name) { return std::find(v.begin(), v.end(), name) != v.end(); };
  EXPECT_TRUE(has(names(Route::kStepAtSpeed), kStepOnly));
  EXPECT_TRUE(has(names(Route::kStepAtSpeed), "ode"));
  for (Route route : {Route::kEvaluate, Route::kSimulate, Route::kStepFree, Route::kCrankTrain})
    EXPECT_FALSE(has(names(route), kStepOnly)) << static_cast<int>(route);
  EXPECT_EQ(findEngine(kStepOnly, Route::kStepAtSpeed).name, kStepOnly);
  EXPECT_THROW(findEngine(kStepOnly), std::invalid_argument);
  const TableSet& tables = getCampaignTables();
  size_t rows = 0;
  for (const SteppedErrorRow& row : getRows(tables, kSteppedErrorsTable)) {
    if (row.engine != kStepOnly) continue;
    ++rows;
    EXPECT_EQ(row.worst_rel_error, 0.0) << row.quantity << " at dt " << row.dt;
  }
  EXPECT_GT(rows, 2u);  // x_p, the drive torque and the loop error, at each step
  for (const char* name : {"crosscheck", "engines", "error_vs_lambda", "harmonics"}) {
    ASSERT_TRUE(tables.count(name)) << name;
    EXPECT_FALSE(mentions(tables.at(name), kStepOnly)) << name;
  }
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
  crankcheck::validation::registerExtraEngine(crankcheck::validation::makeStepOnlyEngine());
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
