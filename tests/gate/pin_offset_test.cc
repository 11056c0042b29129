// The gate for real engines' geometry: pin offsets (desaxe) and balance shafts. Every exact engine (Simbody, MuJoCo)
// against the analytic engine, every quantity, offsets of both signs up to 0.999 (l - r) where the loop is nearly
// singular, a single cylinder, an inline four, a V8 with offsets of alternating sign, an inline four with gas; a
// Lanchester pair, a primary balancer, shafts with offsets and gas; at speed and at rest, at the gate's crank angles and
// at each cylinder's dead centres. The shafts designed by `balance --design N` cancel harmonic N in every engine. Rule and scales: validation/scales.h (the conditioning with lambda + max |delta| / l in
// place of lambda: how close the offset loop comes to its singularity).

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "../support/cases.h"
#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/validation/balance.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/scales.h"

namespace crankcheck {
namespace {

struct OffsetGateCase {
  std::string name;
  Mechanism m;
};
void PrintTo(const OffsetGateCase& c, std::ostream* os) { *os << c.name; }

std::string fractionTag(double f) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%s%04.0f", f < 0 ? "m" : "p", std::fabs(1e4 * f));
  return buffer;
}

std::vector<OffsetGateCase> offsetCases() {
  std::vector<OffsetGateCase> cases;
  auto offset = [](Mechanism m, double fraction) {
    m.machine.pin_offsets.assign(static_cast<size_t>(m.machine.cylinders), fraction * (m.rod.length - m.crank.radius));
    return m;
  };
  const Mechanism single = testing::makeMechanism({1, Cycle::kFourStroke, Acting::kSingle, 0.3, 90.0, 6000.0});
  for (double f : {-0.999, -0.5, -0.0035, 0.0035, 0.5, 0.999}) cases.push_back({"single_offset" + fractionTag(f), offset(single, f)});
  const Mechanism inline4 = testing::makeMechanism({4, Cycle::kFourStroke, Acting::kSingle, 0.3, 37.0, 6000.0});
  for (double f : {-0.9, 0.01, 0.95}) cases.push_back({"inline4_gamma37_offset" + fractionTag(f), offset(inline4, f)});
  const Mechanism lambda09 = testing::makeMechanism({2, Cycle::kTwoStroke, Acting::kSingle, 0.9, 0.0, 3000.0});
  for (double f : {-0.9, 0.9}) cases.push_back({"twin_lambda0p9_offset" + fractionTag(f), offset(lambda09, f)});
  // A V8 with offsets of alternating sign (1 mm), and a gas-driven inline four with a 1.2 mm offset each way.
  Mechanism v8 = loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / "v8_cross_plane.toml");
  for (int j = 0; j < v8.machine.cylinders; ++j) v8.machine.pin_offsets.push_back(j % 2 ? -0.001 : 0.001);
  cases.push_back({"v8_cross_plane_alternating_offsets", v8});
  // Balance shafts: a Lanchester pair and a primary balancer on a single cylinder, off the crank's plane and axis.
  Mechanism lanchester = single;
  lanchester.balance_shafts = {{2.0, 0.3, 0.04, -1.5, {0.05, -0.09, 0.01}}, {-2.0, 0.3, 0.04, -1.6, {-0.05, -0.09, -0.01}}};
  cases.push_back({"single_lanchester_pair", lanchester});
  Mechanism primary = single;
  primary.balance_shafts = {{-1.0, 1.2, 0.035, 1.9, {0.0, 0.11, 0.02}}};
  cases.push_back({"single_primary_balancer", primary});
  Mechanism both = offset(inline4, -0.3);
  both.balance_shafts = {{2.0, 0.5, 0.05, 0.4, {0.06, -0.1, 0.05}}, {-2.0, 0.5, 0.05, 0.2, {-0.06, -0.1, 0.05}},
                         {1.0, 0.2, 0.03, 2.0, {0.0, -0.15, 0.0}}};
  cases.push_back({"inline4_gamma37_offset_m3000_shafts", both});
  const Mechanism gas = loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / "inline4_four_stroke.toml");
  for (double d : {-0.0012, 0.0012}) {
    Mechanism m = gas;
    m.machine.pin_offsets.assign(4, d);
    cases.push_back({std::string("inline4_gas_offset") + (d < 0 ? "_minus" : "_plus") + "1p2mm", m});
  }
  return cases;
}

