// Hard numerical cases of the analytic engine: relative accuracy for tiny lambda (no cancellation in the radical),
// periodicity at large and negative angles, exact zeros at quarter turns.

#include <gtest/gtest.h>

#include <cmath>

#include "../support/cases.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/analytic/reactions.h"

namespace crankcheck::analytic {
namespace {

using testing::isClose;
using testing::kEps;

// A standing single cylinder whose crank-pin terms balance (U2 = 0: the counterweight m_p r_p = m_k r z_k / l), so that U
// and Q come only from the piston's travel, where 1 - sqrt(1 - lambda^2 sin^2) would cancel catastrophically.
Mechanism balancedStanding(double lambda) {
  Mechanism m = testing::makeMechanism({1, Cycle::kFourStroke, Acting::kSingle, lambda, 90.0, 3000.0});
  m.crank.mass = 0.0;
  m.crank.counterweight_mass =
      m.rod.mass * m.crank.radius * (m.rod.com_from_wrist_pin / m.rod.length) / m.crank.counterweight_radius;
  return m;
}

// For lambda <= 1e-4 the series of the radical, 1 - sqrt(1 - u) = u/2 + u^2/8 + ..., u = lambda^2 sin^2, is exact
// to 1e-24 relative after two terms: an independent reference. Relative accuracy 16 eps of |U| and |Q| (a
// cancellation would lose a factor 1/lambda^2 there, i.e. 1e16 at lambda = 1e-8).
TEST(HardCases, TinyLambdaKeepsRelativeAccuracy) {
  for (double lambda : {1e-8, 1e-6, 1e-4}) {
    const Mechanism m = balancedStanding(lambda);
    const double U1 = calcGravityCoefficients(m).U1;
    ASSERT_LE(std::fabs(calcGravityCoefficients(m).U2), 4 * kEps * U1) << "setup: crank-pin terms must balance";
    for (double theta : {1e-3, 0.2, 1.0, 2.0, 3.0, -2.5, 4.0}) {
      const double s = std::sin(theta), c = std::cos(theta), u = lambda * lambda * s * s;
      const double one_minus_root = u / 2 + u * u / 8;
      // U = U1 (x_p(theta) - x_p(0)) / r = U1 (cos - 1 - (1 - root) / lambda), x_p - x_p(0) written with the series
      const double U_ref = U1 * (-2 * std::sin(theta / 2) * std::sin(theta / 2) - one_minus_root / lambda);
      const double Q_ref = -U1 * (s + lambda * s * c * (1 + u / 2 + 3 * u * u / 8));
      SCOPED_TRACE("lambda " + std::to_string(lambda) + " theta " + std::to_string(theta));
      EXPECT_TRUE(isClose(calcPotentialEnergy(m, theta), U_ref, 16 * kEps * std::fabs(U_ref)));
      EXPECT_TRUE(isClose(calcGravityTorque(m, theta), Q_ref, 16 * kEps * std::fabs(Q_ref)));
      // The piston's velocity and acceleration, relative to themselves, against the same series.
      const double r = m.crank.radius, w = m.machine.speed;
      const PistonKinematics k = calcPistonKinematics(m, theta);
      const double v_ref = -r * w * (s + lambda * s * c * (1 + u / 2));
      EXPECT_TRUE(isClose(k.v_p, v_ref, 16 * kEps * std::fabs(v_ref)));
    }
  }
}

// Periodicity: phi and phi - 2 pi n give the same state up to the representation of the angle. At phi = 1e6 rad the
// double's spacing is 1.2e-10 rad and the reduction (in long double, 2 pi to 64 bits) adds < 1e-13 rad; the
// quantities move by their slope times that: bounded by 1e-9 of each scale (slope <= 30 scale per radian here).
TEST(HardCases, PeriodicityAtLargeAndNegativeAngles) {
  const Mechanism m = testing::makeMechanism({4, Cycle::kFourStroke, Acting::kSingle, 0.3, 37.0, 4500.0});
  for (double phi : {1e6, -1e6, 12345.678, -720.5, 1e4}) {
    const double reduced = static_cast<double>(std::remainder(static_cast<long double>(phi), 2 * M_PIl));
    const double spacing = std::fabs(phi) * kEps;
    const double tol_rel = 30 * (spacing + 1e-13) + 64 * kEps;
    SCOPED_TRACE("phi " + std::to_string(phi));
    const Evaluation a = calcEvaluation(m, phi), b = calcEvaluation(m, reduced);
    EXPECT_TRUE(isClose(a.U, b.U, tol_rel * testing::calcEnergyScale(m)));
    EXPECT_TRUE(isClose(a.Q, b.Q, tol_rel * testing::calcEnergyScale(m)));
    EXPECT_TRUE(isClose(a.drive_torque, b.drive_torque, tol_rel * testing::calcTorqueScale(m)));
    EXPECT_TRUE(isClose(a.bearing_force[1], b.bearing_force[1], tol_rel * testing::calcForceScale(m)));
    EXPECT_TRUE(isClose(a.cylinders[2].a_p, b.cylinders[2].a_p, tol_rel * testing::calcAccelerationScale(m)));
  }
}

// Quarter turns given in degrees give exact zeros where the physics has zeros (CONVENTIONS: theta = 0 outer dead
// centre): a lying engine's U at half a turn has no height change from the pistons, a standing engine at the dead
// centres has no torque, velocity or side force.
TEST(HardCases, QuarterTurnsGiveExactZeros) {
  const Mechanism standing = testing::makeMechanism({2, Cycle::kFourStroke, Acting::kSingle, 0.3, 90.0, 3000.0});
  for (double deg : {0.0, 180.0, 360.0, -180.0, 540.0}) {
    const Evaluation ev = calcEvaluation(standing, radiansFromDegrees(deg));
    EXPECT_EQ(ev.Q, 0.0) << deg;
    EXPECT_EQ(ev.drive_torque, 0.0) << deg;
    EXPECT_EQ(ev.bearing_force[0], 0.0) << deg;
    for (const CylinderEvaluation& c : ev.cylinders) {
      EXPECT_EQ(c.v_p, 0.0) << deg;
      EXPECT_EQ(c.wall_force, 0.0) << deg;
    }
  }
  const Mechanism lying = testing::makeMechanism({1, Cycle::kTwoStroke, Acting::kSingle, 0.3, 0.0, 0.0});
  // gamma = 0: only the crank-pin masses change height, U = U2 sin(theta): zero at 0 and 180 degrees.
  EXPECT_EQ(calcPotentialEnergy(lying, radiansFromDegrees(180.0)), 0.0);
  EXPECT_EQ(calcGravityTorque(lying, radiansFromDegrees(90.0)), 0.0);
  EXPECT_EQ(calcGravityTorque(lying, radiansFromDegrees(-270.0)), 0.0);
}

}  // namespace
}  // namespace crankcheck::analytic
