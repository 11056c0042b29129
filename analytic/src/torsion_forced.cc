#include "crankcheck/analytic/torsion_forced.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <complex>
#include <limits>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/tools/minima.hpp>
#include <Eigen/Eigenvalues>
#include <unsupported/Eigen/FFT>

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

struct StiffLimitResponse::Impl {
  CrankTrain train;
  std::vector<PreparedThrow> throws;
  Eigen::MatrixXd Kinv;  // K^-1 [rad/(N m)]
  struct KernelCorner {
    int body = 0;
    double angle = 0.0, slope_jump = 0.0;  // [rad], [N m/rad]
  };
  std::vector<KernelCorner> corners;
  Eigen::VectorXcd mu;        // the first-order form's eigenvalues in psi [1/rad]
  Eigen::VectorXcd ring;      // 1 / (1 - e^{mu L})
  Eigen::MatrixXcd Vx;        // the eigenvectors' x rows (n x 2n)
  Eigen::MatrixXcd g;         // V^-1 [0; J^-1 / omega^2] (2n x n)
  std::vector<PeriodicSignal> remainder;  // per body: Re sum_{p <= P} (Z_p^-1 - K^-1) T_sm,p e^{i p tau}
  std::vector<double> ringing;            // [rad] per section
  double p_max = 0.0, p_min = 0.0;

  // Per mode k (one of each conjugate pair, weight 2; a real eigenvalue weight 1) and corner c: s_c e^{-mu_k c} ring_k,
  // and the same times e^{mu_k L} (the corners after psi, whose u = psi - c + L), so that e^{mu u_c} costs no exp.
  std::vector<int> modes;
  std::vector<double> weight;
  Eigen::MatrixXcd before, after;  // (modes x corners)
  void prepareKernels() {
    for (int k = 0; k < mu.size(); ++k)
      if (mu(k).imag() >= 0.0) {
        modes.push_back(k);
        weight.push_back(mu(k).imag() > 0.0 ? 2.0 : 1.0);
      }
    const int nc = static_cast<int>(corners.size());
    before.resize(static_cast<Eigen::Index>(modes.size()), nc);
    after.resize(static_cast<Eigen::Index>(modes.size()), nc);
    for (size_t i = 0; i < modes.size(); ++i)
      for (int c = 0; c < nc; ++c) {
        const std::complex<double> q = mu(modes[i]);
        before(static_cast<Eigen::Index>(i), c) = corners[static_cast<size_t>(c)].slope_jump *
                                                  std::exp(-q * corners[static_cast<size_t>(c)].angle) * ring(modes[i]);
        after(static_cast<Eigen::Index>(i), c) = before(static_cast<Eigen::Index>(i), c) * std::exp(q * train.cycle);
      }
  }
  // The closed form without the remainder series: K^-1 T(psi) + the kernels' dynamic responses.
  Eigen::VectorXd closedForm(double tau) const {
    const int n = train.countBodies();
    const double L = train.cycle;
    double psi = std::fmod(L * tau / (2.0 * M_PI), L);  // in [0, L): the corners' angles are
    if (psi < 0.0) psi += L;
    Eigen::VectorXd T = Eigen::VectorXd::Zero(n);
    for (size_t j = 0; j < throws.size(); ++j) {
      const ThrowLoads l = calcThrowLoads(throws[j], psi);
      T(train.getThrowBody(static_cast<int>(j))) = l.gas_torque - l.gravity_torque - 0.5 * train.omega * train.omega * l.dJ;
    }
    Eigen::VectorXd x = Kinv * T;
    // Per body: sum_c s_c (u_c / L - 1/2) and sum_c s_c (the kernels' slow parts).
    Eigen::VectorXd saw = Eigen::VectorXd::Zero(n), jumps = Eigen::VectorXd::Zero(n);
    std::vector<double> u(corners.size());
    for (size_t c = 0; c < corners.size(); ++c) {
      double v = std::fmod(psi - corners[c].angle, L);
      if (v < 0.0) v += L;
      u[c] = v;
      saw(corners[c].body) += corners[c].slope_jump * (v / L - 0.5);
      jumps(corners[c].body) += corners[c].slope_jump;
    }
    Eigen::VectorXcd modal = Eigen::VectorXcd::Zero(mu.size());
    for (size_t i = 0; i < modes.size(); ++i) {
      const int k = modes[i];
      const std::complex<double> q = mu(k), q2 = q * q, e = std::exp(q * psi);
      std::vector<std::complex<double>> ringing(static_cast<size_t>(n), 0.0);
      for (size_t c = 0; c < corners.size(); ++c)
        ringing[static_cast<size_t>(corners[c].body)] +=
            (psi >= corners[c].angle ? before : after)(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(c));
      std::complex<double> sum = 0.0;
      for (int b = 0; b < n; ++b)
        sum += g(k, b) * ((saw(b) + e * ringing[static_cast<size_t>(b)]) / q2 + jumps(b) / (L * q2 * q));
      modal(k) = weight[i] * sum;
    }
    x += (Vx * modal).real();
    return x;
  }
  Eigen::VectorXd bodies(double tau, const std::vector<PeriodicSignal>* extra) const {
    Eigen::VectorXd x = closedForm(tau);
    for (int b = 0; b < x.size(); ++b) {
      x(b) += remainder[static_cast<size_t>(b)].evaluate(tau);
      if (extra) x(b) += (*extra)[static_cast<size_t>(b)].evaluate(tau);
    }
    return x;
  }
};

