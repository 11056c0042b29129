#include "crankcheck/analytic/torsion_forced.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <complex>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include <boost/math/quadrature/gauss.hpp>

#include "crankcheck/analytic/torsion.h"

namespace crankcheck::analytic {
namespace {

// Throw j's torque orders T_p, p = 0 .. P, in the rigid motion (calcRigidThrowTorque):
//   T_0 = (1/cycle) int T dpsi,  T_p = (2/cycle) int T(psi) e^{-i p tau} dpsi,  tau = 2 pi psi / cycle.
// The orders p <= kQuadratureOrders by 10-point Gauss-Legendre (Boost.Math) on panels of at most half a period of
// the highest of them, the cycle split first at the pressure table's corners (each cylinder's firing angle plus each
// table angle), between which the torque is smooth: each to about rounding, where an FFT of samples would carry the
// corners' aliasing (falling only as N^-2). The orders above by an FFT of 4P samples with the corners taken out and
// their orders added in closed form (getOrders): what the FFT sees is C^1, its aliasing about T_1 / P^3, which matters
// where a stiff shaft's natural frequencies lie above p and the twist takes the orders with gain 1/K.
// T = A - (1/2) omega^2 B with the speed-free A = T_gas - Q and B = J': their orders are computed (and kept by
// ThrowLoadOrders for every speed of a sweep), T_p = A_p - (1/2) omega^2 B_p.
constexpr int kQuadratureOrders = 256;

// Throw tm's speed-free loads at psi: A = T_gas - Q [N m] and B = J' [kg m^2/rad], of which its rigid torque at any
// omega is T = A - (1/2) omega^2 B (calcRigidThrowTorque).
std::pair<double, double> calcSpeedFreeLoads(const PreparedThrow& tm, double psi) {
  const ThrowLoads loads = calcThrowLoads(tm, psi);
  return {loads.gas_torque - loads.gravity_torque, loads.dJ};
}

// The sums (cycle / 2) A_p' and (cycle / 2) B_p' of throw j's speed-free loads A = T_gas - Q and B = J' for the
// orders p = 0 .. Q by the quadrature above (A_p = 2 sum_p / cycle, A_0 = sum_0 / cycle; B alike).
std::pair<std::vector<std::complex<double>>, std::vector<std::complex<double>>> calcQuadratureSums(const CrankTrain& t,
                                                                                                   int j, int Q) {
  const Mechanism& tm = t.throws[static_cast<size_t>(j)];
  const PreparedThrow prepared = prepareThrow(tm);
  std::vector<double> cuts = {0.0, t.cycle};
  if (tm.gas)
    for (double firing : tm.firing_angles)
      for (double a : tm.gas->cycle_angles) cuts.push_back(std::fmod(firing + a, t.cycle));
  std::sort(cuts.begin(), cuts.end());
  using Rule = boost::math::quadrature::gauss<double, 10>;
  const auto& x = Rule::abscissa();  // the positive half: nodes +-x_i
  const auto& wq = Rule::weights();
  std::vector<std::complex<double>> sum_a(static_cast<size_t>(Q + 1), 0.0), sum_b(static_cast<size_t>(Q + 1), 0.0);
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
          const auto [A, B] = calcSpeedFreeLoads(prepared, psi);
          const double weight_a = 0.5 * h * wq[i] * A;
          const double weight_b = 0.5 * h * wq[i] * B;
          const double tau = 2.0 * M_PI * psi / t.cycle;
          const std::complex<double> step = std::polar(1.0, -tau);
          std::complex<double> z(1.0, 0.0);
          for (int p = 0; p <= Q; ++p) {
            if (p % 64 == 0) z = std::polar(1.0, -p * tau);  // renormalized against the recurrence's drift
            sum_a[static_cast<size_t>(p)] += weight_a * z;
            sum_b[static_cast<size_t>(p)] += weight_b * z;
            z *= step;
          }
        }
    }
  }
  return {std::move(sum_a), std::move(sum_b)};
}

// The corners of throw j's speed-free torque A = T_gas - Q: the angles [rad] of the cycle where a cylinder's pressure
// table has a point (its firing angle plus each table angle), between which A is smooth, and the jump of A' there,
// A'(c+) - A'(c-) [N m/rad], by one-sided second-order differences (step h = 1e-5 rad: truncation h^2 A''' and
// rounding eps |A| / h both below 1e-9 of the jump's scale |A| / h on the example scenes). Empty without gas.
struct Corner {
  double angle = 0.0, slope_jump = 0.0;
};
std::vector<Corner> findCorners(const CrankTrain& t, int j, const PreparedThrow& prepared) {
  const Mechanism& tm = t.throws[static_cast<size_t>(j)];
  std::vector<double> cuts;
  if (tm.gas)
    for (double firing : tm.firing_angles)
      for (double a : tm.gas->cycle_angles) cuts.push_back(std::fmod(firing + a, t.cycle));
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end(), [&](double x, double y) { return y - x <= 1e-12 * t.cycle; }),
             cuts.end());
  constexpr double h = 1e-5;
  auto A = [&](double psi) { return calcSpeedFreeLoads(prepared, psi).first; };
  std::vector<Corner> out;
  for (double c : cuts) {
    const double at = A(c);
    const double right = (-3.0 * at + 4.0 * A(c + h) - A(c + 2.0 * h)) / (2.0 * h);
    const double left = (3.0 * at - 4.0 * A(c - h) + A(c - 2.0 * h)) / (2.0 * h);
    out.push_back({c, right - left});
  }
  return out;
}

