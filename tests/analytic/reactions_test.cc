// Joint reactions against balances they were not computed from: the power balance drive_torque * omega =
// d(kinetic + potential energy)/dt, the static limit drive_torque = Q (eq 13), the whole mechanism's momentum
// balance, the rod's moment balance about its centre of mass, and exact zeros at the dead centres.

#include <gtest/gtest.h>

#include <cmath>

#include "../support/cases.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/analytic/reactions.h"

namespace crankcheck::analytic {
namespace {

using testing::CaseSpec;
using testing::isClose;
using testing::kEps;

struct Frame {
  Vec2 e, n;
};
Frame cylinderFrame(const Mechanism& m) {
  const double g = m.machine.cylinder_angle;
  return {{std::cos(g), std::sin(g)}, {-std::sin(g), std::cos(g)}};
}

// Kinetic energy of the whole mechanism from the (separately tested) kinematics: pistons, rods (velocity of
// the centre of mass and spin about it, I_G = I_o - m_k z_k^2), crank point masses.
double calcKineticEnergy(const Mechanism& m, double phi) {
  const double r = m.crank.radius, l = m.rod.length, w = m.machine.speed, mu = m.rod.com_from_wrist_pin / l;
  const double I_G = m.rod.inertia_about_wrist_pin - m.rod.mass * m.rod.com_from_wrist_pin * m.rod.com_from_wrist_pin;
  double T = 0.0;
  for (double alpha : m.machine.crank_angles) {
    const double theta = phi + alpha;
    const PistonKinematics p = calcPistonKinematics(m, theta);
    const RodKinematics rod = calcRodKinematics(m, theta);
    // cylinder frame: v_A = (v_p, 0), v_B = w r (-sin, cos)
    const double vG_e = (1 - mu) * p.v_p - mu * w * r * std::sin(theta), vG_n = mu * w * r * std::cos(theta);
    T += 0.5 * m.piston.mass * p.v_p * p.v_p + 0.5 * m.rod.mass * (vG_e * vG_e + vG_n * vG_n) +
         0.5 * I_G * rod.beta_dot * rod.beta_dot +
         0.5 * (m.crank.mass * m.crank.com_radius * m.crank.com_radius +
                m.crank.counterweight_mass * m.crank.counterweight_radius * m.crank.counterweight_radius) * w * w;
  }
  return T;
}

class ReactionsTest : public ::testing::TestWithParam<CaseSpec> {
 protected:
  Mechanism mechanismAt(double lambda, double rpm) const {
    CaseSpec spec = GetParam();
    spec.lambda = lambda;
    spec.rpm = rpm;
    return testing::makeMechanism(spec);
  }
};

// Power balance: the drive torque's power equals the rate of change of kinetic plus potential energy. d/dt = w d/dphi
// by a five-point difference with h = 1e-3: truncation h^4/30 |E^(5)| with |E^(5)| <= 32 (T + U scale) (1 - lambda^2)^(-9/2),
// rounding 3 eps (T + U) / h; lambda <= 0.9.
TEST_P(ReactionsTest, DriveTorquePowerEqualsEnergyRate) {
  for (double lambda : testing::sweepModerateLambdas()) {
    const Mechanism m = mechanismAt(lambda, 4500.0);
    const double w = m.machine.speed, h = 1e-3;
    const auto energy = [&](double phi) { return calcKineticEnergy(m, phi) + calcPotentialEnergy(m, phi); };
    const double energy_scale = testing::calcTorqueScale(m);  // >= peak kinetic energy per radian of crank
    const double tol = energy_scale * (std::pow(h, 4) * 32 / 30 * std::pow((1 - lambda) * (1 + lambda), -4.5) + 3 * kEps / h);
    for (double phi_deg : testing::sweepPhisDeg()) {
      const double phi = radiansFromDegrees(phi_deg);
      const double rate = (energy(phi - 2 * h) - 8 * energy(phi - h) + 8 * energy(phi + h) - energy(phi + 2 * h)) / (12 * h);
      EXPECT_TRUE(isClose(calcReactions(m, phi).drive_torque, rate, tol)) << "lambda " << lambda << " phi_deg " << phi_deg;
      (void)w;
    }
  }
}

// At rest the drive torque is the holding torque, +Q (CONVENTIONS.md): Newton-Euler of every body against eq (13).
// Both are O(10 k) roundings of terms bounded by the energy scale; 64 eps of it.
TEST_P(ReactionsTest, StaticDriveTorqueEqualsQ) {
  for (double lambda : testing::sweepLambdas()) {
    const Mechanism m = mechanismAt(lambda, 0.0);
    for (double phi_deg : testing::sweepPhisDeg()) {
      const double phi = radiansFromDegrees(phi_deg);
      EXPECT_TRUE(isClose(calcReactions(m, phi).drive_torque, calcGravityTorque(m, phi),
                          64 * kEps * testing::calcEnergyScale(m) / (1 - lambda * lambda)))
          << "lambda " << lambda << " phi_deg " << phi_deg;
    }
  }
}

// Momentum of the whole mechanism: bearing force + wall forces + weights = sum of m a over every mass.
// The accelerations come from the kinematics; 64 eps of the force scale.
TEST_P(ReactionsTest, ExternalForcesBalanceMomentumRate) {
  for (double lambda : testing::sweepLambdas()) {
    for (double rpm : {0.0, 6000.0}) {
      const Mechanism m = mechanismAt(lambda, rpm);
      const Frame f = cylinderFrame(m);
      const double r = m.crank.radius, w = m.machine.speed, g = m.machine.gravity, mu = m.rod.com_from_wrist_pin / m.rod.length;
      for (double phi_deg : testing::sweepPhisDeg()) {
        const double phi = radiansFromDegrees(phi_deg);
        const Reactions reactions = calcReactions(m, phi);
        double Fx = reactions.bearing_force[0], Fy = reactions.bearing_force[1], max_x = 0, max_y = 0;
        double total_mass = 0;
        for (size_t j = 0; j < m.machine.crank_angles.size(); ++j) {
          const double theta = phi + m.machine.crank_angles[j];
          Fx += reactions.cylinders[j].wall_force * f.n[0];
          Fy += reactions.cylinders[j].wall_force * f.n[1];
          const PistonKinematics p = calcPistonKinematics(m, theta);
          // accelerations in the cylinder frame, then global
          const double aB_e = -w * w * r * std::cos(theta), aB_n = -w * w * r * std::sin(theta);
          const double aG_e = (1 - mu) * p.a_p + mu * aB_e, aG_n = mu * aB_n;
          const double crank_first_moment = m.crank.mass * m.crank.com_radius - m.crank.counterweight_mass * m.crank.counterweight_radius;
          const double ma_e = m.piston.mass * p.a_p + m.rod.mass * aG_e + crank_first_moment / r * aB_e;
          const double ma_n = m.rod.mass * aG_n + crank_first_moment / r * aB_n;
          max_x += ma_e * f.e[0] + ma_n * f.n[0];
          max_y += ma_e * f.e[1] + ma_n * f.n[1];
          total_mass += m.piston.mass + m.rod.mass + m.crank.mass + m.crank.counterweight_mass;
        }
        Fy -= total_mass * g;
        const double tol = 64 * kEps * testing::calcForceScale(m);
        EXPECT_TRUE(isClose(Fx, max_x, tol)) << "X, lambda " << lambda << " rpm " << rpm << " phi_deg " << phi_deg;
        EXPECT_TRUE(isClose(Fy, max_y, tol)) << "Y, lambda " << lambda << " rpm " << rpm << " phi_deg " << phi_deg;
      }
    }
  }
}

// The rod's moment balance about its centre of mass G (the library balances moments about the wrist pin A):
// I_G psi_ddot = (A - G) x (-F_A) + (B - G) x F_B, psi_ddot = -beta_ddot. The moments' lever is the rod, so the
// scale is force scale times (l + r); 64 eps of it.
TEST_P(ReactionsTest, RodMomentBalanceAboutCentreOfMass) {
  for (double lambda : testing::sweepLambdas()) {
    const Mechanism m = mechanismAt(lambda, 6000.0);
    const Frame f = cylinderFrame(m);
    const double r = m.crank.radius, mu = m.rod.com_from_wrist_pin / m.rod.length;
    const double I_G = m.rod.inertia_about_wrist_pin - m.rod.mass * m.rod.com_from_wrist_pin * m.rod.com_from_wrist_pin;
    for (double phi_deg : testing::sweepPhisDeg()) {
      const double phi = radiansFromDegrees(phi_deg);
      const Reactions reactions = calcReactions(m, phi);
      for (size_t j = 0; j < m.machine.crank_angles.size(); ++j) {
        const double theta = phi + m.machine.crank_angles[j];
        const double x = calcPistonKinematics(m, theta).x_p;
        const Vec2 A{x * f.e[0], x * f.e[1]};
        const Vec2 B{r * (std::cos(theta) * f.e[0] + std::sin(theta) * f.n[0]),
                     r * (std::cos(theta) * f.e[1] + std::sin(theta) * f.n[1])};
        const Vec2 G{A[0] + mu * (B[0] - A[0]), A[1] + mu * (B[1] - A[1])};
        const Vec2& F_A = reactions.cylinders[j].wrist_pin_force;  // rod on piston: the piston pushes the rod with -F_A
        const Vec2& F_B = reactions.cylinders[j].crank_pin_force;
        const double moment = -((A[0] - G[0]) * F_A[1] - (A[1] - G[1]) * F_A[0]) + ((B[0] - G[0]) * F_B[1] - (B[1] - G[1]) * F_B[0]);
        const double psi_ddot = -calcRodKinematics(m, theta).beta_ddot;
        EXPECT_TRUE(isClose(I_G * psi_ddot, moment, 64 * kEps * testing::calcForceScale(m) * (m.rod.length + r)))
            << "lambda " << lambda << " phi_deg " << phi_deg << " cylinder " << j;
      }
    }
  }
}

std::vector<CaseSpec> reactionCases() {
  std::vector<CaseSpec> cases;
  for (int k : {1, 2, 3, 4, 5, 6, 8, 12})
    for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke})
      for (double gamma : testing::sweepGammasDeg()) cases.push_back({k, cycle, Acting::kSingle, 0.3, gamma, 3000.0});
  cases.push_back({2, Cycle::kTwoStroke, Acting::kDouble, 0.3, 37.0, 3000.0});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Sweep, ReactionsTest, ::testing::ValuesIn(reactionCases()),
                         [](const auto& info) { return testing::caseNameWithoutLambda(info.param); });

// A standing single cylinder at its dead centres: everything lies on the vertical cylinder axis, so the wall
// force and every horizontal component vanish exactly (no rounding residue: the angles are exact quarter turns).
TEST(Reactions, StandingDeadCentresHaveExactZeros) {
  const Mechanism m = testing::makeMechanism({1, Cycle::kFourStroke, Acting::kSingle, 0.3, 90.0, 3000.0});
  for (double phi_deg : {0.0, 180.0, -180.0, 360.0}) {
    const Reactions reactions = calcReactions(m, radiansFromDegrees(phi_deg));
    EXPECT_EQ(reactions.cylinders[0].wall_force, 0.0) << phi_deg;
    EXPECT_EQ(reactions.cylinders[0].crank_pin_force[0], 0.0) << phi_deg;
    EXPECT_EQ(reactions.cylinders[0].wrist_pin_force[0], 0.0) << phi_deg;
    EXPECT_EQ(reactions.bearing_force[0], 0.0) << phi_deg;
    EXPECT_EQ(reactions.drive_torque, 0.0) << phi_deg;
  }
}

}  // namespace
}  // namespace crankcheck::analytic
