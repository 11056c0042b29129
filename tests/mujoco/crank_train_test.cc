// MuJoCo's elastic crank train on its own (no analytic library, no Simbody; the agreement with the analytic steady
// state is a gate test, tests/gate/torsion_test.cc): the throw's crank torque line against MuJoCo's own evaluations,
// and what the train refuses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "crankcheck/mujoco_models/crank_train.h"
#include "crankcheck/mujoco_models/k_crank_mujoco_model.h"
#include "crankcheck/scene/scene_file.h"
#include "../support/test_numbers.h"

namespace crankcheck {
namespace {

using mujoco_models::KCrankMujocoModel;

using testing::kEps;

Mechanism loadExample(const char* name) { return loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / name); }

// The line's rest at the scene's speed is evaluate's drive torque (the same multipliers: to rounding, 8 eps of the
// largest torque), at rest without gas the holding torque Q; its inertia's slope dJ/dphi (central differences, h =
// 1e-4 rad: truncation h^2 J''' / 6, about 1e-9 of max |J'|) is 2 (rest(omega) - rest(0)) / omega^2 without gravity's
// and gas's part, i.e. the mass matrix (mj_crb) and the inverse dynamics (mj_rne) tell one J(phi). Tolerance 1e-7 of
// max |J'| for the slope; largest found: 2e-10.
TEST(MujocoCrankTrain, ThrowTorqueLineIsMujocosOwnInverseDynamics) {
  const Mechanism m = loadExample("inline4_four_stroke.toml");
  const Mechanism tm = selectThrow(m, 1);
  KCrankMujocoModel model(tm);
  const Mechanism still = withLoads(tm, false, true, true);
  KCrankMujocoModel at_rest(still);
  const double w = tm.machine.speed, h = 1e-4;
  double largest_torque = 0.0, largest_slope = 0.0;
  for (int k = 0; k < 72; ++k) largest_torque = std::max(largest_torque, std::fabs(model.evaluate(k * M_PI / 18).drive_torque));
  for (int k = 0; k < 72; ++k) {
    const double phi = k * M_PI / 18;
    largest_slope = std::max(largest_slope, std::fabs(model.calcCrankTorqueLine(phi + h, 0.0).inertia -
                                                      model.calcCrankTorqueLine(phi - h, 0.0).inertia) / (2 * h));
  }
  for (int k = 0; k < 72; ++k) {
    const double phi = k * M_PI / 18;  // four-stroke: two turns, the gas cycle
    SCOPED_TRACE(phi);
    const mujoco_models::CrankTorqueLine line = model.calcCrankTorqueLine(phi, w);
    EXPECT_GT(line.inertia, 0.0);
    EXPECT_NEAR(line.rest, model.evaluate(phi).drive_torque, 8 * kEps * largest_torque);
    EXPECT_NEAR(at_rest.calcCrankTorqueLine(phi, 0.0).rest, at_rest.calcHoldingTorque(phi), 8 * kEps * largest_torque);
    const double slope = (model.calcCrankTorqueLine(phi + h, 0.0).inertia - model.calcCrankTorqueLine(phi - h, 0.0).inertia) / (2 * h);
    const double velocity_part = at_rest.calcCrankTorqueLine(phi, w).rest - at_rest.calcCrankTorqueLine(phi, 0.0).rest;
    EXPECT_NEAR(slope, 2 * velocity_part / (w * w), 1e-7 * largest_slope);
  }
}

TEST(MujocoCrankTrain, TheSoftVariantsHaveNoTorqueLine) {
  KCrankMujocoModel soft(selectThrow(loadExample("inline4_four_stroke.toml"), 0), mujoco_models::Variant::kSoftDefault);
  EXPECT_THROW(soft.calcCrankTorqueLine(0.0, 1.0), std::invalid_argument);
}

void expectRefusal(const Mechanism& m, const CrankTrainRunOptions& options, const std::string& key) {
  try {
    mujoco_models::simulateCrankTrainSteadyState(m, options);
    FAIL() << "ran; expected a refusal naming " << key;
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind(key + ":", 0), 0u) << e.what();
  }
}

TEST(MujocoCrankTrain, RefusesNamingTheRule) {
  const Mechanism four = loadExample("inline4_four_stroke.toml");
  expectRefusal(loadExample("v8_cross_plane.toml"), {}, "[crankshaft]");
  Mechanism m = four;
  m.machine.speed = 0.0;
  expectRefusal(m, {}, "[engine].speed_rpm");
  m = four;
  CrankshaftParams short_of_one = four.crankshaft.value();
  short_of_one.stiffness.resize(short_of_one.stiffness.size() - 1);
  m.crankshaft = short_of_one;
  expectRefusal(m, {}, "invalid mechanism");
  for (const CrankTrainRunOptions& bad : {CrankTrainRunOptions{-1e-10, 0.0, 1024, 2000},
                                          CrankTrainRunOptions{0.0, NAN, 1024, 2000},
                                          CrankTrainRunOptions{0.0, 0.0, 1023, 2000},
                                          CrankTrainRunOptions{0.0, 0.0, 8, 2000},
                                          CrankTrainRunOptions{0.0, 0.0, 1024, -1}})
    expectRefusal(four, bad, "CrankTrainRunOptions");
}