// Loads at two angles that no pressure table corner or quarter turn is likely to hit: the fingerprint by which a
// ThrowLoadOrders knows the throws it serves.
std::vector<double> calcFingerprint(const CrankTrain& t) {
  std::vector<double> out = {t.cycle, static_cast<double>(t.throws.size())};
  for (const Mechanism& tm : t.throws)
    for (double psi : {0.7310585786300049, 3.9261228373}) {
      const ThrowLoads l = calcThrowLoads(tm, psi);
      out.insert(out.end(), {l.J, l.dJ, l.gas_torque, l.gravity_torque});
    }
  return out;
}

}  // namespace

struct ThrowLoadOrders::Impl {
  std::mutex mutex;
  std::vector<double> fingerprint;  // empty until the first train
  // Per throw: the quadrature sums by Q, the orders by P, and the largest FFT grid's samples of A and B so far.
  struct Throw {
    std::map<int, std::pair<std::vector<std::complex<double>>, std::vector<std::complex<double>>>> sums;
    std::map<int, Orders> orders;
    std::vector<double> samples_a, samples_b;
  };
  std::vector<Throw> throws;
};

ThrowLoadOrders::ThrowLoadOrders() : impl_(std::make_unique<Impl>()) {}
ThrowLoadOrders::~ThrowLoadOrders() = default;

const ThrowLoadOrders::Orders& ThrowLoadOrders::getOrders(const CrankTrain& t, int j, int P) {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  if (impl_->fingerprint.empty()) {
    impl_->fingerprint = calcFingerprint(t);
    impl_->throws.resize(t.throws.size());
  } else if (calcFingerprint(t) != impl_->fingerprint) {
    throw std::invalid_argument("torsion: the shared torque orders serve another scene's crank train");
  }
  Impl::Throw& cache = impl_->throws.at(static_cast<size_t>(j));
  const auto found = cache.orders.find(P);
  if (found != cache.orders.end()) return found->second;

  const int Q = std::min(P, kQuadratureOrders);
  auto sums = cache.sums.find(Q);
  if (sums == cache.sums.end()) sums = cache.sums.emplace(Q, calcQuadratureSums(t, j, Q)).first;
  Orders orders;
  for (auto [sum, out] : {std::pair{&sums->second.first, &orders.A}, std::pair{&sums->second.second, &orders.B}}) {
    out->assign(static_cast<size_t>(P + 1), 0.0);
    (*out)[0] = (*sum)[0].real() / t.cycle;
    for (int p = 1; p <= Q; ++p) (*out)[static_cast<size_t>(p)] = 2.0 * (*sum)[static_cast<size_t>(p)] / t.cycle;
  }
  if (P > Q) {
    // The orders above by an FFT of N = 4P samples of each load; the angle cycle k / N is bit for bit the cycle
    // (k / s) / (N / s) of a grid s times coarser at k a multiple of s (s a power of 2): those samples are reused.
    const int N = 4 * P;
    std::vector<double> a(static_cast<size_t>(N)), b(static_cast<size_t>(N));
    const int known = static_cast<int>(cache.samples_a.size());
    const bool coarser = known > 0 && known < N && N % known == 0;
    const bool finer = known >= N && known % N == 0;
    const PreparedThrow tm = prepareThrow(t.throws[static_cast<size_t>(j)]);
    for (int k = 0; k < N; ++k) {
      if (finer) {
        a[static_cast<size_t>(k)] = cache.samples_a[static_cast<size_t>(k * (known / N))];
        b[static_cast<size_t>(k)] = cache.samples_b[static_cast<size_t>(k * (known / N))];
      } else if (coarser && k % (N / known) == 0) {
        a[static_cast<size_t>(k)] = cache.samples_a[static_cast<size_t>(k / (N / known))];
        b[static_cast<size_t>(k)] = cache.samples_b[static_cast<size_t>(k / (N / known))];
      } else {
        std::tie(a[static_cast<size_t>(k)], b[static_cast<size_t>(k)]) = calcSpeedFreeLoads(tm, t.cycle * k / N);
      }
    }
    // A's corners taken out before the FFT and their orders added back exactly: with L = cycle, the periodic kernel
    // f(u) = u/2 - u^2 / (2L) on [0, L) has a unit jump of f' at u = 0 and f'' = -1/L elsewhere, so its orders are
    // f_p = (2/L) / -(2 pi p / L)^2 (those of f'' = delta - 1/L over -(2 pi p / L)^2), shifted by c: f_p e^{-i p tau_c}.
    // What is left is C^1: its FFT's aliasing falls as P^-3 instead of P^-2 (A' jumps at the corners). Without it, the
    // aliasing of the orders below the natural frequencies reaches the twist with gain 1/K, not 1/((p omega)^2 J):
    // a shaft 100 x the example four's stiffness did not converge in 65536 harmonics.
    const std::vector<Corner> corners = findCorners(t, j, tm);
    std::vector<double> smooth(a);
    for (const Corner& c : corners)
      for (int k = 0; k < N; ++k) {
        double u = t.cycle * k / N - c.angle;
        if (u < 0.0) u += t.cycle;
        smooth[static_cast<size_t>(k)] -= c.slope_jump * (0.5 * u - u * u / (2.0 * t.cycle));
      }
    const PeriodicSignal fft_a = calcSignalFromSamples(smooth), fft_b = calcSignalFromSamples(b);
    for (int p = Q + 1; p <= P; ++p) {
      const double k = 2.0 * M_PI * p / t.cycle;
      std::complex<double> kernels = 0.0;
      for (const Corner& c : corners)
        kernels += c.slope_jump * -2.0 / (t.cycle * k * k) * std::polar(1.0, -k * c.angle);
      orders.A[static_cast<size_t>(p)] = fft_a.coefficients[static_cast<size_t>(p)] + kernels;
      orders.B[static_cast<size_t>(p)] = fft_b.coefficients[static_cast<size_t>(p)];
    }
    if (!finer) {
      cache.samples_a = std::move(a);
      cache.samples_b = std::move(b);
    }
  }
  return cache.orders.emplace(P, std::move(orders)).first->second;
}

