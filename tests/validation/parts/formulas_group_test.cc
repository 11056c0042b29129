// describe() of the parts that judge the closed forms and the printed formulas (error_vs_lambda, speed_vs_error,
// integrator_pareto, errata, flywheel) on small fixed tables of their own, written as the CSV text the report writes
// and read back through the parts' schemas (csv.h, as `report merge` reads them): the CSV headers below are written by
// hand, so a column renamed, moved or given another unit fails here. Every expected number is worked out by hand from
// the rows below.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "crankcheck/validation/csv.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/parts.h"
#include "part_fixture.h"

namespace crankcheck::validation {
namespace {

using testing::readTable;

// The paragraphs of `part` (its sentences and its blocks' paragraphs), in order.
std::vector<std::string> listParagraphs(const ReportPart& part) {
  std::vector<std::string> out = part.paragraphs;
  for (const ReportBlock& b : part.blocks)
    if (b.kind == ReportBlock::kParagraph) out.push_back(b.text);
  return out;
}

// The paragraph that starts with `start`, or "" (the expectations on it then fail).
std::string findParagraphStartingWith(const ReportPart& part, const std::string& start) {
  for (const std::string& p : listParagraphs(part))
    if (p.rfind(start, 0) == 0) return p;
  return "";
}

// The first table block of `part`, or nullptr.
const ReportBlock* findTableBlock(const ReportPart& part) {
  for (const ReportBlock& b : part.blocks)
    if (b.kind == ReportBlock::kTable) return &b;
  return nullptr;
}

TEST(FormulasGroupTest, PartsWriteTheirTables) {
  EXPECT_EQ(findPart("error_vs_lambda").tables(), std::vector<std::string>{"error_vs_lambda"});
  EXPECT_EQ(findPart("speed_vs_error").tables(), std::vector<std::string>{"speed_vs_error"});
  EXPECT_EQ(findPart("integrator_pareto").tables(), std::vector<std::string>{"integrator_pareto"});
  EXPECT_EQ(findPart("errata").tables(),
            (std::vector<std::string>{"errata", "eq5_layouts", "eq15_coefficients", "eq15_engines"}));
  EXPECT_EQ(findPart("flywheel").tables(), (std::vector<std::string>{"flywheel", "flywheel_sizing", "flywheel_norton"}));
  // `report merge` finds each of them through the parts' schemas.
  for (const char* name : {"error_vs_lambda", "speed_vs_error", "integrator_pareto", "errata", "eq5_layouts",
                                  "eq15_coefficients", "eq15_engines", "flywheel", "flywheel_sizing", "flywheel_norton"})
    EXPECT_NE(findTableSchema(name), nullptr) << name;
}

// ---- error_vs_lambda: its figure alone --------------------------------------------------------------------------

TEST(FormulasGroupTest, ErrorVsLambdaIsItsFigure) {
  const Part& part = findPart("error_vs_lambda");
  const TableSet tables = {
      {"error_vs_lambda",
       readTable("error_vs_lambda",
                    "quantity,method,lambda [-],max_abs_error [SI],max_rel_error [-],resolved\n"
                    "x_p,norton_two_term,0.3,0.0002,0.004,1\n"
                    "Q,analytic_vs_simbody,0.3,1e-15,2e-16,0\n")}};
  const ReportPart d = part.describe(tables);
  EXPECT_EQ(d.heading, part.heading());
  EXPECT_NE(d.caption.find("Max error over the crank turn against lambda"), std::string::npos) << d.caption;
  EXPECT_TRUE(part.describe({}).heading.empty());
  // Its maxima (tests/cli/quick_report_test.cc): columns of the table, the engines' agreement a bound.
  ASSERT_EQ(part.maxima().size(), 1u);
  EXPECT_EQ(part.maxima()[0].bound_column, "resolved");
  EXPECT_EQ(part.maxima()[0].bound_value, "0");
}

// ---- speed_vs_error: the figure, the table to 4 digits, the note on resolution ----------------------------------

TEST(FormulasGroupTest, SpeedVsErrorListsEveryMethod) {
  const Part& part = findPart("speed_vs_error");
  const TableSet tables = {
      {"speed_vs_error", readTable("speed_vs_error",
                                      "method,ns_per_eval [ns],max_rel_error [-],resolved\n"
                                      "exact_closed_form,45.09569847526984,6.865069790820466e-16,0\n"
                                      "fourier_order_4,135.24,7.28312e-06,1\n")}};
  const ReportPart d = part.describe(tables);
  EXPECT_EQ(d.heading, part.heading());
  const ReportBlock* table = findTableBlock(d);
  ASSERT_NE(table, nullptr);
  EXPECT_EQ(table->header,
            (std::vector<std::string>{"method", "time per evaluation [ns]", "max error / energy scale [-]", "resolved"}));
  EXPECT_EQ(table->rows, (std::vector<std::vector<std::string>>{{"exact_closed_form", "45.1", "6.865e-16", "0"},
                                                                 {"fourier_order_4", "135.2", "7.283e-06", "1"}}));
  EXPECT_NE(findParagraphStartingWith(d, "Each error is the maximum over the turn").size(), 0u);
  EXPECT_TRUE(part.describe({}).heading.empty());
}

// ---- integrator_pareto: the table, a failed run as nan ----------------------------------------------------------

TEST(FormulasGroupTest, IntegratorParetoListsEveryRunAFailedOneAsNan) {
  const Part& part = findPart("integrator_pareto");
  const TableSet tables = {
      {"integrator_pareto",
       readTable("integrator_pareto",
                    "integrator,accuracy [-],ns_per_revolution [ns],delta_error [-],energy_drift [-],status,engine\n"
                    "CPodes,1e-07,31118234.5,4.62712e-05,3.61711e-06,ok,simbody\n"
                    "ExplicitEuler,0.001,nan,nan,nan,failed,simbody\n")}};
  const ReportPart d = part.describe(tables);
  EXPECT_EQ(d.heading, part.heading());
  EXPECT_EQ(d.rows, (std::vector<std::vector<std::string>>{{"CPodes", "1e-07", "3.112e+07", "4.627e-05", "3.617e-06", "ok"},
                                                            {"ExplicitEuler", "0.001", "nan", "nan", "nan", "failed"}}));
  EXPECT_TRUE(part.describe({}).heading.empty());
}

// ---- errata: rows found by their full item and measure ----------------------------------------------------------

// The base's lambda is 0.45 here: its items ("... at lambda = 0.45") start like the paper's ("... at lambda = 0.4"),
// so a row found by the start of its item would be the wrong one.
const char* const kErrataCsv =
    "item,printed,holds,measure,value [see measure],verdict\n"
    "Stanczak eq (5): U1 for the base rod (z_k / l = 0.250),\"U1 = M_t + l_z M_z, l_z = z_k / l\",U1 from eq (2),"
    "printed / true,1.5,error\n"
    "Stanczak eq (5): U2 for the base rod (z_k / l = 0.250),\"U2 = M_s - M_sp + l_z* M_z, l_z* = (l - z_k) / l\","
    "U2 from eq (2),printed / true,0.2,error\n"
    "\"Stanczak eq (5): Q of a standing single cylinder, worst: k = 1\",\"U1, U2 as printed\",\"U1, U2 from eq (2)\","
    "max |Q_printed - Q| / max |Q|,0.05,error\n"
    "\"Stanczak eq (5): Q of a standing single cylinder, worst: k = 1\",\"U1, U2 as printed\",\"U1, U2 from eq (2)\","
    "max |Q_printed| / max |Q|,1.01,error\n"
    "\"Stanczak eq (5): Q of a standing multi-cylinder, worst: k = 3 four-stroke\",\"U1, U2 as printed\","
    "\"U1, U2 from eq (2)\",max |Q_printed - Q| / max |Q|,0.2,error\n"
    "\"Stanczak eq (5): Q of a standing multi-cylinder, worst: k = 3 four-stroke\",\"U1, U2 as printed\","
    "\"U1, U2 from eq (2)\",max |Q_printed| / max |Q|,1.25,error\n"
    "\"Stanczak eq (5): Q of a lying single cylinder, worst: k = 1\",\"U1, U2 as printed\",\"U1, U2 from eq (2)\","
    "max |Q_printed| / max |Q|,0.8,error\n"
    "Stanczak eq (15): Lambda_12 at lambda = 0.45,power series to lambda^11,exact Lambda_n,printed / exact - 1,-0.5,"
    "truncation\n"
    "Stanczak eq (15): Lambda_12 at lambda = 0.4,power series to lambda^11,exact Lambda_n,printed / exact - 1,-0.375,"
    "truncation\n"
    "Stanczak eq (15): Lambda_10 at lambda = 0.45,power series to lambda^11,exact Lambda_n,printed / exact - 1,-0.1,"
    "truncation\n"
    "Stanczak eq (15): Lambda_10 at lambda = 0.4,power series to lambda^11,exact Lambda_n,printed / exact - 1,-0.07,"
    "truncation\n"
    "Stanczak eq (15): Lambda_8 at lambda = 0.45,power series to lambda^11,exact Lambda_n,printed / exact - 1,-0.02,"
    "truncation\n"
    "Stanczak eq (15): Lambda_8 at lambda = 0.4,power series to lambda^11,exact Lambda_n,printed / exact - 1,-0.01,"
    "truncation\n"
    "Stanczak eq (15): Q of a standing k = 12 two-stroke at lambda = 0.45,Lambda_2..Lambda_12 to lambda^11,"
    "exact Lambda_n,max |Q_printed - Q| / max |Q|,0.5,truncation\n"
    "Stanczak eq (15): Q of a standing k = 12 two-stroke at lambda = 0.4,Lambda_2..Lambda_12 to lambda^11,"
    "exact Lambda_n,max |Q_printed - Q| / max |Q|,0.375,truncation\n"
    "Stanczak eq (15): Q of a standing k = 5 two-stroke at lambda = 0.4,Lambda_2..Lambda_12 to lambda^11,"
    "exact Lambda_n,max |Q_printed - Q| / max |Q|,0.07,truncation\n"
    "Stanczak eq (15): Q of a standing k = 5 four-stroke at lambda = 0.4,Lambda_2..Lambda_12 to lambda^11,"
    "exact Lambda_n,max |Q_printed - Q| / max |Q|,0.07,truncation\n"
    "Stanczak eq (15): printed coefficients,\"Lambda_2..Lambda_12, lambda^1..lambda^11\",exact rationals,"
    "count printed,21,count\n"
    "Stanczak eq (15): printed coefficients,six decimals,exact rational rounded to six decimals,"
    "count equal to the rounded exact value,20,count\n"
    "\"Stanczak section 7: first surviving order, k = 7 two-stroke\",for example k = 7: first non-zero at Lambda_14,"
    "exact integer analysis,harmonic order,14,confirmed\n"
    "\"Stanczak section 7: first surviving order, k = 7 four-stroke\",(not stated),exact integer analysis,"
    "harmonic order,14,confirmed\n";

// The standing engines: k = 2 two-stroke has no errata row (not the worst), k = 3 four-stroke has.
const char* const kEq5LayoutsCsv =
    "cycle,k [-],gamma_deg [deg],max_abs_Q [N m],max_abs_Q_printed [N m],ratio_of_maxima [-],max_error_rel [-]\n"
    "two-stroke,1,90,10,10.1,1.01,0.05\n"
    "two-stroke,2,90,1,1.2,1.2,0.19\n"
    "four-stroke,3,90,1,1.25,1.25,0.2\n"
    "two-stroke,1,0,10,8,0.8,0.2\n";

const char* const kEq15CoefficientsCsv =
    "n [-],lambda [-],printed [-],exact [-],relative_error [-]\n"
    "12,0.4,6.25e-08,1e-07,-0.375\n"
    "12,0.45,1e-07,2e-07,-0.5\n";

// k = 3 two-stroke: under 1 %, no errata row, not listed.
const char* const kEq15EnginesCsv =
    "cycle,k [-],lambda [-],first_order [-],max_abs_Q [N m],max_abs_Q_printed [N m],ratio_of_maxima [-],"
    "max_error_rel [-]\n"
    "two-stroke,3,0.4,6,1,1.001,1.001,0.001\n"
    "two-stroke,5,0.4,10,1,1.07,1.07,0.07\n"
    "four-stroke,5,0.4,10,1,1.07,1.07,0.07\n"
    "two-stroke,12,0.4,12,1,1.375,1.375,0.375\n"
    "two-stroke,12,0.45,12,1,1.5,1.5,0.5\n";

TableSet makeErrataTables() {
  return {{"errata", readTable("errata", kErrataCsv)},
          {"eq5_layouts", readTable("eq5_layouts", kEq5LayoutsCsv)},
          {"eq15_coefficients", readTable("eq15_coefficients", kEq15CoefficientsCsv)},
          {"eq15_engines", readTable("eq15_engines", kEq15EnginesCsv)}};
}

TEST(FormulasGroupTest, ErrataReadsEachEntryByItsItemAndMeasure) {
  const Part& part = findPart("errata");
  const ReportPart d = part.describe(makeErrataTables());
  EXPECT_EQ(d.heading, part.heading());
  // The table: every row, the value to 3 digits.
  const ReportBlock* table = findTableBlock(d);
  ASSERT_NE(table, nullptr);
  ASSERT_EQ(table->rows.size(), 21u);
  EXPECT_EQ(table->rows[8], (std::vector<std::string>{"Stanczak eq (15): Lambda_12 at lambda = 0.4",
                                                      "power series to lambda^11", "exact Lambda_n",
                                                      "printed / exact - 1", "-0.375", "truncation"}));
  // U1 1.5, U2 0.2; standing single cylinder 5 %; the standing multi-cylinder worst (k = 3 four-stroke) 1.25 - 1 =
  // 25 %; lying 1 - 0.8 = 20 %.
  EXPECT_EQ(findParagraphStartingWith(d, "Eq (5) as printed"),
            "Eq (5) as printed: for the base rod the printed U1 is 1.5 x and U2 0.2 x the true values. A standing single "
            "cylinder hides it (Q is off by 5 % of its maximum, U1 + U2 barely changes); a standing engine whose first "
            "surviving harmonic is even (two-stroke k >= 2, four-stroke k >= 3: Q carries U1 alone) gets max |Q| 25 % "
            "too high; a lying single cylinder (Q carries U2 alone) 20 % too low. data/eq5_layouts.csv has every "
            "layout.");
  // At lambda = 0.4: Lambda_12 37.5 %, Lambda_10 7 %, Lambda_8 1 %; at the base's 0.45 Lambda_12 50 %. The engines
  // over 1 % at 0.4, largest first (a tie by name): not k = 12 at 0.45 (50 %), not k = 3 (no row).
  EXPECT_EQ(findParagraphStartingWith(d, "Eq (15) is a power series"),
            "Eq (15) is a power series truncated at lambda^11, so each printed Lambda_n falls short of the exact one: at "
            "lambda = 0.4, the paper's largest crank ratio, Lambda_12 by 37.5 % (still 50 % at the base's lambda = "
            "0.45), Lambda_10 by 7 %, Lambda_8 by 1 % (data/eq15_coefficients.csv). 'A close approximation' holds for "
            "the engines dominated by Lambda_2 and Lambda_4, not where only high harmonics survive: max |Q_printed - Q| "
            "/ max |Q| at lambda = 0.4 is k = 12 two-stroke 37.5 %, k = 5 four-stroke 7 %, k = 5 two-stroke 7 %; for "
            "k = 7, 9, 11 the table holds no surviving harmonic and gives Q = 0 (data/eq15_engines.csv, every engine).");
  // 21 printed, 20 rounded: 1 misprint.
  EXPECT_EQ(findParagraphStartingWith(d, "Eq (15) prints"),
            "Eq (15) prints 21 coefficients; 20 of them are the exact rationals rounded to six decimals, the other 1 is "
            "a misprint (Lambda_2, lambda^9).");
  // Two of the six engines have rows: two-stroke first.
  EXPECT_EQ(findParagraphStartingWith(d, "Section 7 says"),
            "Section 7 says that 'for example' k = 7 first gives a non-zero value at Lambda_14. The first surviving "
            "harmonic order, from the exact integer analysis: k = 7 two-stroke: 14, k = 7 four-stroke: 14.");
}

TEST(FormulasGroupTest, ErrataLeavesOutWhatItsTablesDoNotHold) {
  const Part& part = findPart("errata");
  EXPECT_TRUE(part.describe({}).heading.empty());
  // Without eq5_layouts the standing multi-cylinder row is not found: no eq (5) sentence; the others stay.
  TableSet tables = makeErrataTables();
  tables.erase("eq5_layouts");
  ReportPart d = part.describe(tables);
  EXPECT_EQ(d.heading, part.heading());
  EXPECT_EQ(findParagraphStartingWith(d, "Eq (5) as printed"), "");
  EXPECT_NE(findParagraphStartingWith(d, "Eq (15) prints").size(), 0u);
  // Without eq15_coefficients no base lambda: the sentence keeps the paper's lambda alone.
  tables = makeErrataTables();
  tables.erase("eq15_coefficients");
  d = part.describe(tables);
  const std::string eq15 = findParagraphStartingWith(d, "Eq (15) is a power series");
  EXPECT_NE(eq15.find("Lambda_12 by 37.5 %, Lambda_10 by 7 %"), std::string::npos) << eq15;
  // An empty errata table: the part is shown, its table empty, only the sentences that need no row.
  tables = makeErrataTables();
  tables["errata"] = readTable("errata", "item,printed,holds,measure,value [see measure],verdict\n");
  d = part.describe(tables);
  EXPECT_EQ(d.heading, part.heading());
  ASSERT_NE(findTableBlock(d), nullptr);
  EXPECT_TRUE(findTableBlock(d)->rows.empty());
  EXPECT_EQ(findParagraphStartingWith(d, "Eq (5) as printed"), "");
  EXPECT_EQ(findParagraphStartingWith(d, "Eq (15)"), "");
  EXPECT_EQ(findParagraphStartingWith(d, "Section 7"), "");
  EXPECT_NE(findParagraphStartingWith(d, "Eq (12) refers").size(), 0u);
}

// ---- flywheel: Norton's error, Simbody's agreement -------------------------------------------------------------

const char* const kFlywheelSizingCsv =
    "scene,cycle,k [-],speed_rpm [rpm],exact_inertia [kg m^2],norton_inertia [kg m^2],norton_error [-],"
    "norton_delta [-]\n"
    "car,four-stroke,4,3000,0.2,0.18,-0.1,0.011\n";
const char* const kFlywheelNortonCsv =
    "speed_rpm [rpm],k [-],exact_inertia [kg m^2],norton_inertia [kg m^2],norton_error [-],norton_delta [-]\n"
    "3000,1,1,1.05,0.05,0.01\n"
    "3000,4,1,0.8,-0.2,0.012\n";
// Simbody's run at one point (empty at the other).
const char* const kFlywheelCsv =
    "scene,flywheel_inertia [kg m^2],exact_delta [-],simbody_delta [-]\n"
    "car,0.2,0.01,0.0101\n"
    "car,0.3,0.007,\n";

TableSet makeFlywheelTables() {
  return {{"flywheel_sizing", readTable("flywheel_sizing", kFlywheelSizingCsv)},
          {"flywheel_norton", readTable("flywheel_norton", kFlywheelNortonCsv)},
          {"flywheel", readTable("flywheel", kFlywheelCsv)}};
}

TEST(FormulasGroupTest, FlywheelReadsNortonsErrorAndSimbodysAgreement) {
  const Part& part = findPart("flywheel");
  const ReportPart d = part.describe(makeFlywheelTables());
  EXPECT_EQ(d.heading, part.heading());
  EXPECT_EQ(part.title(), "Flywheel sizing: the exact inertia, Norton's method, Simbody's run");
  EXPECT_EQ(findParagraphStartingWith(d, "car at C = 0.01"),
            "car at C = 0.01: the exact flywheel is 0.2 kg m^2, Norton's 0.18 kg m^2 (-10 %), which really gives delta = "
            "0.011.");
  // |error| 5 % at k = 1 (best), 20 % at k = 4 (worst).
  EXPECT_NE(findParagraphStartingWith(d, "On the base scene's parts")
                .find("Norton's inertia is off by 5 % at best (k = 1, 3000 rpm) and 20 % at worst (k = 4, 3000 rpm)"),
            std::string::npos);
  // 0.0101 / 0.01 - 1 = 0.01 at the one point Simbody ran (the empty cell is no point).
  EXPECT_EQ(findParagraphStartingWith(d, "Simbody's run"),
            "Simbody's run agrees with the exact energy integral's delta to 0.01 (relative) at every point it was run.");
}

TEST(FormulasGroupTest, FlywheelNeedsItsThreeTables) {
  const Part& part = findPart("flywheel");
  EXPECT_TRUE(part.describe({}).heading.empty());
  for (const char* missing : {"flywheel", "flywheel_sizing", "flywheel_norton"}) {
    TableSet tables = makeFlywheelTables();
    tables.erase(missing);
    EXPECT_TRUE(part.describe(tables).heading.empty()) << missing;
  }
  // No engine of the sweep needs a flywheel: the scenes' sentences alone.
  TableSet tables = makeFlywheelTables();
  tables["flywheel_norton"] = readTable(
      "flywheel_norton",
      "speed_rpm [rpm],k [-],exact_inertia [kg m^2],norton_inertia [kg m^2],norton_error [-],norton_delta [-]\n");
  const ReportPart d = part.describe(tables);
  EXPECT_EQ(d.heading, part.heading());
  EXPECT_EQ(d.paragraphs.size(), 1u);
  EXPECT_NE(findParagraphStartingWith(d, "car at C = 0.01").size(), 0u);
}

}  // namespace
}  // namespace crankcheck::validation
