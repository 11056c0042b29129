#include "crankcheck/analytic/torsion_forced.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>

#include <boost/math/quadrature/gauss.hpp>

#include "crankcheck/analytic/torsion.h"

namespace crankcheck::analytic {
namespace {

// Throw j's torque orders T_p, p = 0 .. P, in the rigid motion (calcRigidThrowTorque):
//   T_0 = (1/cycle) int T dpsi,  T_p = (2/cycle) int T(psi) e^{-i p tau} dpsi,  tau = 2 pi psi / cycle.
// The orders p <= kQuadratureOrders by 10-point Gauss-Legendre (Boost.Math) on panels of at most half a period of
// the highest of them, the cycle split first at the pressure table's corners (each cylinder's firing angle plus each
// table angle), between which the torque is smooth: each to about rounding, where an FFT of samples would carry the
// corners' aliasing (falling only as N^-2). The orders above by an FFT of 4P samples: their aliasing, about T_1 / P^2,
// enters the twist through gains below 1 / (p omega)^2 J, far above the natural frequencies: below 1e-12 of it.
constexpr int kQuadratureOrders = 256;

// What the doublings of P share, per throw: the quadrature of the orders p <= kQuadratureOrders (the same for every
// P >= kQuadratureOrders) and the last FFT grid's torque samples (every other sample of the next grid).
struct TorqueOrderCache {
  std::vector<std::vector<std::complex<double>>> quadrature;
  std::vector<std::vector<double>> samples;
};

// The sums (cycle / 2) T_p' of the orders p = 0 .. Q by the quadrature above (T_p = 2 sum_p / cycle, T_0 = sum_0 / cycle).
std::vector<std::complex<double>> calcQuadratureSums(const CrankTrain& t, int j, int Q) {
  const Mechanism& tm = t.throws[static_cast<size_t>(j)];
  std::vector<double> cuts = {0.0, t.cycle};
  if (tm.gas)
    for (double firing : tm.firing_angles)
      for (double a : tm.gas->cycle_angles) cuts.push_back(std::fmod(firing + a, t.cycle));
  std::sort(cuts.begin(), cuts.end());
  using Rule = boost::math::quadrature::gauss<double, 10>;
  const auto& x = Rule::abscissa();  // the positive half: nodes +-x_i
  const auto& wq = Rule::weights();
  std::vector<std::complex<double>> sum(static_cast<size_t>(Q + 1), 0.0);
  const double panel = t.cycle / (2.0 * std::max(Q, 1));
  for (size_t c = 0; c + 1 < cuts.size(); ++c) {
    const double length = cuts[c + 1] - cuts[c];
    if (!(length > 0.0)) continue;
    const int panels = static_cast<int>(std::ceil(length / panel));
    const double h = length / panels;
    for (int q = 0; q < panels; ++q) {
      const double mid = cuts[c] + (q + 0.5) * h;
      for (size_t i = 0; i < x.size(); ++i)
        for (double sign : {-1.0, 1.0}) {
          const double psi = mid + sign * 0.5 * h * x[i];
          const double weight = 0.5 * h * wq[i] * calcRigidThrowTorque(tm, psi, t.omega);
          const double tau = 2.0 * M_PI * psi / t.cycle;
          const std::complex<double> step = std::polar(1.0, -tau);
          std::complex<double> z(1.0, 0.0);
          for (int p = 0; p <= Q; ++p) {
            if (p % 64 == 0) z = std::polar(1.0, -p * tau);  // renormalized against the recurrence's drift
            sum[static_cast<size_t>(p)] += weight * z;
            z *= step;
          }
        }
    }
  }
  return sum;
}

std::vector<std::complex<double>> calcTorqueOrders(const CrankTrain& t, int j, int P, TorqueOrderCache& cache) {
  const Mechanism& tm = t.throws[static_cast<size_t>(j)];
  const size_t throw_index = static_cast<size_t>(j);
  cache.quadrature.resize(t.throws.size());
  cache.samples.resize(t.throws.size());
  const int Q = std::min(P, kQuadratureOrders);
  std::vector<std::complex<double>>& sum = cache.quadrature[throw_index];
  if (static_cast<int>(sum.size()) != Q + 1) sum = calcQuadratureSums(t, j, Q);
  std::vector<std::complex<double>> orders(static_cast<size_t>(P + 1));
  orders[0] = sum[0].real() / t.cycle;
  for (int p = 1; p <= Q; ++p) orders[static_cast<size_t>(p)] = 2.0 * sum[static_cast<size_t>(p)] / t.cycle;
  if (P > Q) {
    const int N = 4 * P;
    std::vector<double>& last = cache.samples[throw_index];
    std::vector<double> samples(static_cast<size_t>(N));
    // The angle cycle k / N is bit for bit the last grid's cycle (k / 2) / (N / 2) at even k: reused.
    const bool halves = static_cast<int>(last.size()) * 2 == N;
    for (int k = 0; k < N; ++k)
      samples[static_cast<size_t>(k)] = halves && k % 2 == 0 ? last[static_cast<size_t>(k / 2)]
                                                              : calcRigidThrowTorque(tm, t.cycle * k / N, t.omega);
    const PeriodicSignal fft = calcSignalFromSamples(samples);
    last = std::move(samples);
    for (int p = Q + 1; p <= P; ++p) orders[static_cast<size_t>(p)] = fft.coefficients[static_cast<size_t>(p)];
  }
  return orders;
}

// One pass with the orders p = 0 .. P per cycle: the bodies' and sections' signals, the peak-to-peaks.
HolzerResponse solveWithOrders(const CrankTrain& t, const std::vector<double>& inertias, int P, TorqueOrderCache& cache) {
  const int n = t.countBodies();
  const int throws = static_cast<int>(t.throws.size());
  HolzerResponse out;
  out.inertias = inertias;
  out.orders = P;
  out.torque_orders.resize(P + 1, throws);
  for (int j = 0; j < throws; ++j) {
    const std::vector<std::complex<double>> T = calcTorqueOrders(t, j, P, cache);
    for (int p = 0; p <= P; ++p) out.torque_orders(p, j) = T[static_cast<size_t>(p)];
  }
  const Eigen::MatrixXd K = calcStiffnessMatrix(t), C = calcDampingMatrix(t);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) J(i, i) = inertias[static_cast<size_t>(i)];
  out.bodies.assign(static_cast<size_t>(n), PeriodicSignal{});
  out.twists.assign(static_cast<size_t>(n), PeriodicSignal{});
  std::vector<PeriodicSignal> twists24(static_cast<size_t>(n));
  const double order_per_p = 2.0 * M_PI / t.cycle;  // n = p 2 pi / cycle
  for (int p = 0; p <= P; ++p) {
    const double w = p * order_per_p * t.omega;  // [rad/s] the order's frequency
    const Eigen::MatrixXcd A = (K - w * w * J).cast<std::complex<double>>() + std::complex<double>(0.0, w) * C;
    Eigen::VectorXcd T = Eigen::VectorXcd::Zero(n);
    for (int j = 0; j < throws; ++j) T(t.getThrowBody(j)) = out.torque_orders(p, j);
    const Eigen::VectorXcd X = A.partialPivLu().solve(T);
    for (int i = 0; i < n; ++i) {
      out.bodies[static_cast<size_t>(i)].coefficients.push_back(X(i));
      const std::complex<double> twist = i + 1 < n ? X(i + 1) - X(i) : -X(i);
      out.twists[static_cast<size_t>(i)].coefficients.push_back(twist);
      if (p * order_per_p <= 24.0 + 1e-9) twists24[static_cast<size_t>(i)].coefficients.push_back(twist);
    }
  }
  for (int i = 0; i < n; ++i) {
    out.peak_to_peak.push_back(findSignalExtremes(out.twists[static_cast<size_t>(i)]).peakToPeak());
    out.peak_to_peak_order24.push_back(findSignalExtremes(twists24[static_cast<size_t>(i)]).peakToPeak());
  }
  return out;
}

}  // namespace

