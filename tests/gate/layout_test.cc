// The gate over engine layouts (issue 12): every layout of the balance table (V, W-less V12, boxer, radial, inline
// with its textbook crank), standing, lying and hanging, at rest and at speed: the analytic engine against Simbody
// for every quantity, the shaking force and moment included. Same rule as the inline gate (validation/scales.h):
// |a - b| <= 64 eps x scale x conditioning; the shaking moment's scale is the force scale times the largest
// moment arm, l + r + max |z_j| (a moving part's position about O).

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <utility>
#include <string>
#include <vector>

#include "../support/cases.h"
#include "crankcheck/analytic/motion.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/analytic/shaking.h"
#include "crankcheck/simbody_models/k_crank_model.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/balance.h"
#include "crankcheck/validation/layouts.h"
#include "crankcheck/validation/scales.h"

namespace crankcheck {
namespace {

using analytic::RodInertiaForm;

struct LayoutCase {
  validation::Layout layout;
  double rotation_deg = 0.0;
};
std::string caseName(const LayoutCase& c) {
  return c.layout.name + (c.rotation_deg == 0.0 ? "_standing" : c.rotation_deg == 90.0 ? "_lying" : "_hanging");
}
void PrintTo(const LayoutCase& c, std::ostream* os) { *os << caseName(c); }

// The passenger-car parts of the gate's cases (tests/support/cases.h) at lambda 0.3, 6000 rpm.
Mechanism parts() { return testing::makeMechanism(testing::CaseSpec{1, Cycle::kFourStroke, Acting::kSingle, 0.3, 90.0, 6000.0}); }

// A spark-ignition pressure table (the example scenes'), each cylinder firing at its own outer dead centre
// (firing_j = -alpha_j), with a 86 mm bore: gas forces of up to 33 kN, ten times the inertia forces.
Mechanism withGas(Mechanism m) {
  GasParams gas;
  gas.bore = 0.086;
  gas.cycle = 4.0 * M_PI;
  for (double deg : {0.0, 10.0, 20.0, 30.0, 45.0, 60.0, 90.0, 120.0, 180.0, 200.0, 360.0, 540.0, 640.0, 690.0})
    gas.cycle_angles.push_back(radiansFromDegrees(deg));
  gas.pressures = {3.2e6, 5.2e6, 5.6e6, 4.8e6, 3.4e6, 2.4e6, 1.3e6, 0.8e6, 0.35e6, 0.05e6, 0.02e6, -0.02e6, 0.25e6, 1.1e6};
  m.gas = gas;
  m.firing_angles.clear();
  for (double alpha : m.machine.crank_angles) m.firing_angles.push_back(std::fmod(4.0 * M_PI - alpha, 4.0 * M_PI));
  return m;
}

class LayoutGateTest : public ::testing::TestWithParam<LayoutCase> {};

// At speed and at rest, without and with gas (the gas force enters every reaction and the drive torque; the force
// scale then includes the largest gas force): the analytic engine against every other exact engine (Simbody, MuJoCo).
TEST_P(LayoutGateTest, EveryQuantityAgrees) {
  for (const auto& [rpm, gas] : {std::pair{6000.0, false}, std::pair{0.0, false}, std::pair{6000.0, true}, std::pair{0.0, true}}) {
    Mechanism m = validation::makeLayoutMechanism(GetParam().layout, parts(), GetParam().rotation_deg);
    if (gas) m = withGas(m);
    m.speed_rpm = rpm;
    m.machine.speed = rpm * (M_PI / 30.0);
    // every exact engine besides the analytic one: simbody, mujoco (the registry's references)
    std::vector<std::pair<const Engine*, std::unique_ptr<EngineModel>>> references;
    for (const Engine* engine : validation::listReferenceEngines()) references.emplace_back(engine, engine->build(m));
    for (double phi_deg : testing::sweepPhisDeg()) {
      SCOPED_TRACE(caseName(GetParam()) + " at " + std::to_string(rpm) + " rpm" + (gas ? " with gas" : "") + ", phi_deg " +
                   std::to_string(phi_deg));
      const double phi = radiansFromDegrees(phi_deg);
      const Evaluation a = analytic::calcEvaluation(m, phi);
      for (auto& [engine, model] : references) {
        const Evaluation s = model->evaluate(phi);
        ASSERT_EQ(a.cylinders.size(), s.cylinders.size());
        for (const validation::Comparison& c : validation::compareEvaluations(m, a, s))
          EXPECT_TRUE(c.agrees()) << c.quantity << (c.cylinder >= 0 ? " of cylinder " + std::to_string(c.cylinder) : "")
                                  << ": analytic " << c.a << ", " << engine->name << " " << c.b << ", |difference| "
                                  << c.error() << " > tol " << c.tolerance();
      }
      if (gas) {
        for (size_t j = 0; j < a.cylinders.size(); ++j)
          EXPECT_EQ(a.cylinders[j].gas_force, calcGasForce(m, static_cast<int>(j), phi));  // the input, as given
      }
      if (rpm == 0.0) {  // at rest nothing accelerates: no shaking at all, exactly, in the closed form
        EXPECT_EQ(a.shaking_force[0], 0.0);
        EXPECT_EQ(a.shaking_force[1], 0.0);
        for (double moment : a.shaking_moment) EXPECT_EQ(moment, 0.0);
      }
    }
  }
}

std::vector<LayoutCase> layoutCases() {
  std::vector<LayoutCase> cases;
  for (const validation::Layout& layout : validation::getBalanceLayouts())
    for (double rotation : {0.0, 90.0, 180.0}) cases.push_back({layout, rotation});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Gate, LayoutGateTest, ::testing::ValuesIn(layoutCases()),
                         [](const auto& info) { return caseName(info.param); });

// The drive torque split into gas, inertia and gravity parts (eval --split): each part by one engine with the other
// loads off. The parts agree between the engines, and in each engine they add up to the whole: the equations are
// linear in the loads at a given motion, so the sum differs from the whole by rounding of the drive torque only
// (the gate's 64 eps x torque scale x conditioning).
TEST_P(LayoutGateTest, DriveTorqueSplitsIntoGasInertiaAndGravity) {
  const Mechanism m = withGas(validation::makeLayoutMechanism(GetParam().layout, parts(), GetParam().rotation_deg));
  const validation::Scales sc = validation::calcScales(m);
  const double tol = validation::kAgreementMultiple * validation::kEps * sc.torque * sc.acceleration_conditioning;
  const Mechanism cases[3] = {withLoads(m, true, false, false), withLoads(m, false, true, false), withLoads(m, false, false, true)};
  simbody_models::KCrankModel whole(m), gas(cases[0]), inertia(cases[1]), gravity(cases[2]);
  simbody_models::KCrankModel* models[3] = {&gas, &inertia, &gravity};
  for (double phi_deg : {0.0, 17.0, 133.0, 222.5, 300.0, 400.0, 700.0}) {
    SCOPED_TRACE(caseName(GetParam()) + " phi_deg " + std::to_string(phi_deg));
    const double phi = radiansFromDegrees(phi_deg);
    double sum_a = 0.0, sum_s = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double a = analytic::calcReactions(cases[i], phi).drive_torque, s = models[i]->evaluate(phi).drive_torque;
      EXPECT_TRUE(testing::isClose(a, s, tol)) << "part " << i;
      sum_a += a;
      sum_s += s;
    }
    EXPECT_TRUE(testing::isClose(sum_a, analytic::calcReactions(m, phi).drive_torque, tol));
    EXPECT_TRUE(testing::isClose(sum_s, whole.evaluate(phi).drive_torque, tol));
    // The gravity part at rest is Q (CONVENTIONS: the static holding torque).
    EXPECT_TRUE(testing::isClose(analytic::calcReactions(cases[2], phi).drive_torque, analytic::calcEvaluation(m, phi).Q,
                                 validation::kAgreementMultiple * validation::kEps * sc.energy * sc.conditioning));
  }
}

// The two-mass rod (m_k1 at the wrist pin, m_k3 at the crank pin) against Simbody's rigid rod. It is exact when
// Delta_I = I_o - l z_k m_k = 0, and with the paper's Delta_I correction; without it, on a rod whose central inertia
// is twice the two-mass value (Delta_I = I_G / 2), the drive torque is off by more than 1e5 times the gate's
// tolerance (4e-3 N m at lambda = 0.1 to 3 N m at 0.6 on this car engine at 6000 rpm): the error is Delta_I psi_ddot
// carried through the rod's moment balance, of order Delta_I lambda omega^2.
TEST(RodModelGate, TwoMassRodIsExactOnlyWithDeltaIOrWhenItVanishes) {
  for (double lambda : {0.1, 0.3, 0.6}) {
    SCOPED_TRACE("lambda " + std::to_string(lambda));
    Mechanism m = testing::makeMechanism(testing::CaseSpec{3, Cycle::kFourStroke, Acting::kSingle, lambda, 90.0, 6000.0});
    const double l = m.rod.length, z = m.rod.com_from_wrist_pin, m_k = m.rod.mass;
    const double two_mass_central = m_k * z * (l - z);  // I_G of the two point masses
    for (double f : {1.0, 2.0}) {
      m.rod.inertia_about_wrist_pin = m_k * z * z + f * two_mass_central;  // I_G = f x the two-mass value
      const validation::Scales sc = validation::calcScales(m);
      const double tol = validation::kAgreementMultiple * validation::kEps * sc.torque * sc.acceleration_conditioning;
      simbody_models::KCrankModel model(m);
      double worst_without = 0.0, worst_with = 0.0;
      for (double phi_deg : testing::sweepPhisDeg()) {
        const double phi = radiansFromDegrees(phi_deg);
        const Evaluation s = model.evaluate(phi);
        const analytic::Reactions without = analytic::calcReactions(m, phi, RodInertiaForm::kTwoMassWithoutDeltaI);
        const analytic::Reactions with = analytic::calcReactions(m, phi, RodInertiaForm::kTwoMassWithDeltaI);
        worst_without = std::max(worst_without, std::fabs(without.drive_torque - s.drive_torque));
        worst_with = std::max(worst_with, std::fabs(with.drive_torque - s.drive_torque));
        // With Delta_I every reaction is the rigid rod's too (the paper's reduction, checked the same way).
        const double force_tol = validation::kAgreementMultiple * validation::kEps * sc.force * sc.acceleration_conditioning;
        for (int i = 0; i < 2; ++i) {
          EXPECT_TRUE(testing::isClose(with.bearing_force[i], s.bearing_force[i], force_tol));
          for (size_t j = 0; j < s.cylinders.size(); ++j) {
            EXPECT_TRUE(testing::isClose(with.cylinders[j].crank_pin_force[i], s.cylinders[j].crank_pin_force[i], force_tol));
            EXPECT_TRUE(testing::isClose(with.cylinders[j].wrist_pin_force[i], s.cylinders[j].wrist_pin_force[i], force_tol));
          }
        }
        for (size_t j = 0; j < s.cylinders.size(); ++j)
          EXPECT_TRUE(testing::isClose(with.cylinders[j].wall_force, s.cylinders[j].wall_force, force_tol));
      }
      EXPECT_LE(worst_with, tol) << "with Delta_I the two-mass rod is the rigid rod";
      if (f == 1.0) EXPECT_LE(worst_without, tol) << "Delta_I = 0: nothing to drop";
      else EXPECT_GT(worst_without, 1e5 * tol) << "Delta_I = I_G / 2 dropped: an error far beyond rounding";
    }
  }
}

// Balance: the closed-form harmonics against a DFT of each exact engine's (Simbody's, MuJoCo's) shaking force and moment
// (64 angles, harmonics 1..8),
// for every layout of the balance table. Each DFT coefficient is (2 / N) sum of N samples, each within the gate's
// 64 eps x scale x conditioning of the closed form: the coefficients agree within twice that. Aliasing folds
// harmonic 64 - n onto n: below lambda^56 = 1e-29 of the primary at lambda = 0.3. Where a harmonic vanishes
// exactly by symmetry, each engine's must be rounding too.
class BalanceGateTest : public ::testing::TestWithParam<LayoutCase> {};

TEST_P(BalanceGateTest, HarmonicsAgreeWithEachEnginesDft) {
  const Mechanism m = validation::makeLayoutMechanism(GetParam().layout, parts(), GetParam().rotation_deg);
  const validation::Scales sc = validation::calcScales(m);
  const double force_tol = 2 * validation::kAgreementMultiple * validation::kEps * sc.force * sc.acceleration_conditioning;
  const double moment_tol = 2 * validation::kAgreementMultiple * validation::kEps * sc.moment * sc.acceleration_conditioning;
  for (const validation::BalanceRow& row : validation::calcBalance(m, 8, 64)) {
    ASSERT_EQ(row.engines.size(), validation::listReferenceEngines().size());
    for (const auto& [engine, h] : row.engines) {
      SCOPED_TRACE(engine + ", harmonic " + std::to_string(row.n));
      for (int i = 0; i < 2; ++i) {
        EXPECT_TRUE(testing::isClose(row.analytic.force_cos[i], h.force_cos[i], force_tol));
        EXPECT_TRUE(testing::isClose(row.analytic.force_sin[i], h.force_sin[i], force_tol));
      }
      for (int i = 0; i < 3; ++i) {
        EXPECT_TRUE(testing::isClose(row.analytic.moment_cos[i], h.moment_cos[i], moment_tol));
        EXPECT_TRUE(testing::isClose(row.analytic.moment_sin[i], h.moment_sin[i], moment_tol));
      }
      ASSERT_TRUE(row.symmetry.decided);
      if (row.symmetry.force_cancels) EXPECT_LT(h.calcForceAmplitude(), 2 * force_tol);
      if (row.symmetry.moment_z_cancels) EXPECT_LT(h.calcMomentAmplitude(2), 2 * moment_tol);
      if (row.symmetry.moment_xy_cancels)
        EXPECT_LT(std::hypot(h.calcMomentAmplitude(0), h.calcMomentAmplitude(1)), 2 * moment_tol);
    }
  }
}

std::vector<LayoutCase> standingLayouts() {
  std::vector<LayoutCase> cases;
  for (const validation::Layout& layout : validation::getBalanceLayouts()) cases.push_back({layout, 0.0});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Gate, BalanceGateTest, ::testing::ValuesIn(standingLayouts()),
                         [](const auto& info) { return caseName(info.param); });

// A layout whose cylinders share one bank and one plane is the inline engine: the general code paths give the
// inline answers (the V8's left bank alone against the same four cylinders described inline).
TEST(LayoutGate, OneBankLayoutIsTheInlineEngine) {
  Mechanism inline4 = parts();
  inline4.machine.cylinders = 4;
  inline4.machine.explicit_crank_angles = true;
  inline4.machine.crank_angles = {0.0, M_PI, M_PI, 0.0};
  validation::Layout one_bank{"one_bank", "", {{90.0, 90.0, 0.0}, {90.0, 270.0, 0.0}, {90.0, 270.0, 0.0}, {90.0, 90.0, 0.0}}};
  const Mechanism layout = validation::makeLayoutMechanism(one_bank, parts());
  for (double phi_deg : testing::sweepPhisDeg()) {
    const double phi = radiansFromDegrees(phi_deg);
    const Evaluation a = analytic::calcEvaluation(inline4, phi), b = analytic::calcEvaluation(layout, phi);
    // The same operations on the same numbers: equal to rounding of the angle arithmetic (4 eps of each scale).
    const validation::Scales sc = validation::calcScales(inline4);
    EXPECT_TRUE(testing::isClose(a.Q, b.Q, 4 * validation::kEps * sc.energy));
    EXPECT_TRUE(testing::isClose(a.drive_torque, b.drive_torque, 4 * validation::kEps * sc.torque));
    EXPECT_TRUE(testing::isClose(a.shaking_force[1], b.shaking_force[1], 4 * validation::kEps * sc.force));
    EXPECT_TRUE(testing::isClose(a.shaking_moment[2], b.shaking_moment[2], 4 * validation::kEps * sc.moment));
  }
}

}  // namespace
}  // namespace crankcheck
