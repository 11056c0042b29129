// Piston and rod kinematics against references the closed forms did not produce: the loop-closure equation
// and its implicit derivatives, finite differences of the geometry, dead-centre values, Taylor bounds for
// Norton's approximation and the Fourier series at high order.

#include <gtest/gtest.h>

#include <cmath>

#include "../support/cases.h"
#include "crankcheck/analytic/kinematics.h"

namespace crankcheck::analytic {
namespace {

using testing::CaseSpec;
using testing::isClose;
using testing::kEps;

class KinematicsTest : public ::testing::TestWithParam<double> {
 protected:
  Mechanism mechanism() const { return testing::makeMechanism({1, Cycle::kFourStroke, Acting::kSingle, GetParam(), 90.0, 4200.0}); }
};

std::string lambdaName(const ::testing::TestParamInfo<double>& info) {
  return "lambda" + testing::lambdaTag(info.param);
}

// Loop closure |A - B| = l, differentiated implicitly: with D = x - r cos(theta) = sqrt(l^2 - r^2 sin^2):
//   D D' + r^2 sin cos = 0,  D D'' + D'^2 + r^2 cos 2theta = 0,  D D''' + 3 D' D'' - 2 r^2 sin 2theta = 0,
// and x' = D' - r sin, x'' = D'' - r cos, x''' = D''' + r sin. A different route from the code's derivatives.
TEST_P(KinematicsTest, DerivativesMatchImplicitLoopClosure) {
  const Mechanism m = mechanism();
  const double r = m.crank.radius, l = m.rod.length, w = m.machine.speed, lambda = r / l;
  const double stiff = 1.0 / ((1.0 - lambda) * (1.0 + lambda));  // 1 / (1 - lambda^2)
  for (double phi_deg = -180.0; phi_deg <= 540.0; phi_deg += 7.5) {
    SCOPED_TRACE("phi_deg = " + std::to_string(phi_deg));
    const double theta = radiansFromDegrees(phi_deg);
    const double s = std::sin(theta), c = std::cos(theta);
    const double D = std::sqrt(l * l - r * r * s * s);
    const double D1 = -r * r * s * c / D;
    const double D2 = -(D1 * D1 + r * r * std::cos(2 * theta)) / D;
    const double D3 = (2 * r * r * std::sin(2 * theta) - 3 * D1 * D2) / D;
    const PistonKinematics k = calcPistonKinematics(m, theta);
    // Both sides are O(20) roundings of quantities bounded by the scales below; each derivative amplifies
    // rounding by at most 1/(1 - lambda^2)^(1/2) per order. 64 eps of the scale covers it with margin.
    EXPECT_TRUE(isClose(k.x_p, D + r * c, 64 * kEps * (r + l)));
    EXPECT_TRUE(isClose(k.v_p, w * (D1 - r * s), 64 * kEps * r * w * (1 + std::sqrt(stiff))));
    EXPECT_TRUE(isClose(k.a_p, w * w * (D2 - r * c), 64 * kEps * r * w * w * (1 + std::pow(stiff, 1.5))));
    EXPECT_TRUE(isClose(k.j_p, w * w * w * (D3 + r * s), 64 * kEps * r * w * w * w * (1 + std::pow(stiff, 2.5))));
  }
}

TEST_P(KinematicsTest, DeadCentresAreExact) {
  const Mechanism m = mechanism();
  const double r = m.crank.radius, l = m.rod.length;
  const PistonKinematics outer = calcPistonKinematics(m, radiansFromDegrees(0.0));
  const PistonKinematics inner = calcPistonKinematics(m, radiansFromDegrees(180.0));
  const PistonKinematics inner_neg = calcPistonKinematics(m, radiansFromDegrees(-180.0));
  EXPECT_EQ(outer.x_p, r + l);
  EXPECT_EQ(inner.x_p, l - r);
  EXPECT_EQ(inner_neg.x_p, l - r);
  EXPECT_EQ(outer.v_p, 0.0);
  EXPECT_EQ(inner.v_p, 0.0);
  EXPECT_EQ(outer.j_p, 0.0);
  EXPECT_EQ(inner.j_p, 0.0);
  // At the dead centres the rod is aligned with the cylinder: a_p = -r w^2 (1 +- lambda), exactly as far as
  // the closed form's roundings allow (4 eps of the value).
  const double w = m.machine.speed, lambda = r / l;
  EXPECT_TRUE(isClose(outer.a_p, -r * w * w * (1 + lambda), 4 * kEps * r * w * w * (1 + lambda)));
  EXPECT_TRUE(isClose(inner.a_p, r * w * w * (1 - lambda), 4 * kEps * r * w * w * (1 + lambda)));
  const RodKinematics rod = calcRodKinematics(m, radiansFromDegrees(180.0));
  EXPECT_EQ(rod.beta, 0.0);
  EXPECT_EQ(rod.beta_ddot, 0.0);
}

// The rod angle from the geometry (wrist pin from x_p, crank pin from theta), differentiated by a five-point
// central difference. Truncation h^4/30 |beta^(5)| with |beta^(5)| <= 30 (1 - lambda^2)^(-9/2) for lambda <= 0.9,
// rounding 1.5 eps |beta| / h; h = 1e-3 gives tol = h^4 (1-lambda^2)^(-9/2) + 2 eps/h per radian-derivative.
// References that need lambda <= 0.9 (finite differences, truncated series).
class KinematicsSeriesTest : public KinematicsTest {};

TEST_P(KinematicsSeriesTest, RodAngleDerivativesMatchFiniteDifferences) {
  const Mechanism m = mechanism();
  const double r = m.crank.radius, l = m.rod.length, lambda = r / l, w = m.machine.speed;
  const auto beta_of = [&](double theta) {
    const double x = calcPistonKinematics(m, theta).x_p;
    // B - A in the cylinder frame: (r cos - x, r sin) = l (-cos beta, sin beta)
    return std::atan2(r * std::sin(theta), x - r * std::cos(theta));
  };
  const double h = 1e-3;
  const double tol_per_order = std::pow(h, 4) * std::pow((1 - lambda) * (1 + lambda), -4.5) + 2 * kEps / h;
  for (double theta = -3.0; theta <= 7.0; theta += 0.37) {
    const double f_m2 = beta_of(theta - 2 * h), f_m1 = beta_of(theta - h), f_0 = beta_of(theta),
                 f_p1 = beta_of(theta + h), f_p2 = beta_of(theta + 2 * h);
    const double d1 = (f_m2 - 8 * f_m1 + 8 * f_p1 - f_p2) / (12 * h);
    const double d2 = (-f_m2 + 16 * f_m1 - 30 * f_0 + 16 * f_p1 - f_p2) / (12 * h * h);
    const RodKinematics k = calcRodKinematics(m, theta);
    EXPECT_TRUE(isClose(k.beta, f_0, 4 * kEps));
    EXPECT_TRUE(isClose(k.beta_dot, w * d1, w * tol_per_order));
    EXPECT_TRUE(isClose(k.beta_ddot, w * w * d2, w * w * tol_per_order / h));
  }
}

// Norton 13.3a keeps sqrt(1 - u) ~ 1 - u/2 with u = lambda^2 sin^2: the remainder lies in [-u^2/(8(1-u)^(3/2)), 0]
// (Taylor with Lagrange remainder), so l (exact radical - Norton's) is never positive and bounded by l lambda^4 / (8 (1 - lambda^2)^(3/2)).
TEST_P(KinematicsTest, NortonTwoTermErrorWithinTaylorBound) {
  const Mechanism m = mechanism();
  const double r = m.crank.radius, l = m.rod.length, lambda = r / l;
  const double bound = l * std::pow(lambda, 4) / (8 * std::pow((1 - lambda) * (1 + lambda), 1.5));
  for (double theta = 0.0; theta < 2 * M_PI; theta += 0.05) {
    const double error = calcPistonKinematics(m, theta).x_p - calcPistonKinematicsNorton(m, theta).x_p;
    EXPECT_LE(error, 8 * kEps * (r + l));
    EXPECT_GE(error, -bound - 8 * kEps * (r + l));
  }
}

// With exact coefficients, the Fourier series converges geometrically (ratio q, fourier_series.h): at order 120
// the truncation is below q^60 < 1e-24 for lambda <= 0.9; what remains is the rounding of ~60 terms.
TEST_P(KinematicsSeriesTest, FourierSeriesOfHighOrderEqualsExact) {
  const Mechanism m = mechanism();
  const double r = m.crank.radius, l = m.rod.length, w = m.machine.speed, lambda = r / l;
  for (double theta = -1.0; theta < 7.0; theta += 0.29) {
    const PistonKinematics exact = calcPistonKinematics(m, theta);
    const PistonKinematics series = calcPistonKinematicsFourier(m, theta, 120);
    // 64 eps of the scale: 60 terms each rounded once, coefficients exact to a few eps.
    EXPECT_TRUE(isClose(series.x_p, exact.x_p, 64 * kEps * (r + l)));
    EXPECT_TRUE(isClose(series.v_p, exact.v_p, 64 * kEps * r * w / (1 - lambda * lambda)));
    EXPECT_TRUE(isClose(series.a_p, exact.a_p, 256 * kEps * r * w * w / std::pow(1 - lambda * lambda, 1.5)));
  }
}

INSTANTIATE_TEST_SUITE_P(Sweep, KinematicsTest, ::testing::ValuesIn(testing::sweepLambdas()), lambdaName);
INSTANTIATE_TEST_SUITE_P(Sweep, KinematicsSeriesTest, ::testing::ValuesIn(testing::sweepModerateLambdas()), lambdaName);

TEST(NortonTwoTerm, IsTheSecondOrderFourierApproximation) {
  // Norton's 13.3c-e equal the exact kinematics to first order in lambda: at lambda = 1e-3 the acceleration
  // error is O(lambda^3) r w^2 (the lambda^3 terms of a_p), so below r w^2 lambda^2.
  const Mechanism m = testing::makeMechanism({1, Cycle::kFourStroke, Acting::kSingle, 1e-3, 90.0, 3000.0});
  const double r = m.crank.radius, w = m.machine.speed;
  for (double theta = 0.0; theta < 2 * M_PI; theta += 0.1) {
    const PistonKinematics exact = calcPistonKinematics(m, theta), norton = calcPistonKinematicsNorton(m, theta);
    EXPECT_LE(std::fabs(exact.a_p - norton.a_p), r * w * w * 1e-6);
    EXPECT_LE(std::fabs(exact.v_p - norton.v_p), r * w * 1e-6);
  }
}

}  // namespace
}  // namespace crankcheck::analytic
