#include "crankcheck/analytic/torsion_steady.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include <boost/numeric/odeint.hpp>

#include "crankcheck/analytic/torsion.h"
#include "crankcheck/analytic/torsion_domain.h"
#include "crankcheck/analytic/torsion_forced.h"

namespace crankcheck::analytic {
namespace {

namespace odeint = boost::numeric::odeint;
using State = std::vector<double>;

// The train's equations in s = omega t, y = (x, x_s), x_s = dx/ds (crank_train.h):
//   M_b omega^2 x_ss,b = L_b(psi_b) - (1/2) J_b'(psi_b) omega^2 (1 + x_s,b)^2 - (K x)_b - omega (C x_s)_b,
// psi_b = s + x_b, M_b = J_t + J_b(psi_b) for a throw (J_F and no loads for the front mass), L = T_gas - Q.
struct TrainEquations {
  const CrankTrain& t;
  Eigen::MatrixXd K, C;
  int n;
  std::vector<int> throw_of_body;  // -1: the front mass
  std::vector<PreparedThrow> throws;
  long long max_evaluations;             // SteadyStateOptions::max_evaluations
  mutable long long evaluations = 0;     // of accelerations(), by every run and Jacobian so far

  TrainEquations(const CrankTrain& train, long long limit)
      : t(train), K(calcStiffnessMatrix(train)), C(calcDampingMatrix(train)), n(train.countBodies()),
        max_evaluations(limit) {
    throw_of_body.assign(static_cast<size_t>(n), -1);
    for (int j = 0; j < static_cast<int>(t.throws.size()); ++j) {
      throw_of_body[static_cast<size_t>(t.getThrowBody(j))] = j;
      throws.push_back(prepareThrow(t.throws[static_cast<size_t>(j)]));
    }
  }

  struct Body {
    double M = 0.0, L = 0.0, dJ = 0.0;
  };

  // Why the work ran out, from the train's two fastest rates per crank radian at phi = 0: its stiffness's
  // (sqrt(K_bb / M_b) / omega, the highest frequency over the speed) and its damping's (C_bb / (M_b omega)). A damping
  // rate past the stiffness's makes the equations stiff in the damping (1e18 N m s/rad once got "add damping").
  std::string describeCause() const {
    double stiffness = 0.0, damping = 0.0;
    for (int b = 0; b < n; ++b) {
      const double M = body(b, 0.0).M;
      stiffness = std::max(stiffness, std::sqrt(K(b, b) / M) / t.omega);
      damping = std::max(damping, C(b, b) / (M * t.omega));
    }
    char rates[160];
    std::snprintf(rates, sizeof rates, " (per crank radian: the stiffness's fastest rate %.3g, the damping's %.3g)",
                  stiffness, damping);
    if (damping > stiffness)
      return "a damping this heavy against the train's inertias makes its equations too stiff for the analytic "
             "route" + std::string(rates) + "; reduce [crankshaft].section_damping or throw_damping";
    return "a shaft this stiff, or a resonance this lightly damped, is beyond the analytic route's work limit" +
           std::string(rates) + "; add damping, or change the speed or [crankshaft].stiffness";
  }
  Body body(int b, double psi) const {
    const int j = throw_of_body[static_cast<size_t>(b)];
    if (j < 0) return {t.front_inertia, 0.0, 0.0};
    const ThrowLoads l = calcThrowLoads(throws[static_cast<size_t>(j)], psi);
    return {t.throw_inertia + l.J, l.gas_torque - l.gravity_torque, l.dJ};
  }

  // x_ss of every body; `bodies` (optional) receives each body's loads.
  // @throws std::runtime_error past max_evaluations (the work limit).
  void accelerations(const double* y, double s, double* x_ss, std::vector<Body>* bodies = nullptr) const {
    if (++evaluations > max_evaluations)
      throw std::runtime_error("torsion: the steady state needed more than " + std::to_string(max_evaluations) +
                               " evaluations of the train's equations (SteadyStateOptions::max_evaluations): " +
                               describeCause());
    const double w = t.omega, w2 = w * w;
    for (int b = 0; b < n; ++b) {
      const Body B = body(b, s + y[b]);
      double f = B.L - 0.5 * B.dJ * w2 * (1.0 + y[n + b]) * (1.0 + y[n + b]);
      for (int c = 0; c < n; ++c) f -= K(b, c) * y[c] + w * C(b, c) * y[n + c];
      x_ss[b] = f / (B.M * w2);
      if (bodies) bodies->push_back(B);
    }
  }

