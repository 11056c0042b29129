// The tables of `crankcheck grade` (grade.h) through their schemas: the CSV files a grade writes keep the columns
// users and scripts read (docs/grade.md, reports/grade_error_vs_lambda.gp address them by header name), a report's
// files read back into typed rows and are written again byte for byte, and the exit status reads the typed verdicts.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "crankcheck/validation/csv.h"
#include "crankcheck/validation/table_schemas.h"
#include "crankcheck/validation/grade.h"

namespace crankcheck::validation {
namespace {

std::string headerOf(const TableSchema& schema) {
  const std::string text = formatCsv(schema.makeTable());
  return text.substr(0, text.find('\n'));
}

// The table `name` of the CSV `text`, read through its schema (the way `report merge` and readTables read it).
Table readCsv(const std::string& name, const std::string& text) { return parseTable(name, parseCsv(text, name), name, findTableSchema(name)); }

// The headers as grade wrote them before its tables were typed (the reference engines of this build: simbody and
// mujoco; the closed forms, analytic).
const std::string kSummaryHeader =
    "quantity,regime,asked [-],provided [-],largest_rel_error [-],largest_rel_error_simbody [-],"
    "largest_rel_error_analytic [-],largest_rel_error_mujoco [-],largest_where_case,largest_where_phi_deg [deg],"
    "largest_where_speed_rpm [rpm],rel_error_at_worst_ratio [-],worst_ratio [-],tolerance_rel [-],where_case,"
    "where_phi_deg [deg],where_speed_rpm [rpm],verdict";
const std::string kFailuresHeader =
    "case,family,lambda [-],quantity,cylinder [-],phi_deg [deg],speed_rpm [rpm],program_value [SI],simbody_value [SI],"
    "analytic_value [SI],rel_error [-],tolerance_rel [-],mujoco_value [SI]";

TEST(GradeTablesTest, TheColumnsAreTheOnesGradeAlwaysWrote) {
  EXPECT_EQ(headerOf(getGradeSummarySchema()), kSummaryHeader);
  EXPECT_EQ(headerOf(getGradeErrorVsLambdaSchema()),
            "quantity,lambda [-],program_max_rel_error [-],analytic_max_rel_error [-]");
  EXPECT_EQ(headerOf(getGradeFailuresSchema()), kFailuresHeader);
  for (const TableSchema* schema : {static_cast<const TableSchema*>(&getGradeSummarySchema()),
                                    static_cast<const TableSchema*>(&getGradeErrorVsLambdaSchema()),
                                    static_cast<const TableSchema*>(&getGradeFailuresSchema())}) {
    EXPECT_EQ(findGradeTableSchema(schema->name()), schema) << schema->name();
    EXPECT_EQ(findTableSchema(schema->name()), schema) << schema->name() << ": the CSV reader finds it";
  }
  EXPECT_EQ(findGradeTableSchema("crosscheck"), nullptr);
}

TEST(GradeTablesTest, AReportsFilesReadBackIntoTypedRowsAndAreWrittenAgainByteForByte) {
  // A provided quantity (every number there), one not provided (its numbers empty), as grade writes them.
  const std::string summary = kSummaryHeader + "\n"
      "x_p,all,672,336,0.084,0.0025,0.084,0.0025,c_lambda0p9_0rpm,270,0,0.083,5.6e+12,1.4880214483528175e-14,"
      "c_lambda0p9_0rpm,270,0,FAIL\n"
      "U,all,672,0,,,,,,,,,,,,,,not provided\n";
  const Table s = readCsv("grade_summary", summary);
  ASSERT_EQ(s.schema(), &getGradeSummarySchema());
  const std::vector<GradeSummaryRow>& rows = s.getRows(getGradeSummarySchema());
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].quantity, "x_p");
  EXPECT_EQ(rows[0].asked, 672);
  EXPECT_EQ(rows[0].provided, 336);
  EXPECT_EQ(rows[0].largest_rel_error, 0.084);
  // One error per judge, in listGradeJudges()'s order: simbody, analytic, mujoco.
  ASSERT_EQ(rows[0].largest_rel_error_by.size(), 3u);
  EXPECT_EQ(rows[0].largest_rel_error_by[0], 0.0025);
  EXPECT_EQ(rows[0].largest_rel_error_by[1], 0.084);
  EXPECT_EQ(rows[0].largest_rel_error_by[2], 0.0025);
  EXPECT_EQ(rows[0].largest_where_phi_deg, 270.0);
  EXPECT_EQ(rows[0].worst_ratio, 5.6e12);
  EXPECT_EQ(rows[0].tolerance_rel, 1.4880214483528175e-14);
  EXPECT_EQ(rows[0].where_case, "c_lambda0p9_0rpm");
  EXPECT_EQ(rows[0].verdict, "FAIL");
  EXPECT_EQ(rows[1].provided, 0);
  EXPECT_FALSE(rows[1].largest_rel_error.has_value());
  for (const auto& x : rows[1].largest_rel_error_by) EXPECT_FALSE(x.has_value());
  EXPECT_FALSE(rows[1].where_phi_deg.has_value());
  EXPECT_EQ(rows[1].where_case, "");
  EXPECT_EQ(formatCsv(s), summary);

