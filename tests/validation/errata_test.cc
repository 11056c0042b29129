// The errata table of the report (campaign task "errata") against computations it does not make: Lambda_n by a DFT
// of eq (14)'s defining function, eq (2)'s split of the rod worked out from the scene's numbers, the identities that
// tie Q of a layout to U1 or U2 alone, and the first surviving harmonic from a complex sum over the throws.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <map>
#include <string>
#include <variant>

#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/validation/campaign.h"

namespace crankcheck::validation {
namespace {

class ErrataTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    CampaignOptions options;
    options.quick = true;
    for (const Task& task : buildCampaign(options))
      if (task.id == "errata") tables_ = task.run();
  }
  // The value of the row whose item starts with `item` and whose measure is `measure` (the table's typed cells).
  static double value(const std::string& item, const std::string& measure) {
    const Table& t = tables_.at("errata");
    const size_t item_column = columnOf(t, "item"), measure_column = columnOf(t, "measure"),
                 value_column = columnOf(t, "value");
    for (size_t r = 0; r < t.size(); ++r)
      if (std::get<std::string>(t.cell(r, item_column)).rfind(item, 0) == 0 &&
          std::get<std::string>(t.cell(r, measure_column)) == measure)
        return std::get<double>(t.cell(r, value_column));
    ADD_FAILURE() << "no row " << item << " / " << measure;
    return std::nan("");
  }
  static TableSet tables_;
};
TableSet ErrataTest::tables_;

// Lambda_n = (1/pi) integral of lambda sin cos / sqrt(1 - lambda^2 sin^2) sin(n theta) (eq 14): a DFT of 4096 points
// is exact to rounding for this analytic periodic function (its Fourier coefficients fall like q^(n/2), q = 0.04).
double lambdaByDft(int n, double lambda) {
  const int N = 4096;
  double sum = 0.0;
  for (int i = 0; i < N; ++i) {
    const double t = 2.0 * M_PI * i / N, s = std::sin(t);
    sum += lambda * s * std::cos(t) / std::sqrt(1.0 - lambda * lambda * s * s) * std::sin(n * t);
  }
  return 2.0 * sum / N;
}

double printedLambda(int n, double lambda) {  // eq (15) as printed (Lambda_2 with the OCR's lost lambda restored)
  static const std::map<int, std::vector<double>> table = {
      {2, {0.5, 0.125, 0.058594, 0.034180, 0.022432, 0.015862}}, {4, {0.0, -0.0625, -0.046875, -0.034180, -0.025635, -0.019827}},
      {6, {0.0, 0.0, 0.011719, 0.014648, 0.014420, 0.013218}},  {8, {0.0, 0.0, 0.0, -0.002441, -0.004272, -0.005287}},
      {10, {0.0, 0.0, 0.0, 0.0, 0.000534, 0.001202}},           {12, {0.0, 0.0, 0.0, 0.0, 0.0, -0.000120}}};
  double sum = 0.0;
  for (int p = 0; p < 6; ++p) sum += table.at(n)[p] * std::pow(lambda, 2 * p + 1);
  return sum;
}

TEST_F(ErrataTest, Eq15CoefficientErrorsMatchADftOfTheExactFunction) {
  for (int n : {8, 10, 12}) {
    const double expected = printedLambda(n, 0.4) / lambdaByDft(n, 0.4) - 1.0;
    // The DFT's Lambda_12 (1e-7) carries about 4096 x eps of the O(0.1) summands: 1e-9 relative to it at most.
    EXPECT_NEAR(value("Stanczak eq (15): Lambda_" + std::to_string(n) + " at lambda = 0.4", "printed / exact - 1"), expected, 1e-8)
        << "Lambda_" << n;
  }
  // The size the issue and docs/ERRATA.md quote, to three digits (37.5 %): within one unit of that last digit (the
  // exact value is checked to 1e-8 just above; this checks the quoted sentence).
  EXPECT_NEAR(value("Stanczak eq (15): Lambda_12 at lambda = 0.4", "printed / exact - 1"), -0.375, 0.001);
  EXPECT_EQ(value("Stanczak eq (15): printed coefficients", "count printed"), 6 + 5 + 4 + 3 + 2 + 1);
  EXPECT_EQ(value("Stanczak eq (15): printed coefficients", "count equal to the rounded exact value"), 20);
}

