#include "crankcheck/analytic/torsion_domain.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "crankcheck/analytic/crank_train.h"

namespace crankcheck::analytic {
namespace {

std::string formatNumber(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", x);
  return text;
}

}  // namespace

void checkTorsionDomain(const Mechanism& m) {
  const CrankTrain t = makeCrankTrain(m);
  const int n = t.countBodies();
  // T_0 of each throw: the orders' p = 0 term (A_0: gas and gravity; the inertia's B_0 = mean of J' is 0 over a turn).
  ThrowLoadOrders orders;
  Eigen::VectorXd T0 = Eigen::VectorXd::Zero(n);
  for (int j = 0; j < static_cast<int>(t.throws.size()); ++j)
    T0(t.getThrowBody(j)) = orders.getOrders(t, j, 64).A[0].real();
  // The chain clamped at the flywheel: section i carries the mean torques of bodies 0 .. i, its twist that over K_i
  // (the same as calcSectionTwists of K^-1 T_0, without a solve that could lose a soft section's digits).
  double carried = 0.0;
  for (int i = 0; i < n; ++i) {
    carried += T0(i);
    const double K = t.stiffness[static_cast<size_t>(i)];
    const double twist = std::fabs(carried) / K;
    if (!(twist <= kMaxShaftTwist))
      throw std::invalid_argument(
          "[crankshaft].stiffness[" + std::to_string(i) + "]: the throws' mean torque (" + formatNumber(std::fabs(carried)) +
          " N m) twists this section by " + formatNumber(twist) + " rad, beyond the " + formatNumber(kMaxShaftTwist) +
          " rad of a crankshaft (the torsion analysis's domain); it needs at least " +
          formatNumber(std::fabs(carried) / kMaxShaftTwist) + " N m/rad (got " + formatNumber(K) + ")");
  }
}

void checkHolzerTwist(const HolzerResponse& holzer, double speed_rpm) {
  for (size_t i = 0; i < holzer.twists.size(); ++i) {
    const SignalExtremes e = findSignalExtremes(holzer.twists[i]);
    const double largest = std::fmax(std::fabs(e.min), std::fabs(e.max));
    if (!(largest <= kMaxShaftTwist))
      throw std::runtime_error("torsion: at " + formatNumber(speed_rpm) + " rpm Holzer's linear response twists section " +
                               std::to_string(i) + " by " + formatNumber(largest) + " rad, beyond the " +
                               formatNumber(kMaxShaftTwist) + " rad of a crankshaft (the torsion analysis's domain): "
                               "not computed; stiffen [crankshaft].stiffness or add damping near a critical speed");
  }
}

}  // namespace crankcheck::analytic
