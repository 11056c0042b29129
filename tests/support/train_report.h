#pragma once
// The report's torsion part's check of each gated engine's own elastic train (data/torsion_engines.csv of a report folder), for
// the quick and the full campaign alike: every section's peak-to-peak twist within twice the periodicity the run was
// stopped at (of the twist scale) of the analytic steady state's: a run stopped at a cycle-to-cycle change c keeps
// about c of its transient, and a peak-to-peak is the difference of two such values. Every gated engine with a train
// route must be there.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <variant>

#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/report.h"

namespace crankcheck::testing {

inline void expectGatedTrainsAgree(const std::filesystem::path& report) {
  const validation::TableSet tables = validation::readTables(report);
  ASSERT_TRUE(tables.count("torsion_engines")) << report;
  const validation::Table& t = tables.at("torsion_engines");  // typed: read through its schema
  const size_t engine = validation::columnOf(t, "engine"), difference = validation::columnOf(t, "difference"),
               periodicity = validation::columnOf(t, "periodicity");
  std::set<std::string> seen;
  for (size_t r = 0; r < t.size(); ++r) {
    const std::string name = std::get<std::string>(t.cell(r, engine));
    if (!validation::findEngine(name).crank_train_gated) continue;
    EXPECT_LE(std::fabs(std::get<double>(t.cell(r, difference))), 2 * std::get<double>(t.cell(r, periodicity))) << name;
    seen.insert(name);
  }
  for (const Engine& e : validation::listEngines())
    if (e.simulate_crank_train && e.crank_train_gated && !e.closed_form) EXPECT_TRUE(seen.count(e.name)) << e.name;
}

}  // namespace crankcheck::testing
