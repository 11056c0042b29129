// Holzer's constant throw inertia (analytic/torsion.h) against Simbody: J_eq,j - J_t is the mean over a turn of the
// throw's reduced inertia, and Simbody gives that inertia as 2 T / omega^2 from its own kinetic energy of the throw's
// bodies (crank, rods, pistons) assembled and moving at omega: another model of the same mechanism, never the analytic
// J(phi). Scenes: the example four and marine six (their [crankshaft] tables), and the V8 (two cylinders a throw).

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>

#include "crankcheck/analytic/crank_train.h"
#include "crankcheck/analytic/torsion.h"
#include "crankcheck/analytic/torsion_steady.h"
#include "crankcheck/simbody_models/crank_train.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/simbody_models/k_crank_model.h"
#include "crankcheck/validation/engines.h"
#include "../support/test_numbers.h"

namespace crankcheck {
namespace {

using testing::kEps;

// The mean of Simbody's J over a turn by the trapezoidal sum (exact for a smooth periodic function up to its Fourier
// terms of order N: geometric convergence), N doubled from 16 until two sums agree to 4 eps.
double calcSimbodyMeanInertia(const Mechanism& throw_mechanism) {
  simbody_models::KCrankModel model(throw_mechanism);
  const double w = throw_mechanism.machine.speed;
  auto J = [&](double phi) { return 2.0 * model.calcKineticEnergy(phi) / (w * w); };
  int n = 16;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) sum += J(2 * M_PI * i / n);
  double mean = sum / n;
  for (;;) {
    for (int i = 0; i < n; ++i) sum += J(2 * M_PI * (2 * i + 1) / (2 * n));
    n *= 2;
    const double next = sum / n;
    if (std::fabs(next - mean) <= 4 * kEps * next || n >= 4096) return next;
    mean = next;
  }
}

// Tolerance 16 eps x J_eq: Simbody's kinetic energy at an assembled state carries the position projection's rounding
// (a few eps of l + r) and the velocity projection's, squared into T as a few eps relative; the sums of both sides add
// a few eps more. A wrong inertia (a rod's inertia about the wrong point, a missing cylinder of a V pair) is off by
// percent. Largest found: 1.8 eps (marine six and V8; CRANKCHECK_PRINT_RATIOS=1).
TEST(TorsionGate, ThrowInertiaIsTheMeanOfSimbodysKineticEnergy) {
  const std::filesystem::path dir = CRANKCHECK_SCENES_DIR;
  for (const char* name : {"inline4_four_stroke.toml", "inline6_two_stroke_marine.toml", "v8_cross_plane.toml"}) {
    SCOPED_TRACE(name);
    Mechanism m = loadSceneFile(dir / name);
    if (!m.crankshaft) {  // the V8: a train for this test only
      m.crankshaft = CrankshaftParams{};
      m.crankshaft->throw_inertia = 3.0e-3;
      m.crankshaft->stiffness.assign(static_cast<size_t>(countShaftSections(m)), 5e5);
    }
    const int throws = static_cast<int>(findThrows(m).size());
    for (int j = 0; j < throws; ++j) {
      Mechanism tm = analytic::makeThrowMechanism(m, j);
      tm.machine.speed = 100.0;  // any speed: J = 2 T / omega^2
      const double simbody = m.crankshaft->throw_inertia + calcSimbodyMeanInertia(tm);
      const double exact = analytic::calcThrowInertia(m, j).exact;
      EXPECT_NEAR(simbody, exact, 16 * kEps * exact) << "throw " << j;
      if (std::getenv("CRANKCHECK_PRINT_RATIOS"))
        std::printf("%s throw %d: %.2f eps\n", name, j, std::fabs(simbody - exact) / (kEps * exact));
    }
  }
}

// The exact periodic steady state of the train: the analytic engine's (shooting on its own equations) against
// Simbody's (bodies, constraints, springs, integrated from the rigid motion until periodic: crank_train.h), each
// section's twist over the cycle and its peak-to-peak value. Cases: the example four at 6000 rpm and at 5450 rpm (the
// first mode's critical speed of order 6), the marine six at its 105 rpm. Tolerance 2 x periodicity x the twist scale
// (the largest deviation of the analytic orbit), periodicity = 1e-6: Simbody's run stops when its cycle-to-cycle
// change is below periodicity x the largest deviation, so what is left of its transient is about that, moving a
// sample or an extreme by up to it and a peak-to-peak by up to twice it; its integration error per cycle (1e-7 of the
// twist at accuracy 1e-10) and the analytic engine's (1e-9) are below. The largest difference found: 1.4e-7 of the scale
// (CRANKCHECK_PRINT_RATIOS=1 prints them; the run's extrapolation of its cycle starts, periodic_run.h, does not change the
// stopping rule: what is left after it is measured over whole integrated cycles).
struct SteadyCase {
  const char* scene;
  double rpm;
};
void PrintTo(const SteadyCase& c, std::ostream* os) { *os << c.scene << " " << c.rpm; }
class TorsionSteadyGateTest : public ::testing::TestWithParam<SteadyCase> {};

TEST_P(TorsionSteadyGateTest, SimbodyAgreesWithTheAnalyticSteadyState) {
  Mechanism m = loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / GetParam().scene);
  m.speed_rpm = GetParam().rpm;
  m.machine.speed = GetParam().rpm * M_PI / 30.0;
  const analytic::ExactSteadyState exact = analytic::calcExactSteadyState(m);
  const CrankTrainRunOptions options;  // Simbody's defaults
  const CrankTrainRun run = simbody_models::simulateCrankTrainSteadyState(m, options);
  ASSERT_EQ(run.twists.size(), exact.peak_to_peak.size());
  const double tolerance = 2 * simbody_models::kCrankTrainPeriodicity * exact.twist_scale;
  double worst = 0.0;
  for (size_t i = 0; i < run.twists.size(); ++i) {
    const double p2p = analytic::findSignalExtremes(analytic::calcSignalFromSamples(run.twists[i])).peakToPeak();
    EXPECT_NEAR(p2p, exact.peak_to_peak[i], tolerance) << "section " << i;
    worst = std::max(worst, std::fabs(p2p - exact.peak_to_peak[i]));
    for (int k = 0; k < options.samples; ++k) {
      const double tau = 2 * M_PI * k / options.samples;
      const double expected = exact.twists[i].evaluate(tau);
      ASSERT_NEAR(run.twists[i][static_cast<size_t>(k)], expected, tolerance) << "section " << i << " sample " << k;
      worst = std::max(worst, std::fabs(run.twists[i][static_cast<size_t>(k)] - expected));
    }
  }
  if (std::getenv("CRANKCHECK_PRINT_RATIOS"))
    std::printf("%s %g rpm: worst %.2e of the scale (%d cycles, %lld steps)\n", GetParam().scene, GetParam().rpm,
                worst / exact.twist_scale, run.cycles, run.steps);
}

