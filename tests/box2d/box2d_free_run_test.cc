// The Box2D stepped engine's free run ("box2d" step_free, box2d_models/free_run.h) against the exact free run of
// crankcheck::analytic (analytic/motion.h: phi_dot(phi) from the energy integral, released at phi = 0 with the start's
// speed; its time t(phi) = integral of dphi / phi_dot by Gauss-Legendre quadrature here, inverted by Newton): the
// phase error and its order in dt, the instant of omega, and the refusal of a scene without flywheel.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "crankcheck/analytic/motion.h"
#include "crankcheck/box2d_models/stepped_engine.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/run_measures.h"
#include "exact_free_run.h"
#include "stepped_engine_support.h"

namespace crankcheck::box2d_models {
namespace {

using crankcheck::testing::findStepped;
using crankcheck::testing::loadSteppedExample;

constexpr double kTwoPi = 2.0 * std::numbers::pi;

const Engine& box2d() {
  static const std::vector<Engine> engines = describeEngines();
  return findStepped(engines, "box2d");
}

using crankcheck::testing::ExactFreeRun;

Trajectory runFree(const Mechanism& m, double dt, double seconds, const std::string& settings = "defaults") {
  SteppedFreeRunOptions o;
  o.dt = dt;
  o.steps = static_cast<long>(std::ceil(seconds / dt)) + 1;
  o.settings = settings;
  o.start = testing::calcExactStartState(m);
  return box2d().step_free(m, o);
}

/// [rad] phi_run - phi_exact at the run's sample nearest the exact run's time of `turns` revolutions.
double phaseErrorAfter(const ExactFreeRun& exact, const Trajectory& run, double dt, double turns) {
  const size_t i = static_cast<size_t>(std::lround(exact.time(turns * kTwoPi) / dt)) - 1;
  return run.phi.at(i) - exact.phi(run.time.at(i));
}


/// The fraction of its step omega belongs to, from the run's own steps: (phi_i - phi_{i-1}) / dt is the speed at the
/// step's middle to second order, so (phi_i - phi_{i-1}) / dt - omega_i = (1/2 - f) dt alpha + what the position pass
/// turns the crank by; a least-squares fit of it to a + c dt alpha (alpha the exact acceleration at the step's
/// middle) gives f = 1/2 - c.
double fitOmegaFraction(const ExactFreeRun& exact, const Trajectory& run, double dt) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(run.phi.size() - 1);
  for (size_t i = 1; i < run.phi.size(); ++i) {
    const double x = dt * exact.acceleration(0.5 * (run.phi[i - 1] + run.phi[i]));
    const double y = (run.phi[i] - run.phi[i - 1]) / dt - run.omega[i];
    sx += x; sy += y; sxx += x * x; sxy += x * y;
  }
  return 0.5 - (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

const std::vector<double> kSteps{1e-3, 1e-4, 1e-5};

// The phase error after two revolutions, at Box2D's defaults (the tightened settings change it by under 3%: the free
// run's error is not the iterations'). Measured (rad, 1e-3 / 1e-4 / 1e-5 s): the single -9.72e-2 / -9.58e-3 /
// -2.08e-3, the inline four -0.644 / -7.27e-2 / -9.07e-3: negative (the run loses energy, below), first order from
// 1e-3 to 1e-4 s (1.01, 0.95), the four still 0.90 to 1e-5 s; the single's flattens there (0.66) where a float angle of
// 12 rad rounds by 1e-6 rad at each of its 4000 steps. Band for a first order: [0.85, 1.15]; the single's last
// interval above 0.5, its error at 1e-5 s below a third of 1e-4 s's.
TEST(Box2dFreeRunTest, PhaseErrorFallsAtFirstOrder) {
  for (const char* scene : {"single_cylinder.toml", "inline4_four_stroke.toml"}) {
    SCOPED_TRACE(scene);
    const Mechanism m = loadSteppedExample(scene, true);
    ASSERT_TRUE(m.flywheel_inertia.has_value());
    const ExactFreeRun exact(m, m.machine.speed, 4);
    const double two_turns = exact.time(2.0 * kTwoPi);
    std::vector<double> errors;
    for (double dt : kSteps) {
      const Trajectory run = runFree(m, dt, 1.01 * two_turns);
      ASSERT_EQ(run.time.size(), run.phi.size());
      ASSERT_EQ(run.omega.size(), run.phi.size());
      errors.push_back(phaseErrorAfter(exact, run, dt, 2.0));
      EXPECT_LT(errors.back(), 0.0) << dt;  // behind the exact run: slower
    }
    const double order1 = validation::calcObservedOrder({kSteps[0], kSteps[1]}, {errors[0], errors[1]});
    const double order2 = validation::calcObservedOrder({kSteps[1], kSteps[2]}, {errors[1], errors[2]});
    EXPECT_GT(order1, 0.85);
    EXPECT_LT(order1, 1.15);
    if (std::string(scene) == "inline4_four_stroke.toml") {
      EXPECT_GT(order2, 0.85);
      EXPECT_LT(order2, 1.15);
    } else {
      EXPECT_GT(order2, 0.5);
      EXPECT_LT(std::fabs(errors[2]), std::fabs(errors[1]) / 3.0);
    }
  }
}

// The free run loses energy at first order: Box2D's velocity solve projects each step's velocity onto the joints'
// tangent at the step's start, an inelastic projection. The crank's speed at 2 turns, omega read at the instant
// Trajectory states, against the exact speed there: measured 4.7 / 0.48 / 0.10 rad/s on the single (1.5e-2 /
// 1.5e-3 / 3.2e-4 of its speed), 62 / 7.2 / 0.90 on the four; from 1e-3 to 1e-4 s 9.8 and 8.7 times smaller (first
// order; band [0.85, 1.15]).
TEST(Box2dFreeRunTest, LosesEnergyAtFirstOrder) {
  for (const char* scene : {"single_cylinder.toml", "inline4_four_stroke.toml"}) {
    SCOPED_TRACE(scene);
    const Mechanism m = loadSteppedExample(scene, true);
    const ExactFreeRun exact(m, m.machine.speed, 4);
    std::vector<double> errors;
    for (double dt : {1e-3, 1e-4}) {
      const Trajectory run = runFree(m, dt, 1.01 * exact.time(2.0 * kTwoPi));
      const size_t i = static_cast<size_t>(std::lround(exact.time(2.0 * kTwoPi) / dt)) - 1;
      const double phi = run.phi[i - 1] + testing::findOmegaStepFraction(run) * (run.phi[i] - run.phi[i - 1]);
      errors.push_back(run.omega[i] - exact.speed(phi));
      EXPECT_LT(errors.back(), 0.0) << dt;
    }
    const double order = validation::calcObservedOrder({1e-3, 1e-4}, errors);
    EXPECT_GT(order, 0.85);
    EXPECT_LT(order, 1.15);
  }
}

// omega's instant, from the run's own steps (fitOmegaFraction): at 1e-4 s, where neither Box2D's 5 mm slop nor the
// float angle's rounding shows, the crank's step phi_i - phi_{i-1} is dt omega_i plus (1/2) dt^2 alpha: the position
// pass, closing the loop that the explicit update opened along the start's tangent, turns the crank by the rest, so
// omega_i acts as the speed at the step's start (measured -0.020 and 0.009 on the single and the four; at 1e-3 s
// 0.14 and 0.11; at 1e-5 s 0.41 and 0.45, where the float angle's rounding, 1e-6 rad a step, is 1e3 times the lag
// term). Band at 1e-4 s: within 0.1 of 0, and read at the step's middle it would be 0.5 away.
TEST(Box2dFreeRunTest, OmegaBelongsToTheStepsStart) {
  EXPECT_EQ(testing::findOmegaStepFraction(box2d().step_free(
                loadSteppedExample("single_cylinder.toml", true),
                {.dt = 1e-4, .steps = 8, .settings = "defaults",
                 .start = testing::calcExactStartState(loadSteppedExample("single_cylinder.toml", true))})),
            0.0);
  for (const char* scene : {"single_cylinder.toml", "inline4_four_stroke.toml"}) {
    SCOPED_TRACE(scene);
    const Mechanism m = loadSteppedExample(scene, true);
    const ExactFreeRun exact(m, m.machine.speed, 4);
    const Trajectory run = runFree(m, 1e-4, exact.time(2.0 * kTwoPi));
    // Within 0.1 of a step: the fit measured -0.02 (single) and 0.01 (four) at 1e-4 s; the position pass's own move
    // (1/2 dt^2 alpha) and the first-order energy loss shift it by a few hundredths, against the 0.5 that would mean the
    // step's middle.
    EXPECT_NEAR(fitOmegaFraction(exact, run, 1e-4), testing::findOmegaStepFraction(run), 0.1);
  }
}

// A scene without flywheel is refused by name; so is an unknown settings name. A scene with gas runs without it: the
// same run as the gasless scene's.
TEST(Box2dFreeRunTest, RefusesASceneWithoutFlywheelAndDropsTheGas) {
  Mechanism m = loadSteppedExample("inline4_four_stroke.toml");
  ASSERT_TRUE(m.gas.has_value());
  SteppedFreeRunOptions o;
  o.dt = 1e-4;
  o.steps = 100;
  o.start = testing::calcExactStartState(m);
  const Trajectory with_gas = box2d().step_free(m, o);
  m.gas.reset();
  const Trajectory without = box2d().step_free(m, o);
  EXPECT_EQ(with_gas.phi, without.phi);
  EXPECT_EQ(with_gas.omega, without.omega);
  m.flywheel_inertia.reset();
  try {
    box2d().step_free(m, o);
    ADD_FAILURE() << "ran without flywheel";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("[flywheel].inertia"), std::string::npos) << e.what();
  }
  m.flywheel_inertia = 0.12;
  o.settings = "neutralised";
  EXPECT_THROW(box2d().step_free(m, o), std::invalid_argument);
}

}  // namespace
}  // namespace crankcheck::box2d_models
