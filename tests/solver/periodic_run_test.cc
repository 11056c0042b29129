// The crank trains' run to periodic (crankcheck/solver/periodic_run.h): the extrapolation against the fixed point of a
// linear cycle map solved by LU, and the policy on a cycle map whose slowest mode contracts 3 % a cycle.
#include "crankcheck/solver/periodic_run.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <vector>
#include "../support/test_numbers.h"

namespace crankcheck {
namespace {

using testing::kEps;

// y -> M y + b on (x_0, x_1, x_0', x_1'): two modes, rotations by 0.7 and 2.1 rad a cycle contracted to 0.97 and 0.5
// (a lightly damped train's slow mode and a well damped one), mixed by a fixed invertible matrix.
struct LinearCycleMap {
  Eigen::Matrix4d M;
  Eigen::Vector4d b{0.3, -0.2, 0.05, 0.1};
  LinearCycleMap() {
    Eigen::Matrix4d D = Eigen::Matrix4d::Zero();
    auto block = [&](int at, double rho, double angle) {
      D.block<2, 2>(at, at) << rho * std::cos(angle), -rho * std::sin(angle), rho * std::sin(angle), rho * std::cos(angle);
    };
    block(0, 0.97, 0.7);
    block(2, 0.5, 2.1);
    Eigen::Matrix4d P;
    P << 1, 0.2, 0, 0.1, 0, 1, 0.3, 0, 0.1, 0, 1, 0.2, 0, 0.4, 0, 1;
    M = P * D * P.inverse();
  }
  Eigen::Vector4d apply(const Eigen::Vector4d& y) const { return M * y + b; }
  // The fixed point by LU on (I - M) y = b: not the extrapolation's computation.
  Eigen::Vector4d fixedPoint() const { return (Eigen::Matrix4d::Identity() - M).partialPivLu().solve(b); }
};

std::vector<double> toStd(const Eigen::Vector4d& v) { return {v(0), v(1), v(2), v(3)}; }

// Six iterates (five differences, above the degree 4 of M's minimal polynomial): the fixed point to rounding. The
// least squares' error is about eps x the condition number of its differences' matrix (measured here by its singular
// values) x |y|; 16 x that covers the sums around it.
TEST(PeriodicRun, ExtrapolationOfALinearCycleMapIsItsFixedPoint) {
  const LinearCycleMap map;
  std::vector<std::vector<double>> iterates;
  Eigen::Vector4d y = Eigen::Vector4d::Zero();
  Eigen::MatrixXd U(4, 5);
  for (int j = 0; j < 6; ++j) {
    iterates.push_back(toStd(y));
    const Eigen::Vector4d next = map.apply(y);
    if (j < 5) U.col(j) = next - y;
    y = next;
  }
  Eigen::MatrixXd A = U.rightCols(4).colwise() - U.col(0);
  const Eigen::VectorXd sigma = Eigen::JacobiSVD<Eigen::MatrixXd>(A).singularValues();
  const double condition = sigma(0) / sigma(sigma.size() - 1);
  const std::optional<std::vector<double>> fixed = findExtrapolatedFixedPoint(iterates);
  ASSERT_TRUE(fixed.has_value());
  const Eigen::Vector4d expected = map.fixedPoint();
  for (int i = 0; i < 4; ++i)
    EXPECT_NEAR((*fixed)[static_cast<size_t>(i)], expected(i), 16 * kEps * condition * expected.norm()) << i;
}

// A map without a fixed point (a translation: every difference the same): nothing is gained, nothing returned.
TEST(PeriodicRun, ExtrapolationWithoutAFixedPointIsRefused) {
  std::vector<std::vector<double>> iterates;
  for (int j = 0; j < 5; ++j) iterates.push_back({0.1 * j, -0.2 * j, 0.0, 0.3 * j});
  EXPECT_FALSE(findExtrapolatedFixedPoint(iterates).has_value());
  EXPECT_THROW(findExtrapolatedFixedPoint({{1.0}, {2.0}}), std::invalid_argument);
}

// The linear map as a run seen at its cycles' starts (a whole cycle applies the map; the probes within it read the
// start): exact at every accuracy, so the policy's staging changes nothing here.
class MapRun final : public CycleRun {
 public:
  explicit MapRun(const LinearCycleMap& map) : map_(map) {}
  void startCycle(double, double) override {}
  void stepTo(double target) override {
    if (target == 2 * M_PI) {
      y_ = map_.apply(y_);
      ++cycles_;
    }
  }
  void readState(std::vector<double>& x, std::vector<double>& x_s) const override {
    x = {y_(0), y_(1)};
    x_s = {y_(2), y_(3)};
  }
  bool moveTo(const std::vector<double>& y) override {
    y_ << y[0], y[1], y[2], y[3];
    return true;
  }
  long long countSteps() const override { return cycles_; }

 private:
  const LinearCycleMap& map_;
  Eigen::Vector4d y_ = Eigen::Vector4d::Zero();
  long long cycles_ = 0;
};

// Without extrapolation the slow mode (0.97 a cycle) takes hundreds of cycles to a change of 1e-9; with it, a few
// windows. Both stop on the same rule, so both end within what a change of periodicity leaves of the transient: for
// a mode contracting rho a cycle, change / (1 - rho) = 33 x periodicity x the deviations' scale; 100 x covers it.
TEST(PeriodicRun, ExtrapolationReachesTheSamePeriodicStateInFewerCycles) {
  const LinearCycleMap map;
  const Eigen::Vector4d expected = map.fixedPoint();
  CrankTrainRunOptions options;
  options.accuracy = 1e-10;
  options.periodicity = 1e-9;
  options.samples = 16;
  int cycles[2] = {0, 0};
  for (int window : {0, kExtrapolationWindow}) {
    MapRun run(map);
    const CrankTrainRun out = runToPeriodic(run, 2 * M_PI, options, PeriodicPolicy{1e-10, window}, "test");
    cycles[window ? 1 : 0] = out.cycles;
    ASSERT_EQ(out.twists.size(), 2u);
    const double scale = std::max(std::fabs(expected(0)), std::fabs(expected(1)));
    EXPECT_NEAR(out.twists[0].front(), expected(1) - expected(0), 100 * options.periodicity * scale) << window;
    EXPECT_NEAR(out.twists[1].front(), -expected(1), 100 * options.periodicity * scale) << window;
  }
  if (std::getenv("CRANKCHECK_PRINT_RATIOS")) std::printf("cycles without %d, with %d\n", cycles[0], cycles[1]);
  EXPECT_GT(cycles[0], 300);
  EXPECT_LT(cycles[1], 30) << "without: " << cycles[0];
}

}  // namespace
}  // namespace crankcheck
