// Q = dU/dphi: eq (13) against finite differences of U, eq (14) at high order against eq (13), eq (16) against
// eq (14), and the surviving harmonics against the paper's table 1, eq (18) and a DFT of the exact Q.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "../support/cases.h"
#include "crankcheck/analytic/fourier_series.h"
#include "crankcheck/analytic/gravity_torque.h"

namespace crankcheck::analytic {
namespace {

using testing::CaseSpec;
using testing::isClose;
using testing::kEps;

class GravityTorqueTest : public ::testing::TestWithParam<CaseSpec> {
 protected:
  Mechanism mechanismAt(double lambda) const { return testing::makeMechanism(GetParam(), lambda); }
};

// Five-point central difference of U with h = 1e-3: truncation h^4/30 |U^(5)|, and |U^(5)| <= 32 E (1 - lambda^2)^(-9/2)
// (the radical's fifth derivative, E the energy scale); rounding 3 eps E / h. For lambda <= 0.9 this is at most
// 6e-8 E at 0.9 and 1e-10 E at 0.4: a coarse but independent check (the Newton-Euler and Simbody routes are the fine ones).
TEST_P(GravityTorqueTest, Eq13MatchesFiniteDifferenceOfU) {
  for (double lambda : testing::sweepModerateLambdas()) {
    const Mechanism m = mechanismAt(lambda);
    const double E = testing::calcEnergyScale(m), h = 1e-3;
    const double tol = E * (std::pow(h, 4) * 32 / 30 * std::pow((1 - lambda) * (1 + lambda), -4.5) + 3 * kEps / h);
    for (double phi_deg : testing::sweepPhisDeg()) {
      const double phi = radiansFromDegrees(phi_deg);
      const double fd = (calcPotentialEnergy(m, phi - 2 * h) - 8 * calcPotentialEnergy(m, phi - h) +
                         8 * calcPotentialEnergy(m, phi + h) - calcPotentialEnergy(m, phi + 2 * h)) / (12 * h);
      EXPECT_TRUE(isClose(calcGravityTorque(m, phi), fd, tol)) << "lambda " << lambda << " phi_deg " << phi_deg;
    }
  }
}

// Eq (14) with exact Lambda_n converges geometrically (ratio q <= 0.39 for lambda <= 0.9): order 120 leaves
// q^60 < 1e-24; the remaining error is rounding of ~60 terms per throw: 64 eps of the energy scale.
TEST_P(GravityTorqueTest, Eq14OfHighOrderEqualsEq13) {
  for (double lambda : testing::sweepModerateLambdas()) {
    const Mechanism m = mechanismAt(lambda);
    for (double phi_deg : testing::sweepPhisDeg()) {
      const double phi = radiansFromDegrees(phi_deg);
      EXPECT_TRUE(isClose(calcGravityTorqueFourier(m, phi, 120), calcGravityTorque(m, phi),
                          64 * kEps * testing::calcEnergyScale(m)))
          << "lambda " << lambda << " phi_deg " << phi_deg;
    }
  }
}

// Eq (16) carries out the sum over throws in closed form; eq (14) sums term by term. Same order, same Lambda_n:
// they must agree to rounding (k terms per harmonic: 16 k eps of the scale), for exact and printed Lambda_n.
TEST_P(GravityTorqueTest, Eq16EqualsEq14TermByTerm) {
  for (double lambda : testing::sweepLambdas()) {
    const Mechanism m = mechanismAt(lambda);
    for (int order : {2, 6, 12, 24})
      for (LambdaSource source : {LambdaSource::kExact, LambdaSource::kAsPrinted})
        for (double phi_deg : testing::sweepPhisDeg()) {
          const double phi = radiansFromDegrees(phi_deg);
          EXPECT_TRUE(isClose(calcGravityTorqueSummed(m, phi, order, source),
                              calcGravityTorqueFourier(m, phi, order, source),
                              16 * m.machine.cylinders * kEps * testing::calcEnergyScale(m)))
              << "lambda " << lambda << " order " << order << " phi_deg " << phi_deg;
        }
  }
}

// The harmonics of the exact Q, by a discrete Fourier transform over one turn (M = 256 points; aliasing from
// harmonics above 128 is below q^64 ~ 1e-26 at lambda = 0.9), are nonzero exactly for the orders
// findSurvivingHarmonics predicts. lambda = 0.9 makes Lambda_24 ~ 1e-5, so every surviving order up to 24 stands
// far above the rounding floor (~1e-14 E) at which cancelled orders sit (eqs 19, 20: lying engines keep only n = 1).
TEST_P(GravityTorqueTest, SurvivingHarmonicsMatchDftOfExactQ) {
  const Mechanism m = mechanismAt(0.9);
  const int M = 256, max_order = 24;
  const double E = testing::calcEnergyScale(m);
  std::vector<double> q(M);
  for (int i = 0; i < M; ++i) q[i] = calcGravityTorque(m, 2 * M_PI * i / M);
  const std::vector<int> predicted =
      findSurvivingHarmonics(m.machine.cylinders, m.machine.cycle, m.machine.acting, max_order);
  for (int n = 1; n <= max_order; ++n) {
    double a = 0, b = 0;
    for (int i = 0; i < M; ++i) {
      a += q[i] * std::cos(2 * M_PI * n * i / M);
      b += q[i] * std::sin(2 * M_PI * n * i / M);
    }
    const double amplitude = 2 * std::hypot(a, b) / M;
    // Even orders carry W_n = N1 Lambda_n with N1 = -U1 sin(gamma): a lying engine (gamma = 0, 180) has none.
    const bool lying = std::fabs(std::sin(m.machine.cylinder_angle)) < 0.5;
    const bool survives = std::find(predicted.begin(), predicted.end(), n) != predicted.end() && !(lying && n > 1);
    SCOPED_TRACE("n = " + std::to_string(n));
    if (survives) EXPECT_GT(amplitude, 1e-8 * E);
    else EXPECT_LT(amplitude, 1e-12 * E);
  }
}

std::vector<CaseSpec> torqueCases() {
  std::vector<CaseSpec> cases;
  for (int k = 1; k <= 12; ++k)
    for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke})
      for (double gamma : testing::sweepGammasDeg()) cases.push_back({k, cycle, Acting::kSingle, 0.3, gamma, 3000.0});
  for (int k : {1, 2, 3, 4})
    for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke})
      cases.push_back({k, cycle, Acting::kDouble, 0.3, 37.0, 3000.0});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Sweep, GravityTorqueTest, ::testing::ValuesIn(torqueCases()),
                         [](const auto& info) { return testing::caseNameWithoutLambda(info.param); });