HolzerResponse calcHolzerResponse(const CrankTrain& t, const std::vector<double>& inertias,
                                  const HolzerOptions& options) {
  if (static_cast<int>(inertias.size()) != t.countBodies())
    throw std::invalid_argument("torsion: " + std::to_string(inertias.size()) + " inertias for " +
                                std::to_string(t.countBodies()) + " bodies");
  for (double J : inertias)
    if (!(J > 0.0 && std::isfinite(J))) throw std::invalid_argument("torsion: a body of the train has no inertia");
  TorqueOrderCache cache;
  HolzerResponse last = solveWithOrders(t, inertias, 64, cache);
  for (int P = 128; P <= options.max_harmonics; P *= 2) {
    HolzerResponse next = solveWithOrders(t, inertias, P, cache);
    double largest = 0.0, change = 0.0;
    for (size_t i = 0; i < next.peak_to_peak.size(); ++i) {
      largest = std::max(largest, next.peak_to_peak[i]);
      change = std::max(change, std::fabs(next.peak_to_peak[i] - last.peak_to_peak[i]));
    }
    next.change = largest > 0.0 ? change / largest : 0.0;
    if (change <= options.convergence * largest) return next;  // (largest 0: no forcing, no twist: converged at once)
    last = std::move(next);
  }
  throw std::runtime_error("torsion: Holzer's sum over orders did not converge to " +
                           std::to_string(options.convergence) + " with " + std::to_string(options.max_harmonics) +
                           " harmonics per cycle");
}

HolzerResponse calcHolzerResponse(const Mechanism& m, const HolzerOptions& options) {
  const CrankTrain t = makeCrankTrain(m);
  std::vector<double> inertias;
  if (t.has_front) inertias.push_back(t.front_inertia);
  for (int j = 0; j < static_cast<int>(t.throws.size()); ++j) inertias.push_back(calcThrowInertia(m, j).exact);
  return calcHolzerResponse(t, inertias, options);
}

}  // namespace crankcheck::analytic