  void operator()(const State& y, State& dy, double s) const {
    for (int b = 0; b < n; ++b) dy[static_cast<size_t>(b)] = y[static_cast<size_t>(n + b)];
    accelerations(y.data(), s, dy.data() + n);
  }
};

// The state and its variational matrix Phi (2n x 2n, column-major after the state): Phi' = A Phi.
struct VariationalEquations {
  const TrainEquations& e;
  void operator()(const State& y, State& dy, double s) const {
    const int n = e.n, m = 2 * n;
    for (int b = 0; b < n; ++b) dy[static_cast<size_t>(b)] = y[static_cast<size_t>(n + b)];
    std::vector<TrainEquations::Body> bodies;
    e.accelerations(y.data(), s, dy.data() + n, &bodies);
    // A = [[0, I], [Dx, Dxs]]; the loads' derivatives in psi by central differences (the Jacobian need only be rough).
    const double w = e.t.omega, w2 = w * w, h = 1e-5;
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(m, m);
    for (int b = 0; b < n; ++b) {
      A(b, n + b) = 1.0;
      const TrainEquations::Body& B = bodies[static_cast<size_t>(b)];
      const double psi = s + y[static_cast<size_t>(b)], v = 1.0 + y[static_cast<size_t>(n + b)];
      const TrainEquations::Body up = e.body(b, psi + h), down = e.body(b, psi - h);
      const double dL = (up.L - down.L) / (2 * h), ddJ = (up.dJ - down.dJ) / (2 * h);
      for (int c = 0; c < n; ++c) {
        A(n + b, c) = -e.K(b, c) / (B.M * w2);
        A(n + b, n + c) = -w * e.C(b, c) / (B.M * w2);
      }
      const double x_ss = dy[static_cast<size_t>(n + b)];
      A(n + b, b) += (dL - 0.5 * ddJ * w2 * v * v) / (B.M * w2) - x_ss * B.dJ / B.M;
      A(n + b, n + b) += -B.dJ * v / B.M;
    }
    const Eigen::Map<const Eigen::MatrixXd> Phi(y.data() + m, m, m);
    Eigen::Map<Eigen::MatrixXd> dPhi(dy.data() + m, m, m);
    dPhi.noalias() = A * Phi;
  }
};

// The variational equations' accuracy: a Newton step needs the Jacobian only roughly (an error e in it leaves about
// e x the residual). At 1e-5 Newton takes the same iterations as with a tighter Jacobian, in less time, and the
// peak-to-peaks move by a small fraction of their error bound (1000 x tolerance of the twist scale): bench/README.md,
// "The steady state's Jacobian accuracy".
constexpr double kJacobianAccuracy = 1e-5;

struct Integrator {
  const TrainEquations& e;
  double period, abs_tol, rel_tol;

  // One cycle from y by Dormand-Prince 5(4); with `samples` > 0 the states at the `samples` equally spaced phases are
  // appended to `out` (sample k at s = period k / samples): each reached by a step (`Sampling::kStepEnds`: the steps
  // are then at most the samples' spacing), or read off the dense output of steps the error control alone chose
  // (`Sampling::kDenseOutput`: the run's own accuracy, what an error estimate must see). Returns the steps taken.
  enum class Sampling { kStepEnds, kDenseOutput };
  long run(State& y, int samples, std::vector<State>* out, Sampling sampling = Sampling::kStepEnds) const {
    auto stepper = odeint::make_controlled(abs_tol, rel_tol, odeint::runge_kutta_dopri5<State>());
    const double dt = period / 512;
    // The equations by reference: odeint copies a system given by value at every step.
    if (samples <= 0) return static_cast<long>(odeint::integrate_adaptive(stepper, std::cref(e), y, 0.0, period, dt));
    std::vector<double> times;
    for (int k = 0; k <= samples; ++k) times.push_back(period * k / samples);
    auto observe = [&](const State& state, double s) {
      if (s < period * (1.0 - 0.5 / samples)) out->push_back(state);
    };
    if (sampling == Sampling::kDenseOutput)
      return static_cast<long>(
          odeint::integrate_times(odeint::make_dense_output(abs_tol, rel_tol, odeint::runge_kutta_dopri5<State>()),
                                  std::cref(e), y, times.begin(), times.end(), dt, observe));
    return static_cast<long>(odeint::integrate_times(stepper, std::cref(e), y, times.begin(), times.end(), dt, observe));
  }

