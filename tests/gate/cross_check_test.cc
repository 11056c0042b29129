// The cross-check gate: the analytic library against the independent Simbody model, case by case, for every
// quantity: U, Q (holding torque and virtual power), piston kinematics, every reaction and the drive torque;
// and the paper's formulas "as printed", whose disagreement with Simbody is asserted where they are wrong.
//
// Tolerances: validation/scales.h (the rule shared with `crankcheck validate`): |a - b| <= 64 eps x scale x
// conditioning, with the scales of docs/CONVENTIONS-crankcheck.md. Both engines round each quantity at the level
// of a few eps of its scale; Simbody adds its position projection (solved to 2 eps (l + r)) and a k-body
// articulated solve. Conditioning: near lambda = 1 the loop's condition number 1/(1 - lambda^2); for tiny lambda
// Simbody's coordinates are of size l = r / lambda, so its rounding relative to crank-scale quantities grows like
// 1/lambda. The worst ratios are printed with CRANKCHECK_PRINT_RATIOS=1 and listed in docs/contributing.md.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <filesystem>
#include <memory>
#include <utility>
#include <vector>

#include "../support/cases.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/simbody_models/k_crank_gravity_model.h"
#include "crankcheck/simbody_models/k_crank_model.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/scales.h"

namespace crankcheck {
namespace {

using testing::CaseSpec;
using testing::kEps;


// Worst agreement seen per quantity, printed at exit with CRANKCHECK_PRINT_RATIOS=1 (docs/contributing.md's table):
// the error in units of eps x scale x conditioning (what the tolerance allows kAgreementMultiple of), and the plain error / scale
// over the engine range lambda = 0.05..0.4.
struct Worst {
  double in_tolerance_units = 0.0;
  double relative_engine_range = 0.0;
};
std::map<std::string, Worst>& worstRatios() {
  static std::map<std::string, Worst> ratios;
  return ratios;
}
double g_current_lambda = 0.0;  // set by each test before comparing
class RatioPrinter : public ::testing::Environment {
 public:
  void TearDown() override {
    if (std::getenv("CRANKCHECK_PRINT_RATIOS") == nullptr) return;
    std::printf("%-22s %28s %34s\n", "quantity", "worst / (eps scale cond.)", "worst / scale, lambda 0.05..0.4");
    for (const auto& [check, worst] : worstRatios())
      std::printf("%-22s %28.1f %34.2g\n", check.c_str(), worst.in_tolerance_units, worst.relative_engine_range);
  }
};
[[maybe_unused]] const auto* const kRatioPrinter = ::testing::AddGlobalTestEnvironment(new RatioPrinter);

using validation::Comparison;
using validation::Scales;
using validation::calcScales;
using validation::kAgreementMultiple;

// The agreement rule of validation/scales.h, printing both sides; records the worst ratios.
::testing::AssertionResult agree(const Comparison& c) {
  Worst& worst = worstRatios()[c.quantity];
  worst.in_tolerance_units = std::max(worst.in_tolerance_units, c.error() / (kEps * c.scale * c.conditioning));
  if (g_current_lambda >= 0.05 && g_current_lambda <= 0.4)
    worst.relative_engine_range = std::max(worst.relative_engine_range, c.error() / c.scale);
  if (c.agrees()) return ::testing::AssertionSuccess();
  char buffer[360];
  std::snprintf(buffer, sizeof buffer,
                "%s%s: analytic %.17g, simbody %.17g, |difference| %.3e > tol %.3e (= %g eps x scale %.3e x "
                "conditioning %.3g)",
                c.quantity.c_str(), c.cylinder >= 0 ? (" of cylinder " + std::to_string(c.cylinder)).c_str() : "",
                c.a, c.b, c.error(), c.tolerance(), kAgreementMultiple, c.scale, c.conditioning);
  return ::testing::AssertionFailure() << buffer;
}
::testing::AssertionResult agree(const std::string& quantity, double analytic, double simbody, double scale,
                                 double conditioning = 1.0) {
  return agree(Comparison{quantity, -1, analytic, simbody, scale, conditioning});
}

// Every quantity of the two engines' Evaluation at one angle.
void expectEvaluationsAgree(const Mechanism& m, const Evaluation& a, const Evaluation& s) {
  ASSERT_EQ(a.cylinders.size(), s.cylinders.size());
  for (const Comparison& c : validation::compareEvaluations(m, a, s)) EXPECT_TRUE(agree(c));
}

class CrossCheckTest : public ::testing::TestWithParam<CaseSpec> {};

std::vector<CaseSpec> gateCases() {
  std::vector<CaseSpec> cases;
  for (int k = 1; k <= 12; ++k)
    for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke})
      for (double lambda : testing::sweepLambdas())
        for (double gamma : testing::sweepGammasDeg())
          cases.push_back({k, cycle, Acting::kSingle, lambda, gamma, cycle == Cycle::kTwoStroke ? 3000.0 : 6000.0});
  for (int k : {1, 2, 3, 4})
    for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke})
      cases.push_back({k, cycle, Acting::kDouble, 0.3, 37.0, 4500.0});
  return cases;
}


