// The registry of report parts (parts.h), and describe() of parts on a small fixed TableSet: the heading
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
  int numbered = 0;
  bool core = true;  // the parts always run come first
  for (size_t i = 0; i < parts.size(); ++i) {
    const Part& part = *parts[i];
    SCOPED_TRACE(part.key());
    EXPECT_TRUE(keys.insert(part.key()).second) << "key twice";
    if (part.always()) {
      EXPECT_TRUE(core) << "a part always run after a numbered one";
      EXPECT_EQ(part.number(), 0);
      EXPECT_EQ(part.heading(), part.title());
    } else {
      core = false;
      // 1..N in report order, counting the numbered parts only.
      EXPECT_EQ(part.number(), ++numbered);
      EXPECT_EQ(part.heading(), std::to_string(part.number()) + ". " + part.title());
    }
    for (const std::string& t : part.tables()) EXPECT_TRUE(tables.insert(t).second) << t << ": written by two parts";
    // Each figure is drawn from its own table: data/NAME.csv.
    for (const std::string& f : part.figures()) {
      EXPECT_TRUE(figures.insert(f).second) << f;
      const std::vector<std::string> own = part.tables();
      EXPECT_NE(std::find(own.begin(), own.end(), f), own.end()) << f << " is not among the part's tables";
    }
  }
  EXPECT_EQ(parts.back()->number(), numbered);
  EXPECT_EQ(listPartKeys().size(), static_cast<size_t>(numbered));
}

TEST(PartsTest, EveryPartWithAFigureIsLeftOutWithoutItsTables) {
  for (const Part* part : listParts())
    if (!part->figures().empty()) {
      EXPECT_TRUE(part->describe({}).heading.empty()) << part->key();
    }
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

}