namespace {

// A real series' values on M equally spaced phases (its orders above M / 2 folded onto those they alias on the grid,
// exactly: e^{i p tau_m} is periodic in p with period M).
std::vector<double> sampleSeries(const PeriodicSignal& s, int M) {
  std::vector<std::complex<double>> X(static_cast<size_t>(M), 0.0);
  for (size_t p = 0; p < s.coefficients.size(); ++p) {
    const size_t q = p % static_cast<size_t>(M);
    X[q] += 0.5 * M * s.coefficients[p];
    X[(static_cast<size_t>(M) - q) % static_cast<size_t>(M)] += 0.5 * M * std::conj(s.coefficients[p]);
  }
  thread_local Eigen::FFT<double> fft;
  std::vector<std::complex<double>> v;
  fft.inv(v, X);
  std::vector<double> out(static_cast<size_t>(M));
  for (int i = 0; i < M; ++i) out[static_cast<size_t>(i)] = v[static_cast<size_t>(i)].real();
  return out;
}

}  // namespace

Eigen::VectorXd StiffLimitResponse::evaluateBodies(double tau) const { return impl_->bodies(tau, nullptr); }
std::vector<Eigen::VectorXd> StiffLimitResponse::sampleBodies(int N) const {
  const Impl& d = *impl_;
  std::vector<Eigen::VectorXd> out;
  for (int k = 0; k < N; ++k) out.push_back(d.closedForm(2.0 * M_PI * k / N));
  for (int b = 0; b < d.train.countBodies(); ++b) {
    const std::vector<double> r = sampleSeries(d.remainder[static_cast<size_t>(b)], N);
    for (int k = 0; k < N; ++k) out[static_cast<size_t>(k)](b) += r[static_cast<size_t>(k)];
  }
  return out;
}
const std::vector<double>& StiffLimitResponse::ringingAmplitudes() const { return impl_->ringing; }
double StiffLimitResponse::highestOrder() const { return impl_->p_max; }
double StiffLimitResponse::lowestOrder() const { return impl_->p_min; }

