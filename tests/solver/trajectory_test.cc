// TrajectoryReader (solver/trajectory.h) against what it did not produce: polynomials the interpolation reproduces
// exactly (Lagrange on six samples is exact for degree 5), the quadratic formula's root for a phase, and omega's
// instants read from the half-step flag as from instants given sample by sample.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "crankcheck/solver/trajectory.h"

namespace crankcheck {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// phi(t) = t + t^2 / 10 + t^5 / 50 on [0, 2] (increasing), omega(t) = 3 - t^3 + t^4 / 4, at uneven instants.
double phiOf(double t) { return t + 0.1 * t * t + 0.02 * std::pow(t, 5); }
double omegaOf(double t) { return 3.0 - t * t * t + 0.25 * std::pow(t, 4); }

Trajectory makeQuintic(int n) {
  Trajectory run;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * (i + 0.3 * std::sin(i)) / (n - 1);  // uneven, increasing
    run.time.push_back(t);
    run.phi.push_back(phiOf(t));
    run.omega.push_back(omegaOf(t));
  }
  return run;
}

// Degree 5 or less is reproduced: to the rounding of the six weights' products (five factors each) and of their sum,
// amplified by the weights' sum of magnitudes (Lebesgue's constant, below about 30 on these near-even nodes): 256
// ulps of the values' scale, 8 (phi up to 2.6, omega up to 3, taken at about 3 x), bound it.
TEST(TrajectoryReaderTest, ReadsAQuinticExactlyBetweenItsSamples) {
  const Trajectory run = makeQuintic(40);
  const TrajectoryReader reader(run);
  for (double t = 0.0; t <= run.time.back(); t += 0.0173) {
    EXPECT_NEAR(reader.findPhi(t), phiOf(t), 256 * kEps * 8.0) << t;
    EXPECT_NEAR(reader.findOmega(t), omegaOf(t), 256 * kEps * 8.0) << t;
  }
}

// phi(t) = t + t^2 / 10 reaches phase p at t = 5 (sqrt(1 + 0.4 p) - 1): TOMS 748 to 52 bits, an ulp of t, and the
// interpolated phi's rounding (a few ulps of phi, over a slope phi' >= 1): 16 ulps of the scale 3 (t, omega up to 3).
TEST(TrajectoryReaderTest, FindsThePhasesTimeByTheQuadraticFormula) {
  Trajectory run;
  for (int i = 0; i <= 30; ++i) {
    const double t = 0.1 * i;
    run.time.push_back(t);
    run.phi.push_back(t + 0.1 * t * t);
    run.omega.push_back(1.0 + 0.2 * t);
  }
  const TrajectoryReader reader(run);
  for (double p = 0.05; p < run.phi.back(); p += 0.37) {
    const double t = 5.0 * (std::sqrt(1.0 + 0.4 * p) - 1.0);
    EXPECT_NEAR(reader.findTimeAtPhase(p), t, 16 * kEps * 3.0) << p;
    EXPECT_NEAR(reader.findOmegaAtPhase(p), 1.0 + 0.2 * t, 16 * kEps * 3.0) << p;
  }
  EXPECT_EQ(reader.findTimeAtPhase(-1.0), run.time.front());
  EXPECT_EQ(reader.findTimeAtPhase(1e3), run.time.back());
}

// omega half a step behind its sample: a speed linear in time, given at the steps' midpoints, reads as that line. The
// reader's midpoints, t - (t - t_prev) / 2, and the test's, (t + t_prev) / 2, differ by an ulp of t (below 1); the
// line's slope 0.5 carries that into omega (about 3) with the six weights' rounding (their sum is 1, each below about
// 3 here): 64 ulps of omega's scale, 3, bound both with room.
TEST(TrajectoryReaderTest, HalfStepBehindReadsAtTheMidpoints) {
  Trajectory run;
  for (int i = 0; i <= 20; ++i) {
    const double t = 0.05 * i * (1.0 + 0.01 * i);
    const double before = i == 0 ? 0.0 : 0.05 * (i - 1) * (1.0 + 0.01 * (i - 1));
    run.time.push_back(t);
    run.phi.push_back(t);
    run.omega.push_back(i == 0 ? 1e9 : 2.0 + 0.5 * (t + before) / 2.0);  // omega[0] is not used
  }
  run.omega_half_step_behind = true;
  const TrajectoryReader reader(run);
  for (double t = 0.1; t < 1.0; t += 0.071) EXPECT_NEAR(reader.findOmega(t), 2.0 + 0.5 * t, 64 * kEps * 3.0) << t;
}

TEST(TrajectoryReaderTest, OmegaInstantsThatDoNotFitAreRefused) {
  Trajectory run = makeQuintic(10);
  run.omega_time = run.time;
  run.omega_time.pop_back();
  EXPECT_THROW(TrajectoryReader{run}, std::invalid_argument);
  run.omega_time = run.time;
  run.omega_time[4] = run.omega_time[3];
  EXPECT_THROW(TrajectoryReader{run}, std::invalid_argument);
  run.omega_time[4] = std::nan("");
  EXPECT_THROW(TrajectoryReader{run}, std::invalid_argument);
}

}  // namespace
}  // namespace crankcheck
