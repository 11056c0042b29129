#pragma once
/// @file
/// Test cases shared by the unit tests and the cross-check gate: mechanisms with non-unit masses and an
/// off-centre rod centre of mass, readable case names, the physical scales tolerances are built on, and a
/// comparison that prints both sides.

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/scales.h"
#include "test_numbers.h"  // testing::kEps

namespace crankcheck::testing {

/// The sweep values of the issues: lambda 0.05 .. 0.4 plus the hard values, the cylinder angles.
const std::vector<double>& sweepLambdas();      // 1e-6, 0.05, 0.1, ..., 0.4, 0.9, 0.999
/// The same without 0.999, for references (finite differences, truncated series) that need lambda <= 0.9.
const std::vector<double>& sweepModerateLambdas();
const std::vector<double>& sweepGammasDeg();    // 0, 180, 90, -90, 37
/// Crank angles [deg] around the full turn including both dead centres and quarter turns.
const std::vector<double>& sweepPhisDeg();

struct CaseSpec {
  int cylinders = 1;
  Cycle cycle = Cycle::kFourStroke;
  Acting acting = Acting::kSingle;
  double lambda = 0.3;
  double gamma_deg = 90.0;
  double rpm = 3000.0;
};

/// r = 0.05 m, l = r / lambda, m_o = 0.43 kg, m_k = 0.61 kg with z_k = 0.3 l (off centre) and
/// I_o = m_k z_k^2 + m_k (0.27 l)^2, m_s = 1.7 kg at r_s = 0.4 r, m_p = 1.3 kg at r_p = 0.8 r, g = 9.80665.
Mechanism makeMechanism(const CaseSpec& spec);
/// The same case at another crank ratio (what parametrized tests that loop over lambda build).
Mechanism makeMechanism(CaseSpec spec, double lambda);

/// e.g. "k4_four_lambda0p30_gamma90_3000rpm" (gamma -90 -> "gammam90", double-acting adds "_double" after the stroke).
std::string caseName(const CaseSpec& spec);
/// e.g. "0p30", "1em06", "0p999".
std::string lambdaTag(double lambda);
/// e.g. "k4_four_gamma90".
std::string caseNameWithoutLambda(const CaseSpec& spec);
/// Prints a case by its name (gtest and ctest show parameters with it).
void PrintTo(const CaseSpec& spec, std::ostream* os);

// The physical scales of a case live in the validation library, shared with `crankcheck validate`.
using validation::calcAccelerationScale;
using validation::calcEnergyScale;
using validation::calcForceScale;
using validation::calcTorqueScale;

/// |a - b| <= tol, printing both values, their difference and the tolerance on failure.
::testing::AssertionResult isClose(double a, double b, double tol);

}  // namespace crankcheck::testing
