// `crankcheck validate --quick` may be coarser than the full campaign but must not change a conclusion: every maximum
// the quick report holds is within 1 % of the full report's, or the quick report marks it as a bound (at rounding
// level, where no maximum can be measured). The quick campaign is the default one, whole, shared with its other
// readers (campaign_fixture.h: the ctest fixture quick_campaign); the full campaign runs here, once, for the one test
// (ctest runs each test of a binary in its own process, so the checks are parts of one test), restricted with
// --parts to the parts whose tables and sentences the checks read (kFullParts, issue 28).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/parts.h"
#include "crankcheck/validation/report.h"
#include "crankcheck/validation/scales.h"
#include "campaign_fixture.h"
#include "run_cli.h"
#include "train_report.h"
#include "../support/read_file.h"

namespace crankcheck {
namespace {
namespace fs = std::filesystem;
using validation::Table;
using validation::TableSet;

using testing::readFile;

// The rows of `table` as the CSV file has them (typed or not: Table::formatRow).
std::vector<std::vector<std::string>> listCsvRows(const Table& table) {
  std::vector<std::vector<std::string>> rows;
  for (size_t r = 0; r < table.size(); ++r) rows.push_back(table.formatRow(r));
  return rows;
}

// Every maximum the parts' tables state (Part::maxima, from the registry).
std::vector<validation::ReportedMaximum> listMaxima() {
  std::vector<validation::ReportedMaximum> out;
  for (const validation::Part* part : validation::listParts())
    for (validation::ReportedMaximum& m : part->maxima()) out.push_back(std::move(m));
  return out;
}

// The reports compared: the quick one (the fixture's) and the full one (run by the test).
struct Reports {
  fs::path quick, full;
  fs::path at(const std::string& name) const { return name == "quick" ? quick : full; }
};

// The parts of the full campaign the checks below read, with every cross-check and the verdict (`validate --parts`
// always runs them): every part with maxima (Part::maxima, from the registry, so a new one is compared too), the parts
// whose sentences are the conclusions (checkSameConclusions: gravity_significance, errata, balance,
// engines; a new part with such a sentence makes that check fail, naming the line, until it is added here) and the
// torsion part (its engine trains). The other parts (the flywheel sizings, the pin offset, the integrators, ...)
// state no maximum or conclusion compared here; the quick report has them all (QuickRunWritesEveryPartOfTheReport).
// These parts cost about four fifths of the full campaign (bench/README.md, "The parts the CLI tests read").
std::string listFullParts() {
  const std::set<std::string> read_here = {"gravity_significance", "errata", "balance", "engines", "torsion"};
  std::string parts;
  for (const validation::Part* part : validation::listParts())
    if (!part->always() && (!part->maxima().empty() || read_here.count(part->key())))  // always() parts run anyway
      parts += (parts.empty() ? "" : ",") + part->key();
  return parts;
}

// 1 %: the rule for a maximum that must not depend on the grid. Maxima found from the exact harmonics or
// refined by Brent's method agree far closer (the same function maximized to an angle tolerance of 1e-10 rad).
constexpr double kRelativeTolerance = 0.01;

void checkEveryMaximumIsWithinOnePercentOrABound(const Reports& reports) {
  const TableSet quick = validation::readTables(reports.quick), full = validation::readTables(reports.full);
  int compared = 0, bounds = 0;
  for (const validation::ReportedMaximum& spec : listMaxima()) {
    SCOPED_TRACE(spec.table);
    const auto q = quick.find(spec.table), f = full.find(spec.table);
    ASSERT_TRUE(f != full.end()) << "the full report has no table " << spec.table;
    ASSERT_TRUE(q != quick.end()) << "the quick report has no table " << spec.table;
    auto keyOf = [&](const Table& t, const std::vector<std::string>& row) {
      std::string key;
      for (const std::string& c : spec.key) key += row[columnOf(t, c)] + "|";
      return key;
    };
    const std::vector<std::vector<std::string>> quick_rows = listCsvRows(q->second), full_csv = listCsvRows(f->second);
    std::map<std::string, const std::vector<std::string>*> full_rows;
    for (const auto& row : full_csv) full_rows[keyOf(f->second, row)] = &row;
    ASSERT_FALSE(quick_rows.empty());
    for (const auto& row : quick_rows) {
      const std::string key = keyOf(q->second, row);
      SCOPED_TRACE(key);
      const auto it = full_rows.find(key);
      ASSERT_TRUE(it != full_rows.end()) << "a row of the quick report that the full report does not have";
      if (!spec.bound_column.empty() && row[columnOf(q->second, spec.bound_column)] == spec.bound_value) {
        ++bounds;
        continue;
      }
      // A maximum the quick report states as a value: the full report states it as a value too, within 1 %.
      if (!spec.bound_column.empty()) {
        EXPECT_NE((*it->second)[columnOf(f->second, spec.bound_column)], spec.bound_value)
            << "the full report calls a bound what the quick report states as a value";
      }
      for (const std::string& c : spec.maxima) {
        const double a = std::strtod(row[columnOf(q->second, c)].c_str(), nullptr);
        const double b = std::strtod((*it->second)[columnOf(f->second, c)].c_str(), nullptr);
        EXPECT_LE(std::fabs(a - b), kRelativeTolerance * std::fabs(b)) << c << ": quick " << a << ", full " << b;
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 200) << "the test compares the report's maxima, not nothing";
  EXPECT_GT(bounds, 0) << "the engines' agreement (rounding) is marked as a bound";
}

// The example of the issue: on a 30 degree grid every sample of sin 6phi is 0, so a grid maximum would report the
// order-4 Fourier series' error (the harmonics from 6 up that it leaves out) far too small. Both reports must give the
// maximum of |eq (14) to order 4 - eq (13)| over the turn, here found independently on a 0.01 degree grid of the
// closed forms (a grid that fine is within (6 x 0.005 deg)^2 / 2 = 1.4e-7 of the true maximum, relative).
void checkFourierErrorDoesNotDependOnTheGrid(const Reports& reports) {
  Mechanism m = validation::buildDefaultScenes().front();  // the base of the figures
  m.speed_rpm = 0.0;
  m.machine.speed = 0.0;
  double dense = 0.0;
  for (int i = 0; i < 36000; ++i) {
    const double phi = 2.0 * M_PI * i / 36000.0;
    dense = std::max(dense, std::fabs(analytic::calcGravityTorqueFourier(m, phi, 4) - analytic::calcGravityTorque(m, phi)));
  }
  dense /= validation::calcEnergyScale(m);
  for (const char* name : {"quick", "full"}) {
    const TableSet tables = validation::readTables(reports.at(name));
    const Table& speed = tables.at("speed_vs_error");
    double reported = 0.0;
    for (const auto& row : listCsvRows(speed))
      if (row[columnOf(speed, "method")] == "fourier_order_4") reported = std::strtod(row[columnOf(speed, "max_rel_error")].c_str(), nullptr);
    // 1e-6: the dense grid's own shortfall (1.4e-7) plus rounding of a difference of two O(1) values at 1e-5.
    EXPECT_NEAR(reported, dense, 1e-6 * dense) << name;
  }
}

// The conclusions of gravity_significance (the paper's claims tested) and the errata sentences are the same in both reports.
void checkSameConclusions(const Reports& reports) {
  auto conclusions = [](const std::string& index) {
    std::string out;
    std::stringstream lines(index);
    for (std::string line; std::getline(lines, line);)
      if (line.find("hold") != std::string::npos || line.rfind("Eq (", 0) == 0 || line.rfind("Section 7", 0) == 0)
        out += line + "\n";
    return out;
  };
  const std::string quick = conclusions(readFile(reports.quick / "index.md"));
  EXPECT_NE(quick.find("does not hold"), std::string::npos) << quick;
  EXPECT_EQ(quick, conclusions(readFile(reports.full / "index.md")));
}

TEST(QuickReportTest, QuickReportDrawsTheFullReportsConclusions) {
  const testing::CampaignRun quick = testing::getQuickCampaign();
  testing::FreshFolder folder;
  const Reports reports{quick.report, folder.path() / "full"};
  const validation::ProgramResult full =
      testing::runCrankcheck({"validate", "--parts", listFullParts(), "--out", reports.full.string()});
  for (const auto& [name, r] : {std::pair<const char*, const validation::ProgramResult&>{"quick", quick.result},
                                {"full", full}}) {
    ASSERT_EQ(r.exit_status, 0) << name << ": " << r.err;
    // A passing run, full or quick, tells its verdict in at most 15 lines (issue 27).
    EXPECT_LE(std::count(r.out.begin(), r.out.end(), '\n'), 15) << r.out;
    EXPECT_NE(r.out.find("\n100% of comparisons agree, 0 failed out of "), std::string::npos) << r.out;
  }
  {
    SCOPED_TRACE("every maximum within 1 % or a bound");
    checkEveryMaximumIsWithinOnePercentOrABound(reports);
  }
  {
    SCOPED_TRACE("the order-4 Fourier error");
    checkFourierErrorDoesNotDependOnTheGrid(reports);
  }
  {
    SCOPED_TRACE("the same conclusions");
    checkSameConclusions(reports);
  }
  {
    SCOPED_TRACE("the torsion part's engine trains in the full report (the quick one: QuickRunWritesEveryPartOfTheReport)");
    testing::expectGatedTrainsAgree(reports.full);
  }
}

}  // namespace
}  // namespace crankcheck
