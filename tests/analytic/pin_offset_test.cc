// The pin offset (desaxe) in the analytic engine, against references the closed forms did not produce: the loop
// closure |A - B| = l with A = x_p e + delta n differentiated implicitly, the geometry of the dead centres, Q against a
// central difference of U, and the shaking harmonics (a converged DFT) summed back into the shaking force and moment.
// Offsets of both signs up to 0.99 (l - r), where the loop is nearly singular.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "../support/cases.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/analytic/shaking.h"

namespace crankcheck::analytic {
namespace {

using testing::isClose;
using testing::kEps;

struct OffsetCase {
  double lambda, fraction;  // delta = fraction (l - r)
};
std::string caseName(const ::testing::TestParamInfo<OffsetCase>& info) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "lambda%s_offset%s%03.0f", testing::lambdaTag(info.param.lambda).c_str(),
                info.param.fraction < 0 ? "m" : "p", std::fabs(1000.0 * info.param.fraction));
  return buffer;
}

class PinOffsetTest : public ::testing::TestWithParam<OffsetCase> {
 protected:
  Mechanism mechanism() const {
    Mechanism m = testing::makeMechanism({1, Cycle::kFourStroke, Acting::kSingle, GetParam().lambda, 37.0, 4200.0});
    m.machine.pin_offsets = {GetParam().fraction * (m.rod.length - m.crank.radius)};
    return m;
  }
  double delta() const { return mechanism().machine.pin_offsets[0]; }
  // 1 / cos^2(beta) at its largest: (1 - (lambda + |delta| / l)^2)^-1, how close the loop comes to its singularity.
  double stiffness() const {
    const Mechanism m = mechanism();
    const double s = (m.crank.radius + std::fabs(delta())) / m.rod.length;
    return 1.0 / ((1.0 - s) * (1.0 + s));
  }
};

// |A - B| = l with A = x e + delta n, B = r (cos, sin): D = x - r cos = sqrt(l^2 - (r sin - delta)^2), and
//   D D' + (r sin - delta) r cos = 0,  D D'' + D'^2 + f = 0 with f = r^2 cos^2 - (r sin - delta) r sin,
//   D D''' + 3 D' D'' + f' = 0 with f' = -3 r^2 sin cos - (r sin - delta) r cos;
// x' = D' - r sin, x'' = D'' - r cos, x''' = D''' + r sin. Tolerance: each derivative divides by D = l cos(beta) once
// more, so derivative n carries the rounding of a few terms times (1 / cos^2 beta)^(n + 1/2) of r omega^n; 64 eps of it.
TEST_P(PinOffsetTest, DerivativesMatchImplicitLoopClosure) {
  const Mechanism m = mechanism();
  const double r = m.crank.radius, l = m.rod.length, w = m.machine.speed, d = delta(), k = stiffness();
  for (double deg = -180.0; deg <= 540.0; deg += 7.5) {
    SCOPED_TRACE("theta_deg = " + std::to_string(deg));
    const double theta = radiansFromDegrees(deg);
    const double s = std::sin(theta), c = std::cos(theta), u = r * s - d;
    const double D = std::sqrt(l * l - u * u);
    const double D1 = -u * r * c / D;
    const double f = r * r * c * c - u * r * s, f1 = -3.0 * r * r * s * c - u * r * c;
    const double D2 = -(D1 * D1 + f) / D;
    const double D3 = -(3.0 * D1 * D2 + f1) / D;
    const PistonKinematics p = calcPistonKinematics(m, theta, d);
    EXPECT_TRUE(isClose(p.x_p, r * c + D, 64 * kEps * (l + r)));
    EXPECT_TRUE(isClose(p.v_p, w * (D1 - r * s), 64 * kEps * r * w * std::pow(k, 1.5)));
    EXPECT_TRUE(isClose(p.a_p, w * w * (D2 - r * c), 64 * kEps * r * w * w * std::pow(k, 2.5)));
    EXPECT_TRUE(isClose(p.j_p, w * w * w * (D3 + r * s), 64 * kEps * r * w * w * w * std::pow(k, 3.5)));
    // The rod: B - A = l (-cos(beta) e + sin(beta) n).
    const RodKinematics rod = calcRodKinematics(m, theta, d);
    EXPECT_TRUE(isClose(l * std::sin(rod.beta), r * s - d, 8 * kEps * l));
    EXPECT_TRUE(isClose(l * std::cos(rod.beta), r * c - p.x_p + 2.0 * (p.x_p - r * c), 64 * kEps * (l + r)));
  }
}

// beta' and beta'' against central differences of beta (step h = 1e-4 rad: truncation h^2 / 6 |beta'''| with
// |beta'''| <= 3 lambda k^2.5, rounding 2 eps / h).
TEST_P(PinOffsetTest, RodRatesMatchFiniteDifferences) {
  Mechanism m = mechanism();
  m.machine.speed = 1.0;
  const double h = 1e-4, d = delta(), k = stiffness(), lambda = m.crank.radius / m.rod.length;
  for (double deg = 0.0; deg < 360.0; deg += 15.0) {
    const double theta = radiansFromDegrees(deg);
    const RodKinematics at = calcRodKinematics(m, theta, d), plus = calcRodKinematics(m, theta + h, d),
                        minus = calcRodKinematics(m, theta - h, d);
    const double tol = h * h / 6 * 3 * lambda * std::pow(k, 2.5) + 4 * kEps / h * std::pow(k, 0.5);
    EXPECT_NEAR(at.beta_dot, (plus.beta - minus.beta) / (2 * h), tol) << deg;
    EXPECT_NEAR(at.beta_ddot, (plus.beta_dot - minus.beta_dot) / (2 * h), tol * k) << deg;
  }
}

