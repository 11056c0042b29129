#pragma once
/// @file
/// The exact free run of a rigid mechanism released at phi = 0 with omega0 under gravity, as a function of time, for the
/// stepped engines' free-run tests (tests/ode, tests/bullet, tests/box2d): phi_dot(phi) from the energy integral
/// (analytic::calcFreeRunSpeed), t(phi) = integral of dphi / phi_dot by 8-point Gauss-Legendre on 400 cells a turn
/// (phi_dot is smooth and varies by well under 1 % a cell on the example scenes: the quadrature's error is far below
/// 1e-12 s), phi(t) by Newton's method on t(phi) = t. The test target links crankcheck_analytic.

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "crankcheck/analytic/motion.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::testing {

class ExactFreeRun {
 public:
  /// The run over its first `turns` turns (times and angles beyond them are extrapolated by the last cell).
  ExactFreeRun(const Mechanism& m, double omega0, int turns) : m_(m), omega0_(omega0) {
    node_time_.push_back(0.0);
    for (int i = 0; i < kCells * std::max(turns, 1); ++i)
      node_time_.push_back(node_time_.back() + integrate(i * h_, (i + 1) * h_));
  }
  /// [rad/s] phi_dot at the angle phi.
  double speed(double phi) const { return analytic::calcFreeRunSpeed(m_, omega0_, phi); }
  /// [rad/s^2] d phi_dot / dt = phi_dot d phi_dot / d phi (a central difference of relative step 1e-5).
  double acceleration(double phi) const {
    const double d = 1e-5;
    return speed(phi) * (speed(phi + d) - speed(phi - d)) / (2.0 * d);
  }
  /// [s] The time the crank reaches phi >= 0.
  double time(double phi) const {
    const int i = std::clamp(static_cast<int>(phi / h_), 0, static_cast<int>(node_time_.size()) - 2);
    return node_time_[static_cast<size_t>(i)] + integrate(i * h_, phi);
  }
  /// [rad] The crank's angle at time t >= 0.
  double phi(double t) const {
    const auto it = std::upper_bound(node_time_.begin(), node_time_.end(), t);
    const size_t i = static_cast<size_t>(std::max<std::ptrdiff_t>(it - node_time_.begin() - 1, 0));
    double phi = static_cast<double>(i) * h_ + (t - node_time_[i]) * speed(static_cast<double>(i) * h_);
    for (int k = 0; k < 50; ++k) {
      const double step = (t - time(phi)) * speed(phi);
      phi += step;
      if (std::fabs(step) < 1e-15 * (1.0 + std::fabs(phi))) break;
    }
    return phi;
  }

 private:
  static constexpr int kCells = 400;
  double integrate(double a, double b) const {
    static constexpr std::array<double, 4> x{0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
    static constexpr std::array<double, 4> w{0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
    const double c = 0.5 * (a + b), r = 0.5 * (b - a);
    double sum = 0.0;
    for (size_t k = 0; k < x.size(); ++k) sum += w[k] * (1.0 / speed(c - r * x[k]) + 1.0 / speed(c + r * x[k]));
    return r * sum;
  }
  Mechanism m_;
  double omega0_;
  double h_ = 2.0 * std::numbers::pi / kCells;
  std::vector<double> node_time_;
};

}  // namespace crankcheck::testing