class OffsetGateTest : public ::testing::TestWithParam<OffsetGateCase> {};

TEST_P(OffsetGateTest, EveryExactEngineAgrees) {
  for (bool at_speed : {true, false}) {
    Mechanism m = GetParam().m;
    if (!at_speed) m.machine.speed = m.speed_rpm = 0.0;
    std::vector<double> phis;
    for (double deg : testing::sweepPhisDeg()) phis.push_back(radiansFromDegrees(deg));
    for (int j = 0; j < m.machine.cylinders; ++j) {  // each cylinder's dead centres, in phi
      const analytic::DeadCentres dc = analytic::calcDeadCentres(m, getPinOffset(m, j));
      phis.push_back(dc.outer - m.machine.crank_angles[static_cast<size_t>(j)]);
      phis.push_back(dc.inner - m.machine.crank_angles[static_cast<size_t>(j)]);
    }
    for (const Engine* engine : validation::listReferenceEngines()) {
      const std::unique_ptr<EngineModel> model = engine->build(m);
      for (double phi : phis) {
        SCOPED_TRACE(engine->name + (at_speed ? " at speed" : " at rest") + ", phi " + std::to_string(phi) + " rad");
        const Evaluation a = analytic::calcEvaluation(m, phi), e = model->evaluate(phi);
        for (const validation::Comparison& c : validation::compareEvaluations(m, a, e))
          EXPECT_TRUE(c.agrees()) << c.quantity << (c.cylinder >= 0 ? " of cylinder " + std::to_string(c.cylinder) : "")
                                  << ": analytic " << c.a << ", " << engine->name << " " << c.b << ", |difference| "
                                  << c.error() << " > tol " << c.tolerance();
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Gate, OffsetGateTest, ::testing::ValuesIn(offsetCases()),
                         [](const auto& info) { return info.param.name; });

// balance --design N: the shafts cancel harmonic N of the shaking force in the closed form and in each exact engine's
// DFT (tolerance: the DFT's, twice the gate's rule on the force scale with the shafts, as BalanceGateTest), for a single
// cylinder's primary (n = 1) and an inline four's secondary (n = 2), with a pin offset too.
TEST(BalanceShaftDesign, CancelsTheHarmonicInEveryEngine) {
  Mechanism single = testing::makeMechanism({1, Cycle::kFourStroke, Acting::kSingle, 0.3, 90.0, 6000.0});
  Mechanism inline4 = testing::makeMechanism({4, Cycle::kFourStroke, Acting::kSingle, 0.3, 90.0, 6000.0});
  inline4.machine.pin_offsets.assign(4, -0.001);
  for (auto [m, n] : {std::pair{single, 1}, std::pair{inline4, 2}}) {
    const double before = validation::calcBalance(m, n, 64)[static_cast<size_t>(n - 1)].analytic.calcForceAmplitude();
    const std::vector<BalanceShaftParams> shafts = validation::designBalanceShafts(m, n);
    ASSERT_FALSE(shafts.empty());
    m.balance_shafts.insert(m.balance_shafts.end(), shafts.begin(), shafts.end());
    const validation::Scales sc = validation::calcScales(m);
    const double tol = 2 * validation::kAgreementMultiple * validation::kEps * sc.force * sc.acceleration_conditioning;
    const validation::BalanceRow row = validation::calcBalance(m, n, 64)[static_cast<size_t>(n - 1)];
    SCOPED_TRACE(m.name + ", harmonic " + std::to_string(n));
    EXPECT_GT(before, 1e6 * tol) << "a harmonic worth cancelling";
    EXPECT_LE(row.analytic.calcForceAmplitude(), tol);
    for (const auto& [engine, h] : row.engines) EXPECT_LE(h.calcForceAmplitude(), tol) << engine;
  }
}

}  // namespace
}  // namespace crankcheck
