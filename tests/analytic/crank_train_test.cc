// The crank train's pieces (analytic/crank_train.h) against what they did not produce: each throw's torque in the rigid
// motion against the drive torque of reactions.h (Newton-Euler on every body, another route than the energy's J' and
// Q), the gas torque against the drive torque of the gas alone, and the periodic signals against trigonometric
// polynomials known in closed form.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <vector>

#include "crankcheck/analytic/crank_train.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/analytic/motion.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/scene/scene_file.h"
#include "../support/crankshaft_scene.h"
#include "../support/test_numbers.h"

namespace crankcheck::analytic {
namespace {

using testing::kEps;

Mechanism loadWithCrankshaft(const std::string& scene, const std::string& crankshaft_table) {
  return testing::loadSceneWithCrankshaft(std::filesystem::path(CRANKCHECK_SCENES_DIR) / scene, crankshaft_table);
}

// A torque scale of a throw at omega: its largest inertia, gravity and gas torques' sizes, summed over its cylinders:
// (m_o + m_k) r^2 omega^2 + (m_o + m_k + m_c) g r + p_max A r (never zero: the masses are positive).
double calcTorqueScale(const Mechanism& tm, double omega) {
  const double r = tm.crank.radius, masses = tm.piston.mass + tm.rod.mass;
  double p_max = 0.0;
  if (tm.gas)
    for (double p : tm.gas->pressures) p_max = std::max(p_max, std::fabs(p));
  const double area = tm.gas ? M_PI * tm.gas->bore * tm.gas->bore / 4.0 : 0.0;
  return tm.machine.cylinders * (masses * r * r * omega * omega + (masses + tm.crank.mass) * tm.machine.gravity * r +
                                p_max * area * r);
}

// T_gas - Q - J' omega^2 / 2 (the energy route) against minus the drive torque that holds the throw alone at omega
// (reactions.h: Newton-Euler on pistons, rods and crank), on every throw of an inline four with gas and of a V8 (two
// cylinders a throw), at 720 angles. Tolerance 256 eps x the throw's torque scale: both sides are closed forms of a
// few dozen roundings each, at quantities up to the scale (the largest error found: 6 eps, CRANKCHECK_PRINT_RATIOS).
TEST(CrankTrainLoads, RigidThrowTorqueIsMinusTheDriveTorqueOfReactions) {
  for (const auto& [scene, table] :
       {std::pair{"inline4_four_stroke.toml", "throw_inertia = 2.0e-3\nstiffness = [5.5e5, 5.5e5, 5.5e5, 7.0e5]\n"},
        std::pair{"v8_cross_plane.toml", "throw_inertia = 3.0e-3\nstiffness = [3e5, 4e5, 5e5, 6e5]\n"}}) {
    SCOPED_TRACE(scene);
    const Mechanism m = loadWithCrankshaft(scene, table);
    const CrankTrain train = makeCrankTrain(m);
    double worst = 0.0;
    for (size_t j = 0; j < train.throws.size(); ++j) {
      Mechanism at_speed = train.throws[j];
      at_speed.machine.speed = train.omega;
      const double scale = calcTorqueScale(at_speed, train.omega);
      for (int i = 0; i < 720; ++i) {
        const double psi = 4.0 * M_PI * i / 720.0;
        const double expected = -calcReactions(at_speed, psi).drive_torque;
        const double got = calcRigidThrowTorque(train.throws[j], psi, train.omega);
        EXPECT_NEAR(got, expected, 256 * kEps * scale) << "throw " << j << " psi " << psi;
        worst = std::max(worst, std::fabs(got - expected) / (kEps * scale));
      }
    }
    if (std::getenv("CRANKCHECK_PRINT_RATIOS")) std::printf("%s: worst %.2f eps of the scale\n", scene, worst);
  }
}

// The gas torque alone: minus the drive torque of the throw with gas, at rest and without gravity (withLoads).
// Tolerance as above.
TEST(CrankTrainLoads, GasTorqueIsMinusTheDriveTorqueOfTheGasAlone) {
  const Mechanism m = loadWithCrankshaft("inline4_four_stroke.toml",
                                         "throw_inertia = 2.0e-3\nstiffness = [5.5e5, 5.5e5, 5.5e5, 7.0e5]\n");
  const CrankTrain train = makeCrankTrain(m);
  for (size_t j = 0; j < train.throws.size(); ++j) {
    const Mechanism gas_only = withLoads(train.throws[j], true, false, false);
    const double scale = calcTorqueScale(train.throws[j], 0.0);
    for (int i = 0; i < 720; ++i) {
      const double psi = 4.0 * M_PI * i / 720.0;
      EXPECT_NEAR(calcThrowLoads(train.throws[j], psi).gas_torque, -calcReactions(gas_only, psi).drive_torque,
                  256 * kEps * scale);
    }
  }
}

// calcThrowLoads computes each cylinder's angle once for the inertia and gravity's sums (cylinder_terms.h): a route
// equivalence, so bit for bit the separate functions' values (each held against other formulations above and in
// motion_test.cc), on every throw of every example scene (one and two cylinders a throw, banks, pin offsets, gas or
// none) at 720 angles over two turns and at quarter turns (the exact sin and cos of exact_trig.h).
TEST(CrankTrainLoads, ThrowLoadsAreTheSeparateFunctionsBitForBit) {
  for (const auto& entry : std::filesystem::directory_iterator(CRANKCHECK_SCENES_DIR)) {
    SCOPED_TRACE(entry.path().filename().string());
    const Mechanism m = loadSceneFile(entry.path());
    for (size_t j = 0; j < findThrows(m).size(); ++j) {
      const Mechanism tm = makeThrowMechanism(m, static_cast<int>(j));
      std::vector<double> angles;
      for (int i = 0; i < 720; ++i) angles.push_back(4.0 * M_PI * i / 720.0 + 1e-3);
      for (int q = -8; q <= 8; ++q) angles.push_back(q * M_PI_2);
      for (double psi : angles) {
        const ThrowLoads loads = calcThrowLoads(tm, psi);
        const ReducedInertia J = calcReducedInertia(tm, psi);
        EXPECT_EQ(loads.J, J.J) << "throw " << j << " psi " << psi;
        EXPECT_EQ(loads.dJ, J.dJ) << "throw " << j << " psi " << psi;
        EXPECT_EQ(loads.gravity_torque, calcGravityTorque(tm, psi)) << "throw " << j << " psi " << psi;
        EXPECT_EQ(loads.gas_torque, calcGasTorque(tm, psi)) << "throw " << j << " psi " << psi;
      }
    }
  }
}

// The train's matrices: K of a chain clamped at the flywheel, C with c_t on the throws only.
TEST(CrankTrainLoads, MatricesOfAFrontMassAndTwoThrows) {
  Mechanism m = loadWithCrankshaft("inline4_four_stroke.toml",
                                   "throw_inertia = 2.0e-3\nfront_inertia = 4.0e-3\nstiffness = [1, 2, 3, 4, 5]\n"
                                   "section_damping = [0.1, 0.2, 0.3, 0.4, 0.5]\nthrow_damping = 7\n");
  const CrankTrain train = makeCrankTrain(m);
  const Eigen::MatrixXd K = calcStiffnessMatrix(train), C = calcDampingMatrix(train);
  ASSERT_EQ(K.rows(), 5);
  EXPECT_EQ(K(0, 0), 1.0);
  EXPECT_EQ(K(0, 1), -1.0);
  EXPECT_EQ(K(1, 1), 3.0);
  EXPECT_EQ(K(4, 4), 9.0);
  EXPECT_EQ(K(3, 4), -4.0);
  EXPECT_EQ(C(0, 0), 0.1);                // the front mass: no absolute damping
  EXPECT_DOUBLE_EQ(C(1, 1), 0.3 + 7.0);   // a throw: its two sections and c_t
  EXPECT_DOUBLE_EQ(C(4, 4), 0.9 + 7.0);
  const Eigen::VectorXd twist = calcSectionTwists(Eigen::Vector3d(1.0, 3.0, 6.0));
  EXPECT_EQ(twist, Eigen::Vector3d(2.0, 3.0, -6.0));
}

// s(tau) = 0.3 + cos(tau) + 0.5 sin(3 tau + 0.2): 16 samples give c_0 = 0.3, c_1 = 1, c_3 = 0.5 e^{i (0.2 - pi/2)}
// to a few eps (an FFT of 16 points); its extremes against a grid of 2^20 points (within h^2 |s''|_max / 8 = 2e-11
// of the true ones, |s''| <= 5.5) and Brent's refinement at least as good as the grid.
TEST(PeriodicSignals, SamplesGiveTheCoefficientsAndTheExtremes) {
  auto s = [](double tau) { return 0.3 + std::cos(tau) + 0.5 * std::sin(3 * tau + 0.2); };
  std::vector<double> samples;
  for (int k = 0; k < 16; ++k) samples.push_back(s(2 * M_PI * k / 16));
  const PeriodicSignal signal = calcSignalFromSamples(samples);
  ASSERT_EQ(signal.coefficients.size(), 9u);
  EXPECT_NEAR(signal.coefficients[0].real(), 0.3, 8 * kEps);
  EXPECT_NEAR(std::abs(signal.coefficients[1] - 1.0), 0.0, 8 * kEps);
  EXPECT_NEAR(std::abs(signal.coefficients[3] - std::polar(0.5, 0.2 - M_PI / 2)), 0.0, 8 * kEps);
  for (int p : {2, 4, 5, 6, 7, 8}) EXPECT_NEAR(std::abs(signal.coefficients[static_cast<size_t>(p)]), 0.0, 8 * kEps);
  double lo = 1e300, hi = -1e300;
  const int grid = 1 << 20;
  for (int k = 0; k < grid; ++k) {
    lo = std::min(lo, s(2 * M_PI * k / grid));
    hi = std::max(hi, s(2 * M_PI * k / grid));
  }
  const SignalExtremes e = findSignalExtremes(signal);
  const double bound = std::pow(2 * M_PI / grid, 2) * 5.5 / 8 + 16 * kEps;
  EXPECT_LE(e.max, hi + bound);
  EXPECT_GE(e.max, hi - 16 * kEps);
  EXPECT_GE(e.min, lo - bound);
  EXPECT_LE(e.min, lo + 16 * kEps);
  EXPECT_NEAR(s(e.tau_max), e.max, 16 * kEps);
}

}  // namespace
}  // namespace crankcheck::analytic
