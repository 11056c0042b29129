// The measure of a stepped engine's run (validation/stepped_errors.h) on synthetic runs whose errors are known from
// other formulas: values read a known fraction of a step away from their stated instant are off by the quantity's
// derivative times that angle (x_p's derivative is v_p / omega, the analytic engine's own velocity formula, not the
// position formula the measure calls); the loop error is the largest given; the order of C dt^p is p.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "cases.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/validation/stepped_errors.h"
#include "crankcheck/validation/variants.h"

namespace crankcheck::validation {
namespace {

// A synthetic stepped engine: x_p and the drive torque read from the closed forms at phi_start + shift x step, stated
// as belonging to the step's start; a loop error of loop_amplitude |sin phi_end|. Counts its calls' steps.
Engine makeSyntheticEngine(double shift, double loop_amplitude, long* steps_asked) {
  Engine e;
  e.name = "synthetic";
  e.library = "none";
  e.settings = {"defaults", "other"};
  e.settings_meaning = {"the only one", "the same"};
  e.step_at_speed = [shift, loop_amplitude, steps_asked](const Mechanism& m, const ConstantSpeedRunOptions& o) {
    *steps_asked = o.steps;
    Trajectory run;
    run.reported = {{QuantityId::kPistonPosition, 0.0}, {QuantityId::kDriveTorque, 0.0}};
    const double step = m.machine.speed * o.dt;
    double phi_start = o.start.phi;
    for (long i = 0; i < o.steps; ++i) {
      const double phi_end = phi_start + step;
      run.time.push_back((i + 1) * o.dt);
      run.phi.push_back(phi_end);
      run.omega.push_back(m.machine.speed);
      Evaluation& values = run.values.emplace_back(analytic::calcEvaluation(m, phi_start + shift * step));
      values.U = std::numeric_limits<double>::quiet_NaN();  // not reported: must not be read
      run.loop_error.push_back(loop_amplitude * std::fabs(std::sin(phi_end)));
      phi_start = phi_end;
    }
    return run;
  };
  return e;
}

Mechanism singleCylinder() { return testing::makeMechanism({1, Cycle::kFourStroke, Acting::kSingle, 0.3, 90.0, 3000.0}); }

TEST(SteppedErrorsTest, ValuesAtTheirStatedInstantHaveNoError) {
  const Mechanism m = singleCylinder();
  long steps = 0;
  const SteppedMeasure measure = measureSteppedRun(makeSyntheticEngine(0.0, 0.0, &steps), m, "defaults", 1e-4);
  ASSERT_EQ(measure.errors.size(), 3u);  // x_p, drive_torque, loop_error
  for (const SteppedError& e : measure.errors) EXPECT_EQ(e.worst_rel_error, 0.0) << e.quantity;
  EXPECT_EQ(measure.errors[0].quantity, "x_p");
  EXPECT_EQ(measure.errors[2].quantity, kLoopErrorName);
  // One turn at 3000 rpm and 1e-4 s: ceil(2 pi / (100 pi 1e-4)) = 200 steps; settled max(64, 200).
  EXPECT_EQ(measure.measured_steps, 200);
  EXPECT_EQ(measure.settling_steps, 200);
  EXPECT_EQ(steps, 400);
}

TEST(SteppedErrorsTest, AHalfStepLagIsTheDerivativeTimesHalfAStep) {
  const Mechanism m = singleCylinder();
  const Scales scales = calcScales(m);
  const double omega = m.machine.speed;
  // The largest |dx_p/dphi| = |v_p| / omega over a fine grid (the velocity formula, independent of x_p's).
  double slope = 0.0;
  for (int i = 0; i < 36000; ++i)
    slope = std::max(slope, std::fabs(analytic::calcEvaluation(m, 2.0 * std::numbers::pi * i / 36000).cylinders[0].v_p) / omega);
  for (double dt : {1e-4, 1e-5}) {
    long steps = 0;
    const SteppedMeasure measure = measureSteppedRun(makeSyntheticEngine(0.5, 0.0, &steps), m, "defaults", dt);
    const double half_step = 0.5 * omega * dt;
    const double expected = slope * half_step / scales.position;
    // The lag is slope x h - (1/2) x_p'' h^2 + ...: relative to the first term, |x_p''| / |x_p'| h / 2 <= ~h (both
    // of order r on this crank); the grid's maximum misses the true one by (grid step)^2 relative.
    EXPECT_NEAR(measure.errors[0].worst_rel_error / expected, 1.0, 2.0 * half_step + 1e-6) << "dt " << dt;
  }
}

TEST(SteppedErrorsTest, LoopErrorIsTheLargestAndWhere) {
  const Mechanism m = singleCylinder();
  long steps = 0;
  const SteppedMeasure measure = measureSteppedRun(makeSyntheticEngine(0.0, 1e-6, &steps), m, "defaults", 1e-5);
  const SteppedError& loop = measure.errors.back();
  const Scales scales = calcScales(m);
  // |sin| peaks at 90 and 270 deg; the step 0.3 deg puts a sample within 0.15 deg of a peak: sin off by 3.4e-6.
  EXPECT_NEAR(loop.worst_rel_error, 1e-6 / scales.position, 4e-6 * 1e-6 / scales.position);
  EXPECT_NEAR(std::fmod(loop.where_phi_deg, 180.0), 90.0, 0.16);
}

TEST(SteppedErrorsTest, RefusesUnknownSettingsNamingTheEngines) {
  long steps = 0;
  try {
    measureSteppedRun(makeSyntheticEngine(0.0, 0.0, &steps), singleCylinder(), "tight", 1e-3);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("defaults, other"), std::string::npos) << e.what();
  }
  EXPECT_THROW(measureSteppedRun(makeSyntheticEngine(0.0, 0.0, &steps), withSpeed(singleCylinder(), 0.0), "defaults", 1e-3),
               std::invalid_argument);
}

// calcStartState's velocities against central differences of its own positions at phi +- h (its positions are the
// closed forms' x_p and rod angle; its velocities their v_p and rod_omega, other formulas), and the rod's length.
TEST(SteppedErrorsTest, StartStateVelocitiesAreTheRatesOfItsPositions) {
  Mechanism m = testing::makeMechanism({4, Cycle::kFourStroke, Acting::kSingle, 0.35, 37.0, 3000.0});
  const double omega = m.machine.speed, h = 1e-5, l = m.rod.length;
  for (double phi : {0.0, 0.7, 2.9}) {
    const StartState s = calcStartState(m, analytic::calcEvaluation(m, phi));
    const StartState before = calcStartState(m, analytic::calcEvaluation(m, phi - h));
    const StartState after = calcStartState(m, analytic::calcEvaluation(m, phi + h));
    for (size_t j = 0; j < s.cylinders.size(); ++j) {
      const CylinderStartState& c = s.cylinders[j];
      EXPECT_NEAR(std::hypot(c.p_WB_W[0] - c.p_WA_W[0], c.p_WB_W[1] - c.p_WA_W[1]), l, 16 * testing::kEps * l);
      // Central differences: error (h omega)^2 / 6 x third derivative ~ 1e-10 of r omega; rounding eps r / h ~ 1e-11.
      const double v_scale = m.crank.radius * omega;
      for (int a = 0; a < 2; ++a) {
        const double fd = (after.cylinders[j].rod.p_WBcm_W[a] - before.cylinders[j].rod.p_WBcm_W[a]) / (2.0 * h) * omega;
        EXPECT_NEAR(c.rod.v_WBcm_W[a], fd, 1e-8 * v_scale) << "phi " << phi << " j " << j << " axis " << a;
        const double fd_piston = (after.cylinders[j].piston.p_WBcm_W[a] - before.cylinders[j].piston.p_WBcm_W[a]) / (2.0 * h) * omega;
        EXPECT_NEAR(c.piston.v_WBcm_W[a], fd_piston, 1e-8 * v_scale);
      }
      const double fd_angle = (after.cylinders[j].rod.angle - before.cylinders[j].rod.angle) / (2.0 * h) * omega;
      EXPECT_NEAR(c.rod.omega, fd_angle, 1e-8 * omega);
    }
  }
}

TEST(SteppedErrorsTest, ObservedOrderOfAPowerLaw) {
  EXPECT_NEAR(calcObservedStepOrder(3.0 * 1e-4 * 1e-4, 1e-4, 3.0 * 1e-5 * 1e-5, 1e-5), 2.0, 1e-14);
  EXPECT_TRUE(std::isnan(calcObservedStepOrder(0.0, 1e-4, 1e-6, 1e-5)));
  EXPECT_TRUE(std::isnan(calcObservedStepOrder(1e-3, 1e-4, 1e-6, 1e-4)));
}

}  // namespace
}  // namespace crankcheck::validation
