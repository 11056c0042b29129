// describe() of the report parts offset, gravity_significance, balance, balance_shafts, pin_load_polar, torque_split
// and rod_models on small fixed tables read the way `report merge` reads them (csv.h: through each table's schema into
// typed rows): the numbers of their sentences and tables, worked out by hand from the rows below, and the part left out
// without its tables. And each table's CSV header, written out by hand: the schemas must keep the files' columns.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "crankcheck/validation/csv.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/parts.h"
#include "part_fixture.h"

namespace crankcheck::validation {
namespace {

using testing::findParagraph;
using testing::readTable;

// "ENGINE" + suffix for every reference engine of the registry, joined by commas, each preceded by one: the
// per-engine columns of a header.
std::string engineColumns(const std::vector<std::string>& suffixes) {
  std::string s;
  for (const Engine* e : listReferenceEngines())
    for (const std::string& suffix : suffixes) s += "," + e->name + suffix;
  return s;
}

// The table block whose header's column `column` is `name`; nullptr when there is none.
const ReportBlock* findTableBlock(const ReportPart& part, size_t column, const std::string& name) {
  for (const ReportBlock& b : part.blocks)
    if (b.kind == ReportBlock::kTable && b.header.size() > column && b.header[column] == name) return &b;
  return nullptr;
}

// The CSV header of every table of these parts, as the campaign wrote it before the tables were typed.
TEST(LoadsGroupTest, EveryTableKeepsItsCsvHeader) {
  const std::vector<std::pair<std::string, std::string>> headers = {
      {"offset", "quantity,offset_over_r [-],max_rel_error [-]" + engineColumns({"_max_rel_error [-]"})},
      {"offset_thrust", "engine,offset_over_r [-],peak_major_thrust [N],peak_minor_thrust [N],thrust_reversal_deg [deg],"
                        "max_abs_drive_torque [N m]"},
      {"gravity_significance",
       "cycle,k [-],max_abs_Q [N m],ratio_to_k1 [-],max_inertia_torque [N m],ratio_to_inertia [-],first_order [-],"
       "paper_negligible,rounding_bound [N m]" +
           engineColumns({"_max_abs_Q [N m]", "_resolved", "_ratio_to_k1 [-]"})},
      {"balance", "layout,description,part,textbook,vanishes_exactly,analytic_amplitude [N m]" +
                      engineColumns({"_amplitude [SI]"}) + ",relative_amplitude [-],verdict"},
      {"balance_harmonics", "layout_index [-],layout,n [-],force_relative [-],couple_relative [-],rocking_relative [-],"
                            "force_vanishes,couple_vanishes"},
      {"balance_shafts", "case,shafts,engine,n [-],force_amplitude [N],force_relative [-]"},
      {"pin_load_polar", "scene_index [-],engine,phi_deg [deg],crank_pin_radial [N],crank_pin_tangential [N],bearing_x [N],"
                         "bearing_y [N],scene"},
      {"pin_load_polar_summary", "scene,engine,force,max_magnitude [N],phi_deg_at_max [deg],max_difference_rel [-]"},
      {"torque_split", "engine,phi_deg [deg],drive_torque [N m],gas_torque [N m],inertia_torque [N m],gravity_torque [N m]" +
                           engineColumns({"_drive_torque [N m]"})},
      {"gravity_share", "cycle,k [-],speed_rpm [rpm],mean_abs_drive_torque [N m],mean_abs_gravity_torque [N m],share [-],"
                        "resolved"},
      {"rod_models", "engine,variable,x [SI],two_mass_error [-],two_mass_delta_I_error [-],two_mass_delta_I_resolved,"
                     "reference"}};
  for (const auto& [name, header] : headers) {
    const TableSchema* schema = findTableSchema(name);
    ASSERT_NE(schema, nullptr) << name;
    EXPECT_EQ(formatCsv(schema->makeTable()), header + "\n") << name;
  }
  // Each part declares its own tables, and no other.
  const std::vector<std::pair<std::string, std::vector<std::string>>> owned = {
      {"offset", {"offset", "offset_thrust"}},
      {"gravity_significance", {"gravity_significance"}},
      {"balance", {"balance", "balance_harmonics"}},
      {"balance_shafts", {"balance_shafts"}},
      {"pin_load_polar", {"pin_load_polar", "pin_load_polar_summary"}},
      {"torque_split", {"torque_split", "gravity_share"}},
      {"rod_models", {"rod_models"}}};
  for (const auto& [key, tables] : owned) EXPECT_EQ(findPart(key).tables(), tables) << key;
}

// A row of the typed table reads back the number it was given, an empty optional cell as empty.
TEST(LoadsGroupTest, TypedRowsReadBackTheCsvFields) {
  const Table t = readTable("offset_thrust",
                            "engine,offset_over_r [-],peak_major_thrust [N],peak_minor_thrust [N],thrust_reversal_deg [deg],"
                            "max_abs_drive_torque [N m]\n"
                            "analytic,0.04,1100.5,450,,81\n");
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(std::get<double>(t.cell(0, 2)), 1100.5);
  EXPECT_TRUE(std::holds_alternative<std::monostate>(t.cell(0, 4)));
  EXPECT_EQ(formatCsv(t).substr(formatCsv(t).find('\n') + 1), "analytic,0.04,1100.5,450,,81\n");
}

TEST(LoadsGroupTest, OffsetReadsTheCentricErrorAndTheThrust) {
  const std::string engines = engineColumns({"_max_rel_error [-]"});
  // One reference engine's column per reference engine: the fixture's values repeat for each.
  auto costRow = [](const std::string& fields, const std::string& reference) {
    std::string row = fields;
    for (size_t i = 0; i < listReferenceEngines().size(); ++i) row += "," + reference;
    return row + "\n";
  };
  const Table cost = readTable("offset", "quantity,offset_over_r [-],max_rel_error [-]" + engines + "\n" +
                                             costRow("x_p,0.04,0.001", "1e-15") + costRow("a_p,0.04,0.002", "2e-15") +
                                             costRow("x_p,-0.04,0.5", "1"));
  const Table thrust = readTable("offset_thrust",
                                 "engine,offset_over_r [-],peak_major_thrust [N],peak_minor_thrust [N],"
                                 "thrust_reversal_deg [deg],max_abs_drive_torque [N m]\n"
                                 "analytic,0,1000,500,,80\n"
                                 "analytic,0.04,1100,450,12.5,81\n"
                                 "simbody,0.04,1,1,1,1\n");
  const Part& part = findPart("offset");
  EXPECT_EQ(part.title(), "Pin offset: what the centric formulas cost, what the offset buys");
  const ReportPart d = part.describe({{"offset", cost}, {"offset_thrust", thrust}});
  EXPECT_EQ(d.heading, part.heading());
  // Only delta / r = +0.04 counts (the negative row is not read), and the worst of the two rows over the reference
  // engines: 2e-15.
  EXPECT_EQ(findParagraph(d, "At |delta| / r = 0.04"),
            "At |delta| / r = 0.04 the centric forms are off by 0.001 in x_p, 0.002 in a_p (relative to each scale; the "
            "exact offset engine agrees with every reference engine to 2e-15).");
  // 1100 / 1000 - 1 = 10 %; the centric engine's thrust does not change sign within 90 degrees (its cell is empty).
  EXPECT_EQ(findParagraph(d, "delta / r = 0.04:"),
            "delta / r = 0.04: the peak major thrust is 1100 N against 1000 N centric (10 %), the peak minor thrust 450 N "
            "against 500 N, and the side thrust changes sign at 12.5 degrees from the firing outer dead centre (centric: "
            "none within 90).");
  // No row at 0.5, -0.04 or -0.5 in the thrust table: two sentences on the cost at 0.04 and the thrust at 0.04.
  EXPECT_EQ(d.paragraphs.size(), 2u);
  // Without its thrust table, or without the centric errors, the part is left out.
  EXPECT_TRUE(part.describe({{"offset", cost}}).heading.empty());
  EXPECT_TRUE(part.describe({{"offset_thrust", thrust}}).heading.empty());
}

TEST(LoadsGroupTest, GravitySignificanceTestsThePapersClaims) {
  // max |Q| / max |Q|(k = 1) of a two-stroke: the weakest of the engines the paper says gravity matters for is k = 12
  // (1e-6), the strongest it calls negligible k = 7 (1e-12): the dividing line holds by a factor 1e6.
  const std::vector<std::pair<int, std::string>> ratio = {{1, "1"},     {2, "0.5"},   {3, "0.01"},   {4, "0.3"},
                                                          {5, "1e-4"},  {6, "1e-3"},  {7, "1e-12"},  {8, "1e-4"},
                                                          {9, "1e-13"}, {10, "1e-5"}, {11, "1e-14"}, {12, "1e-6"}};
  std::string csv = "cycle,k [-],max_abs_Q [N m],ratio_to_k1 [-],max_inertia_torque [N m],ratio_to_inertia [-],"
                    "first_order [-],paper_negligible,rounding_bound [N m]" +
                    engineColumns({"_max_abs_Q [N m]", "_resolved", "_ratio_to_k1 [-]"}) + "\n";
  for (const auto& [k, r] : ratio) {
    csv += "two-stroke," + std::to_string(k) + "," + r + "," + r + ",2.34567," + r + ",1," +
           (k == 7 || k == 9 || k == 11 ? "1" : "0") + ",0";
    for (size_t i = 0; i < listReferenceEngines().size(); ++i) csv += "," + r + ",yes," + r;
    csv += "\n";
  }
  const Part& part = findPart("gravity_significance");
  EXPECT_EQ(part.title(), "When gravity matters");
  const ReportPart d = part.describe({{"gravity_significance", readTable("gravity_significance", csv)}});
  EXPECT_EQ(d.heading, part.heading());
  EXPECT_NE(findParagraph(d, "two-stroke: the weakest engine the paper says gravity matters for (k = 12) has 1e+06 times the "
                             "max |Q| of the strongest it calls negligible (k = 7), so the line holds for any threshold "
                             "between 1e-12 and 1e-06 of the single cylinder's max |Q|").size(), 0u);
  // The data table: cycle, k, first order, then the numbers to 4 digits (2.34567 -> 2.346), each engine's max |Q| and
  // whether it resolves it.
  const ReportBlock* data = findTableBlock(d, 0, "cycle");
  ASSERT_NE(data, nullptr);
  ASSERT_EQ(data->rows.size(), 12u);
  std::vector<std::string> k3 = {"two-stroke", "3", "1", "0.01", "0.01", "2.346", "0.01", "0"};
  for (size_t i = 0; i < listReferenceEngines().size(); ++i) k3.insert(k3.end(), {"0.01", "yes"});
  EXPECT_EQ(data->rows[2], k3);
  EXPECT_EQ(data->header.size(), k3.size());
  // The claims table: the dividing line, then the practical list at 1e-3 (k = 3 and 6 reach it, the paper says
  // 1, 2, 4) and at 1e-5.
  const ReportBlock* claims = findTableBlock(d, 0, "claim (Stanczak section 7)");
  ASSERT_NE(claims, nullptr);
  ASSERT_EQ(claims->rows.size(), 3u);
  EXPECT_EQ(claims->rows[0].back(), "holds, by a factor 1e+06");
  EXPECT_EQ(claims->rows[1][4], "{1, 2, 3, 4, 6}");
  EXPECT_EQ(claims->rows[1][5], "k = 3: 0.01, k = 6: 0.001");
  EXPECT_EQ(claims->rows[1].back(), "does not hold");
  // At 1e-5: k = 1..6, 8, 10 reach it (k = 12 at 1e-6 does not); the paper says 1, 2, 3, 4, 6.
  EXPECT_EQ(claims->rows[2][4], "{1, 2, 3, 4, 5, 6, 8, 10}");
  EXPECT_EQ(claims->rows[2].back(), "does not hold");
  EXPECT_TRUE(part.describe({}).heading.empty());
}

TEST(LoadsGroupTest, BalanceReadsTheTableAndTheHarmonicsAboveTwo) {
  std::string summary = "layout,description,part,textbook,vanishes_exactly,analytic_amplitude [N m]" +
                        engineColumns({"_amplitude [SI]"}) + ",relative_amplitude [-],verdict\n" +
                        "inline4,inline four,F2,does not vanish,no,1234.5678";
  for (size_t i = 0; i < listReferenceEngines().size(); ++i) summary += ",1234.4321";
  summary += ",0.123456,agrees\n";
  // inline4: above n = 2 the force's largest is n = 6 (0.03 > 0.01), the couple's n = 3 (0.002); single: nothing above
  // n = 2.
  const std::string harmonics =
      "layout_index [-],layout,n [-],force_relative [-],couple_relative [-],rocking_relative [-],force_vanishes,"
      "couple_vanishes\n"
      "0,inline4,1,0,0,0,1,1\n"
      "0,inline4,2,0.5,0,0,0,1\n"
      "0,inline4,3,0,0.002,0,1,0\n"
      "0,inline4,4,0.01,0,0,0,1\n"
      "0,inline4,6,0.03,0,0,0,1\n"
      "1,single,1,1,0,0,0,1\n"
      "1,single,2,0.3,0,0,0,1\n";
  const Part& part = findPart("balance");
  EXPECT_EQ(part.title(), "Balance of engine layouts");
  EXPECT_EQ(part.figures(), std::vector<std::string>{"balance_harmonics"});
  const TableSet tables = {{"balance", readTable("balance", summary)},
                           {"balance_harmonics", readTable("balance_harmonics", harmonics)}};
  const ReportPart d = part.describe(tables);
  EXPECT_EQ(d.heading, part.heading());
  const ReportBlock* table = findTableBlock(d, 1, "part");
  ASSERT_NE(table, nullptr);
  ASSERT_EQ(table->rows.size(), 1u);
  // The amplitudes to 4 digits: 1234.5678 -> 1235, 1234.4321 -> 1234, 0.123456 -> 0.1235.
  std::vector<std::string> row = {"inline4", "F2", "does not vanish", "no", "1235"};
  for (size_t i = 0; i < listReferenceEngines().size(); ++i) row.push_back("1234");
  row.insert(row.end(), {"0.1235", "agrees"});
  EXPECT_EQ(table->rows[0], row);
  const ReportBlock* beyond = findTableBlock(d, 1, "largest force harmonic above 2");
  ASSERT_NE(beyond, nullptr);
  ASSERT_EQ(beyond->rows.size(), 2u);
  EXPECT_EQ(beyond->rows[0], (std::vector<std::string>{"inline4", "n = 6", "0.03", "n = 3", "0.002"}));
  EXPECT_EQ(beyond->rows[1], (std::vector<std::string>{"single", "none up to 8", "0", "none up to 8", "0"}));
  // Without the harmonics the part is left out.
  EXPECT_TRUE(part.describe({{"balance", readTable("balance", summary)}}).heading.empty());
}

TEST(LoadsGroupTest, BalanceShaftsReadWhatTheShaftsCancel) {
  // Force scale 100 N / 0.5 = 200 N; the shafts take harmonic 1 to 0 in closed form, Simbody leaves 5e-16 of the
  // scale, harmonic 2 is unchanged. Case "plain": the shafts change nothing.
  const Table t = readTable("balance_shafts",
                            "case,shafts,engine,n [-],force_amplitude [N],force_relative [-]\n"
                            "single,none,analytic,1,100,0.5\n"
                            "single,none,analytic,2,20,0.1\n"
                            "single,with,analytic,1,0,0\n"
                            "single,with,analytic,2,20,0.1\n"
                            "single,with,simbody,1,1e-13,5e-16\n"
                            "single,with,simbody,2,20,0.1\n"
                            "plain,none,analytic,1,10,0.1\n"
                            "plain,with,analytic,1,10,0.1\n");
  const Part& part = findPart("balance_shafts");
  EXPECT_EQ(part.title(), "Balance shafts: what a designed set cancels, by every engine");
  const ReportPart d = part.describe({{"balance_shafts", t}});
  EXPECT_EQ(d.heading, part.heading());
  ASSERT_EQ(d.paragraphs.size(), 2u);
  EXPECT_EQ(d.paragraphs[0],
            "single: harmonic 1 of the shaking force falls from 100 N (0.5 of the force scale) to 0 N in closed form; the "
            "largest residual of the other exact engines is 5e-16 of the force scale (simbody); the closed form of every "
            "other harmonic is unchanged.");
  EXPECT_EQ(d.paragraphs[1], "plain: the shafts cancel no harmonic of the shaking force.");
  EXPECT_TRUE(part.describe({}).heading.empty());
}

TEST(LoadsGroupTest, PinLoadPolarListsTheLargestForces) {
  const Table polar = readTable("pin_load_polar",
                                "scene_index [-],engine,phi_deg [deg],crank_pin_radial [N],crank_pin_tangential [N],"
                                "bearing_x [N],bearing_y [N],scene\n"
                                "0,analytic,0,1,2,3,4,car\n");
  const Table summary = readTable("pin_load_polar_summary",
                                  "scene,engine,force,max_magnitude [N],phi_deg_at_max [deg],max_difference_rel [-]\n"
                                  "car,analytic,crank_pin,12345.678,10,1.23456e-15\n"
                                  "car,simbody,bearing,0.5,20,0\n");
  const Part& part = findPart("pin_load_polar");
  EXPECT_EQ(part.title(), "Pin loads over a working cycle (polar diagrams)");
  const ReportPart d = part.describe({{"pin_load_polar", polar}, {"pin_load_polar_summary", summary}});
  EXPECT_EQ(d.heading, part.heading());
  EXPECT_FALSE(d.caption.empty());
  // The summary's rows, max |F| and the difference to 4 digits (where the force is largest is not shown).
  ASSERT_EQ(d.rows.size(), 2u);
  EXPECT_EQ(d.rows[0], (std::vector<std::string>{"car", "analytic", "crank_pin", "1.235e+04", "1.235e-15"}));
  EXPECT_EQ(d.rows[1], (std::vector<std::string>{"car", "simbody", "bearing", "0.5", "0"}));
  EXPECT_EQ(d.header.size(), d.rows[0].size());
  // The polar table is the figure's: without it the part is left out.
  EXPECT_TRUE(part.describe({{"pin_load_polar_summary", summary}}).heading.empty());
}

// torque_split and rod_models are their figure alone: shown when their table is there, left out when it is not.
TEST(LoadsGroupTest, TorqueSplitAndRodModelsAreTheirFigure) {
  const Table split = readTable("torque_split", "engine,phi_deg [deg],drive_torque [N m],gas_torque [N m],"
                                                "inertia_torque [N m],gravity_torque [N m]" +
                                                    engineColumns({"_drive_torque [N m]"}) + "\n");
  const Table rods = readTable("rod_models", "engine,variable,x [SI],two_mass_error [-],two_mass_delta_I_error [-],"
                                             "two_mass_delta_I_resolved,reference\n"
                                             "car,lambda,0.3,0.01,1e-16,0,simbody\n");
  for (const auto& [key, table] : {std::pair<std::string, const Table&>{"torque_split", split}, {"rod_models", rods}}) {
    SCOPED_TRACE(key);
    const Part& part = findPart(key);
    const ReportPart d = part.describe({{key, table}});
    EXPECT_EQ(d.heading, part.heading());
    EXPECT_FALSE(d.caption.empty());
    EXPECT_TRUE(d.paragraphs.empty());
    EXPECT_TRUE(part.describe({}).heading.empty());
  }
  EXPECT_EQ(findPart("torque_split").title(), "The working torque: gas, inertia and gravity");
  EXPECT_EQ(findPart("rod_models").title(), "What the two-mass rod costs");
}

}  // namespace
}  // namespace crankcheck::validation