std::vector<SignalExtremes> StiffLimitResponse::findTwistExtremes(const std::vector<PeriodicSignal>* extra) const {
  const Impl& d = *impl_;
  const int n = d.train.countBodies();
  // The grid: the closed form at M points, the series summed by FFT onto it.
  size_t longest = d.remainder.front().coefficients.size();
  if (extra) longest = std::max(longest, extra->front().coefficients.size());
  int M = 4096;
  while (static_cast<size_t>(M) < 8 * longest && M < (1 << 16)) M *= 2;
  std::vector<Eigen::VectorXd> grid;
  for (int i = 0; i < M; ++i) grid.push_back(d.closedForm(2.0 * M_PI * i / M));
  for (int b = 0; b < n; ++b) {
    std::vector<double> r = sampleSeries(d.remainder[static_cast<size_t>(b)], M);
    if (extra) {
      const std::vector<double> e = sampleSeries((*extra)[static_cast<size_t>(b)], M);
      for (int i = 0; i < M; ++i) r[static_cast<size_t>(i)] += e[static_cast<size_t>(i)];
    }
    for (int i = 0; i < M; ++i) grid[static_cast<size_t>(i)](b) += r[static_cast<size_t>(i)];
  }
  const double h = 2.0 * M_PI / M;
  constexpr int kBits = std::numeric_limits<double>::digits;
  std::vector<SignalExtremes> out;
  for (int section = 0; section < n; ++section) {
    auto twistOf = [&](const Eigen::VectorXd& x) { return section + 1 < n ? x(section + 1) - x(section) : -x(section); };
    std::vector<double> v(static_cast<size_t>(M));
    for (int i = 0; i < M; ++i) v[static_cast<size_t>(i)] = twistOf(grid[static_cast<size_t>(i)]);
    auto f = [&](double tau) { return twistOf(d.bodies(tau, extra)); };
    // Brent (full precision: an extreme at a pressure-table corner is a kink) from the grid's four best local
    // extremes of each kind: two maxima nearly equal on the grid are both refined.
    SignalExtremes e;
    for (double sign : {1.0, -1.0}) {  // +1: the maximum, -1: the minimum
      std::vector<int> local;
      for (int i = 0; i < M; ++i) {
        const double a = sign * v[static_cast<size_t>((i + M - 1) % M)], b = sign * v[static_cast<size_t>(i)],
                     c = sign * v[static_cast<size_t>((i + 1) % M)];
        if (b >= a && b >= c) local.push_back(i);
      }
      std::sort(local.begin(), local.end(),
                [&](int a, int b) { return sign * v[static_cast<size_t>(a)] > sign * v[static_cast<size_t>(b)]; });
      if (local.size() > 4) local.resize(4);
      double best = -std::numeric_limits<double>::infinity(), where = 0.0;
      for (int i : local) {
        const auto r = boost::math::tools::brent_find_minima([&](double tau) { return -sign * f(tau); }, (i - 1) * h,
                                                             (i + 1) * h, kBits);
        const bool refined = -r.second >= sign * v[static_cast<size_t>(i)];
        const double value = refined ? -r.second : sign * v[static_cast<size_t>(i)];
        if (value > best) {
          best = value;
          where = refined ? r.first : i * h;
        }
      }
      if (sign > 0) {
        e.max = best;
        e.tau_max = where;
      } else {
        e.min = -best;
        e.tau_min = where;
      }
    }
    out.push_back(e);
  }
  return out;
}

