// Reduced inertia, the gas torque and the free run against independent routes: the paper's two-mass rod with Delta_I
// (an identity), finite differences of J, the Newton-Euler drive torque (Lagrange's equation at constant speed; the gas
// alone for the gas torque), and a direct Runge-Kutta integration of Lagrange's equation for the free run.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "../support/cases.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/analytic/motion.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/scene/scene_file.h"

namespace crankcheck::analytic {
namespace {

using testing::CaseSpec;
using testing::isClose;
using testing::kEps;

class MotionTest : public ::testing::TestWithParam<CaseSpec> {
 protected:
  Mechanism mechanismAt(double lambda) const { return testing::makeMechanism(GetParam(), lambda); }
};

// The two-mass rod with Delta_I has the rod's mass, first moment and inertia about the wrist pin, hence the same
// kinetic energy: J agrees to rounding (16 eps of J); without Delta_I it does not (Delta_I != 0 here).
TEST_P(MotionTest, TwoMassRodWithDeltaIIsExact) {
  for (double lambda : testing::sweepModerateLambdas()) {
    const Mechanism m = mechanismAt(lambda);
    for (double phi_deg : testing::sweepPhisDeg()) {
      const double phi = radiansFromDegrees(phi_deg);
      const ReducedInertia a = calcReducedInertia(m, phi), b = calcReducedInertia(m, phi, RodInertiaForm::kTwoMassWithDeltaI);
      EXPECT_TRUE(isClose(a.J, b.J, 16 * kEps * a.J)) << lambda << " " << phi_deg;
      EXPECT_TRUE(isClose(a.dJ, b.dJ, 16 * kEps * a.J / (1 - lambda * lambda))) << lambda << " " << phi_deg;
    }
  }
}

// Lagrange's equation at constant speed (phi'' = 0, no load): the drive torque is (1/2) J' w^2 + Q. The reactions
// compute it by Newton-Euler of every body: an independent route. 64 eps of the torque scale.
TEST_P(MotionTest, NewtonEulerDriveTorqueIsLagrangesEquation) {
  for (double lambda : testing::sweepLambdas()) {
    const Mechanism m = mechanismAt(lambda);
    const double w = m.machine.speed;
    for (double phi_deg : testing::sweepPhisDeg()) {
      const double phi = radiansFromDegrees(phi_deg);
      const double lagrange = 0.5 * calcReducedInertia(m, phi).dJ * w * w + calcGravityTorque(m, phi);
      EXPECT_TRUE(isClose(calcReactions(m, phi).drive_torque, lagrange,
                          64 * kEps * testing::calcTorqueScale(m) / (1 - lambda * lambda)))
          << lambda << " " << phi_deg;
    }
  }
}

// dJ/dphi against a five-point difference of J (h = 1e-3; truncation h^4/30 |J^(5)|, |J^(5)| <= 32^2 J (1 - lambda^2)^(-5)).
TEST_P(MotionTest, DerivativeOfJMatchesFiniteDifference) {
  for (double lambda : testing::sweepModerateLambdas()) {
    const Mechanism m = mechanismAt(lambda);
    const double h = 1e-3;
    for (double phi = -1.0; phi < 6.5; phi += 0.7) {
      const auto J = [&](double p) { return calcReducedInertia(m, p).J; };
      const double fd = (J(phi - 2 * h) - 8 * J(phi - h) + 8 * J(phi + h) - J(phi + 2 * h)) / (12 * h);
      const double scale = J(phi);
      EXPECT_TRUE(isClose(calcReducedInertia(m, phi).dJ, fd,
                          scale * (std::pow(h, 4) * 1024 / 30 * std::pow((1 - lambda) * (1 + lambda), -5) + 3 * kEps / h)))
          << lambda << " " << phi;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Sweep, MotionTest,
                         ::testing::Values(CaseSpec{1, Cycle::kFourStroke, Acting::kSingle, 0.3, 90.0, 3000.0},
                                           CaseSpec{3, Cycle::kTwoStroke, Acting::kSingle, 0.3, 37.0, 4500.0},
                                           CaseSpec{4, Cycle::kFourStroke, Acting::kSingle, 0.3, 0.0, 6000.0}),
                         [](const auto& info) { return testing::caseNameWithoutLambda(info.param); });

// The free run's speed from the energy integral against classical RK4 on Lagrange's equation (state phi, phi_dot;
// 20000 steps per revolution: RK4's error (h w)^4 ~ 1e-16 per step). Agreement to 1e-10 of the speed.
TEST(FreeRun, EnergyIntegralMatchesIntegratedLagrangeEquation) {
  for (bool gravity : {true, false}) {
    Mechanism m = testing::makeMechanism({1, Cycle::kFourStroke, Acting::kSingle, 0.3, 90.0, 60.0});
    m.flywheel_inertia = 0.002;  // a light flywheel at 60 rpm: gravity makes a visible fluctuation
    const double w0 = m.machine.speed;
    const FreeRun run = calcFreeRun(m, w0, gravity);
    double phi = 0.0, v = w0, t = 0.0, vmax = w0, vmin = w0;
    const double h = 2 * M_PI / run.omega_mean / 20000;
    auto f = [&](double p, double pv) { return calcCrankAcceleration(m, p, pv, 0.0, gravity); };
    double t_rev = 0.0;
    while (phi < 2 * M_PI) {
      const double k1p = v, k1v = f(phi, v);
      const double k2p = v + 0.5 * h * k1v, k2v = f(phi + 0.5 * h * k1p, v + 0.5 * h * k1v);
      const double k3p = v + 0.5 * h * k2v, k3v = f(phi + 0.5 * h * k2p, v + 0.5 * h * k2v);
      const double k4p = v + h * k3v, k4v = f(phi + h * k3p, v + h * k3v);
      const double phi_next = phi + h / 6 * (k1p + 2 * k2p + 2 * k3p + k4p);
      const double v_next = v + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
      if (phi_next >= 2 * M_PI) t_rev = t + h * (2 * M_PI - phi) / (phi_next - phi);
      phi = phi_next;
      v = v_next;
      t += h;
      vmax = std::max(vmax, v);
      vmin = std::min(vmin, v);
      if (phi < 2 * M_PI) EXPECT_TRUE(isClose(v, calcFreeRunSpeed(m, w0, phi, gravity), 1e-10 * w0)) << phi;
    }
    // The revolution time by linear interpolation of the last step: error (h^2 phi''/8) / phi_dot ~ 1e-12 s.
    EXPECT_TRUE(isClose(2 * M_PI / t_rev, run.omega_mean, 1e-9 * w0)) << "gravity " << gravity;
    // Sampled extremes lie within the exact ones, by at most the sampling error (h w)^2 |phi''| / 8.
    EXPECT_LE(vmax, run.omega_max * (1 + 1e-12));
    EXPECT_GE(vmin, run.omega_min * (1 - 1e-12));
    EXPECT_TRUE(isClose(vmax, run.omega_max, 1e-7 * w0));
    EXPECT_TRUE(isClose(vmin, run.omega_min, 1e-7 * w0));
    EXPECT_GT(run.delta, 0.0);
  }
}

TEST(FreeRun, GravityOffIsTheInertiaOnlyFluctuation) {
  Mechanism m = testing::makeMechanism({1, Cycle::kFourStroke, Acting::kSingle, 0.3, 90.0, 300.0});
  const FreeRun with = calcFreeRun(m, m.machine.speed, true), without = calcFreeRun(m, m.machine.speed, false);
  EXPECT_NE(with.delta, without.delta);
  m.machine.gravity = 0.0;  // no weight: the two must be the same computation
  EXPECT_EQ(calcFreeRun(m, m.machine.speed, true).delta, calcFreeRun(m, m.machine.speed, false).delta);
}

TEST(FreeRun, RefusesARunThatCannotCompleteARevolution) {
  // Hanging (gamma = -90): at phi = 0 the piston is at its lowest, so every other angle lifts it.
  Mechanism m = testing::makeMechanism({1, Cycle::kFourStroke, Acting::kSingle, 0.3, -90.0, 1.0});
  m.flywheel_inertia = 1e-4;
  EXPECT_THROW(calcFreeRun(m, m.machine.speed, true), std::domain_error);
  m.flywheel_inertia.reset();
  EXPECT_THROW(calcFreeRun(m, 10.0, true), std::invalid_argument);
}

// The gas torque by virtual work (calcGasTorque, -sum F_gas dx_p/dphi) against minus the drive torque of the gas alone
// from the force balance of every body (reactions.h), on the example scenes with [gas] (the V8's two banks, the inline
// four, the pin-offset four), over their whole working cycle, on and off the pressure table's corners. Tolerance: both
// sum k terms of size F_gas,max r; the force balance takes about ten roundings per term (the rod's moment, the two
// components of F_A, F_B, the cross product), the virtual work three: 32 eps x k x F_gas,max r covers both (seen:
// 0.89 eps x k x F_gas,max r).
class GasTorqueTest : public ::testing::TestWithParam<std::string> {};

TEST_P(GasTorqueTest, VirtualWorkEqualsMinusTheDriveTorqueOfTheGasAlone) {
  const Mechanism m = loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / GetParam());
  ASSERT_TRUE(m.gas.has_value()) << GetParam() << " has no [gas]";
  const Mechanism gas_only = withLoads(m, true, false, false);
  const double cycle = m.machine.cycle == Cycle::kFourStroke ? 4.0 * M_PI : 2.0 * M_PI;
  double largest = 0.0;  // the largest gas force of any cylinder over the cycle
  for (int i = 0; i < 1440; ++i)
    for (int j = 0; j < m.machine.cylinders; ++j) largest = std::max(largest, std::fabs(calcGasForce(m, j, cycle * i / 1440)));
  const double scale = m.machine.cylinders * largest * m.crank.radius;
  ASSERT_GT(scale, 0.0);
  for (int i = 0; i <= 1440; ++i)
    for (double off : {0.0, 1e-3}) {
      const double phi = cycle * i / 1440 + off;
      EXPECT_NEAR(calcGasTorque(m, phi), -calcReactions(gas_only, phi).drive_torque, 32.0 * kEps * scale) << phi;
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, GasTorqueTest,
                         ::testing::Values("v8_cross_plane.toml", "inline4_four_stroke.toml", "inline4_pin_offset.toml"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param.substr(0, info.param.find('.'));
                         });

// Without [gas] the gas torque is 0; a scene at rest cannot give dx_p/dphi as v_p / omega and is refused.
TEST(GasTorque, ZeroWithoutGasAndRefusedAtRest) {
  Mechanism m = loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / "inline4_four_stroke.toml");
  Mechanism no_gas = withLoads(m, false, true, true);
  EXPECT_EQ(calcGasTorque(no_gas, 0.3), 0.0);
  EXPECT_THROW(calcGasTorque(withLoads(m, true, false, true), 0.3), std::invalid_argument);
}

}  // namespace
}  // namespace crankcheck::analytic
