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
  Table t("example", {{"method", kText}, {"ns_per_eval", "ns"}, {"max_rel_error", "-"},
                             {"max_abs_Q", "N m"}, {"value", "see measure"}});
  t.rows.push_back({"analytic", "12.5", "1e-16", "3", "0.5"});
  const TableSet written = {{"example", t}};
  const FreshFolder dir;
  writeTables(written, dir.path());
  std::ifstream in(dir.path() / "data" / "example.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "method,ns_per_eval [ns],max_rel_error [-],max_abs_Q [N m],value [see measure]");
  const TableSet read = readTables(dir.path());
  ASSERT_EQ(read.count("example"), 1u);
  EXPECT_EQ(read.at("example").columns(), t.columns());
  EXPECT_EQ(read.at("example").rows, t.rows);
  // Tables read back append to tables built in code: their columns, units included, are the same.
  TableSet merged = written;
  appendTables(merged, read);
  EXPECT_EQ(merged.at("example").rows.size(), 2u);
}

// A text cell that a spreadsheet would run as a formula (= + - @, a tab or a carriage return first: OWASP's CSV
// injection) is written with a leading ', and so is one that begins with ' itself; number columns and a lone "-" are
// as they were. Reading the file back gives exactly the cells written (the expected lines are written out by hand).
TEST(TableTest, TextThatASpreadsheetWouldRunIsWrittenQuotedAndReadBackAsItWas) {
  Table t("example", {{"scene", kText}, {"value", "m"}});
  for (const char* name : {"=HYPERLINK(\"x\")", "+1", "-2", "@SUM(A1)", "'quoted", "\tlead", "-", "plain"})
    t.rows.push_back({name, "-1.5"});
  const FreshFolder dir;
  writeTables({{"example", t}}, dir.path());
  std::ifstream in(dir.path() / "data" / "example.csv");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(),
            "scene,value [m]\n\"'=HYPERLINK(\"\"x\"\")\",-1.5\n'+1,-1.5\n'-2,-1.5\n'@SUM(A1),-1.5\n''quoted,-1.5\n"
            "'\tlead,-1.5\n-,-1.5\nplain,-1.5\n");
  const TableSet read = readTables(dir.path());
  ASSERT_EQ(read.count("example"), 1u);
  EXPECT_EQ(read.at("example").rows, t.rows);
}

TEST(TableTest, AppendRefusesTheSameColumnInAnotherUnit) {
  TableSet into = {{"offset", Table("offset", {{"offset_over_r", "-"}})}};
  const TableSet from = {{"offset", Table("offset", {{"offset_over_r", "m"}})}};
  EXPECT_THROW(appendTables(into, from), std::runtime_error);
}

// The report's order (campaign.h: sortTables): column by column, numerically where both fields are numbers ("9" before
// "10", "1e-3" before "0.01"), else as text ("" first); a row that is another's start first; rows equal in every
// column ("1" and "1.0") keep the order they came in. The expected order is written out by hand.
TEST(TableTest, SortOrdersRowsColumnByColumnNumbersAsNumbers) {
  TableSet tables;
  Table t("crosscheck", {{"engine", kText}, {"value", "-"}, {"note", kText}});
  t.rows = {{"simbody", "10", "b"}, {"mujoco", "0.01", "a"}, {"simbody", "9", "c"},  {"mujoco", "1e-3", "z"},
            {"simbody", "1.0", "first"}, {"simbody", "1", "first"}, {"analytic", "", "x"}, {"analytic", "text", "x"},
            {"analytic", "2"}, {"analytic", "2", "y"}};
  tables["crosscheck"] = t;
  sortTables(tables);
  const std::vector<std::vector<std::string>> expected = {
      {"analytic", "", "x"},  {"analytic", "2"},       {"analytic", "2", "y"},      {"analytic", "text", "x"},
      {"mujoco", "1e-3", "z"}, {"mujoco", "0.01", "a"}, {"simbody", "1.0", "first"}, {"simbody", "1", "first"},
      {"simbody", "9", "c"},  {"simbody", "10", "b"}};
  EXPECT_EQ(tables["crosscheck"].rows, expected);
  sortTables(tables);  // sorted already: unchanged
  EXPECT_EQ(tables["crosscheck"].rows, expected);
}

}  // namespace
}  // namespace crankcheck::validation
