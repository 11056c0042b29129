// What `balance` prints of an engine's DFT (balance.h): its amplitude below the resolution is rounding, and an engine
// whose harmonic differs from the closed form's beyond the resolution sits out. The disagreement rule is held against
// harmonics built by hand (a part moved by a known amount), the slow scene against the closed form's own amplitudes.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "crankcheck/scene/scene_file.h"
#include "crankcheck/validation/balance.h"

namespace crankcheck::validation {
namespace {

analytic::ShakingHarmonic makeHarmonic() {
  analytic::ShakingHarmonic h;
  h.n = 3;
  h.force_cos = {100.0, -50.0};
  h.force_sin = {25.0, 12.5};
  h.moment_cos = {1.0, 2.0, 3.0};
  h.moment_sin = {-1.0, -2.0, -3.0};
  return h;
}

TEST(BalanceDisagreement, NamesThePartThatDiffersBeyondTheResolution) {
  const BalanceResolution resolution{1e-6, 1e-7};
  const analytic::ShakingHarmonic closed = makeHarmonic();
  EXPECT_EQ(findBalanceDisagreement(closed, closed, 3, resolution), "");
  analytic::ShakingHarmonic within = closed;
  within.force_sin[1] += 0.5e-6;  // half the resolution
  within.moment_cos[2] -= 0.5e-7;
  EXPECT_EQ(findBalanceDisagreement(closed, within, 3, resolution), "");
  analytic::ShakingHarmonic beyond = closed;
  beyond.force_sin[1] += 4e-6;  // four times it
  const std::string said = findBalanceDisagreement(closed, beyond, 3, resolution);
  EXPECT_EQ(said.rfind("harmonic 3's F_Y sine differs from the closed form by ", 0), 0u) << said;
  EXPECT_NE(said.find(" N, beyond the resolution 1e-06 N"), std::string::npos) << said;
  analytic::ShakingHarmonic moment = closed;
  moment.moment_sin[0] += 2e-7;
  EXPECT_NE(findBalanceDisagreement(closed, moment, 3, resolution).find("M_X sine"), std::string::npos);
  analytic::ShakingHarmonic broken = closed;
  broken.moment_cos[2] = std::numeric_limits<double>::quiet_NaN();  // not a number always differs
  EXPECT_NE(findBalanceDisagreement(closed, broken, 3, resolution).find("M_Z cosine"), std::string::npos);
}

// At 1e-6 rpm the static loads set the scales, and the orders above the second are nothing but each engine's
// rounding: both exact engines stay within the resolution of the closed form (none sits out), and their order-8
// amplitudes are below it, while the closed form's own order 8 (about 1e-21 N: the speed's omega^2) is far below.
TEST(BalanceDisagreement, AtASlowSpeedTheHighOrdersAreBelowTheResolution) {
  Mechanism m = loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / "inline4_four_stroke.toml");
  m.crankshaft.reset();
  m.speed_rpm = 1e-6;
  m.machine.speed = 1e-6 * 2 * M_PI / 60;
  const BalanceResolution resolution = calcBalanceResolution(m);
  EXPECT_GT(resolution.force, 0.0);
  std::vector<SatOut> sat_out;
  const std::vector<BalanceRow> rows = calcBalance(m, 8, 0, &sat_out);
  EXPECT_TRUE(sat_out.empty()) << sat_out.front().engine << ": " << sat_out.front().reason;
  const BalanceRow& eighth = rows.back();
  ASSERT_EQ(eighth.n, 8);
  EXPECT_LT(eighth.analytic.calcForceAmplitude(), 1e-9 * resolution.force);
  ASSERT_FALSE(eighth.engines.empty());
  for (const auto& [engine, harmonic] : eighth.engines)
    EXPECT_LT(harmonic.calcForceAmplitude(), resolution.force) << engine;
}

}  // namespace
}  // namespace crankcheck::validation
