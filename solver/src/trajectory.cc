#include "crankcheck/solver/trajectory.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include <boost/math/tools/roots.hpp>

namespace crankcheck {

namespace {

constexpr int kWindow = 6;  // Lagrange interpolation of degree 5

// y(x) by Lagrange interpolation on the six samples around x (a run of fewer is refused before it is read:
// validation/run_measures.h kMinRunSamples).
double interpolate(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  const int n = static_cast<int>(xs.size());
  const int cell = static_cast<int>(std::upper_bound(xs.begin(), xs.end(), x) - xs.begin()) - 1;
  const int first = std::clamp(cell - kWindow / 2 + 1, 0, n - kWindow);
  double y = 0.0;
  for (int j = first; j < first + kWindow; ++j) {
    if (x == xs[static_cast<size_t>(j)]) return ys[static_cast<size_t>(j)];
    double w = 1.0;
    for (int k = first; k < first + kWindow; ++k)
      if (k != j) w *= (x - xs[static_cast<size_t>(k)]) / (xs[static_cast<size_t>(j)] - xs[static_cast<size_t>(k)]);
    y += w * ys[static_cast<size_t>(j)];
  }
  return y;
}

}  // namespace

void checkStrictlyIncreasing(const std::vector<double>& v, const char* what, const char* who) {
  for (size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i]))
      throw std::invalid_argument(std::string(who) + ": " + what + "[" + std::to_string(i) + "] is not finite");
    if (i > 0 && !(v[i] > v[i - 1]))
      throw std::invalid_argument(std::string(who) + ": " + what + " is not strictly increasing at sample " +
                                  std::to_string(i));
  }
}

TrajectoryReader::TrajectoryReader(const Trajectory& run) : run_(run) {
  if (!run.omega_time.empty()) {
    if (run.omega_time.size() != run.omega.size())
      throw std::invalid_argument("the run has " + std::to_string(run.omega.size()) + " omega samples but " +
                                  std::to_string(run.omega_time.size()) + " omega instants");
    checkStrictlyIncreasing(run.omega_time, "omega's instants", "the run");
    omega_time_ = run.omega_time;
    omega_ = run.omega;
  } else if (run.omega_half_step_behind) {
    for (size_t i = 1; i < run.time.size(); ++i) {
      omega_time_.push_back(run.time[i] - 0.5 * (run.time[i] - run.time[i - 1]));
      omega_.push_back(run.omega[i]);
    }
  } else {
    omega_time_ = run.time;
    omega_ = run.omega;
  }
}

double TrajectoryReader::findPhi(double t) const { return interpolate(run_.time, run_.phi, t); }

double TrajectoryReader::findOmega(double t) const { return interpolate(omega_time_, omega_, t); }

double TrajectoryReader::findTimeAtPhase(double target) const {
  const auto& phi = run_.phi;
  const size_t upper = static_cast<size_t>(std::upper_bound(phi.begin(), phi.end(), target) - phi.begin());
  if (upper == 0) return run_.time.front();
  const size_t i = upper - 1;
  if (phi[i] == target || i + 1 == phi.size()) return run_.time[i];
  const double a = run_.time[i], b = run_.time[i + 1];
  auto g = [&](double t) { return findPhi(t) - target; };
  const double ga = phi[i] - target, gb = phi[i + 1] - target;
  std::uintmax_t iterations = 100;
  const auto root =
      boost::math::tools::toms748_solve(g, a, b, ga, gb, boost::math::tools::eps_tolerance<double>(52), iterations);
  return 0.5 * (root.first + root.second);
}

}  // namespace crankcheck