TEST(PartsTest, TorsionFindsTheResonancesAndReadsHolzersError) {
  // One scene "s", three speeds. The exact curve peaks at 2000 rpm (1, 3, 2 mrad): the parabola through the three
  // points has its vertex at 2000 + 500 (1 - 2) / (1 - 6 + 2) = 2166.67 rpm. Order 6 rises there (2 mrad against its
  // neighbours' 0.5: +1.5), order 2 does not (1, 1, 1), so the peak is order 6 at 6 x 2166.67 / 60 = 216.67 Hz, nearest
  // mode 2 (250 Hz; mode 1 is at 100 Hz), whose order-6 critical speed is 250 x 60 / 6 = 2500 rpm. Holzer's curve
  // (1, 2, 3 mrad) rises throughout: no peak, so Holzer misses the exact one.
  const std::vector<Column> sweep_columns = {{"scene", kText},        {"speed_rpm", "rpm"},    {"holzer", "rad"},
                                             {"holzer_order24", "rad"}, {"exact", "rad"},       {"difference", "-"},
                                             {"worst_difference", "-"}, {"section", kText},     {"worst_section", kText},
                                             {"error_bound", "rad"}};
  TableSet tables = {
      {"torsion", makeTable("torsion", sweep_columns,
                            {{"s", "1000", "0.001", "0.00101", "0.001", "0", "0.005", "a-b", "a-b", "1e-10"},
                             {"s", "2000", "0.002", "0.002", "0.003", "0.5", "0.5", "a-b", "a-b", "1e-10"},
                             {"s", "3000", "0.003", "0.003", "0.002", "-0.333", "-0.2", "a-b", "b-c", "1e-10"}})},
      {"torsion_orders",
       makeTable("torsion_orders", {{"scene", kText}, {"speed_rpm", "rpm"}, {"order", "-"}, {"holzer", "rad"}, {"exact", "rad"}},
                 {{"s", "1000", "2", "0.001", "0.001"}, {"s", "1000", "6", "0.0005", "0.0005"},
                  {"s", "2000", "2", "0.001", "0.001"}, {"s", "2000", "6", "0.0005", "0.002"},
                  {"s", "3000", "2", "0.001", "0.001"}, {"s", "3000", "6", "0.0005", "0.0005"}})},
      {"torsion_modes", makeTable("torsion_modes", {{"scene", kText}, {"mode", "-"}, {"holzer_hz", "Hz"}, {"min_hz", "Hz"},
                                                    {"max_hz", "Hz"}, {"firings_per_turn", "-"}},
                                  {{"s", "1", "100", "90", "110", "2"}, {"s", "2", "250", "240", "260", "2"}})},
      {"torsion_inertia",
       makeTable("torsion_inertia", {{"scene", kText}, {"throw", "-"}, {"exact_inertia", "kg m^2"}, {"min_inertia", "kg m^2"},
                                     {"max_inertia", "kg m^2"}, {"half_reciprocating", "kg m^2"},
                                     {"half_reciprocating_error", "-"}, {"second_order", "kg m^2"},
                                     {"second_order_error", "-"}},
                 {{"s", "0", "0.01", "0.009", "0.012", "0.0099", "-0.01", "0.01", "0"}})},
      {"torsion_ratio",
       makeTable("torsion_ratio", {{"scene", kText}, {"piston_mass_factor", "-"}, {"ratio", "-"}, {"order", "-"},
                                   {"speed_rpm", "rpm"}, {"holzer", "rad"}, {"exact", "rad"}, {"worst_difference", "-"}},
                 {{"s", "1", "0.5", "6", "1000", "0.001", "0.00102", "0.02"},
                  {"s", "4", "2", "6", "800", "0.001", "0.0012", "0.2"},
                  {"s", "16", "8", "6", "600", "0.001", "", ""}})},
      {"torsion_cost", makeTable("torsion_cost", {{"scene", kText}, {"route", kText}, {"speed_rpm", "rpm"}, {"seconds", "s"}},
                                 {{"s", "holzer", "1000", "0.1"}, {"s", "holzer", "2000", "0.3"}})}};
  const Part& part = partNumbered(17);
  part.derive(tables);
  ASSERT_TRUE(tables.count("torsion_resonances"));
  const Table& peaks = tables.at("torsion_resonances");
  ASSERT_EQ(peaks.rows.size(), 1u);
  EXPECT_EQ(peaks.rows[0][1], "exact");
  EXPECT_EQ(peaks.rows[0][2], "6");
  EXPECT_EQ(peaks.rows[0][3], "2");
  EXPECT_NEAR(std::stod(peaks.rows[0][4]), 2000.0 + 500.0 / 3.0, 1e-9);
  EXPECT_NEAR(std::stod(peaks.rows[0][5]), 6.0 * (2000.0 + 500.0 / 3.0) / 60.0, 1e-9);
  EXPECT_NEAR(std::stod(peaks.rows[0][6]), 2500.0, 1e-9);
  const ReportPart d = part.describe(tables);
  EXPECT_EQ(d.heading, "17. Torsional vibration: Holzer's constant inertia against the exact crank train");
  // |worst difference| 0.005 <= 1 % at 1000 rpm; 0.5 > 10 % at 2000; 0.2 > 10 % at 3000. The cut at 24: 1 % at 1000.
  EXPECT_EQ(findParagraph(d, "3 speeds"),
            "s, 3 speeds from 1000 to 3000 rpm: Holzer's peak-to-peak twist (every order summed) is within 1 % of the exact "
            "steady state's on every section at 1 of them and off by more than 10 % on some section at 2; at worst 50 % "
            "(a-b, 2000 rpm). The textbook's sum cut at order 24 differs from the converged sum by up to 1 % (at 1000 rpm).");
  EXPECT_NE(findParagraph(d, "s: the exact steady state peaks at order 6 at 2167 rpm (mode 2; Holzer's critical speed 2500 "
                             "rpm, -13.3 %), where Holzer's sum has no peak within 5 %").size(), 0u);
  // Mode 1: 100 Hz, band 90 .. 110 Hz: 20 %.
  EXPECT_NE(findParagraph(d, "at 110 and 90 Hz: a spread of 20 %").size(), 0u);
  // The ratio sweep: 2 % at 0.5, 20 % at 2 (the first beyond 10 %), no periodic state at 8.
  EXPECT_NE(findParagraph(d, "off by 2 % at 0.5, 20 % at 2, no periodic state at 8. The constant-inertia model is off by "
                             "more than 10 % from a ratio of 2 on.").size(), 0u);
  EXPECT_NE(findParagraph(d, "holzer 0.2 s (2 points)").size(), 0u);
}

}  // namespace
}  // namespace crankcheck::validation
