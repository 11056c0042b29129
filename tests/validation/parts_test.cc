// The registry of report parts (parts.h), and describe() of parts on a small fixed TableSet: the heading
// and the numbers the sentences read from the data. Every expected number is worked out by hand from the rows below.

#include "crankcheck/validation/parts.h"

#include <gtest/gtest.h>

#include "crankcheck/validation/csv.h"
#include "crankcheck/validation/table_schemas.h"

#include <algorithm>
#include <map>
#include <set>
#include <string>

#include "crankcheck/validation/engines.h"
#include "part_fixture.h"

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
  return parseTable(name, parseCsv(formatCsv(t), name), name, findTableSchema(name));
}

using testing::findParagraph;

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

}  // namespace
}  // namespace crankcheck::validation