  // A per-cylinder quantity's failure (cylinder 1) and one of the whole engine's (no cylinder).
  const std::string failures = kFailuresHeader + "\n"
      "c_lambda0p3_0rpm,c,0.296551724137931,x_p,1,45,0,0.12792202076473397,0.1277947153347162,0.1277947153347162,"
      "0.0006771565426476894,1.4880214483528175e-14,0.1277947153347163\n"
      "c_lambda0p9_3000rpm,c,0.9,U,,90,3000,12.5,12,12.25,0.5,2e-14,12\n";
  const Table f = readCsv("grade_failures", failures);
  const std::vector<GradeFailureRow>& fr = f.getRows(getGradeFailuresSchema());
  ASSERT_EQ(fr.size(), 2u);
  EXPECT_EQ(fr[0].cylinder, 1);
  EXPECT_EQ(fr[0].phi_deg, 45.0);
  EXPECT_EQ(fr[0].rel_error, 0.0006771565426476894);
  EXPECT_EQ(fr[0].judge_values, (std::vector<double>{0.1277947153347162, 0.1277947153347162, 0.1277947153347163}));
  EXPECT_FALSE(fr[1].cylinder.has_value());
  EXPECT_EQ(fr[1].speed_rpm, 3000.0);
  EXPECT_EQ(fr[1].program_value, 12.5);
  EXPECT_EQ(fr[1].judge_values, (std::vector<double>{12.0, 12.25, 12.0}));
  EXPECT_EQ(formatCsv(f), failures);

  const std::string by_lambda = "quantity,lambda [-],program_max_rel_error [-],analytic_max_rel_error [-]\n"
                                "a_p,0.9,0.089,3.3e-16\n";
  const Table l = readCsv("grade_error_vs_lambda", by_lambda);
  const std::vector<GradeLambdaRow>& lr = l.getRows(getGradeErrorVsLambdaSchema());
  ASSERT_EQ(lr.size(), 1u);
  EXPECT_EQ(lr[0].lambda, 0.9);
  EXPECT_EQ(lr[0].program_max_rel_error, 0.089);
  EXPECT_EQ(formatCsv(l), by_lambda);
}

// The verdict is the summary's "all" rows': 1 when one fails or none was provided, 0 when every provided one passes.
TEST(GradeTablesTest, TheExitStatusReadsTheVerdictsOverAllCases) {
  auto status = [](std::vector<GradeSummaryRow> rows) {
    return findGradeExitStatus(getGradeSummarySchema().tableSet(std::move(rows)));
  };
  auto row = [](const std::string& quantity, const std::string& regime, const std::string& verdict) {
    GradeSummaryRow r;
    r.quantity = quantity;
    r.regime = regime;
    r.verdict = verdict;
    return r;
  };
  EXPECT_EQ(status({row("x_p", "all", "pass"), row("U", "all", "not provided")}), 0);
  EXPECT_EQ(status({row("x_p", "all", "pass"), row("v_p", "all", "FAIL")}), 1);
  EXPECT_EQ(status({row("U", "all", "not provided")}), 1) << "nothing provided is not a pass";
  EXPECT_EQ(status({}), 1);
  EXPECT_EQ(findGradeExitStatus(TableSet{}), 1) << "no summary at all";
}

}  // namespace
}  // namespace crankcheck::validation