// The dead centres: the piston stops there (v_p = 0), the outer one is the farthest position of the turn, the inner
// one the nearest, and their difference is the stroke, 2 r only when centric (longer with an offset).
TEST_P(PinOffsetTest, DeadCentresAndStroke) {
  const Mechanism m = mechanism();
  const double r = m.crank.radius, l = m.rod.length, d = delta(), w = m.machine.speed, k = stiffness();
  const DeadCentres dc = calcDeadCentres(m, d);
  const PistonKinematics outer = calcPistonKinematics(m, dc.outer, d), inner = calcPistonKinematics(m, dc.inner, d);
  EXPECT_NEAR(outer.v_p, 0.0, 16 * kEps * r * w * std::sqrt(k));
  EXPECT_NEAR(inner.v_p, 0.0, 16 * kEps * r * w * std::sqrt(k));
  EXPECT_NEAR(outer.x_p - inner.x_p, dc.stroke, 16 * kEps * (l + r));
  for (double deg = 0.0; deg < 360.0; deg += 0.5) {
    const double x = calcPistonKinematics(m, radiansFromDegrees(deg), d).x_p;
    EXPECT_LE(x, outer.x_p + 4 * kEps * (l + r));
    EXPECT_GE(x, inner.x_p - 4 * kEps * (l + r));
  }
  if (d != 0.0) EXPECT_GT(dc.stroke, 2.0 * r);
  // The outer dead centre lies on the side of the offset: theta_outer has delta's sign.
  EXPECT_EQ(std::signbit(dc.outer), std::signbit(d));
}

// Q = dU/dphi: a central difference of U (step h = 1e-4: truncation h^2 / 6 |U'''| <= h^2 / 6 x 3 E k^2.5, rounding
// 4 eps E_abs / h with E_abs the absolute potential of the masses up to l + r away).
TEST_P(PinOffsetTest, GravityTorqueIsTheDerivativeOfThePotential) {
  const Mechanism m = mechanism();
  const double h = 1e-4, k = stiffness();
  const double E = m.machine.gravity * (m.piston.mass + m.rod.mass + m.crank.mass + m.crank.counterweight_mass);
  const double tol = h * h / 6 * 3 * E * m.crank.radius * std::pow(k, 2.5) + 4 * kEps * E * (m.rod.length + m.crank.radius) / h;
  for (double deg = 0.0; deg < 360.0; deg += 15.0) {
    const double phi = radiansFromDegrees(deg);
    EXPECT_NEAR(calcGravityTorque(m, phi), (calcPotentialEnergy(m, phi + h) - calcPotentialEnergy(m, phi - h)) / (2 * h), tol)
        << deg;
  }
  EXPECT_EQ(calcPotentialEnergy(m, 0.0), 0.0);
}

// The shaking harmonics of an offset motion (a DFT resolved to rounding) summed back give the exact shaking force and
// moment at angles off the DFT's grid (the mean of -dP/dt and -dH/dt over a turn is zero). Tolerance: 64 eps of the
// force scale per harmonic summed (40).
class PinOffsetHarmonicsTest : public PinOffsetTest {};

TEST_P(PinOffsetHarmonicsTest, ShakingHarmonicsSumToTheShaking) {
  const Mechanism m = mechanism();
  const std::vector<ShakingHarmonic> h = calcShakingHarmonics(m, 40);
  const double w = m.machine.speed;
  const double scale = (m.piston.mass + m.rod.mass + m.crank.mass + m.crank.counterweight_mass) * m.crank.radius * w * w *
                       stiffness() * stiffness();
  for (double phi : {0.1, 1.3, 2.9, 4.4}) {
    const Shaking exact = calcShaking(m, phi);
    Vec2 force{};
    double moment_z = 0.0;
    for (const ShakingHarmonic& x : h) {
      const double c = std::cos(x.n * phi), s = std::sin(x.n * phi);
      for (int i = 0; i < 2; ++i) force[i] += x.force_cos[i] * c + x.force_sin[i] * s;
      moment_z += x.moment_cos[2] * c + x.moment_sin[2] * s;
    }
    EXPECT_NEAR(force[0], exact.force[0], 64 * 40 * kEps * scale);
    EXPECT_NEAR(force[1], exact.force[1], 64 * 40 * kEps * scale);
    EXPECT_NEAR(moment_z, exact.moment[2], 64 * 40 * kEps * scale * (m.rod.length + m.crank.radius));
  }
}

std::vector<OffsetCase> offsetCases() {
  std::vector<OffsetCase> cases;
  for (double lambda : {0.05, 0.3, 0.9})
    for (double fraction : {-0.99, -0.3, -0.01, 0.0, 0.004, 0.5, 0.99}) cases.push_back({lambda, fraction});
  return cases;
}
INSTANTIATE_TEST_SUITE_P(Sweep, PinOffsetTest, ::testing::ValuesIn(offsetCases()), caseName);
// Cases with lambda + |delta| / l <= 0.34: the harmonics decay at least like 0.34^n, so the tail beyond harmonic 40 is
// below 0.34^40 ~ 1e-19 of the primary, under the check's rounding.
INSTANTIATE_TEST_SUITE_P(Sweep, PinOffsetHarmonicsTest,
                         ::testing::Values(OffsetCase{0.05, -0.01}, OffsetCase{0.05, 0.004}, OffsetCase{0.3, 0.0},
                                           OffsetCase{0.05, -0.3}, OffsetCase{0.3, -0.01}, OffsetCase{0.3, 0.004}),
                         caseName);

}  // namespace
}  // namespace crankcheck::analytic