// MuJoCo's exact route (mujoco_models/crank_train.h: each throw's inertia and torque from MuJoCo's closed loops, the
// train's equations integrated from the rigid motion until periodic with Simbody's policy), through the engine
// registry, against the same analytic steady state on the same cases. Tolerance 2 x periodicity x the twist scale,
// periodicity = 1e-6 (MuJoCo's default, as Simbody's): the run stops when its cycle-to-cycle change is below
// periodicity x the largest deviation, so what is left of its transient moves a sample by up to about that (twice it
// for a twist, a difference of two deviations); its integration error per cycle (Dormand-Prince at 1e-10 per step)
// and the analytic engine's (1e-9 of the scale) are below. Worst found: 4.9e-8 of the scale (CRANKCHECK_PRINT_RATIOS=1
// prints it and the seconds per case: 1.6, 1.6 and 1.4 s; the marine six runs 13 cycles, its first mode damped 2 %,
// 66 without the extrapolation of its cycle starts).
TEST_P(TorsionSteadyGateTest, MujocoAgreesWithTheAnalyticSteadyState) {
  Mechanism m = loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / GetParam().scene);
  m.speed_rpm = GetParam().rpm;
  m.machine.speed = GetParam().rpm * M_PI / 30.0;
  const analytic::ExactSteadyState exact = analytic::calcExactSteadyState(m);
  const Engine& mujoco = validation::findEngine("mujoco");
  ASSERT_TRUE(mujoco.simulate_crank_train);
  EXPECT_TRUE(mujoco.crank_train_gated);
  const CrankTrainRunOptions options;  // MuJoCo's defaults
  const auto start = std::chrono::steady_clock::now();
  const CrankTrainRun run = mujoco.simulate_crank_train(m, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(run.twists.size(), exact.twists.size());
  constexpr double kPeriodicity = 1e-6;
  const double tolerance = 2 * kPeriodicity * exact.twist_scale;
  double worst = 0.0;
  for (size_t i = 0; i < run.twists.size(); ++i) {
    ASSERT_EQ(run.twists[i].size(), static_cast<size_t>(options.samples));
    for (int k = 0; k < options.samples; ++k) {
      const double expected = exact.twists[i].evaluate(2 * M_PI * k / options.samples);
      ASSERT_NEAR(run.twists[i][static_cast<size_t>(k)], expected, tolerance) << "section " << i << " sample " << k;
      worst = std::max(worst, std::fabs(run.twists[i][static_cast<size_t>(k)] - expected));
    }
  }
  if (std::getenv("CRANKCHECK_PRINT_RATIOS"))
    std::printf("mujoco %s %g rpm: worst %.2e of the scale (%d cycles, %lld steps, %.1f s)\n", GetParam().scene,
                GetParam().rpm, worst / exact.twist_scale, run.cycles, run.steps, seconds);
}

// The work limit of Simbody's train (CrankTrainRunOptions::max_steps, default simbody_models::kCrankTrainMaxSteps):
// past it the run is refused with one line naming the limit, not run on (100 steps: less than a cycle).
TEST(TorsionSteadyGate, SimbodyPastMaxStepsIsARuntimeError) {
  CrankTrainRunOptions options;
  options.max_steps = 100;
  try {
    simbody_models::simulateCrankTrainSteadyState(
        loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / "inline4_four_stroke.toml"), options);
    ADD_FAILURE() << "not refused";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("more than 100 integrator steps (CrankTrainRunOptions::max_steps"),
              std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Trains, TorsionSteadyGateTest,
                         ::testing::Values(SteadyCase{"inline4_four_stroke.toml", 6000.0},
                                           SteadyCase{"inline4_four_stroke.toml", 5450.0},
                                           SteadyCase{"inline6_two_stroke_marine.toml", 105.0}));

}  // namespace
}  // namespace crankcheck
