// The batch kernels against the scalar closed form (eq 13), angle by angle.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "../support/cases.h"
#include "crankcheck/analytic/batch.h"
#include "crankcheck/analytic/gravity_torque.h"

namespace crankcheck::analytic {
namespace {

using testing::CaseSpec;
using testing::isClose;
using testing::kEps;

class BatchTest : public ::testing::TestWithParam<CaseSpec> {};

// Arbitrary angles: sin and cos of each throw's angle come from rotating phi by alpha_j (two more roundings than
// the scalar sin(phi + alpha_j)), and the rest is the same arithmetic: 8 eps of the energy scale, k throws summed.
TEST_P(BatchTest, ArbitraryAnglesMatchScalar) {
  for (double lambda : testing::sweepLambdas()) {
    const Mechanism m = testing::makeMechanism(GetParam(), lambda);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> angle(-20.0, 20.0);
    std::vector<double> phi(1000), Q(1000);
    for (double& p : phi) p = angle(rng);
    calcGravityTorqueBatch(m, phi, Q);
    const double tol = 8 * m.engine.cylinders * kEps * testing::calcEnergyScale(m) / (1 - lambda * lambda);
    for (size_t i = 0; i < phi.size(); ++i)
      ASSERT_TRUE(isClose(Q[i], calcGravityTorque(m, phi[i]), tol)) << "lambda " << lambda << " phi " << phi[i];
  }
}

// Uniform grid: the angle-addition recurrence adds one rounding per step between anchors 32 steps apart, so
// sin and cos drift by at most ~32 eps; the bound is 1e-13 of the case's scale. Near lambda = 1, Q's slope grows like
// 1/(1 - lambda^2) (the radical's derivative), and so does the effect of that drift: the bound carries the factor.
TEST_P(BatchTest, UniformGridMatchesScalarWithin1em13) {
  for (double lambda : testing::sweepLambdas()) {
    const Mechanism m = testing::makeMechanism(GetParam(), lambda);
    const double phi0 = -1.3, step = 2 * M_PI / 997;
    std::vector<double> Q(5000);
    calcGravityTorqueOnGrid(m, phi0, step, Q);
    const double tol = 1e-13 * testing::calcEnergyScale(m) / (1 - lambda * lambda);
    for (size_t i = 0; i < Q.size(); ++i)
      ASSERT_TRUE(isClose(Q[i], calcGravityTorque(m, phi0 + static_cast<double>(i) * step), tol))
          << "lambda " << lambda << " i " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Sweep, BatchTest,
                         ::testing::Values(CaseSpec{1, Cycle::kFourStroke, Acting::kSingle, 0.3, 90.0, 0.0},
                                           CaseSpec{3, Cycle::kTwoStroke, Acting::kSingle, 0.3, 37.0, 0.0},
                                           CaseSpec{4, Cycle::kFourStroke, Acting::kSingle, 0.3, -90.0, 0.0},
                                           CaseSpec{12, Cycle::kTwoStroke, Acting::kSingle, 0.3, 0.0, 0.0}),
                         [](const auto& info) { return testing::caseNameWithoutLambda(info.param); });

TEST(Batch, RefusesMismatchedSpans) {
  const Mechanism m = testing::makeMechanism({});
  std::vector<double> phi(3), Q(2);
  EXPECT_THROW(calcGravityTorqueBatch(m, phi, Q), std::invalid_argument);
}

}  // namespace
}  // namespace crankcheck::analytic
