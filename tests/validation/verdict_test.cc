// The verdict (verdict.h) on a small fixed crosscheck table: counts, the worst comparison against its tolerance, the
// ctest-style closing line, the soft engines' line, and the engine x quantity matrix. Every expected number is
// counted by hand from the rows below.

#include "crankcheck/validation/verdict.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "crankcheck/validation/report.h"
#include "crankcheck/validation/report_document.h"

namespace crankcheck::validation {
namespace {

Table crosscheck() {
  Table t = kCrossCheckTable.table();
  std::vector<CrossCheckRow>& rows = t.getRows(kCrossCheckTable);
  // simbody: 2 cases, 4 comparisons; the worst ratio 0.5 (x_p of case b), the largest error 4e-15 (Q of case a,
  // ratio 0.04).
  rows.push_back({"fam", "simbody", "a", 0.3, "Q", 4e-15, 45, 6000, 1e-13, "pass"});
  rows.push_back({"fam", "simbody", "a", 0.3, "x_p", 1e-16, 90, 6000, 1e-14, "pass"});
  rows.push_back({"fam", "simbody", "b", 0.9, "Q", 1e-15, 0, 0, 1e-13, "pass"});
  rows.push_back({"fam", "simbody", "b", 0.9, "x_p", 5e-15, 180, 0, 1e-14, "pass"});
  // mujoco: 1 case, 2 comparisons, one beyond its tolerance (ratio 3).
  rows.push_back({"fam", "mujoco", "a", 0.3, "Q", 3e-13, 90, 6000, 1e-13, "FAIL"});
  rows.push_back({"fam", "mujoco", "a", 0.3, "x_p", 1e-16, 90, 6000, 1e-14, "pass"});
  // a soft engine: measured, never gated; its largest error 0.2 of the scale.
  rows.push_back({"fam", "mujoco-soft", "a", 0.3, "Q", 0.2, 90, 6000, 1e-13, "reported"});
  rows.push_back({"fam", "mujoco-soft", "a", 0.3, "x_p", 0.01, 90, 6000, 1e-14, "reported"});
  return t;
}

TEST(VerdictTest, CountsCasesComparisonsAndTheWorstAgainstItsTolerance) {
  const std::vector<EngineVerdict> v = calcVerdicts({{"crosscheck", crosscheck()}});
  ASSERT_EQ(v.size(), 3u);
  // The registry's order: simbody, mujoco, mujoco-soft.
  EXPECT_EQ(v[0].engine, "simbody");
  EXPECT_EQ(v[0].cases, 2u);
  EXPECT_EQ(v[0].comparisons, 4u);
  EXPECT_EQ(v[0].failed, 0u);
  EXPECT_DOUBLE_EQ(v[0].worst_ratio, 0.5);
  EXPECT_DOUBLE_EQ(v[0].worst_error, 5e-15);
  EXPECT_EQ(v[0].worst_quantity, "x_p");
  EXPECT_EQ(v[0].worst_where, "b, phi 180 deg, 0 rpm");
  EXPECT_TRUE(v[0].pass());
  EXPECT_EQ(v[1].engine, "mujoco");
  EXPECT_EQ(v[1].failed, 1u);
  EXPECT_DOUBLE_EQ(v[1].worst_ratio, 3.0);
  EXPECT_FALSE(v[1].pass());
  EXPECT_EQ(v[2].engine, "mujoco-soft");
  EXPECT_FALSE(v[2].gated);
  EXPECT_TRUE(v[2].pass());
  EXPECT_DOUBLE_EQ(v[2].worst_error, 0.2);  // the largest error, whatever its ratio
  EXPECT_FALSE(allAgree(v));
}

// Issue 47: the terminal (the tables in the order the tasks ended) and the report (sorted) named different places for
// the same worst comparison of an exact tie. One rule now (isWorseComparison): of equal values the smaller `where`,
// in whatever order the rows come; the report's summary by the same rule.
TEST(VerdictTest, AnExactTieIsBrokenTheSameWayInEveryOrder) {
  Table t = crosscheck();
  std::vector<CrossCheckRow>& rows = t.getRows(kCrossCheckTable);
  rows.resize(4);  // simbody's rows; a second x_p of ratio exactly 0.5 (5e-15 / 1e-14), at case a
  rows.push_back({"fam", "simbody", "a", 0.3, "x_p", 5e-15, 270, 6000, 1e-14, "pass"});
  for (int order = 0; order < 2; ++order) {
    if (order == 1) std::reverse(rows.begin(), rows.end());
    const std::vector<EngineVerdict> v = calcVerdicts({{"crosscheck", t}});
    ASSERT_EQ(v.size(), 1u);
    EXPECT_EQ(v[0].worst_where, "a, phi 270 deg, 6000 rpm") << order;  // "a, ..." before "b, ..."
    for (const SummaryRow& s : summarize({{"crosscheck", t}}))
      if (s.quantity == "x_p") EXPECT_EQ(s.where, "a, phi 270 deg, 6000 rpm") << order;
  }
}

TEST(VerdictTest, ClosesWithOneLineInCtestsStyle) {
  const std::string text = formatVerdict(calcVerdicts({{"crosscheck", crosscheck()}}));
  // 6 gated comparisons, 1 failed: 5 * 100 / 6 = 83.3, floored.
  EXPECT_NE(text.find("\n83% of comparisons agree, 1 failed out of 6 (gated engines: simbody, mujoco)\n"), std::string::npos)
      << text;
  EXPECT_NE(text.find("FAIL (1)"), std::string::npos) << text;
  EXPECT_NE(text.find("comparisons  pass\n    worst 0.5 of tolerance (x_p: b, phi 180 deg, 0 rpm)\n"), std::string::npos)
      << text;
  EXPECT_NE(text.find("comparisons  not gated\n    largest error 0.2 of scale (Q)\n"), std::string::npos) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 7);  // two lines per engine (within 100 columns), one closing
}

TEST(VerdictTest, AllAgreeIsOneHundredPercentAndNothingElse) {
  Table t = crosscheck();
  t.getRows(kCrossCheckTable).erase(t.getRows(kCrossCheckTable).begin() + 4);  // the failing row
  const std::vector<EngineVerdict> v = calcVerdicts({{"crosscheck", t}});
  EXPECT_TRUE(allAgree(v));
  EXPECT_NE(formatVerdict(v).find("\n100% of comparisons agree, 0 failed out of 5 "), std::string::npos);
  // One failure in 1000 is 99%, never a rounded-up 100%.
  Table many = t;
  std::vector<CrossCheckRow>& many_rows = many.getRows(kCrossCheckTable);
  many_rows.resize(0);
  for (int i = 0; i < 999; ++i) many_rows.push_back({"fam", "simbody", "c" + std::to_string(i), 0.3, "Q", 1e-15, 0, 0, 1e-13, "pass"});
  many_rows.push_back({"fam", "simbody", "x", 0.3, "Q", 1e-12, 0, 0, 1e-13, "FAIL"});
  EXPECT_NE(formatVerdict(calcVerdicts({{"crosscheck", many}})).find("\n99% of comparisons agree, 1 failed out of 1000 "),
            std::string::npos);
}

TEST(VerdictTest, MatrixHoldsTheWorstRatioOfEachGatedEngineAndQuantity) {
  const VerdictMatrix m = calcVerdictMatrix({{"crosscheck", crosscheck()}});
  ASSERT_EQ(m.engines, (std::vector<std::string>{"simbody", "mujoco"}));  // soft engines are not gated
  ASSERT_EQ(m.quantities, (std::vector<std::string>{"Q", "x_p"}));         // eval's order
  EXPECT_DOUBLE_EQ(m.ratio[0][0], 0.04);
  EXPECT_DOUBLE_EQ(m.ratio[0][1], 0.5);
  EXPECT_DOUBLE_EQ(m.ratio[1][0], 3.0);
  EXPECT_DOUBLE_EQ(m.ratio[1][1], 0.01);
  EXPECT_EQ(formatMatrixCell(0.04), std::string(kCellMarks[0]) + " 0.04");
  EXPECT_EQ(formatMatrixCell(0.5), std::string(kCellMarks[1]) + " 0.5");
  EXPECT_EQ(formatMatrixCell(0.75), std::string(kCellMarks[2]) + " 0.75");
  EXPECT_EQ(formatMatrixCell(3.0), std::string(kCellMarks[3]) + " 3 FAIL");
  EXPECT_EQ(formatMatrixCell(-1.0), "-");
}

TEST(VerdictTest, NoCrosscheckTableMeansNoVerdictAndNoClaim) {
  EXPECT_TRUE(calcVerdicts({}).empty());
  EXPECT_EQ(formatVerdict({}), "No comparison of a gated engine: nothing was checked\n");
}

}  // namespace
}  // namespace crankcheck::validation
