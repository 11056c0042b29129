// The cross-check gate: the analytic library against the independent Simbody model, case by case, for every
// quantity: U, Q (holding torque and virtual power), piston kinematics, every reaction and the drive torque;
// and the paper's formulas "as printed", whose disagreement with Simbody is asserted where they are wrong.
//
// Tolerances (CONVENTIONS.md): a multiple of machine epsilon times a physical scale of the case.
//   E   energy scale k g (r (m_o + m_k) + m_s r_s + m_p r_p)                      (U, Q)
//   E_V E + k g (m_o + m_k)(l + r): Simbody's U is V(phi) - V(0) of absolute heights up to l + r
//   X   l + r (positions), V = r w (1 + (1 - lambda^2)^(-1/2)) (velocities), A = calcAccelerationScale
//   F   calcForceScale (forces), T = F max(r, r_s, r_p) (drive torque)
// Both engines round each quantity at the level of a few eps of its scale; Simbody adds its position projection
// (solved to 8 eps (l + r), see simbody_models/README.md) which moves forces by F x that relative error, and its
// accelerations come from a k-body articulated solve (O(10 k) operations). kMultiple = 256 covers these with
// margin at every case of the sweep; the worst ratios seen are printed with CRANKCHECK_PRINT_RATIOS=1 and listed
// in the README.
// Conditioning: near lambda = 1 the rod's angular acceleration grows like (1 - lambda^2)^(-1/2) and both engines'
// rounding is amplified by the loop's condition number 1/(1 - lambda^2); for tiny lambda Simbody's coordinates
// are of size l = r / lambda, so its rounding relative to crank-scale quantities grows like 1/lambda (calcScales).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <filesystem>
#include <memory>

#include "../support/cases.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/simbody_models/k_crank_model.h"