namespace {

// Holzer's response on the stiff-limit route (torsion_forced.h): the closed form, the smooth part's dynamic remainder
// summed to P doubled from 64 until (the last doubling's bound 2 max_i sum_{P/2 < p <= P} |R_p,i|) x (1 + log2(p_min /
// P)) is within `convergence` of the largest peak-to-peak.
HolzerResponse solveStiffLimit(const CrankTrain& t, const std::vector<double>& inertias, const HolzerOptions& options,
                               ThrowLoadOrders& shared, double p_max, double p_min) {
  const int n = t.countBodies();
  const double L = t.cycle, w = t.omega;
  auto impl = std::make_shared<StiffLimitResponse::Impl>();
  StiffLimitResponse::Impl& d = *impl;
  d.train = t;
  d.p_max = p_max;
  d.p_min = p_min;
  for (const Mechanism& tm : t.throws) d.throws.push_back(prepareThrow(tm));
  const Eigen::MatrixXd K = calcStiffnessMatrix(t), C = calcDampingMatrix(t);
  d.Kinv = K.inverse();
  for (int j = 0; j < static_cast<int>(t.throws.size()); ++j)
    for (const Corner& c : findCorners(t, j, d.throws[static_cast<size_t>(j)]))
      d.corners.push_back({t.getThrowBody(j), c.angle, c.slope_jump});
  // The first-order form in psi, the rates scaled by s (so that both blocks are of one size): y = (x, x_psi / s).
  Eigen::VectorXd Jinv(n);
  for (int i = 0; i < n; ++i) Jinv(i) = 1.0 / inertias[static_cast<size_t>(i)];
  const double s = p_max * 2.0 * M_PI / L;  // [1/rad] the fastest mode's rate in psi
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  A.topRightCorner(n, n) = s * Eigen::MatrixXd::Identity(n, n);
  A.bottomLeftCorner(n, n) = -(Jinv.asDiagonal() * K) / (w * w * s);
  A.bottomRightCorner(n, n) = -(Jinv.asDiagonal() * C) / w;
  const Eigen::EigenSolver<Eigen::MatrixXd> eigen(A);
  d.mu = eigen.eigenvalues();
  const Eigen::MatrixXcd V = eigen.eigenvectors();
  d.Vx = V.topRows(n);
  Eigen::MatrixXcd B = Eigen::MatrixXcd::Zero(2 * n, n);
  for (int i = 0; i < n; ++i) B(n + i, i) = Jinv(i) / (w * w * s);
  d.g = V.partialPivLu().solve(B);
  d.ring.resize(d.mu.size());
  for (int k = 0; k < d.mu.size(); ++k) d.ring(k) = 1.0 / (1.0 - std::exp(d.mu(k) * L));
  d.prepareKernels();
  // Ringing amplitudes a_i: mode k's ringing, e^{mu_k psi} times a sum over corners that is constant between corners,
  // has its largest modulus just after a corner (|e^{mu u}| falls with u: Re mu < 0); so a_i = sum_k weight_k |twist_i
  // of Vx_k| max over corners c0 of |sum_c g_k,b_c s_c ring_k e^{mu_k u_c(c0+)} / mu_k^2|.
  d.ringing.assign(static_cast<size_t>(n), 0.0);
  for (size_t m = 0; m < d.modes.size(); ++m) {
    const int k = d.modes[m];
    double most = 0.0;
    for (const auto& c0 : d.corners) {
      std::complex<double> sum = 0.0;
      for (const auto& c : d.corners) {
        double u = std::fmod(c0.angle - c.angle, L);
        if (u < 0.0) u += L;
        sum += d.g(k, c.body) * c.slope_jump * d.ring(k) * std::exp(d.mu(k) * u);
      }
      most = std::max(most, std::abs(sum / (d.mu(k) * d.mu(k))));
    }
    for (int i = 0; i < n; ++i) {
      const std::complex<double> tw = i + 1 < n ? d.Vx(i + 1, k) - d.Vx(i, k) : -d.Vx(i, k);
      d.ringing[static_cast<size_t>(i)] += d.weight[m] * std::abs(tw) * most;
    }
  }
  // The kernels' orders (p >= 1): e_b s_c (-2 / (L k^2)) e^{-i p tau_c}, k = 2 pi p / L.
  auto kernelOrders = [&](int p) {
    Eigen::VectorXcd out = Eigen::VectorXcd::Zero(n);
    const double k = 2.0 * M_PI * p / L;
    for (const auto& c : d.corners) out(c.body) += c.slope_jump * -2.0 / (L * k * k) * std::polar(1.0, -k * c.angle);
    return out;
  };
  HolzerResponse out;
  out.inertias = inertias;
  out.stiff_limit = true;
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) J(i, i) = inertias[static_cast<size_t>(i)];
  double ringing_bound = 0.0, tail = 0.0;  // [rad] 4 max_i a_i; the remainder's tail beyond P
  for (double a : d.ringing) ringing_bound = std::max(ringing_bound, 4.0 * a);
  double largest = 0.0;  // the largest peak-to-peak, read off the closed form at P = 64 (the convergence's unit)
  std::vector<std::vector<std::complex<double>>> R(static_cast<size_t>(n)), X(static_cast<size_t>(n));
  int P = 64;
  const int throws = static_cast<int>(t.throws.size());
  for (;; P *= 2) {
    if (P > options.max_harmonics) {
      char convergence[32];
      std::snprintf(convergence, sizeof convergence, "%g", options.convergence);
      throw std::runtime_error("torsion: Holzer's stiff-limit sum did not converge to " + std::string(convergence) +
                               " with " + std::to_string(options.max_harmonics) + " harmonics per cycle");
    }
    out.torque_orders.resize(P + 1, throws);
    std::vector<const ThrowLoadOrders::Orders*> loads;
    for (int j = 0; j < throws; ++j) loads.push_back(&shared.getOrders(t, j, P));
    double octave = 0.0;  // max over sections of sum |R_p twist| over the orders added
    // Every order anew: the FFT's orders (p > 256) move a little with its grid of 4P samples.
    for (auto& v : R) v.clear();
    for (auto& v : X) v.clear();
    for (int p = 0; p <= P; ++p) {
      Eigen::VectorXcd T = Eigen::VectorXcd::Zero(n);
      for (int j = 0; j < throws; ++j) {
        const std::complex<double> Tp =
            loads[static_cast<size_t>(j)]->A[static_cast<size_t>(p)] - 0.5 * w * w * loads[static_cast<size_t>(j)]->B[static_cast<size_t>(p)];
        out.torque_orders(p, j) = Tp;
        T(t.getThrowBody(j)) = Tp;
      }
      const double wp = p * 2.0 * M_PI / L * w;
      const Eigen::MatrixXcd Z = (K - wp * wp * J).cast<std::complex<double>>() + std::complex<double>(0.0, wp) * C;
      const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(Z);
      const Eigen::VectorXcd Xp = lu.solve(T);
      Eigen::VectorXcd Rp = Eigen::VectorXcd::Zero(n);
      if (p > 0) {
        const Eigen::VectorXcd Tsm = T - kernelOrders(p);
        Rp = lu.solve(Tsm) - d.Kinv.cast<std::complex<double>>() * Tsm;
      }
      for (int i = 0; i < n; ++i) {
        R[static_cast<size_t>(i)].push_back(Rp(i));
        X[static_cast<size_t>(i)].push_back(Xp(i));
      }
    }
    for (int i = 0; i < n; ++i) {
      double sum = 0.0;
      for (int p = P / 2 + 1; p <= P; ++p) {
        const std::complex<double> a = i + 1 < n ? R[static_cast<size_t>(i + 1)][static_cast<size_t>(p)] -
                                                       R[static_cast<size_t>(i)][static_cast<size_t>(p)]
                                                 : -R[static_cast<size_t>(i)][static_cast<size_t>(p)];
        sum += std::abs(a);
      }
      octave = std::max(octave, 2.0 * sum);
    }
    d.remainder.assign(static_cast<size_t>(n), PeriodicSignal{});
    for (int i = 0; i < n; ++i) d.remainder[static_cast<size_t>(i)].coefficients = R[static_cast<size_t>(i)];
    if (P == 64) {
      const StiffLimitResponse view(impl);
      for (const SignalExtremes& e : view.findTwistExtremes()) largest = std::max(largest, e.peakToPeak());
      continue;  // the orders 0 .. 64 are the first sum, not a doubling's change
    }
    const double octaves = 1.0 + std::max(0.0, std::log2(p_min / P));
    tail = octave * octaves;
    out.change = largest > 0.0 ? tail / largest : 0.0;
    // Converged at `convergence`, or where the tail is a tenth of the ringing's bound, which it can no longer move.
    if (tail <= options.convergence * largest || tail <= 0.1 * ringing_bound) break;
  }
  out.orders = P;
  const StiffLimitResponse view(impl);
  const std::vector<SignalExtremes> extremes = view.findTwistExtremes();
  const double order_per_p = 2.0 * M_PI / L;
  for (int i = 0; i < n; ++i) {
    PeriodicSignal body, twist, twist24;
    body.coefficients = X[static_cast<size_t>(i)];
    for (int p = 0; p <= P; ++p) {
      const std::complex<double> tw = i + 1 < n ? X[static_cast<size_t>(i + 1)][static_cast<size_t>(p)] -
                                                      X[static_cast<size_t>(i)][static_cast<size_t>(p)]
                                                : -X[static_cast<size_t>(i)][static_cast<size_t>(p)];
      twist.coefficients.push_back(tw);
      if (p * order_per_p <= 24.0 + 1e-9) twist24.coefficients.push_back(tw);
    }
    out.bodies.push_back(std::move(body));
    out.twists.push_back(std::move(twist));
    out.peak_to_peak.push_back(extremes[static_cast<size_t>(i)].peakToPeak());
    out.peak_to_peak_order24.push_back(findSignalExtremes(twist24).peakToPeak());
  }
  out.stiff_bound = ringing_bound + tail;
  out.stiff = std::make_shared<const StiffLimitResponse>(impl);
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
  {
    // The route: the plain sum needs P beyond the highest natural frequency's order (its tail then falls as P^-3);
    // where 8 p_max exceeds max_harmonics it cannot converge, and the stiff-limit route is taken.
    const TorsionModes modes = calcChainModes(inertias, t.stiffness);
    const double per_order = t.cycle / (2.0 * M_PI * t.omega);  // p per rad/s
    const double p_max = modes.frequencies.maxCoeff() * per_order, p_min = modes.frequencies.minCoeff() * per_order;
    if (8.0 * p_max > options.max_harmonics) return solveStiffLimit(t, inertias, options, shared, p_max, p_min);
  }
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
