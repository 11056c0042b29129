// findMaxAbsOverTurn against maxima known in closed form: the result must not depend on the grid once the grid has
// a sample on the hump that holds the maximum.

#include "crankcheck/validation/extremum.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include "../support/test_numbers.h"

namespace crankcheck::validation {
namespace {

using testing::kEps;

// a sin(n phi + c) + b: max |f| = |a| + |b| (b same sign side), at phi = (pi/2 - c)/n + 2 pi j / n.
TEST(ExtremumTest, SingleHarmonicMaximumIsExactOnEveryGrid) {
  for (int samples : {12, 13, 36, 72, 360})
    for (double c : {0.0, 0.1, 0.77}) {
      const auto f = [c](double phi) { return 0.3 * std::sin(2.0 * phi + c) + 0.05; };
      const TurnMaximum m = findMaxAbsOverTurn(f, samples);
      // A smooth maximum refined to 1e-10 rad: its value is exact to rounding (f'' h^2 / 2 = 1e-21); 4 eps of 0.35.
      EXPECT_NEAR(m.value, 0.35, 4 * kEps * 0.35) << samples << " samples, c = " << c;
      EXPECT_NEAR(std::fabs(f(m.phi)), m.value, 0.0);
    }
}

// Two harmonics: f = sin phi + 0.3 sin 3 phi has max 2 sqrt(0.9)^3 / ... found in closed form by its derivative:
// f' = cos phi + 0.9 cos 3phi = 0 with cos 3phi = 4 c^3 - 3 c: 3.6 c^3 - 1.7 c = 0, c^2 = 1.7 / 3.6.
TEST(ExtremumTest, TwoHarmonicMaximumMatchesTheDerivativesRoot) {
  const double c = std::sqrt(1.7 / 3.6), s = std::sqrt(1.0 - c * c);
  const double expected = s + 0.3 * (3.0 * s - 4.0 * s * s * s);  // sin 3phi = 3 s - 4 s^3
  for (int samples : {9, 24, 72, 1000}) {
    const TurnMaximum m = findMaxAbsOverTurn([](double phi) { return std::sin(phi) + 0.3 * std::sin(3.0 * phi); }, samples);
    EXPECT_NEAR(m.value, expected, 4 * kEps * expected) << samples;
  }
}

// The trap: a 30 degree grid lands on every zero of sin 6phi. With 3 or more samples per period (18, 36 and
// 72 per turn) the maximum is found.
TEST(ExtremumTest, GridOnTheZerosIsAvoidedByThreeSamplesPerPeriod) {
  const auto f = [](double phi) { return 7.3e-6 * std::sin(6.0 * phi); };
  for (int samples : {18, 36, 72}) EXPECT_NEAR(findMaxAbsOverTurn(f, samples).value, 7.3e-6, 4 * kEps * 7.3e-6) << samples;
}

// The quick campaign's angle tolerance (getAngleTolerance(true), 1e-6 rad) against the full campaign's on maxima known
// in closed form. Brent's method (refineMaxAbs) stops when its bracket around its best point is at most 4 tol / 3 wide,
// so the maximizer is within d = 4 tol / 3 of it and the value it returns is below the maximum by at most
// |f''| d^2 / 2 at a smooth maximum and |f'| d at a corner (never above it but for rounding: 4 eps of the value).
TEST(ExtremumTest, TheQuickToleranceCostsLessAndMovesAMaximumByItsBracket) {
  // The two-harmonic maximum of the test above; f'' = -sin phi - 2.7 sin 3 phi there (-2.47).
  const double c = std::sqrt(1.7 / 3.6), s = std::sqrt(1.0 - c * c);
  const double sin3 = 3.0 * s - 4.0 * s * s * s;
  const double expected = s + 0.3 * sin3, curvature = std::fabs(-s - 2.7 * sin3);
  int fine_calls = 0, quick_calls = 0;
  const auto counted = [](int& calls) {
    return [&calls](double phi) { ++calls; return std::sin(phi) + 0.3 * std::sin(3.0 * phi); };
  };
  const TurnMaximum fine = findMaxAbsOverTurn(counted(fine_calls), 24, 4, kFineAngleTolerance);
  const TurnMaximum quick = findMaxAbsOverTurn(counted(quick_calls), 24, 4, getAngleTolerance(true));
  EXPECT_EQ(getAngleTolerance(false), kFineAngleTolerance);
  EXPECT_NEAR(fine.value, expected, 4 * kEps * expected);
  const double d = 4.0 / 3.0 * getAngleTolerance(true);
  EXPECT_LE(quick.value, expected + 4 * kEps * expected);
  EXPECT_GE(quick.value, expected - 0.5 * curvature * d * d - 4 * kEps * expected);  // 2.2e-12 below at most
  EXPECT_LT(quick_calls, fine_calls);
  // A corner: f = 1 - |sin((phi - 1) / 2)| (2 pi periodic, slope 1/2 on either side of its maximum 1 at phi = 1).
  const auto corner = [](double phi) { return 1.0 - std::fabs(std::sin(0.5 * (phi - 1.0))); };
  for (const double tolerance : {getAngleTolerance(true), kFineAngleTolerance}) {
    const double value = findMaxAbsOverTurn(corner, 48, 1, tolerance).value;
    EXPECT_LE(value, 1.0 + 4 * kEps) << tolerance;
    EXPECT_GE(value, 1.0 - 0.5 * 4.0 / 3.0 * tolerance - 4 * kEps) << tolerance;  // slope 1/2 times d
  }
}

TEST(ExtremumTest, BadArgumentsAreRefused) {
  EXPECT_THROW(findMaxAbsOverTurn([](double) { return 1.0; }, 2), std::invalid_argument);
  EXPECT_THROW(findMaxAbsOverTurn([](double) { return 1.0; }, 10, -1), std::invalid_argument);
  EXPECT_THROW(findMaxAbsOverTurn([](double) { return 1.0; }, 10, 1, 0.0), std::invalid_argument);
  EXPECT_THROW(findMaxAbsOverTurn([](double) { return 1.0; }, std::vector<double>(10, 1.0), 1, -1e-6),
               std::invalid_argument);
}

}  // namespace
}  // namespace crankcheck::validation