namespace crankcheck {
namespace {

using testing::CaseSpec;
using testing::kEps;

constexpr double kMultiple = 256;

std::map<std::string, double>& worstRatios() {
  static std::map<std::string, double> ratios;
  return ratios;
}
class RatioPrinter : public ::testing::Environment {
 public:
  void TearDown() override {
    if (std::getenv("CRANKCHECK_PRINT_RATIOS") == nullptr) return;
    for (const auto& [check, ratio] : worstRatios())
      std::printf("worst |analytic - simbody| / scale  %-28s %.3g  (= %.1f eps)\n", check.c_str(), ratio, ratio / kEps);
  }
};
[[maybe_unused]] const auto* const kRatioPrinter = ::testing::AddGlobalTestEnvironment(new RatioPrinter);

// |a - b| <= kMultiple eps scale conditioning, printing both sides; records the ratio to the scale.
::testing::AssertionResult agree(const std::string& quantity, double analytic, double simbody, double scale,
                                 double conditioning = 1.0) {
  const double error = std::fabs(analytic - simbody);
  double& worst = worstRatios()[quantity];
  worst = std::max(worst, error / scale);
  const double tol = kMultiple * kEps * scale * conditioning;
  if (error <= tol) return ::testing::AssertionSuccess();
  char buffer[320];
  std::snprintf(buffer, sizeof buffer,
                "%s: analytic %.17g, simbody %.17g, |difference| %.3e > tol %.3e (= %g eps x scale %.3e x "
                "conditioning %.3g)",
                quantity.c_str(), analytic, simbody, error, tol, kMultiple, scale, conditioning);
  return ::testing::AssertionFailure() << buffer;
}

struct Scales {
  double E, E_V, X, V, A, F, T, conditioning;
};
Scales calcScales(const Mechanism& m) {
  const double lambda = m.crank.radius / m.rod.length, r = m.crank.radius, l = m.rod.length;
  const double stiff = 1.0 / ((1.0 - lambda) * (1.0 + lambda));
  Scales s;
  s.E = testing::calcEnergyScale(m);
  s.E_V = s.E + m.engine.cylinders * m.engine.gravity * (m.piston.mass + m.rod.mass) * (l + r);
  s.X = l + r;
  s.V = r * m.engine.speed * (1.0 + std::sqrt(stiff));
  s.A = testing::calcAccelerationScale(m);
  s.F = testing::calcForceScale(m);
  s.T = testing::calcTorqueScale(m);
  // 1 / (1 - lambda^2) (1.19 at 0.4, 5.3 at 0.9, 500 at 0.999) for the loop's condition near lambda = 1, times
  // (l + r) / r because Simbody holds the rod in absolute coordinates: its roundoff is eps (l + r), i.e. eps / lambda
  // relative to crank-scale quantities (4.3 at lambda = 0.3, 1e6 at lambda = 1e-6, where the rod is 50 km long).
  s.conditioning = stiff * (l + r) / r;
  return s;
}

// Every quantity of the two engines' Evaluation at one angle.
void expectEvaluationsAgree(const Mechanism& m, const Evaluation& a, const Evaluation& s) {
  const Scales sc = calcScales(m);
  EXPECT_TRUE(agree("U", a.U, s.U, sc.E_V));
  EXPECT_TRUE(agree("Q (holding torque)", a.Q, s.Q, sc.E, sc.conditioning));
  EXPECT_TRUE(agree("drive_torque", a.drive_torque, s.drive_torque, sc.T, sc.conditioning));
  EXPECT_TRUE(agree("bearing_force", a.bearing_force[0], s.bearing_force[0], sc.F, sc.conditioning));
  EXPECT_TRUE(agree("bearing_force", a.bearing_force[1], s.bearing_force[1], sc.F, sc.conditioning));
  ASSERT_EQ(a.cylinders.size(), s.cylinders.size());
  for (size_t j = 0; j < a.cylinders.size(); ++j) {
    SCOPED_TRACE("cylinder " + std::to_string(j));
    const CylinderEvaluation &ca = a.cylinders[j], &cs = s.cylinders[j];
    EXPECT_TRUE(agree("x_p", ca.x_p, cs.x_p, sc.X));
    EXPECT_TRUE(agree("v_p", ca.v_p, cs.v_p, sc.V, sc.conditioning));
    EXPECT_TRUE(agree("a_p", ca.a_p, cs.a_p, sc.A, sc.conditioning));
    for (int i = 0; i < 2; ++i) {
      EXPECT_TRUE(agree("crank_pin_force", ca.crank_pin_force[i], cs.crank_pin_force[i], sc.F, sc.conditioning));
      EXPECT_TRUE(agree("wrist_pin_force", ca.wrist_pin_force[i], cs.wrist_pin_force[i], sc.F, sc.conditioning));
    }
    EXPECT_TRUE(agree("wall_force", ca.wall_force, cs.wall_force, sc.F, sc.conditioning));
  }
}

class CrossCheckTest : public ::testing::TestWithParam<CaseSpec> {};

// At the case's speed (3000 rpm two-stroke, 6000 rpm four-stroke) and at rest, around the full turn.
TEST_P(CrossCheckTest, EveryQuantityAgrees) {
  for (double rpm : {GetParam().rpm, 0.0}) {
    CaseSpec spec = GetParam();
    spec.rpm = rpm;
    const Mechanism m = testing::makeMechanism(spec);
    simbody_models::KCrankModel model(m);
    const Scales sc = calcScales(m);
    for (double phi_deg : testing::sweepPhisDeg()) {
      SCOPED_TRACE(testing::caseName(spec) + " phi_deg " + std::to_string(phi_deg));
      const double phi = radiansFromDegrees(phi_deg);
      const Evaluation a = analytic::calcEvaluation(m, phi);
      expectEvaluationsAgree(m, a, model.evaluate(phi));
      if (rpm == 0.0) EXPECT_TRUE(agree("Q (virtual power)", a.Q, model.calcVirtualPowerQ(phi), sc.E, sc.conditioning));
    }
  }
}

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

INSTANTIATE_TEST_SUITE_P(Gate, CrossCheckTest, ::testing::ValuesIn(gateCases()),
                         [](const auto& info) {
                           const std::string name = testing::caseName(info.param);
                           return name.substr(0, name.rfind('_'));  // the speed is implied by the stroke
                         });

// Every example scene, both engines, through the same scene files the CLI reads.
TEST(CrossCheckScenes, EveryExampleSceneAgrees) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(CRANKCHECK_SCENES_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    const Mechanism m = loadSceneFile(entry.path());
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

}  // namespace
}  // namespace crankcheck
