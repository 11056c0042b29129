// Tables declare each column's unit with its name (campaign.h: Column, kText): a number's column without a unit is
// refused, naming the table and the column; the units written in the CSV headers come back when the tables are read.

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/report.h"
#include "fresh_folder.h"

namespace crankcheck::validation {
namespace {

using testing::FreshFolder;

TEST(TableTest, RefusesANumbersColumnWithoutAUnit) {
  try {
    Table t("error_vs_lambda", {{"quantity", kText}, {"max_rel_error", ""}});
    FAIL() << "a number's column without a unit was accepted";
  } catch (const std::logic_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("table error_vs_lambda"), std::string::npos) << message;
    EXPECT_NE(message.find("column max_rel_error"), std::string::npos) << message;
  }
}

TEST(TableTest, TextColumnsAreMarkedNotUnitless) {
  const Table t("crosscheck", {{"engine", kText}, {"worst_rel_error", "-"}});
  ASSERT_EQ(t.columns().size(), 2u);
  EXPECT_TRUE(t.columns()[0].text);
  EXPECT_EQ(t.columns()[0].unit, "");
  EXPECT_FALSE(t.columns()[1].text);
  EXPECT_EQ(t.names(), (std::vector<std::string>{"engine", "worst_rel_error"}));
  EXPECT_EQ(columnOf(t, "worst_rel_error"), 1u);
}

TEST(TableTest, UnitsRoundTripThroughTheCsvHeaders) {
  Table t("speed_vs_error", {{"method", kText}, {"ns_per_eval", "ns"}, {"max_rel_error", "-"},
                             {"max_abs_Q", "N m"}, {"value", "see measure"}});
  t.rows.push_back({"analytic", "12.5", "1e-16", "3", "0.5"});
  const TableSet written = {{"speed_vs_error", t}};
  const FreshFolder dir;
  writeTables(written, dir.path());
  std::ifstream in(dir.path() / "data" / "speed_vs_error.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "method,ns_per_eval [ns],max_rel_error [-],max_abs_Q [N m],value [see measure]");
  const TableSet read = readTables(dir.path());
  ASSERT_EQ(read.count("speed_vs_error"), 1u);
  EXPECT_EQ(read.at("speed_vs_error").columns(), t.columns());
  EXPECT_EQ(read.at("speed_vs_error").rows, t.rows);
  // Tables read back append to tables built in code: their columns, units included, are the same.
  TableSet merged = written;
  appendTables(merged, read);
  EXPECT_EQ(merged.at("speed_vs_error").rows.size(), 2u);
}

TEST(TableTest, AppendRefusesTheSameColumnInAnotherUnit) {
  TableSet into = {{"offset", Table("offset", {{"offset_over_r", "-"}})}};
  const TableSet from = {{"offset", Table("offset", {{"offset_over_r", "m"}})}};
  EXPECT_THROW(appendTables(into, from), std::runtime_error);
}

}  // namespace
}  // namespace crankcheck::validation