  Eigen::MatrixXd jacobian(const State& y0) const {
    const int m = 2 * e.n;
    State z(y0);
    z.resize(static_cast<size_t>(m + m * m), 0.0);
    for (int i = 0; i < m; ++i) z[static_cast<size_t>(m + i * m + i)] = 1.0;
    auto stepper = odeint::make_controlled(kJacobianAccuracy * abs_tol / rel_tol, kJacobianAccuracy,
                                           odeint::runge_kutta_dopri5<State>());
    odeint::integrate_adaptive(stepper, VariationalEquations{e}, z, 0.0, period, period / 512);
    return Eigen::Map<const Eigen::MatrixXd>(z.data() + m, m, m);
  }
};

// The stiff limit's result is taken where its error bound is within this fraction of the largest twist; else the
// explicit route computes (it can, near the stiff limit's switch: 3e4 x the example four's stiffness, whose stiff
// bound was 0.8 of the flywheel section's twist).
constexpr double kStiffLimitAccuracy = 1e-2;

// The stiff-limit route (torsion_steady.h): Holzer's closed form x_H (torsion_forced.h) corrected once for what the
// exact equations add, on N = 8192 phases of the cycle.
ExactSteadyState solveStiffLimit(const CrankTrain& t, const HolzerResponse& holzer, double scale) {
  const int n = t.countBodies(), N = 8192;
  const double L = t.cycle, w = t.omega;
  const Eigen::MatrixXd K = calcStiffnessMatrix(t), C = calcDampingMatrix(t);
  const std::vector<Eigen::VectorXd> xH = holzer.stiff->sampleBodies(N);
  std::vector<PreparedThrow> throws;
  for (const Mechanism& tm : t.throws) throws.push_back(prepareThrow(tm));
  // x_H' = dx_H/dpsi by the series of the samples (its Gibbs ripple at the kinks enters only the small x' terms).
  std::vector<Eigen::VectorXd> xp(static_cast<size_t>(N), Eigen::VectorXd::Zero(n));
  for (int b = 0; b < n; ++b) {
    std::vector<double> v;
    for (const Eigen::VectorXd& x : xH) v.push_back(x(b));
    PeriodicSignal s = calcSignalFromSamples(v), ds;
    for (size_t p = 0; p < s.coefficients.size(); ++p)
      ds.coefficients.push_back(s.coefficients[p] * std::complex<double>(0.0, 2.0 * M_PI * static_cast<double>(p) / L));
    for (int k = 0; k < N; ++k) xp[static_cast<size_t>(k)](b) = ds.evaluate(2.0 * M_PI * k / N);
  }
  // The exact equations' residual on x_H, with J_eq w^2 x_H'' = T(psi) - K x_H - w C x_H' (Holzer's equation):
  //   r = L(psi + x) - (1/2) J'(psi + x) w^2 (1 + x')^2 - K x - w C x' - (M(psi + x) / J_eq) (T(psi) - K x - w C x').
  // q: the largest |1 - M / J_eq|, the frozen inertia's relative error in the correction's own equation.
  std::vector<std::vector<double>> r(static_cast<size_t>(n), std::vector<double>(static_cast<size_t>(N), 0.0));
  double q = 0.0;
  for (int k = 0; k < N; ++k) {
    const double psi = L * k / N;
    const Eigen::VectorXd& x = xH[static_cast<size_t>(k)];
    const Eigen::VectorXd Kx = K * x, Cx = C * xp[static_cast<size_t>(k)];
    for (int j = 0; j < static_cast<int>(throws.size()); ++j) {
      const int b = t.getThrowBody(j);
      const ThrowLoads at = calcThrowLoads(throws[static_cast<size_t>(j)], psi + x(b));
      const ThrowLoads rigid = calcThrowLoads(throws[static_cast<size_t>(j)], psi);
      const double T = rigid.gas_torque - rigid.gravity_torque - 0.5 * w * w * rigid.dJ;
      const double M = t.throw_inertia + at.J, Jeq = holzer.inertias[static_cast<size_t>(b)];
      const double v = 1.0 + xp[static_cast<size_t>(k)](b);
      q = std::max(q, std::fabs(1.0 - M / Jeq));
      r[static_cast<size_t>(b)][static_cast<size_t>(k)] = at.gas_torque - at.gravity_torque - 0.5 * at.dJ * w * w * v * v -
                                                           Kx(b) - w * Cx(b) - M / Jeq * (T - Kx(b) - w * Cx(b));
    }
  }
  // The correction: J_eq w^2 xi'' + w C xi' + K xi = r, order by order.
  std::vector<PeriodicSignal> rs;
  for (int b = 0; b < n; ++b) rs.push_back(calcSignalFromSamples(r[static_cast<size_t>(b)]));
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) J(i, i) = holzer.inertias[static_cast<size_t>(i)];
  std::vector<PeriodicSignal> xi(static_cast<size_t>(n));
  for (size_t p = 0; p < rs.front().coefficients.size(); ++p) {
    const double wp = static_cast<double>(p) * 2.0 * M_PI / L * w;
    const Eigen::MatrixXcd Z = (K - wp * wp * J).cast<std::complex<double>>() + std::complex<double>(0.0, wp) * C;
    Eigen::VectorXcd R(n);
    for (int b = 0; b < n; ++b) R(b) = rs[static_cast<size_t>(b)].coefficients[p];
    const Eigen::VectorXcd X = Z.partialPivLu().solve(R);
    for (int b = 0; b < n; ++b) xi[static_cast<size_t>(b)].coefficients.push_back(X(b));
  }
  ExactSteadyState out;
  out.twist_scale = scale;
  out.newton_iterations = 1;
  out.evaluations = 2LL * N * static_cast<long long>(throws.size());
  out.x0.resize(n);
  out.x_dot0.resize(n);
  std::vector<std::vector<double>> xs(static_cast<size_t>(n)), ts(static_cast<size_t>(n));
  double largest_xi = 0.0;
  for (int k = 0; k < N; ++k) {
    Eigen::VectorXd x = xH[static_cast<size_t>(k)];
    for (int b = 0; b < n; ++b) x(b) += xi[static_cast<size_t>(b)].evaluate(2.0 * M_PI * k / N);
    const Eigen::VectorXd tw = calcSectionTwists(x);
    for (int b = 0; b < n; ++b) {
      xs[static_cast<size_t>(b)].push_back(x(b));
      ts[static_cast<size_t>(b)].push_back(tw(b));
      largest_xi = std::max(largest_xi, std::fabs(x(b) - xH[static_cast<size_t>(k)](b)));
    }
  }
  for (int b = 0; b < n; ++b) {
    out.bodies.push_back(calcSignalFromSamples(xs[static_cast<size_t>(b)]));
    out.twists.push_back(calcSignalFromSamples(ts[static_cast<size_t>(b)]));
    out.x0(b) = xs[static_cast<size_t>(b)][0];
    double rate = xp[0](b);
    for (size_t p = 0; p < xi[static_cast<size_t>(b)].coefficients.size(); ++p)
      rate += (xi[static_cast<size_t>(b)].coefficients[p] *
               std::complex<double>(0.0, 2.0 * M_PI * static_cast<double>(p) / L)).real();
    out.x_dot0(b) = rate * w;
  }
  out.residual = largest_xi / scale;
  // The error bound: the ringing (the exact train rings at frequencies moving by q with its inertia, so its ringing
  // may differ from Holzer's by its whole amplitude, (1 + q) x Holzer's stiff_bound), Holzer's own convergence, and
  // the correction's error taken as large as the correction itself (its twist moves by at most 2 |xi|): its first-order
  // estimate, q x that, was exceeded where q is not small (3e4 x the example four's stiffness: the flywheel section
  // 13 % above the explicit route's 1/K-scaled twist, q x 2 |xi| 2 % of it).
  double largest_p2p = 0.0;
  for (const SignalExtremes& e : holzer.stiff->findTwistExtremes(&xi)) {
    out.peak_to_peak.push_back(e.peakToPeak());
    largest_p2p = std::max(largest_p2p, out.peak_to_peak.back());
  }
  out.error_bound = (1.0 + q) * holzer.stiff_bound + holzer.change * largest_p2p + 2.0 * largest_xi;
  return out;
}

// Holzer's response at s: the state y = (x, dx/ds) (d/ds of Re c_p e^{i p tau} with tau = 2 pi s / cycle).
State findHolzerState(const HolzerResponse& holzer, double cycle, double s) {
  const int n = static_cast<int>(holzer.bodies.size());
  State y(static_cast<size_t>(2 * n), 0.0);
  const double tau = 2.0 * M_PI * s / cycle;
  for (int b = 0; b < n; ++b) {
    const PeriodicSignal& x = holzer.bodies[static_cast<size_t>(b)];
    PeriodicSignal rate;
    for (size_t p = 0; p < x.coefficients.size(); ++p)
      rate.coefficients.push_back(x.coefficients[p] * std::complex<double>(0.0, 2.0 * M_PI * static_cast<double>(p) / cycle));
    y[static_cast<size_t>(b)] = x.evaluate(tau);
    y[static_cast<size_t>(n + b)] = rate.evaluate(tau);
  }
  return y;
}

// The twist scale: the largest |x| of Holzer's response over the cycle (the unit of the residual and the error).
double findTwistScale(const HolzerResponse& holzer) {
  double scale = 0.0;
  for (const PeriodicSignal& x : holzer.bodies) {
    const SignalExtremes ex = findSignalExtremes(x);
    scale = std::max({scale, std::fabs(ex.min), std::fabs(ex.max)});
  }
  return scale;
}

// The probe (estimateExactSteadyStateWork): kProbeSlices slices of 1/kProbeSliceFraction of the cycle each, spread
// evenly over it, from Holzer's state at each slice's start, by the accurate integrator; at most kProbeEvaluations
// evaluations in all, the part of a slice covered by then counted. 4 slices of 1/32: the gas torque's peaks of a
// four-cylinder four-stroke (every quarter cycle) each met once; about 6000 evaluations (4 ms) on the example four.
constexpr int kProbeSlices = 4;
constexpr double kProbeSliceFraction = 32.0;
constexpr long long kProbeEvaluations = 200'000;

struct ShootingProbe {
  double steps_per_cycle = 0.0;        // infinite: no step taken within the probe's evaluations
  double evaluations_per_cycle = 0.0;  // likewise
  double seconds_per_evaluation = 0.0;
};

ShootingProbe probeShooting(const CrankTrain& t, const HolzerResponse& holzer, double scale,
                            const SteadyStateOptions& options) {
  const TrainEquations equations(t, kProbeEvaluations);
  const double slice = t.cycle / kProbeSliceFraction;
  double covered = 0.0;
  long long steps = 0;
  double seconds = 0.0;  // of the integration alone
  for (int k = 0; k < kProbeSlices; ++k) {
    const double s0 = t.cycle * k / kProbeSlices;
    State y = findHolzerState(holzer, t.cycle, s0);
    double reached = s0;
    const auto begin = std::chrono::steady_clock::now();
    auto lap = [&] { seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count(); };
    auto stepper = odeint::make_controlled(options.tolerance * scale, options.tolerance, odeint::runge_kutta_dopri5<State>());
    try {
      odeint::integrate_adaptive(stepper, std::cref(equations), y, s0, s0 + slice, t.cycle / 512,
                                 [&](const State&, double s) {
                                   if (s > s0) ++steps;
                                   reached = s;
                                 });
      lap();
      covered += slice;
    } catch (const std::runtime_error&) {  // the probe's evaluations spent (or odeint's step size gave out)
      lap();
      covered += reached - s0;
      break;
    }
  }
  ShootingProbe probe;
  const double evaluations = static_cast<double>(std::min(equations.evaluations, kProbeEvaluations));
  const double infinity = std::numeric_limits<double>::infinity();
  probe.steps_per_cycle = covered > 0.0 ? static_cast<double>(steps) * t.cycle / covered : infinity;
  probe.evaluations_per_cycle = covered > 0.0 ? evaluations * t.cycle / covered : infinity;
  probe.seconds_per_evaluation = evaluations > 0.0 ? seconds / evaluations : 0.0;
  return probe;
}

// @throws std::invalid_argument for options outside their domain.
void checkSteadyStateOptions(const SteadyStateOptions& options) {
  if (!(options.tolerance > 0.0) || options.samples < 16 || options.samples % 2 != 0 || options.max_evaluations < 1)
    throw std::invalid_argument("torsion: the steady state needs a tolerance > 0, an even number of samples >= 16 and "
                                "max_evaluations >= 1");
}

// The train of m, with the options and Holzer's response checked against it.
// @throws std::invalid_argument for options outside their domain or a response of another number of bodies.
CrankTrain makeCheckedTrain(const Mechanism& m, const HolzerResponse& holzer, const SteadyStateOptions& options) {
  checkSteadyStateOptions(options);
  CrankTrain t = makeCrankTrain(m);
  if (static_cast<int>(holzer.bodies.size()) != t.countBodies())
    throw std::invalid_argument("torsion: Holzer's start has " + std::to_string(holzer.bodies.size()) +
                                " bodies for a train of " + std::to_string(t.countBodies()));
  return t;
}

// The stiff limit's state is returned where its error bound is within kStiffLimitAccuracy of its largest twist.
bool isAccurateEnough(const ExactSteadyState& stiff) {
  return stiff.error_bound <= kStiffLimitAccuracy * *std::max_element(stiff.peak_to_peak.begin(), stiff.peak_to_peak.end());
}

// The exact steady state by shooting (Dormand-Prince 5(4) and Newton's method on the one-cycle map) from y0, Holzer's
// start; `scale` > 0 or 0 (no torque: the rigid motion). @throws std::runtime_error past the work limit or without
// convergence.
ExactSteadyState solveByShooting(const CrankTrain& t, const SteadyStateOptions& options, State y0, double scale) {
  const int n = t.countBodies(), dim = 2 * n;
  ExactSteadyState out;
  out.twist_scale = scale;
  const TrainEquations equations(t, options.max_evaluations);
  if (!(scale > 0.0)) {
    // No torque on any throw in the rigid motion: the rigid motion itself is the steady state, exactly.
    out.x0 = out.x_dot0 = Eigen::VectorXd::Zero(n);
    out.bodies.assign(static_cast<size_t>(n), PeriodicSignal{{0.0}});
    out.twists = out.bodies;
    out.peak_to_peak.assign(static_cast<size_t>(n), 0.0);
    return out;
  }
  const Integrator accurate{equations, t.cycle, options.tolerance * scale, options.tolerance};
  // Newton's method with the Jacobian kept while it works (a chord step that cuts the residual at least tenfold keeps
  // it; one that does not, or the first, computes it anew at the current start).
  Eigen::PartialPivLU<Eigen::MatrixXd> newton_matrix;
  bool have_jacobian = false;
  double last_residual = 0.0;
  Eigen::VectorXd R(dim);
  // From the second iteration on, the run that measures the residual is the sampled one (a step end at every sample,
  // the last at s = cycle): the one that converges is then the orbit reported, not integrated again. The first is
  // not sampled: Holzer's start is seldom periodic to the tolerance (a sampled run takes up to twice the steps on the
  // marine six), a Newton step from it usually is.
  std::vector<State> orbit;  // the last sampled run's states at the samples' phases
  for (int iteration = 1;; ++iteration) {
    State yT(y0);
    orbit.clear();
    const bool sampled = iteration > 1;
    const long taken = accurate.run(yT, sampled ? options.samples : 0, sampled ? &orbit : nullptr);
    for (int i = 0; i < dim; ++i) R(i) = yT[static_cast<size_t>(i)] - y0[static_cast<size_t>(i)];
    out.residual = R.cwiseAbs().maxCoeff() / scale;
    out.newton_iterations = iteration;
    if (out.residual <= 1000.0 * options.tolerance) {
      out.steps = taken;
      break;
    }
    if (iteration >= 30 || !std::isfinite(out.residual))
      throw std::runtime_error("torsion: no periodic steady state found (Newton's residual " +
                               std::to_string(out.residual) + " of the twist scale after " +
                               std::to_string(iteration) + " iterations)");
    if (!have_jacobian || out.residual > 0.1 * last_residual) {
      newton_matrix.compute(accurate.jacobian(y0) - Eigen::MatrixXd::Identity(dim, dim));
      have_jacobian = true;
    }
    last_residual = out.residual;
    const Eigen::VectorXd step = newton_matrix.solve(-R);
    for (int i = 0; i < dim; ++i) y0[static_cast<size_t>(i)] += step(i);
  }

  // The distance to the periodic orbit Newton left, as a step: delta = -(P' - I)^-1 R with the last factorization
  // (computed here if Holzer's start was periodic enough at once), no integration: y0 + delta is about where the orbit
  // is. y0 - 2 delta is three times as far, on the other side: the looser run for the error bound starts there (below).
  if (!have_jacobian) newton_matrix.compute(accurate.jacobian(y0) - Eigen::MatrixXd::Identity(dim, dim));
  const Eigen::VectorXd delta = newton_matrix.solve(-R);
  State farther(y0);
  for (int i = 0; i < dim; ++i) farther[static_cast<size_t>(i)] -= 2.0 * delta(i);

  // An orbit's states at the samples' phases: its series (the bodies' deviations, the sections' twists).
  auto calcSignals = [&](const std::vector<State>& states) {
    std::vector<std::vector<double>> x(static_cast<size_t>(n)), twist(static_cast<size_t>(n));
    for (const State& s : states) {
      Eigen::VectorXd xs(n);
      for (int b = 0; b < n; ++b) xs(b) = s[static_cast<size_t>(b)];
      const Eigen::VectorXd tw = calcSectionTwists(xs);
      for (int b = 0; b < n; ++b) {
        x[static_cast<size_t>(b)].push_back(xs(b));
        twist[static_cast<size_t>(b)].push_back(tw(b));
      }
    }
    std::pair<std::vector<PeriodicSignal>, std::vector<PeriodicSignal>> signals;
    for (int b = 0; b < n; ++b) {
      signals.first.push_back(calcSignalFromSamples(x[static_cast<size_t>(b)]));
      signals.second.push_back(calcSignalFromSamples(twist[static_cast<size_t>(b)]));
    }
    return signals;
  };
  if (orbit.empty()) {  // converged at Holzer's start: the orbit from it, sampled
    State y(y0);
    out.steps = accurate.run(y, options.samples, &orbit);
  }
  auto signals = calcSignals(orbit);
  auto& [bodies, twists] = signals;
  out.bodies = std::move(bodies);
  out.twists = std::move(twists);
  for (const PeriodicSignal& s : out.twists) out.peak_to_peak.push_back(findSignalExtremes(s).peakToPeak());
  // The error bound: the same from y0 - 2 delta, at 100 x the tolerance, taking the steps its own error control chooses
  // (dense output). Worse on both counts than the orbit reported, its difference bounds both the integration's part of
  // the error (the looser run's) and the periodicity's: to first order the peak-to-peaks move with the start, and its
  // start's offset from the orbit, -3 delta, is twice as far from y0's, -delta, as y0's own. Before, the looser run
  // started at y0 and took the samples' spacing wherever it was below its own steps (the marine six: 2048 samples,
  // fewer steps): the same computation as the accurate run, blind to the periodicity Newton stopped at; it read 0 on
  // the marine six at 105 rpm, whose peak-to-peaks at 1e-8 were 2.2e-7 of the scale off those at 1e-11.
  const Integrator loose{equations, t.cycle, 100.0 * options.tolerance * scale, 100.0 * options.tolerance};
  std::vector<State> loose_orbit;
  loose.run(farther, options.samples, &loose_orbit, Integrator::Sampling::kDenseOutput);
  const auto loose_signals = calcSignals(loose_orbit);
  for (int i = 0; i < n; ++i)
    out.error_bound = std::max(out.error_bound, std::fabs(findSignalExtremes(loose_signals.second[static_cast<size_t>(i)]).peakToPeak() -
                                                          out.peak_to_peak[static_cast<size_t>(i)]));
  out.evaluations = equations.evaluations;
  out.x0.resize(n);
  out.x_dot0.resize(n);
  for (int b = 0; b < n; ++b) {
    out.x0(b) = y0[static_cast<size_t>(b)];
    out.x_dot0(b) = y0[static_cast<size_t>(n + b)] * t.omega;
  }
  return out;
}

}  // namespace