namespace {

// One pass with the orders p = 0 .. P per cycle: the bodies' and sections' signals, the peak-to-peaks.
HolzerResponse solveWithOrders(const CrankTrain& t, const std::vector<double>& inertias, int P, ThrowLoadOrders& shared) {
  const int n = t.countBodies();
  const int throws = static_cast<int>(t.throws.size());
  HolzerResponse out;
  out.inertias = inertias;
  out.orders = P;
  out.torque_orders.resize(P + 1, throws);
  const double half_omega2 = 0.5 * t.omega * t.omega;
  for (int j = 0; j < throws; ++j) {
    const ThrowLoadOrders::Orders& loads = shared.getOrders(t, j, P);  // T_p = A_p - (1/2) omega^2 B_p
    for (int p = 0; p <= P; ++p)
      out.torque_orders(p, j) = loads.A[static_cast<size_t>(p)] - half_omega2 * loads.B[static_cast<size_t>(p)];
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
                                  const HolzerOptions& options, ThrowLoadOrders& shared) {
  if (static_cast<int>(inertias.size()) != t.countBodies())
    throw std::invalid_argument("torsion: " + std::to_string(inertias.size()) + " inertias for " +
                                std::to_string(t.countBodies()) + " bodies");
  for (double J : inertias)
    if (!(J > 0.0 && std::isfinite(J))) throw std::invalid_argument("torsion: a body of the train has no inertia");
  HolzerResponse last = solveWithOrders(t, inertias, 64, shared);
  for (int P = 128; P <= options.max_harmonics; P *= 2) {
    HolzerResponse next = solveWithOrders(t, inertias, P, shared);
    double largest = 0.0, change = 0.0;
    for (size_t i = 0; i < next.peak_to_peak.size(); ++i) {
      largest = std::max(largest, next.peak_to_peak[i]);
      change = std::max(change, std::fabs(next.peak_to_peak[i] - last.peak_to_peak[i]));
    }
    next.change = largest > 0.0 ? change / largest : 0.0;
    if (change <= options.convergence * largest) return next;  // (largest 0: no forcing, no twist: converged at once)
    last = std::move(next);
  }
  char convergence[32];
  std::snprintf(convergence, sizeof convergence, "%g", options.convergence);
  throw std::runtime_error("torsion: Holzer's sum over orders did not converge to " + std::string(convergence) +
                           " with " + std::to_string(options.max_harmonics) + " harmonics per cycle (a shaft this "
                           "stiff: natural frequencies above that many orders)");
}

HolzerResponse calcHolzerResponse(const CrankTrain& t, const std::vector<double>& inertias,
                                  const HolzerOptions& options) {
  ThrowLoadOrders orders;
  return calcHolzerResponse(t, inertias, options, orders);
}

HolzerResponse calcHolzerResponse(const Mechanism& m, const HolzerOptions& options, ThrowLoadOrders& shared) {
  const CrankTrain t = makeCrankTrain(m);
  std::vector<double> inertias;
  if (t.has_front) inertias.push_back(t.front_inertia);
  for (int j = 0; j < static_cast<int>(t.throws.size()); ++j) inertias.push_back(calcThrowInertia(m, j).exact);
  return calcHolzerResponse(t, inertias, options, shared);
}

HolzerResponse calcHolzerResponse(const Mechanism& m, const HolzerOptions& options) {
  ThrowLoadOrders orders;
  return calcHolzerResponse(m, options, orders);
}

}  // namespace crankcheck::analytic