// Every example scene, both engines, through the same scene files the CLI reads.
// The three-way gate: every other exact engine of the registry (MuJoCo's hard multipliers; a fourth engine joins by
// its registration line) against the analytic engine and against Simbody, over the same sweep, at speed and at rest,
// by the same rule. Soft engines (gated = false) are measured in the report, never here.
::testing::AssertionResult agreeEngines(const Comparison& c, const std::string& a, const std::string& b) {
  if (c.agrees()) return ::testing::AssertionSuccess();
  char buffer[400];
  std::snprintf(buffer, sizeof buffer,
                "%s%s: %s %.17g, %s %.17g, |difference| %.3e > tol %.3e (= %g eps x scale %.3e x conditioning %.3g)",
                c.quantity.c_str(), c.cylinder >= 0 ? (" of cylinder " + std::to_string(c.cylinder)).c_str() : "",
                a.c_str(), c.a, b.c_str(), c.b, c.error(), c.tolerance(), kAgreementMultiple, c.scale, c.conditioning);
  return ::testing::AssertionFailure() << buffer;
}

/// Builds every gated engine besides analytic and simbody for m.
std::vector<std::pair<const Engine*, std::unique_ptr<EngineModel>>> buildOtherExactEngines(const Mechanism& m) {
  std::vector<std::pair<const Engine*, std::unique_ptr<EngineModel>>> models;
  for (const Engine* engine : validation::listReferenceEngines())
    if (engine->name != "simbody") models.emplace_back(engine, engine->build(m));
  return models;
}

void expectThreeWayAgreement(const Mechanism& m, const std::vector<double>& phis_deg, const std::string& trace) {
  simbody_models::KCrankModel simbody(m);
  auto others = buildOtherExactEngines(m);
  ASSERT_FALSE(others.empty()) << "no third exact engine is registered";
  for (double phi_deg : phis_deg) {
    SCOPED_TRACE(trace + " phi_deg " + std::to_string(phi_deg));
    const double phi = radiansFromDegrees(phi_deg);
    const Evaluation a = analytic::calcEvaluation(m, phi), s = simbody.evaluate(phi);
    for (auto& [engine, model] : others) {
      const Evaluation e = model->evaluate(phi);
      ASSERT_EQ(a.cylinders.size(), e.cylinders.size());
      for (const Comparison& c : validation::compareEvaluations(m, a, e)) EXPECT_TRUE(agreeEngines(c, "analytic", engine->name));
      for (const Comparison& c : validation::compareEvaluations(m, s, e)) EXPECT_TRUE(agreeEngines(c, "simbody", engine->name));
    }
  }
}