// The paper's claims (table 1 for two-stroke, eq 18 for four-stroke; getPaperHarmonicClaim transcribes them) against
// the exact integer analysis, for every k and every order the paper covers.
TEST(SurvivingHarmonics, MatchPaperTable1AndEq18) {
  for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke})
    for (int k = 1; k <= 12; ++k) {
      const std::vector<int> survivors = findSurvivingHarmonics(k, cycle, Acting::kSingle, 12);
      for (int n = 1; n <= 12; n = (n == 1 ? 2 : n + 2)) {
        const bool survives = std::find(survivors.begin(), survivors.end(), n) != survivors.end();
        EXPECT_EQ(getPaperHarmonicClaim(k, cycle, n), std::optional<bool>(survives))
            << toString(cycle) << " k = " << k << " n = " << n;
      }
    }
  // Spot values read off table 1 directly: W_6 for k = 3 and 6, W_10 for k = 5, none for k = 7.
  EXPECT_EQ(findSurvivingHarmonics(3, Cycle::kTwoStroke, Acting::kSingle, 12), (std::vector<int>{6, 12}));
  EXPECT_EQ(findSurvivingHarmonics(5, Cycle::kTwoStroke, Acting::kSingle, 12), (std::vector<int>{10}));
  EXPECT_TRUE(findSurvivingHarmonics(7, Cycle::kTwoStroke, Acting::kSingle, 12).empty());
  EXPECT_EQ(findSurvivingHarmonics(4, Cycle::kFourStroke, Acting::kSingle, 12), (std::vector<int>{2, 4, 6, 8, 10, 12}));
}

// The paper's claim (section 7): for k = 7, 9, 11 (two-stroke) the first nonzero term is Lambda_14, Lambda_18,
// Lambda_22, so gravity's torque is O(lambda^13) and smaller. The exact Q of a 7-cylinder engine at lambda = 0.3 is
// bounded by k |N1| |Lambda_14| (1 + geometric tail): check that bound with the DFT-free exact Q.
TEST(SurvivingHarmonics, OddCylinderCountsCancelUpToTwiceK) {
  for (int k : {7, 9, 11}) {
    const std::vector<int> survivors = findSurvivingHarmonics(k, Cycle::kTwoStroke, Acting::kSingle, 2 * k);
    EXPECT_EQ(survivors, std::vector<int>{2 * k}) << "k = " << k;
    const Mechanism m = testing::makeMechanism({k, Cycle::kTwoStroke, Acting::kSingle, 0.3, 90.0, 3000.0});
    const double lambda_2k = std::fabs(calcLambdaCoefficients(0.3, 2 * k)[2 * k]);
    const double N1 = calcGravityCoefficients(m).U1;  // |N1| = U1 |sin gamma|, gamma = 90
    double worst = 0;
    for (double phi = 0; phi < 2 * M_PI; phi += 0.01) worst = std::max(worst, std::fabs(calcGravityTorque(m, phi)));
    EXPECT_LE(worst, 1.1 * k * N1 * lambda_2k + 64 * kEps * testing::calcEnergyScale(m)) << "k = " << k;
    EXPECT_LT(worst, 1e-6 * testing::calcEnergyScale(m)) << "k = " << k;
  }
}

}  // namespace
}  // namespace crankcheck::analytic
