// The crank trains' run to periodic (periodic_run.h).
#include "crankcheck/solver/periodic_run.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <deque>
#include <stdexcept>
#include <string>

namespace crankcheck {

std::optional<std::vector<double>> findExtrapolatedFixedPoint(const std::vector<std::vector<double>>& iterates) {
  if (iterates.size() < 3) throw std::invalid_argument("findExtrapolatedFixedPoint: needs at least 3 iterates");
  const Eigen::Index d = static_cast<Eigen::Index>(iterates.front().size());
  const Eigen::Index k1 = static_cast<Eigen::Index>(iterates.size()) - 1;  // differences u_0 .. u_k
  for (const std::vector<double>& y : iterates)
    if (static_cast<Eigen::Index>(y.size()) != d || d == 0)
      throw std::invalid_argument("findExtrapolatedFixedPoint: iterates of different or no size");
  Eigen::MatrixXd U(d, k1);
  for (Eigen::Index j = 0; j < k1; ++j)
    for (Eigen::Index i = 0; i < d; ++i)
      U(i, j) = iterates[static_cast<size_t>(j + 1)][static_cast<size_t>(i)] - iterates[static_cast<size_t>(j)][static_cast<size_t>(i)];
  // gamma_0 = 1 - sum beta, gamma_j = beta_j: least |u_0 + sum_j beta_j (u_j - u_0)| (rank-revealing QR: dependent
  // differences get a zero weight).
  const Eigen::MatrixXd A = U.rightCols(k1 - 1).colwise() - U.col(0);
  const Eigen::VectorXd beta = A.colPivHouseholderQr().solve(-U.col(0));
  Eigen::VectorXd gamma(k1);
  gamma(0) = 1.0 - beta.sum();
  gamma.tail(k1 - 1) = beta;
  const double residual = (U * gamma).norm(), last = U.col(k1 - 1).norm();
  if (!(gamma.allFinite() && residual < 0.1 * last && gamma.cwiseAbs().sum() <= 1e4)) return std::nullopt;
  std::vector<double> out(static_cast<size_t>(d), 0.0);
  for (Eigen::Index j = 0; j < k1; ++j)
    for (Eigen::Index i = 0; i < d; ++i)
      out[static_cast<size_t>(i)] += gamma(j) * iterates[static_cast<size_t>(j + 1)][static_cast<size_t>(i)];
  return out;
}

std::vector<double> CycleRun::readCycleState() const {
  std::vector<double> x, x_s;
  readState(x, x_s);
  x.insert(x.end(), x_s.begin(), x_s.end());
  return x;
}

CrankTrainRun runToPeriodic(CycleRun& run, double cycle, const CrankTrainRunOptions& options,
                            const PeriodicPolicy& policy, const char* what) {
  constexpr int kProbes = 64;  // the largest deviation of a cycle, sampled
  const std::string name = what;
  if (!(options.accuracy > 0.0 && options.periodicity > 0.0 && policy.first_accuracy >= options.accuracy &&
        policy.extrapolation_window >= 0 && options.max_steps >= 0))
    throw std::invalid_argument(name + ": runToPeriodic: bad options");
  const long long max_steps = options.max_steps > 0 ? options.max_steps : kCrankTrainMaxSteps;
  auto stepTo = [&](double target, int cycle_count) {
    run.stepTo(target);
    if (run.countSteps() > max_steps)
      throw std::runtime_error(name + ": the crank train's run took more than " + std::to_string(max_steps) +
                               " integrator steps (CrankTrainRunOptions::max_steps, the work limit) in " +
                               std::to_string(cycle_count) + " cycles: a shaft this stiff or a train this lightly damped "
                               "costs more than this route allows; raise max_steps, or use the analytic steady state");
  };
  CrankTrainRun out;
  std::vector<double> x, x_s, start, start_s;
  run.readState(start, start_s);
  const size_t n = start.size();
  std::deque<std::vector<double>> window{run.readCycleState()};  // cycle starts at the accuracy in use
  double in_use = policy.first_accuracy, scale = 0.0;
  for (int count = 1;; ++count) {
    run.startCycle(in_use, scale);
    double largest = 0.0;
    for (int k = 1; k <= kProbes; ++k) {
      stepTo(cycle * k / kProbes, count);
      run.readState(x, x_s);
      for (double v : x) largest = std::max(largest, std::fabs(v));
    }
    if (!std::isfinite(largest))
      throw std::runtime_error(name + ": the crank train's deviations became non-finite in cycle " +
                               std::to_string(count));
    double change = 0.0;
    for (size_t i = 0; i < n; ++i) change = std::max({change, std::fabs(x[i] - start[i]), std::fabs(x_s[i] - start_s[i])});
    start = x;
    start_s = x_s;
    out.cycles = count;
    out.cycle_change = largest > 0.0 ? change / largest : 0.0;
    if (largest > 0.0) scale = largest;
    // The loose stage until the change is below first_accuracy / accuracy x periodicity (the loose run's own error per
    // cycle, in proportion to its accuracy, about that far above the final one's), then the final accuracy.
    if (in_use > options.accuracy &&
        out.cycle_change <= policy.first_accuracy / options.accuracy * options.periodicity) {
      in_use = options.accuracy;
      window.assign(1, run.readCycleState());
      continue;
    }
    if (in_use <= options.accuracy && out.cycle_change <= options.periodicity) break;
    if (count >= options.max_cycles)
      throw std::runtime_error(name + ": the elastic crank train is not periodic after " + std::to_string(count) +
                               " cycles (cycle-to-cycle change " + std::to_string(out.cycle_change) +
                               " of the deviations): too lightly damped to settle in this run");
    if (policy.extrapolation_window < 2) continue;
    window.push_back(run.readCycleState());
    if (static_cast<int>(window.size()) < std::min(4, policy.extrapolation_window) + 1) continue;
    const std::optional<std::vector<double>> fixed =
        findExtrapolatedFixedPoint(std::vector<std::vector<double>>(window.begin(), window.end()));
    if (static_cast<int>(window.size()) > policy.extrapolation_window) window.pop_front();
    if (!fixed) continue;
    if (!run.moveTo(*fixed)) continue;
    run.readState(start, start_s);  // as the engine assembled it
    window.assign(1, run.readCycleState());
  }
  // The sampled cycle: twist i = x_{i+1} - x_i (psi_b - psi_a), the last -x_{n-1} (omega t - psi_{n-1}).
  out.twists.assign(n, {});
  run.startCycle(in_use, scale);
  for (int k = 0; k < options.samples; ++k) {
    if (k > 0) stepTo(cycle * k / options.samples, out.cycles + 1);
    run.readState(x, x_s);
    for (size_t i = 0; i < n; ++i) out.twists[i].push_back((i + 1 == n ? 0.0 : x[i + 1]) - x[i]);
  }
  out.steps = run.countSteps();
  return out;
}

}  // namespace crankcheck