TEST_F(ErrataTest, Eq5RatiosFollowFromEq2AndTheScenesNumbers) {
  const Mechanism m = buildDefaultScenes().front();
  const double l = m.rod.length, z = m.rod.com_from_wrist_pin, m_k = m.rod.mass, m_o = m.piston.mass, r = m.crank.radius;
  // Eq (2): the wrist pin carries m_k (l - z_k) / l, the crank pin m_k z_k / l; eq (5) as printed swaps them.
  const double u1 = (m_o + m_k * z / l) / (m_o + m_k * (l - z) / l);
  const double moment = m.crank.mass * m.crank.com_radius - m.crank.counterweight_mass * m.crank.counterweight_radius;
  const double u2 = (m_k * (l - z) / l * r + moment) / (m_k * z / l * r + moment);
  EXPECT_NEAR(value("Stanczak eq (5): U1", "printed / true"), u1, 1e-14);
  EXPECT_NEAR(value("Stanczak eq (5): U2", "printed / true"), u2, 1e-13);
  // A standing engine whose Q holds only even harmonics carries U1 alone (eq 14: W_n = -U1 Lambda_n); a lying single
  // cylinder carries U2 alone (eq 19): the ratios of the maxima are the coefficients' ratios.
  EXPECT_NEAR(value("Stanczak eq (5): Q of a standing multi-cylinder", "max |Q_printed| / max |Q|"), u1, 1e-12);
  EXPECT_NEAR(value("Stanczak eq (5): Q of a lying single cylinder", "max |Q_printed| / max |Q|"), u2, 1e-12);
}

// The first harmonic n in {1, 2, 4, ...} whose sum over the throws, sum_j e^{i n alpha_j}, does not vanish: summed in
// complex floating point (the exact integer analysis of gravity_torque.h is what the campaign uses).
int firstSurvivingByComplexSum(int k, double period) {
  for (int n = 1; n < 100; n = n == 1 ? 2 : n + 2) {
    std::complex<double> sum = 0.0;
    for (int j = 0; j < k; ++j) sum += std::polar(1.0, n * period * j / k);
    if (std::abs(sum) > 1e-9) return n;  // a surviving sum is k; a cancelled one is rounding, 1e-14
  }
  return 0;
}

TEST_F(ErrataTest, Section7FirstSurvivingOrdersMatchComplexSums) {
  for (int k : {7, 9, 11}) {
    EXPECT_EQ(value("Stanczak section 7: first surviving order, k = " + std::to_string(k) + " two-stroke", "harmonic order"),
              firstSurvivingByComplexSum(k, 2.0 * M_PI));
    EXPECT_EQ(value("Stanczak section 7: first surviving order, k = " + std::to_string(k) + " four-stroke", "harmonic order"),
              firstSurvivingByComplexSum(k, 4.0 * M_PI));
    EXPECT_EQ(firstSurvivingByComplexSum(k, 2.0 * M_PI), 2 * k);
  }
}

// gravity_significance's maxima (from eq (16)'s exact harmonics, refined) against eq (13) evaluated on a 0.01 degree grid: a grid that
// fine is within (n x 0.005 deg)^2 / 2 of the maximum (2e-5 relative for the harmonic n = 14 of k = 7), and eq (13)'s
// rounding is about 1e-16 of the energy scale, 1e-5 of k = 7's max |Q|: 1e-4 relative covers both.
TEST(GravitySignificanceTest, MaximaMatchADenseGridOfEq13) {
  TableSet tables;
  for (const Task& task : buildCampaign(CampaignOptions{true, {}}))
    if (task.id.rfind("gravity_significance", 0) == 0) appendTables(tables, task.run());
  const Table& t = tables.at("gravity_significance");
  const Mechanism base = buildDefaultScenes().front();
  int checked = 0;
  const size_t cycle_column = columnOf(t, "cycle"), k_column = columnOf(t, "k"), max_column = columnOf(t, "max_abs_Q");
  for (size_t row = 0; row < t.size(); ++row) {
    const int k = static_cast<int>(std::get<double>(t.cell(row, k_column)));
    const std::string cycle_name = std::get<std::string>(t.cell(row, cycle_column));
    const Cycle cycle = cycle_name == "two-stroke" ? Cycle::kTwoStroke : Cycle::kFourStroke;
    if (!((cycle == Cycle::kTwoStroke && (k == 1 || k == 4 || k == 7 || k == 12)) || (cycle == Cycle::kFourStroke && k == 8))) continue;
    Mechanism m = base;
    m.machine.cylinders = k;
    m.machine.cycle = cycle;
    m.machine.crank_angles = calcPhaseAngles(k, cycle, Acting::kSingle);
    m.machine.cylinder_angle = M_PI / 2.0;
    double dense = 0.0;
    for (int i = 0; i < 36000; ++i) dense = std::max(dense, std::fabs(analytic::calcGravityTorque(m, 2.0 * M_PI * i / 36000.0)));
    const double reported = std::get<double>(t.cell(row, max_column));
    // A 0.01-degree grid misses a harmonic-n maximum by at most (n h)^2 / 8 of it: 2.2e-6 for n <= 24. 1e-4 of the
    // maximum also covers the report's Brent refinement stopping at its own 1e-10 rad bracket; both far below the
    // differences between cylinder counts the table is read for (factors of 10 and more).
    EXPECT_NEAR(reported, dense, 1e-4 * dense) << cycle_name << " k = " << k;
    ++checked;
  }
  EXPECT_EQ(checked, 5);
}

}  // namespace
}  // namespace crankcheck::validation