// A run that has not settled in max_cycles is refused, not returned.
TEST(MujocoCrankTrain, NotPeriodicInMaxCyclesIsARuntimeError) {
  CrankTrainRunOptions options;
  options.max_cycles = 2;
  EXPECT_THROW(mujoco_models::simulateCrankTrainSteadyState(loadExample("inline4_four_stroke.toml"), options),
               std::runtime_error);
}

// The work limit (CrankTrainRunOptions::max_steps): a run past it is refused with one line naming the limit, for the
// exact route and a soft one (100 steps: less than a cycle of either; the default, 4e6, is what the example four at
// 1e6 x its stiffness would exceed). Before, a run had no step limit: 1e-300 N m/rad ran past 120 s.
TEST(MujocoCrankTrain, PastMaxStepsIsARuntimeError) {
  CrankTrainRunOptions options;
  options.max_steps = 100;
  const Mechanism four = loadExample("inline4_four_stroke.toml");
  for (const bool soft : {false, true}) {
    SCOPED_TRACE(soft ? "soft" : "exact");
    try {
      if (soft)
        mujoco_models::simulateCrankTrainSoft(four, mujoco_models::Variant::kSoftDefault, options);
      else
        mujoco_models::simulateCrankTrainSteadyState(four, options);
      ADD_FAILURE() << "not refused";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("more than 100 integrator steps (CrankTrainRunOptions::max_steps"),
                std::string::npos) << e.what();
    }
  }
}

// The soft route (MuJoCo's own soft loops and RK4, simulateCrankTrainSoft) against the exact route on the example four
// at 6000 rpm, all at periodicity 1e-4 (cheap: what is left of the transients moves a twist by up to 2e-4 of the
// largest) on 64 samples, the soft runs at a step of 1/2048 of a cycle (half the default's steps: 4 s in all).
// Findings, bounded as measured (CRANKCHECK_PRINT_RATIOS=1 prints them): at MuJoCo's default solref/solimp the loops
// give way (a time constant of 0.02 s, the whole cycle) and the twists differ by 0.84 of the largest twist (bound 1);
// at the stiffest settings by 1.3e-3 (bound 3e-3; 3.3e-4 at the default step 1/4096: it falls as the step squared,
// the loops' time constant being two steps).
TEST(MujocoCrankTrain, SoftRoutesRunAndDifferFromTheExactOneByWhatWasMeasured) {
  const Mechanism m = loadExample("inline4_four_stroke.toml");
  const CrankTrainRunOptions options{0.0, 1e-4, 64, 0};
  const CrankTrainRun exact = mujoco_models::simulateCrankTrainSteadyState(m, options);
  double largest = 0.0;
  for (const auto& twist : exact.twists)
    for (double v : twist) largest = std::max(largest, std::fabs(v));
  for (const auto& [variant, bound] : {std::pair{mujoco_models::Variant::kSoftStiff, 3e-3},
                                       std::pair{mujoco_models::Variant::kSoftDefault, 1.0}}) {
    SCOPED_TRACE(mujoco_models::toString(variant));
    const CrankTrainRun soft = mujoco_models::simulateCrankTrainSoft(m, variant, {1.0 / 2048, 1e-4, 64, 0});
    ASSERT_EQ(soft.twists.size(), exact.twists.size());
    double worst = 0.0;
    for (size_t i = 0; i < soft.twists.size(); ++i)
      for (size_t k = 0; k < soft.twists[i].size(); ++k)
        worst = std::max(worst, std::fabs(soft.twists[i][k] - exact.twists[i][k]));
    EXPECT_LT(worst, bound * largest);
    EXPECT_LE(soft.cycle_change, options.periodicity);
    if (std::getenv("CRANKCHECK_PRINT_RATIOS"))
      std::printf("%s: worst %.2e of the largest twist (%d cycles, %lld steps)\n", mujoco_models::toString(variant).c_str(),
                  worst / largest, soft.cycles, soft.steps);
  }
  EXPECT_THROW(mujoco_models::simulateCrankTrainSoft(m, mujoco_models::Variant::kExact), std::invalid_argument);
}

}  // namespace
}  // namespace crankcheck
