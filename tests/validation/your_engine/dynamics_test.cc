// The scene sections' topic "Flywheel and torsion" (validation/src/your_engine/dynamics.cc) on the example scenes,
// against computations written here: the speed fluctuation by the energy integral (its own quadrature, its extremes by
// Brent), the critical speeds by Holzer's tabulation (the residual torque at the clamp, its root by TOMS 748); the
// missing lines; the tables read back through their schemas.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/roots.hpp>

#include "crankcheck/analytic/motion.h"
#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/analytic/torsion.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/validation/csv.h"
#include "crankcheck/validation/table_schemas.h"
#include "../../../validation/src/your_engine/topic.h"
#include "scene_section_fixture.h"

namespace crankcheck::validation::your_engine {
namespace {

using testing::loadExample;

const SceneTopic& findDynamics() { return testing::findTopic("Flywheel and torsion"); }

// The topic's tables on m: every task run (the engines' runs left out unless `engines`), the facts row added.
TableSet runTopic(const Mechanism& m, bool engines) {
  TableSet tables;
  for (const Task& task : findDynamics().tasks(m, false)) {
    const bool engine_run = task.id.find(" flywheel") == std::string::npos && task.id.find(" torsion") == std::string::npos;
    if (engine_run && !engines) continue;
    appendTables(tables, task.run());
  }
  addRows(tables, kSceneFactsTable, {calcSceneFacts(m, 0, true)});
  return tables;
}

// The value of column `column` in the row of table `name` whose `key` column is `value`.
double readNumber(const TableSet& tables, const std::string& name, const std::string& key, const std::string& value,
                  const std::string& column) {
  const std::string csv = formatCsv(tables.at(name));
  const std::vector<std::vector<std::string>> records = parseCsv(csv, name);
  const std::vector<std::string>& header = records.front();
  auto index = [&](const std::string& c) {
    for (size_t i = 0; i < header.size(); ++i)
      if (header[i] == c || header[i].rfind(c + " [", 0) == 0) return i;
    throw std::logic_error("no column " + c);
  };
  for (size_t r = 1; r < records.size(); ++r)
    if (records[r][index(key)] == value) return std::stod(records[r][index(column)]);
  throw std::logic_error("no row " + value);
}

// The steady run by the energy integral, independently: W(phi) the gas's work by 20-point Gauss-Legendre on a
// 0.25-degree grid split at the pressure table's corners (the gas torque is smooth between them), the cycle time by
// Gauss on the same intervals, phi_dot(0) by the secant method for the mean speed, the extremes by Brent on the
// continuous phi_dot(phi) from the best grid node's neighbourhood.
struct Reference {
  double delta = 0.0;
  double omega_max = 0.0, omega_min = 0.0;  // [rad/s]
  double at_phi_max = 0.0, at_phi_min = 0.0;  // [rad/s] phi_dot at the angles given
};
Reference calcReferenceRun(const Mechanism& m, double phi_max, double phi_min) {
  using Gauss = boost::math::quadrature::gauss<double, 20>;
  const double cycle = m.gas && m.machine.cycle == Cycle::kFourStroke ? 4.0 * M_PI : 2.0 * M_PI;
  std::vector<double> grid;
  for (int i = 0; i <= 1440 * static_cast<int>(std::lround(cycle / (2.0 * M_PI))); ++i) grid.push_back(i * (M_PI / 720.0));
  grid.back() = cycle;
  if (m.gas)
    for (size_t j = 0; j < m.firing_angles.size(); ++j)
      for (double a : m.gas->cycle_angles) grid.push_back(std::fmod(std::fmod(m.firing_angles[j] + a, cycle) + cycle, cycle));
  std::sort(grid.begin(), grid.end());
  grid.erase(std::unique(grid.begin(), grid.end(), [](double a, double b) { return b - a < 1e-12; }), grid.end());
  auto gas = [&](double phi) { return m.gas ? analytic::calcGasTorque(m, phi) : 0.0; };
  std::vector<double> W(grid.size(), 0.0);
  for (size_t i = 1; i < grid.size(); ++i) W[i] = W[i - 1] + Gauss::integrate(gas, grid[i - 1], grid[i]);
  const double load = W.back() / cycle;
  Mechanism bare = m;
  bare.flywheel_inertia = 0.0;
  const double I = *m.flywheel_inertia;
  auto work = [&](double phi) {  // W - T_L phi - U, W from the grid node below phi
    const size_t i = static_cast<size_t>(std::upper_bound(grid.begin(), grid.end(), phi) - grid.begin()) - 1;
    const double w = W[std::min(i, grid.size() - 1)] + (phi > grid[i] ? Gauss::integrate(gas, grid[i], phi) : 0.0);
    return w - load * phi - analytic::calcPotentialEnergy(m, phi);
  };
  const double omega = m.machine.speed, J0 = analytic::calcReducedInertia(bare, 0.0).J + I, work0 = work(0.0);
  auto speed = [&](double w0, double phi) {
    return std::sqrt(2.0 * (0.5 * J0 * w0 * w0 + work(phi) - work0) / (analytic::calcReducedInertia(bare, phi).J + I));
  };
  auto mean = [&](double w0) {
    double t = 0.0;
    for (size_t i = 1; i < grid.size(); ++i)
      t += Gauss::integrate([&](double phi) { return 1.0 / speed(w0, phi); }, grid[i - 1], grid[i]);
    return cycle / t;
  };
  double x0 = omega, x1 = 1.001 * omega, f0 = mean(x0) - omega, f1 = mean(x1) - omega;
  for (int it = 0; it < 30 && std::fabs(f1) > 1e-14 * omega && f1 != f0; ++it) {
    const double x2 = x1 - f1 * (x1 - x0) / (f1 - f0);
    x0 = x1, f0 = f1, x1 = x2, f1 = mean(x1) - omega;
  }
  size_t imax = 0, imin = 0;
  std::vector<double> w;
  for (double phi : grid) w.push_back(speed(x1, phi));
  for (size_t i = 0; i + 1 < grid.size(); ++i) {
    if (w[i] > w[imax]) imax = i;
    if (w[i] < w[imin]) imin = i;
  }
  auto refine = [&](size_t i, double sign) {
    const double a = i == 0 ? grid[0] - (grid[1] - grid[0]) : grid[i - 1], b = grid[i + 1];
    return boost::math::tools::brent_find_minima([&](double phi) { return -sign * speed(x1, std::fmod(phi + cycle, cycle)); },
                                                 a, b, std::numeric_limits<double>::digits / 2);
  };
  const auto top = refine(imax, 1.0), bottom = refine(imin, -1.0);
  Reference r;
  r.delta = (-top.second - bottom.second) / omega;  // top.second = -omega_max, bottom.second = omega_min
  r.omega_max = -top.second;
  r.omega_min = bottom.second;
  r.at_phi_max = speed(x1, phi_max);
  r.at_phi_min = speed(x1, phi_min);
  return r;
}

// The energy integral's delta against the reference's, and the angles of its extremes: the reference's phi_dot there
// equals its extremes (an angle is checked by its speed: an engine with evenly spaced firings reaches the same extreme
// once per firing). The gas scene's extremes come from a parabola through 0.1-degree samples (analytic/flywheel.h):
// its value's error is third order in the step, below 1e-8 of omega (1e-6 of the example four's delta); its angle's,
// a few thousandths of a degree, puts phi_dot there within (1/2) phi_dot'' dphi^2, below 1e-9 of omega_max -
// omega_min. The free run's extremes are found to double precision (motion.h), its mean speed to rounding. Bound for
// both angles: 1e-6 of omega_max - omega_min.
TEST(DynamicsTopicTest, FlywheelDeltaMatchesAnIndependentEnergyIntegral) {
  for (const std::string stem : {"inline4_four_stroke", "single_cylinder", "inline3_lying_two_stroke"}) {
    const Mechanism m = loadExample(stem);
    const TableSet tables = runTopic(m, false);
    const double delta = readNumber(tables, "your_engine_flywheel", "engine", "analytic", "delta");
    const double phi_max = readNumber(tables, "your_engine_flywheel", "engine", "analytic", "phi_deg_at_omega_max");
    const double phi_min = readNumber(tables, "your_engine_flywheel", "engine", "analytic", "phi_deg_at_omega_min");
    const Reference ref = calcReferenceRun(m, phi_max * M_PI / 180.0, phi_min * M_PI / 180.0);
    EXPECT_NEAR(delta, ref.delta, 1e-6 * ref.delta) << stem;
    const double span = ref.omega_max - ref.omega_min;
    EXPECT_NEAR(ref.at_phi_max, ref.omega_max, 1e-6 * span) << stem;
    EXPECT_NEAR(ref.at_phi_min, ref.omega_min, 1e-6 * span) << stem;
  }
}

// Holzer's residual torque at the clamp for the bodies' inertias J and the sections' stiffnesses K at omega: the front
// body's amplitude 1, each section twisted by the inertia torque of the bodies before it.
double calcHolzerResidual(const std::vector<double>& J, const std::vector<double>& K, double omega) {
  double x = 1.0, torque = 0.0;
  for (size_t i = 0; i < J.size(); ++i) {
    torque += J[i] * omega * omega * x;
    x -= torque / K[i];
  }
  return x;  // the flywheel's amplitude: 0 at a natural frequency
}

// The critical speeds: each throw's J_eq as J_t + the mean of its reduced inertia by a 4096-point trapezoidal sum in
// long double (a smooth periodic function: exact to rounding), the natural frequency by the root of Holzer's residual
// bracketed at 1 % around the table's, to the bracket's rounding: the table's within 1e-9 (the eigen solver's backward
// error, a few n eps of the largest omega^2, on the example trains' frequency spread of at most 30).
TEST(DynamicsTopicTest, CriticalSpeedsMatchHolzersTabulation) {
  for (const std::string stem : {"inline4_four_stroke", "inline6_two_stroke_marine"}) {
    const Mechanism m = loadExample(stem);
    const TableSet tables = runTopic(m, false);
    std::vector<double> J;
    if (m.crankshaft->front_inertia > 0.0) J.push_back(m.crankshaft->front_inertia);
    const int throws = static_cast<int>(findThrows(m).size());
    for (int j = 0; j < throws; ++j) {
      long double sum = 0.0L;
      const int n = 4096;
      for (int i = 0; i < n; ++i) sum += analytic::calcThrowReducedInertia(m, j, 2.0 * M_PI * i / n);
      J.push_back(m.crankshaft->throw_inertia + static_cast<double>(sum / n));
    }
    const std::vector<double>& K = m.crankshaft->stiffness;
    ASSERT_EQ(K.size(), J.size());
    const std::vector<std::vector<std::string>> records =
        parseCsv(formatCsv(tables.at("your_engine_critical")), "your_engine_critical");
    ASSERT_GT(records.size(), 1u) << stem << ": no critical speed in range";
    const double firings = m.machine.cylinders * (m.machine.cycle == Cycle::kFourStroke ? 0.5 : 1.0);
    for (size_t r = 1; r < records.size(); ++r) {
      const int mode = std::stoi(records[r][1]);
      const double order = std::stod(records[r][2]), rpm = std::stod(records[r][3]);
      EXPECT_NEAR(std::remainder(order, firings), 0.0, 1e-12) << "a major order";
      EXPECT_GE(rpm, 0.25 * m.speed_rpm);
      EXPECT_LE(rpm, 1.25 * m.speed_rpm);
      const double w = rpm * order * M_PI / 30.0;
      std::uintmax_t iterations = 100;
      const auto root = boost::math::tools::toms748_solve(
          [&](double x) { return calcHolzerResidual(J, K, x); }, 0.99 * w, 1.01 * w, boost::math::tools::eps_tolerance<double>(50),
          iterations);
      const double exact = 0.5 * (root.first + root.second);
      EXPECT_NEAR(w, exact, 1e-9 * exact) << stem << " mode " << mode << " order " << order;
      // Holzer's residual changes sign once per mode below it: mode i has i - 1 natural frequencies below it.
      int below = 0;
      for (double x = 1e-3 * exact; x < 0.999 * exact; x += 1e-3 * exact)
        if ((calcHolzerResidual(J, K, x) > 0) != (calcHolzerResidual(J, K, x + 1e-3 * exact) > 0)) ++below;
      EXPECT_EQ(below, mode - 1) << stem << " mode " << mode;
      EXPECT_LE(std::stod(records[r][4]), rpm);
      EXPECT_GE(std::stod(records[r][5]), rpm);
    }
  }
}

// Each example scene's row of Norton's method is its prediction E / (I_w omega^2) against the exact delta: it
// differs (Norton's error on the example scenes is 11 % to 265 % at C = 0.01), and the fitness rows are in the
// topic's range of orders.
TEST(DynamicsTopicTest, FitnessRowsInTheirOrders) {
  const Mechanism m = loadExample("inline4_four_stroke");
  const TableSet tables = runTopic(m, false);
  int norton = 0, holzer = 0;
  for (const FitnessRow& row : getRows(tables, kFitnessTable)) {
    EXPECT_EQ(row.scene, m.name);
    EXPECT_GT(row.scale_value, 0.0);
    if (row.order >= 100 && row.order < 110) ++norton;
    if (row.order >= 110) ++holzer;
    EXPECT_GT(row.max_error_rel, 0.0) << row.formula;
  }
  EXPECT_EQ(norton, 1);  // the engines' runs left out here
  EXPECT_EQ(holzer, 3);
}

// A free run with Simbody (the gated engine that simulates) on the single cylinder, gravity alone: its delta within
// what kFlywheelRunAccuracy leaves (the flywheel part's measurement: 3.6e-3 relative with gas; 1e-2 allowed).
TEST(DynamicsTopicTest, EngineRunAgreesWithTheEnergyIntegral) {
  const Mechanism m = loadExample("single_cylinder");
  const TableSet tables = runTopic(m, true);
  const double exact = readNumber(tables, "your_engine_flywheel", "engine", "analytic", "delta");
  int runs = 0;
  for (const std::vector<std::string>& record :
       parseCsv(formatCsv(tables.at("your_engine_flywheel")), "your_engine_flywheel")) {
    if (record[1] != "simbody") continue;
    ++runs;
    EXPECT_NEAR(readNumber(tables, "your_engine_flywheel", "engine", "simbody", "delta"), exact, 1e-2 * exact);
  }
  EXPECT_EQ(runs, 1);
}

using testing::joinText;

TEST(DynamicsTopicTest, MissingTablesGiveOneLineEach) {
  Mechanism m = loadExample("single_cylinder");
  m.flywheel_inertia.reset();
  m.crankshaft.reset();
  const TableSet tables = runTopic(m, false);
  const std::string text = joinText(findDynamics().describe(tables, m.name));
  EXPECT_NE(text.find("No [flywheel] table: add one"), std::string::npos) << text;
  EXPECT_NE(text.find("docs/SCENE-FORMAT.md, [flywheel]"), std::string::npos) << text;
  EXPECT_NE(text.find("No [crankshaft] table: add one to see the torsional vibration (docs/SCENE-FORMAT.md, Crankshaft "
                      "(torsion))"),
            std::string::npos)
      << text;
  // With a flywheel and no gas: gravity alone, said so, and Norton's method not judged.
  const Mechanism with = loadExample("single_cylinder");
  const std::string gravity = joinText(findDynamics().describe(runTopic(with, false), with.name));
  EXPECT_NE(gravity.find("no [gas] table: gravity alone"), std::string::npos) << gravity;
  EXPECT_NE(gravity.find("add a [gas] table (docs/SCENE-FORMAT.md, Gas pressure)"), std::string::npos) << gravity;
}

TEST(DynamicsTopicTest, TablesReadBackThroughTheirSchemas) {
  const Mechanism m = loadExample("inline4_four_stroke");
  const TableSet tables = runTopic(m, false);
  for (const TableSchema* schema : findDynamics().schemas()) {
    const Table& t = tables.at(schema->name());
    const std::string csv = formatCsv(t);
    const Table back = parseTable(schema->name(), parseCsv(csv, schema->name()), schema->name(), findTableSchema(schema->name()));
    EXPECT_EQ(formatCsv(back), csv) << schema->name();
  }
  // The section read from the tables alone: the exact delta and the twist are there.
  const std::string text = joinText(findDynamics().describe(tables, m.name));
  EXPECT_NE(text.find("the exact energy integral gives delta"), std::string::npos) << text;
  EXPECT_NE(text.find("twists most"), std::string::npos) << text;
}

}  // namespace
}  // namespace crankcheck::validation::your_engine
