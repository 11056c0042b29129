// The registry of report parts (parts.h), and describe() of parts 4 and 13-16 on a small fixed TableSet: the heading
// and the numbers the sentences read from the data. Every expected number is worked out by hand from the rows below.

#include "crankcheck/validation/parts.h"

#include <gtest/gtest.h>

#include "crankcheck/validation/csv.h"

#include <algorithm>
#include <map>
#include <set>
#include <string>

#include "crankcheck/validation/engines.h"

namespace crankcheck::validation {
namespace {

// The registered part numbered `number`; fails the test when there is none.
const Part& partNumbered(int number) {
  for (const Part* part : listParts())
    if (part->number() == number) return *part;
  ADD_FAILURE() << "no part " << number;
  return *listParts().front();
}

// Table `name` with its columns (names and units) and rows, read the way `report merge` reads a table (csv.h): into
// the typed rows of its schema where a part declares one.
Table makeTable(const std::string& name, std::vector<Column> columns, std::vector<std::vector<std::string>> rows) {
  Table t(name, std::move(columns));
  t.rows = std::move(rows);
  return parseTable(name, parseCsv(formatCsv(t), name), name);
}

// The paragraph (of the sentences or the blocks) that contains `needle`, or "" (the test then fails on its expectations).
std::string findParagraph(const ReportPart& part, const std::string& needle) {
  for (const std::string& p : part.paragraphs)
    if (p.find(needle) != std::string::npos) return p;
  for (const ReportBlock& b : part.blocks)
    if (b.kind == ReportBlock::kParagraph && b.text.find(needle) != std::string::npos) return b.text;
  ADD_FAILURE() << "no paragraph with \"" << needle << "\"";
  return "";
}

// part.h's contract: a part whose tables are missing (not run: validate --parts) is left out, its heading empty.
TEST(PartsTest, EveryPartIsLeftOutWithoutItsTables) {
  for (const Part* part : listParts()) EXPECT_TRUE(part->describe({}).heading.empty()) << part->key();
}

TEST(PartsTest, KeysAreUniqueAndNumbersFollowTheRegistrysOrder) {
  const std::vector<const Part*>& parts = listParts();
  ASSERT_FALSE(parts.empty());
  std::set<std::string> keys, tables, figures;
  for (size_t i = 0; i < parts.size(); ++i) {
    const Part& part = *parts[i];
    SCOPED_TRACE(part.key());
    EXPECT_TRUE(keys.insert(part.key()).second) << "key twice";
    // 1..N in report order.
    EXPECT_EQ(part.number(), static_cast<int>(i) + 1);
    EXPECT_EQ(part.heading(), std::to_string(part.number()) + ". " + part.title());
    for (const std::string& t : part.tables()) EXPECT_TRUE(tables.insert(t).second) << t << ": written by two parts";
    // Each figure is drawn from its own table: data/NAME.csv.
    for (const std::string& f : part.figures()) {
      EXPECT_TRUE(figures.insert(f).second) << f;
      const std::vector<std::string> own = part.tables();
      EXPECT_NE(std::find(own.begin(), own.end(), f), own.end()) << f << " is not among the part's tables";
    }
  }
  EXPECT_EQ(parts.back()->number(), 17);
}

TEST(PartsTest, EveryPartWithAFigureIsLeftOutWithoutItsTables) {
  for (const Part* part : listParts())
    if (!part->figures().empty()) {
      EXPECT_TRUE(part->describe({}).heading.empty()) << part->key();
    }
}

TEST(PartsTest, GravitySignificanceTestsThePapersClaims) {
  // max |Q| / max |Q|(k = 1) of a two-stroke: the weakest of the engines the paper says gravity matters for is k = 12
  // (1e-6), the strongest it calls negligible k = 7 (1e-12): the dividing line holds by a factor 1e6.
  const std::map<int, std::string> ratio = {{1, "1"},     {2, "0.5"},   {3, "0.01"},  {4, "0.3"},
                                            {5, "1e-4"},  {6, "1e-3"},  {7, "1e-12"}, {8, "1e-4"},
                                            {9, "1e-13"}, {10, "1e-5"}, {11, "1e-14"}, {12, "1e-6"}};
  Table t("gravity_significance", {{"cycle", kText}, {"k", "-"}, {"first_order", "-"}, {"max_abs_Q", "N m"},
                                   {"ratio_to_k1", "-"}, {"max_inertia_torque", "N m"}, {"ratio_to_inertia", "-"},
                                   {"rounding_bound", "N m"}, {"simbody_max_abs_Q", "N m"}, {"simbody_resolved", kText},
                                   {"mujoco_max_abs_Q", "N m"}, {"mujoco_resolved", kText}});
  for (const auto& [k, r] : ratio) t.rows.push_back({"two-stroke", std::to_string(k), "1", r, r, "1", r, "0", r, "yes", r, "yes"});
  const ReportPart d = partNumbered(4).describe({{"gravity_significance", t}});
  EXPECT_EQ(d.heading, "4. When gravity matters");
  EXPECT_NE(findParagraph(d, "two-stroke: the weakest engine the paper says gravity matters for (k = 12) has 1e+06 times the "
                             "max |Q| of the strongest it calls negligible (k = 7), so the line holds for any threshold "
                             "between 1e-12 and 1e-06 of the single cylinder's max |Q|").size(), 0u);
  // The claims table: the dividing line, then the practical list at 1e-3 (k = 3 and 6 reach it, the paper says
  // 1, 2, 4) and at 1e-5.
  const ReportBlock* claims = nullptr;
  for (const ReportBlock& b : d.blocks)
    if (b.kind == ReportBlock::kTable && !b.header.empty() && b.header[0] == "claim (Stanczak section 7)") claims = &b;
  ASSERT_NE(claims, nullptr);
  ASSERT_EQ(claims->rows.size(), 3u);
  EXPECT_EQ(claims->rows[0].back(), "holds, by a factor 1e+06");
  EXPECT_EQ(claims->rows[1][4], "{1, 2, 3, 4, 6}");
  EXPECT_EQ(claims->rows[1][5], "k = 3: 0.01, k = 6: 0.001");
  EXPECT_EQ(claims->rows[1].back(), "does not hold");
}

TEST(PartsTest, EnginesReadCostsAndWorstErrors) {
  // Two engines of the registry: analytic (50 ns at k = 1, worst 1e-15) and simbody (2500 ns, worst 2e-14 on Q).
  const std::string analytic = listEngines().at(0).name, simbody = listEngines().at(1).name;
  const std::vector<Column> columns = {{"engine", kText}, {"quantity", kText}, {"worst_rel_error", "-"},
                                       {"where_case", kText}, {"where_lambda", "-"}, {"where_phi_deg", "deg"},
                                       {"where_speed_rpm", "rpm"}, {"ns_per_eval_k1", "ns"}, {"ns_per_eval_k12", "ns"}};
  const TableSet tables = {{"engines", makeTable("engines", columns,
                                                 {{analytic, "Q", "1e-15", "c1", "0.3", "45", "6000", "50", "400"},
                                                  {simbody, "Q", "2e-14", "c2", "0.25", "90", "0", "2500", "30000"},
                                                  {simbody, "x_p", "1e-16", "c1", "0.3", "0", "6000", "2500", "30000"}})}};
  const Part& part = partNumbered(13);
  const ReportPart d = part.describe(tables);
  EXPECT_EQ(d.heading, "13. Engines: which engine, at what cost, how exact");
  EXPECT_EQ(findParagraph(d, "at k = 1, cheapest"),
            "Cost per evaluation at k = 1, cheapest first (one Google Benchmark run): " + analytic + " 50 ns, " + simbody +
                " 2.5e+03 ns.");
  EXPECT_EQ(findParagraph(d, "at k = 12, cheapest"),
            "Cost per evaluation at k = 12, cheapest first (one Google Benchmark run): " + analytic + " 400 ns, " + simbody +
                " 3e+04 ns.");
  // Both engines within 1e-9: the cheapest is analytic, the cheapest multibody one costs 2500 / 50 = 50 x as much.
  EXPECT_EQ(findParagraph(d, "Within 1e-09"),
            "Within 1e-09 of the scale on every quantity: the cheapest engine is " + analytic + " (50 ns at k = 1); the "
            "cheapest multibody engine is " + simbody + " (2.5e+03 ns at k = 1, 50 x " + analytic + ").");
  EXPECT_NE(findParagraph(d, simbody + " (exact, gated): worst error 2e-14 of the scale, at Q, c2 (lambda 0.25), phi 90 deg, 0 rpm")
                .size(), 0u);
  ASSERT_EQ(d.rows.size(), 3u);
  EXPECT_EQ(d.rows[1][2], "2e-14");
}

TEST(PartsTest, OffsetReadsTheCentricErrorAndTheThrust) {
  const TableSet tables = {
      {"offset", makeTable("offset", {{"quantity", kText}, {"offset_over_r", "-"}, {"max_rel_error", "-"},
                                      {"simbody_max_rel_error", "-"}, {"mujoco_max_rel_error", "-"}},
                           {{"x_p", "0.04", "0.001", "1e-15", "3e-16"}, {"a_p", "0.04", "0.002", "2e-15", "1e-15"},
                            {"x_p", "-0.04", "0.5", "1", "1"}})},
      {"offset_thrust", makeTable("offset_thrust", {{"engine", kText}, {"offset_over_r", "-"},
                                                    {"peak_major_thrust", "N"}, {"peak_minor_thrust", "N"},
                                                    {"thrust_reversal_deg", "deg"}, {"max_abs_drive_torque", "N m"}},
                                  {{"analytic", "0", "1000", "500", "", "80"}, {"analytic", "0.04", "1100", "450", "12.5", "81"},
                                   {"simbody", "0.04", "1", "1", "1", "1"}})}};
  const ReportPart d = partNumbered(14).describe(tables);
  EXPECT_EQ(d.heading, "14. Pin offset: what the centric formulas cost, what the offset buys");
  // Only delta / r = +0.04 counts (the negative row is not read), and the worst of the two rows over both reference
  // engines: 2e-15.
  EXPECT_EQ(findParagraph(d, "At |delta| / r = 0.04"),
            "At |delta| / r = 0.04 the centric forms are off by 0.001 in x_p, 0.002 in a_p (relative to each scale; the "
            "exact offset engine agrees with every reference engine to 2e-15).");
  // 1100 / 1000 - 1 = 10 %; the centric engine's thrust does not change sign within 90 degrees.
  EXPECT_EQ(findParagraph(d, "delta / r = 0.04:"),
            "delta / r = 0.04: the peak major thrust is 1100 N against 1000 N centric (10 %), the peak minor thrust 450 N "
            "against 500 N, and the side thrust changes sign at 12.5 degrees from the firing outer dead centre (centric: "
            "none within 90).");
}

TEST(PartsTest, FlywheelReadsNortonsErrorAndSimbodysAgreement) {
  const TableSet tables = {
      {"flywheel_sizing", makeTable("flywheel_sizing", {{"scene", kText}, {"cycle", kText}, {"k", "-"},
                                                        {"speed_rpm", "rpm"}, {"exact_inertia", "kg m^2"},
                                                        {"norton_inertia", "kg m^2"}, {"norton_error", "-"},
                                                        {"norton_delta", "-"}},
                                    {{"car", "four-stroke", "4", "3000", "0.2", "0.18", "-0.1", "0.011"}})},
      {"flywheel_norton", makeTable("flywheel_norton", {{"speed_rpm", "rpm"}, {"k", "-"}, {"exact_inertia", "kg m^2"},
                                                        {"norton_inertia", "kg m^2"}, {"norton_error", "-"},
                                                        {"norton_delta", "-"}},
                                    {{"3000", "1", "1", "1.05", "0.05", "0.01"}, {"3000", "4", "1", "0.8", "-0.2", "0.012"}})},
      {"flywheel", makeTable("flywheel", {{"scene", kText}, {"flywheel_inertia", "kg m^2"}, {"exact_delta", "-"},
                                          {"simbody_delta", "-"}},
                             {{"car", "0.2", "0.01", "0.0101"}, {"car", "0.3", "0.007", ""}})}};
  const ReportPart d = partNumbered(15).describe(tables);
  EXPECT_EQ(d.heading, "15. Flywheel sizing: the exact inertia, Norton's method, Simbody's run");
  EXPECT_EQ(findParagraph(d, "car at C = 0.01"),
            "car at C = 0.01: the exact flywheel is 0.2 kg m^2, Norton's 0.18 kg m^2 (-10 %), which really gives delta = "
            "0.011.");
  // |error| 5 % at k = 1 (best), 20 % at k = 4 (worst).
  EXPECT_NE(findParagraph(d, "Norton's inertia is off by 5 % at best (k = 1, 3000 rpm) and 20 % at worst (k = 4, 3000 rpm)").size(), 0u);
  // 0.0101 / 0.01 - 1 = 0.01 at the one point Simbody ran.
  EXPECT_NE(findParagraph(d, "delta to 0.01 (relative)").size(), 0u);
}

TEST(PartsTest, BalanceShaftsReadWhatTheShaftsCancel) {
  // Force scale 100 N / 0.5 = 200 N; the shafts take harmonic 1 to 0 in closed form, Simbody leaves 5e-16 of the
  // scale, harmonic 2 is unchanged.
  const TableSet tables = {
      {"balance_shafts", makeTable("balance_shafts", {{"case", kText}, {"shafts", kText}, {"engine", kText}, {"n", "-"},
                                                      {"force_amplitude", "N"}, {"force_relative", "-"}},
                                   {{"single", "none", "analytic", "1", "100", "0.5"},
                                    {"single", "none", "analytic", "2", "20", "0.1"},
                                    {"single", "with", "analytic", "1", "0", "0"},
                                    {"single", "with", "analytic", "2", "20", "0.1"},
                                    {"single", "with", "simbody", "1", "1e-13", "5e-16"},
                                    {"single", "with", "simbody", "2", "20", "0.1"}})}};
  const ReportPart d = partNumbered(16).describe(tables);
  EXPECT_EQ(d.heading, "16. Balance shafts: what a designed set cancels, by every engine");
  ASSERT_EQ(d.paragraphs.size(), 1u);
  EXPECT_EQ(d.paragraphs[0],
            "single: harmonic 1 of the shaking force falls from 100 N (0.5 of the force scale) to 0 N in closed form; the "
            "largest residual of the other exact engines is 5e-16 of the force scale (simbody); the closed form of every "
            "other harmonic is unchanged.");
}

}  // namespace
}  // namespace crankcheck::validation