// The sweep: at the case's speed (3000 rpm two-stroke, 6000 rpm four-stroke) and at rest, around the full turn, the
// analytic engine against Simbody (every quantity, and Simbody's second route to Q at rest), and every other exact
// engine of the registry (MuJoCo) against both: the three-way gate in the same pass, so that Simbody's evaluations of
// a case are made once. Each engine's model is built once per case and evaluated at both speeds (EngineModel::setSpeed).
TEST_P(CrossCheckTest, EveryQuantityAgrees) {
  std::vector<Mechanism> at_speed;
  for (double rpm : {GetParam().rpm, 0.0}) {
    CaseSpec spec = GetParam();
    spec.rpm = rpm;
    at_speed.push_back(testing::makeMechanism(spec));
  }
  g_current_lambda = GetParam().lambda;
  simbody_models::KCrankModel simbody(at_speed.front());
  auto others = buildOtherExactEngines(at_speed.front());
  ASSERT_FALSE(others.empty()) << "no third exact engine is registered";
  for (double phi_deg : testing::sweepPhisDeg()) {
    const double phi = radiansFromDegrees(phi_deg);
    for (const Mechanism& m : at_speed) {
      SCOPED_TRACE(testing::caseName(GetParam()) + " at " + std::to_string(m.speed_rpm) + " rpm, phi_deg " +
                   std::to_string(phi_deg));
      const Scales sc = calcScales(m);
      simbody.setSpeed(m.machine.speed);
      const Evaluation a = analytic::calcEvaluation(m, phi), s = simbody.evaluate(phi);
      expectEvaluationsAgree(m, a, s);
      if (m.speed_rpm == 0.0)
        EXPECT_TRUE(agree("Q (virtual power)", a.Q, simbody.calcVirtualPowerQ(phi), sc.energy, sc.conditioning));
      for (auto& [engine, model] : others) {
        model->setSpeed(m.machine.speed);
        const Evaluation e = model->evaluate(phi);
        ASSERT_EQ(a.cylinders.size(), e.cylinders.size());
        for (const Comparison& c : validation::compareEvaluations(m, a, e)) EXPECT_TRUE(agreeEngines(c, "analytic", engine->name));
        for (const Comparison& c : validation::compareEvaluations(m, s, e)) EXPECT_TRUE(agreeEngines(c, "simbody", engine->name));
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Gate, CrossCheckTest, ::testing::ValuesIn(gateCases()),
                         [](const auto& info) {
                           const std::string name = testing::caseName(info.param);
                           return name.substr(0, name.rfind('_'));  // the speed is implied by the stroke
                         });

TEST(ThreeWayScenes, EveryExampleSceneAgrees) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(CRANKCHECK_SCENES_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    expectThreeWayAgreement(loadSceneFile(entry.path()), testing::sweepPhisDeg(), entry.path().filename().string());
    ++count;
  }
  EXPECT_GE(count, 5);
}

TEST(CrossCheckScenes, EveryExampleSceneAgrees) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(CRANKCHECK_SCENES_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    const Mechanism m = loadSceneFile(entry.path());
    g_current_lambda = calcCrankRatio(m);
    simbody_models::KCrankModel model(m);
    for (double phi_deg : testing::sweepPhisDeg()) {
      SCOPED_TRACE(entry.path().filename().string() + " phi_deg " + std::to_string(phi_deg));
      const double phi = radiansFromDegrees(phi_deg);
      expectEvaluationsAgree(m, analytic::calcEvaluation(m, phi), model.evaluate(phi));
    }
    ++count;
  }
  EXPECT_GE(count, 5);
}


// ---------------------------------------------------------------------------------------------------------------
// The paper and the book "as printed", judged by Simbody. These tests assert disagreement where the printed
// formula is wrong or truncated: the verdict is part of the gate.

class PaperAsPrintedTest : public ::testing::TestWithParam<CaseSpec> {};

// Eq (5) as printed splits the rod as if z_k were measured from the crank pin. Simbody, given the rod's true centre
// of mass at z_k = 0.3 l from the wrist pin, agrees with the derived form and refutes the printed one; with
// z_k = l/2 (where the two readings coincide) both agree. Visible for engines whose crank-pin terms do not cancel
// (k = 1; k = 2 four-stroke).
TEST_P(PaperAsPrintedTest, Eq5AsPrintedDisagreesWithSimbodyUnlessRodIsSymmetric) {
  CaseSpec spec = GetParam();
  spec.rpm = 0.0;
  const Mechanism m = testing::makeMechanism(spec);
  g_current_lambda = spec.lambda;
  Mechanism symmetric = m;
  symmetric.rod.com_from_wrist_pin = 0.5 * m.rod.length;
  symmetric.rod.inertia_about_wrist_pin = m.rod.mass * std::pow(0.5 * m.rod.length, 2) + m.rod.inertia_about_wrist_pin -
                                          m.rod.mass * std::pow(m.rod.com_from_wrist_pin, 2);  // same I_G
  simbody_models::KCrankModel model(m), symmetric_model(symmetric);
  const Scales sc = calcScales(m);
  double worst_printed = 0.0;
  for (double phi_deg : testing::sweepPhisDeg()) {
    SCOPED_TRACE("phi_deg " + std::to_string(phi_deg));
    const double phi = radiansFromDegrees(phi_deg);
    const double U_simbody = model.calcPotentialEnergy(phi), Q_simbody = model.calcHoldingTorque(phi);
    EXPECT_TRUE(agree("U", analytic::calcPotentialEnergy(m, phi), U_simbody, sc.absolute_height_energy));
    EXPECT_TRUE(agree("Q", analytic::calcGravityTorque(m, phi), Q_simbody, sc.energy, sc.conditioning));
    worst_printed = std::max({worst_printed,
                              std::fabs(analytic::calcPotentialEnergy(m, phi, analytic::Eq5Form::kAsPrinted) - U_simbody),
                              std::fabs(analytic::calcGravityTorque(m, phi, analytic::Eq5Form::kAsPrinted) - Q_simbody)});
    EXPECT_TRUE(agree("U", analytic::calcPotentialEnergy(symmetric, phi, analytic::Eq5Form::kAsPrinted),
                      symmetric_model.calcPotentialEnergy(phi), sc.absolute_height_energy));
  }
  // The misplaced rod weight (m_k g = 6 N, 0.4 l off) makes errors of order 1e-2 of the energy scale: more than
  // 1e9 times the gate's tolerance.
  EXPECT_GT(worst_printed, 1e-2 * sc.energy) << "eq (5) as printed agreed with Simbody";
}

INSTANTIATE_TEST_SUITE_P(Gate, PaperAsPrintedTest,
                         ::testing::Values(CaseSpec{1, Cycle::kTwoStroke, Acting::kSingle, 0.3, 90.0, 0.0},
                                           CaseSpec{1, Cycle::kFourStroke, Acting::kSingle, 0.3, 37.0, 0.0},
                                           CaseSpec{1, Cycle::kTwoStroke, Acting::kSingle, 0.3, 0.0, 0.0},
                                           CaseSpec{1, Cycle::kFourStroke, Acting::kSingle, 0.3, -90.0, 0.0},
                                           CaseSpec{2, Cycle::kFourStroke, Acting::kSingle, 0.3, 90.0, 0.0}),
                         [](const auto& info) {
                           const std::string name = testing::caseName(info.param);
                           return name.substr(0, name.rfind('_'));
                         });

// Eq (15) as printed stops at lambda^11 and Lambda_12 (and misprints one coefficient). At lambda = 0.4 eq (14) with
// those coefficients misses Simbody's Q by far more than the gate's tolerance, while eq (14) with exact Lambda_n
// to order 60 (truncation q^30 < 1e-40) agrees with Simbody to rounding.
TEST(PaperAsPrinted, Eq15TableIsVisiblyTruncatedAtLambda0p4) {
  const Mechanism m = testing::makeMechanism({1, Cycle::kTwoStroke, Acting::kSingle, 0.4, 90.0, 0.0});
  g_current_lambda = 0.4;
  simbody_models::KCrankModel model(m);
  const Scales sc = calcScales(m);
  double worst_printed = 0.0;
  for (double phi_deg = 0.0; phi_deg < 360.0; phi_deg += 7.5) {
    const double phi = radiansFromDegrees(phi_deg);
    const double Q_simbody = model.calcHoldingTorque(phi);
    EXPECT_TRUE(agree("Q (eq 14, exact Lambda)", analytic::calcGravityTorqueFourier(m, phi, 60), Q_simbody, sc.energy,
                      sc.conditioning));
    worst_printed = std::max(worst_printed, std::fabs(analytic::calcGravityTorqueFourier(
                                                          m, phi, 12, analytic::LambdaSource::kAsPrinted) - Q_simbody));
  }
  const double tol = kAgreementMultiple * kEps * sc.energy * sc.conditioning;
  EXPECT_GT(worst_printed, 100 * tol) << "the printed Lambda table agreed with Simbody at lambda = 0.4";
  EXPECT_LT(worst_printed, 1e-4 * sc.energy) << "but it is still a close approximation";
}

// Norton's two-term piston motion (13.3c-e) against Simbody's: off by O(lambda^3) r w^2 in acceleration, far
// beyond rounding at lambda = 0.3, within the Taylor bound of the position (kinematics_test.cc).
TEST(PaperAsPrinted, NortonTwoTermIsAnApproximationOfSimbodysMotion) {
  const Mechanism m = testing::makeMechanism({1, Cycle::kFourStroke, Acting::kSingle, 0.3, 90.0, 6000.0});
  g_current_lambda = 0.3;
  simbody_models::KCrankModel model(m);
  const Scales sc = calcScales(m);
  const double lambda = 0.3, bound_x = m.rod.length * std::pow(lambda, 4) / (8 * std::pow(1 - lambda * lambda, 1.5));
  double worst_a = 0.0;
  for (double phi_deg = 0.0; phi_deg < 360.0; phi_deg += 7.5) {
    const double phi = radiansFromDegrees(phi_deg);
    const CylinderEvaluation s = model.evaluate(phi).cylinders[0];
    const analytic::PistonKinematics norton = analytic::calcPistonKinematicsNorton(m, phi);
    EXPECT_LE(std::fabs(norton.x_p - s.x_p), bound_x + kAgreementMultiple * kEps * sc.position);
    worst_a = std::max(worst_a, std::fabs(norton.a_p - s.a_p));
  }
  EXPECT_GT(worst_a, 1e-3 * m.crank.radius * m.machine.speed * m.machine.speed);
}


// ---------------------------------------------------------------------------------------------------------------
// The reduced Simbody model (two-mass rods, one distance constraint per cylinder) computes U and Q by its own
// dynamics; it must agree with the analytic engine and with the full model to the same tolerance.

class ReducedModelTest : public ::testing::TestWithParam<CaseSpec> {};

TEST_P(ReducedModelTest, UAndQAgreeWithAnalyticAndFullModel) {
  for (double lambda : {0.05, 0.3, 0.9, 0.999}) {
    CaseSpec spec = GetParam();
    spec.lambda = lambda;
    spec.rpm = 0.0;
    const Mechanism m = testing::makeMechanism(spec);
    g_current_lambda = lambda;
    simbody_models::KCrankGravityModel reduced(m);
    simbody_models::KCrankModel full(m);
    const Scales sc = calcScales(m);
    for (double phi_deg : testing::sweepPhisDeg()) {
      SCOPED_TRACE(testing::caseName(spec) + " phi_deg " + std::to_string(phi_deg));
      const double phi = radiansFromDegrees(phi_deg);
      const double Q = analytic::calcGravityTorque(m, phi);
      EXPECT_TRUE(agree("U (reduced model)", analytic::calcPotentialEnergy(m, phi), reduced.calcPotentialEnergy(phi), sc.absolute_height_energy));
      EXPECT_TRUE(agree("Q (reduced model, holding torque)", Q, reduced.calcHoldingTorque(phi), sc.energy, sc.conditioning));
      EXPECT_TRUE(agree("Q (reduced model, virtual power)", Q, reduced.calcVirtualPowerQ(phi), sc.energy, sc.conditioning));
      EXPECT_TRUE(agree("Q (reduced against full model)", full.calcHoldingTorque(phi), reduced.calcHoldingTorque(phi), sc.energy,
                        sc.conditioning));
    }
  }
}

std::vector<CaseSpec> reducedCases() {
  std::vector<CaseSpec> cases;
  for (int k = 1; k <= 12; ++k)
    for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke})
      for (double gamma : {90.0, 37.0, 0.0}) cases.push_back({k, cycle, Acting::kSingle, 0.3, gamma, 0.0});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Gate, ReducedModelTest, ::testing::ValuesIn(reducedCases()),
                         [](const auto& info) { return testing::caseNameWithoutLambda(info.param); });

}  // namespace
}  // namespace crankcheck