ExactSteadyState calcExactSteadyState(const Mechanism& m, const SteadyStateOptions& options) {
  checkSteadyStateOptions(options);
  const CrankTrain t = makeCrankTrain(m);
  std::vector<double> inertias;
  if (t.has_front) inertias.push_back(t.front_inertia);
  for (int j = 0; j < static_cast<int>(t.throws.size()); ++j) inertias.push_back(calcThrowInertia(m, j).exact);
  // Holzer's response only starts Newton's method and sets the scale: its sum to 1e-4 is enough.
  return calcExactSteadyState(m, calcHolzerResponse(t, inertias, {1e-4, 1 << 16}), options);
}

ExactSteadyState calcExactSteadyState(const Mechanism& m, const HolzerResponse& holzer,
                                      const SteadyStateOptions& options) {
  const CrankTrain t = makeCheckedTrain(m, holzer, options);
  checkHolzerTwist(holzer, m.speed_rpm);  // the small-twist domain (torsion_domain.h): refused beyond, before any work
  const State y0 = findHolzerState(holzer, t.cycle, 0.0);
  const double scale = findTwistScale(holzer);
  // Stiff shafts: where Holzer's response took the stiff-limit route (8 x the highest natural frequency's order beyond
  // its harmonics), so does the steady state where it is accurate (the explicit integrator's steps would follow that
  // frequency).
  ExactSteadyState stiff;
  if (holzer.stiff_limit && holzer.stiff && scale > 0.0) {
    stiff = solveStiffLimit(t, holzer, scale);
    if (isAccurateEnough(stiff)) return stiff;
  }
  // The explicit route: the shaft is not that stiff, or too little for the stiff limit's accuracy (then its cost, near
  // the stiff limit's switch, within the work limit, or refused naming both routes).
  try {
    return solveByShooting(t, options, y0, scale);
  } catch (const std::runtime_error& e) {
    if (stiff.peak_to_peak.empty()) throw;
    char text[160];
    std::snprintf(text, sizeof text, "; the stiff limit's bound is %.1e of the largest twist (more than %g)",
                  stiff.error_bound / *std::max_element(stiff.peak_to_peak.begin(), stiff.peak_to_peak.end()),
                  kStiffLimitAccuracy);
    throw std::runtime_error(e.what() + std::string(text));
  }
}

SteadyStateWork estimateExactSteadyStateWork(const Mechanism& m, const HolzerResponse& holzer,
                                             const SteadyStateOptions& options) {
  const CrankTrain t = makeCheckedTrain(m, holzer, options);
  SteadyStateWork work;
  const double scale = findTwistScale(holzer);
  if (!(scale > 0.0)) return work;  // the rigid motion: no work
  const ShootingProbe probe = probeShooting(t, holzer, scale, options);
  work.steps_per_cycle = probe.steps_per_cycle;
  if (holzer.stiff_limit && holzer.stiff) {
    // The stiff-limit route first, as calcExactSteadyState: measured, not estimated (a few ms).
    const auto begin = std::chrono::steady_clock::now();
    const ExactSteadyState stiff = solveStiffLimit(t, holzer, scale);
    work.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    work.evaluations = static_cast<double>(stiff.evaluations);
    if (isAccurateEnough(stiff)) {
      work.stiff_limit = true;
      return work;
    }
  }
  const double shooting = kShootingCycles * probe.evaluations_per_cycle;
  work.evaluations += shooting;
  work.seconds += shooting * probe.seconds_per_evaluation;
  return work;
}

}  // namespace crankcheck::analytic
