#include "crankcheck/validation/run_measures.h"

#include <algorithm>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "crankcheck/analytic/motion.h"
#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/validation/extremum.h"

namespace crankcheck::validation {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;
constexpr int kWindow = 6;  // Lagrange interpolation of degree 5
constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

void checkStrictlyIncreasing(const std::vector<double>& v, const char* what, const char* who) {
  for (size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i]))
      throw std::invalid_argument(std::string(who) + ": " + what + "[" + std::to_string(i) + "] is not finite");
    if (i > 0 && !(v[i] > v[i - 1]))
      throw std::invalid_argument(std::string(who) + ": " + what + " is not strictly increasing at sample " +
                                  std::to_string(i));
  }
}

void checkRun(const Mechanism& m, const SteppedRun& run, const char* who) {
  if (run.phi.size() != run.time.size() || run.omega.size() != run.time.size())
    throw std::invalid_argument(std::string(who) + ": time, phi and omega must have as many samples (" +
                                std::to_string(run.time.size()) + ", " + std::to_string(run.phi.size()) + ", " +
                                std::to_string(run.omega.size()) + ")");
  if (run.time.size() < static_cast<size_t>(kMinRunSamples))
    throw std::invalid_argument(std::string(who) + ": too few samples (" + std::to_string(run.time.size()) +
                                "; at least " + std::to_string(kMinRunSamples) + ")");
  checkStrictlyIncreasing(run.time, "time", who);
  checkStrictlyIncreasing(run.phi, "phi", who);
  for (size_t i = 0; i < run.omega.size(); ++i)
    if (!std::isfinite(run.omega[i]))
      throw std::invalid_argument(std::string(who) + ": omega[" + std::to_string(i) + "] is not finite");
  if (!m.flywheel_inertia)
    throw std::invalid_argument(std::string(who) + ": the scene needs the flywheel inertia [flywheel].inertia");
  if (m.gas)
    throw std::invalid_argument(std::string(who) + ": the scene has a [gas] table; these measures judge a free run "
                                "under gravity alone");
}

void checkOneRevolution(const SteppedRun& run, const char* who) {
  if (run.phi.back() - run.phi.front() < kTwoPi)
    throw std::invalid_argument(std::string(who) + ": the run is shorter than one revolution (" +
                                std::to_string(run.phi.back() - run.phi.front()) + " rad)");
}

// y(x) by Lagrange interpolation on the six samples around x (fewer never: the run has at least kMinRunSamples - 1).
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

SteppedRunReader::SteppedRunReader(const SteppedRun& run) : run_(run) {
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

double SteppedRunReader::findPhi(double t) const { return interpolate(run_.time, run_.phi, t); }

double SteppedRunReader::findOmega(double t) const { return interpolate(omega_time_, omega_, t); }

double SteppedRunReader::findTimeAtPhase(double target) const {
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

namespace {

double energyAt(const Mechanism& m, double phi, double omega) {
  return 0.5 * analytic::calcReducedInertia(m, phi).J * omega * omega + analytic::calcPotentialEnergy(m, phi);
}

double leastSquaresSlope(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double mx = 0.0, my = 0.0;
  for (size_t i = 0; i < x.size(); ++i) mx += x[i], my += y[i];
  mx /= n;
  my /= n;
  double sxy = 0.0, sxx = 0.0;
  for (size_t i = 0; i < x.size(); ++i) sxy += (x[i] - mx) * (y[i] - my), sxx += (x[i] - mx) * (x[i] - mx);
  return sxy / sxx;
}

double wrapAngle(double a) {  // to (-pi, pi]
  a = std::remainder(a, kTwoPi);
  return a <= -M_PI ? a + kTwoPi : a;
}

// Release speed at phi = 0 of the free run with energy E (U(0) = 0 by the convention of potential_energy.h).
double releaseSpeed(const Mechanism& m, double E) {
  const double v2 = 2.0 * E / analytic::calcReducedInertia(m, 0.0).J;
  if (!(v2 > 0.0)) throw std::domain_error("the exact free run does not reach phi = 0 (its energy is not > 0)");
  return std::sqrt(v2);
}

}  // namespace

std::vector<double> calcEnergyAtTurns(const Mechanism& m, const SteppedRun& run) {
  constexpr const char* kWho = "calcEnergyAtTurns";
  checkRun(m, run, kWho);
  checkOneRevolution(run, kWho);
  const SteppedRunReader reader(run);
  const double phi0 = run.phi.front();
  const int turns = static_cast<int>(std::floor((run.phi.back() - phi0) / kTwoPi));
  std::vector<double> energy;
  for (int i = 0; i <= turns; ++i) {
    const double phase = phi0 + kTwoPi * i;
    if (phase > run.phi.back()) break;
    energy.push_back(energyAt(m, phase, reader.findOmegaAtPhase(phase)));
  }
  return energy;
}

double calcEnergyTrend(const Mechanism& m, const SteppedRun& run) {
  const std::vector<double> energy = calcEnergyAtTurns(m, run);
  std::vector<double> k;
  for (size_t i = 0; i < energy.size(); ++i) k.push_back(static_cast<double>(i));
  return leastSquaresSlope(k, energy) / energy.front();
}

SpeedFluctuationComparison calcSpeedFluctuation(const Mechanism& m, const SteppedRun& run) {
  constexpr const char* kWho = "calcSpeedFluctuation";
  checkRun(m, run, kWho);
  checkOneRevolution(run, kWho);
  const SteppedRunReader reader(run);
  const double phi0 = run.phi.front(), phi1 = phi0 + kTwoPi;
  // omega against phase over the first revolution: the samples in it and its end, then the extremes refined.
  std::vector<double> phase, omega;
  for (size_t i = 0; i < run.phi.size() && run.phi[i] < phi1; ++i) {
    phase.push_back(run.phi[i]);
    omega.push_back(reader.findOmega(run.time[i]));
  }
  phase.push_back(phi1);
  omega.push_back(reader.findOmegaAtPhase(phi1));
  const size_t imax = static_cast<size_t>(std::max_element(omega.begin(), omega.end()) - omega.begin());
  const size_t imin = static_cast<size_t>(std::min_element(omega.begin(), omega.end()) - omega.begin());
  auto bracket = [&](size_t i) {
    return std::pair{phase[i == 0 ? 0 : i - 1], phase[std::min(i + 1, phase.size() - 1)]};
  };
  auto w = [&](double p) { return reader.findOmegaAtPhase(p); };
  const auto [amax, bmax] = bracket(imax);
  const TurnMaximum top = refineMaxAbs(w, amax, bmax);
  const double ceiling = 2.0 * std::max(top.value, omega[imax]);  // min omega = max of (ceiling - omega) > 0
  const auto [amin, bmin] = bracket(imin);
  const TurnMaximum bottom = refineMaxAbs([&](double p) { return ceiling - w(p); }, amin, bmin);
  const double omega_max = std::max(top.value, omega[imax]), omega_min = std::min(ceiling - bottom.value, omega[imin]);
  const double phi_max = top.value >= omega[imax] ? top.phi : phase[imax];
  const double phi_min = ceiling - bottom.value <= omega[imin] ? bottom.phi : phase[imin];
  const double omega_mean = kTwoPi / (reader.findTimeAtPhase(phi1) - run.time.front());

  SpeedFluctuationComparison out;
  out.run.delta = (omega_max - omega_min) / omega_mean;
  out.run.phi_at_omega_max = std::fmod(std::fmod(phi_max, kTwoPi) + kTwoPi, kTwoPi);
  out.run.phi_at_omega_min = std::fmod(std::fmod(phi_min, kTwoPi) + kTwoPi, kTwoPi);
  // The exact free run, released at phi = 0 with the run's omega at its first phi = 0 (mod 2 pi).
  const double zero = kTwoPi * std::ceil(phi0 / kTwoPi);
  out.omega_at_zero = reader.findOmegaAtPhase(zero);
  const analytic::FreeRun exact = analytic::calcFreeRun(m, out.omega_at_zero);
  out.exact = {exact.delta, exact.phi_at_omega_max, exact.phi_at_omega_min};
  out.delta_error = out.run.delta - out.exact.delta;
  // An extreme can be reached at several phases with speeds the run cannot tell apart (a centric standing single:
  // omega(phi) = omega(-phi), two equal minima; an inline four: two equal humps a turn): the run's phase is compared
  // with the nearest of the exact run's local extremes whose speed is within the run's own speed error of the extreme:
  // |delta error| x omega_mean, or the run's change of speed over the revolution (a run that loses energy is fastest
  // where it starts), at least rounding.
  const double drift = std::fabs(reader.findOmegaAtPhase(phi1) - reader.findOmegaAtPhase(phi0));  // 0 on the exact run
  const double speed_error =
      std::max({std::fabs(out.delta_error) * omega_mean, drift, 64.0 * kEpsilon * exact.omega_max});
  auto nearest = [&](double run_phase, double exact_phase, double extreme, double sign) {
    double best = wrapAngle(run_phase - exact_phase);
    constexpr int kSamples = 720;
    auto w = [&](double p) { return sign * analytic::calcFreeRunSpeed(m, out.omega_at_zero, p); };
    std::vector<double> v(kSamples);
    for (int i = 0; i < kSamples; ++i) v[static_cast<size_t>(i)] = w(kTwoPi * i / kSamples);
    for (int i = 0; i < kSamples; ++i) {
      const double here = v[static_cast<size_t>(i)];
      if (!(here >= v[static_cast<size_t>((i + kSamples - 1) % kSamples)] && here >= v[static_cast<size_t>((i + 1) % kSamples)]))
        continue;  // not a local extreme of the samples
      const TurnMaximum local = refineMaxAbs([&](double p) { return w(p) + 2.0 * exact.omega_max; },
                                             kTwoPi * (i - 1) / kSamples, kTwoPi * (i + 1) / kSamples);
      if (std::fabs(local.value - 2.0 * exact.omega_max - sign * extreme) > speed_error) continue;
      const double error = wrapAngle(run_phase - local.phi);
      if (std::fabs(error) < std::fabs(best)) best = error;
    }
    return best;
  };
  out.phi_max_error = nearest(out.run.phi_at_omega_max, out.exact.phi_at_omega_max, exact.omega_max, 1.0);
  out.phi_min_error = nearest(out.run.phi_at_omega_min, out.exact.phi_at_omega_min, exact.omega_min, -1.0);
  return out;
}

std::vector<double> calcPhaseErrors(const Mechanism& m, const SteppedRun& run, const std::vector<double>& horizons) {
  constexpr const char* kWho = "calcPhaseError";
  checkRun(m, run, kWho);
  for (double horizon : horizons)
    if (!(horizon >= run.time.front() && horizon <= run.time.back()))
      throw std::invalid_argument(std::string(kWho) + ": the horizon " + std::to_string(horizon) +
                                  " s is outside the run's time [" + std::to_string(run.time.front()) + ", " +
                                  std::to_string(run.time.back()) + "] s");
  const SteppedRunReader reader(run);
  const double t0 = run.time.front(), phi0 = run.phi.front();
  const double omega0 = releaseSpeed(m, energyAt(m, phi0, reader.findOmega(t0)));
  const analytic::FreeRun turn = analytic::calcFreeRun(m, omega0);  // throws if it does not turn over
  auto slowness = [&](double p) { return 1.0 / analytic::calcFreeRunSpeed(m, omega0, p); };
  auto integral = [&](double to) {
    return to > 0.0 ? boost::math::quadrature::gauss_kronrod<double, 61>::integrate(slowness, 0.0, to, 10, 1e-11) : 0.0;
  };
  // t(phi) from phi = 0: whole turns times one turn's time plus the rest's integral (the turn's time by the same
  // quadrature as the rest's, so that t(phi) has no step at a whole turn).
  const double period = integral(kTwoPi);
  auto elapsed = [&](double p) {
    const double turns = std::floor(p / kTwoPi);
    return turns * period + integral(p - turns * kTwoPi);
  };
  const double start = elapsed(phi0);
  std::vector<double> out;
  for (double horizon : horizons) {
    const double dt = horizon - t0;
    if (dt == 0.0) {
      out.push_back(reader.findPhi(horizon) - phi0);
      continue;
    }
    const double target = start + dt;
    auto g = [&](double p) { return elapsed(p) - target; };
    // phi advances at least omega_min and at most omega_max per second.
    double a = phi0 + turn.omega_min * dt, b = phi0 + turn.omega_max * dt;
    const double margin = 1e-9 * (std::fabs(b) + 1.0);
    a -= margin;
    b += margin;
    std::uintmax_t iterations = 100;
    const auto root =
        boost::math::tools::toms748_solve(g, a, b, boost::math::tools::eps_tolerance<double>(52), iterations);
    out.push_back(reader.findPhi(horizon) - 0.5 * (root.first + root.second));
  }
  return out;
}

double calcPhaseError(const Mechanism& m, const SteppedRun& run, double horizon) {
  return calcPhaseErrors(m, run, {horizon}).front();
}

double calcObservedOrder(const std::vector<double>& steps, const std::vector<double>& errors) {
  if (steps.size() != errors.size())
    throw std::invalid_argument("calcObservedOrder: " + std::to_string(steps.size()) + " steps but " +
                                std::to_string(errors.size()) + " errors");
  if (steps.size() < 2) throw std::invalid_argument("calcObservedOrder: too few points (at least 2)");
  std::vector<double> x, y;
  for (size_t i = 0; i < steps.size(); ++i) {
    if (!(std::isfinite(steps[i]) && steps[i] > 0.0))
      throw std::invalid_argument("calcObservedOrder: step " + std::to_string(i) + " is not finite and > 0");
    if (!std::isfinite(errors[i]) || errors[i] == 0.0)
      throw std::invalid_argument("calcObservedOrder: error " + std::to_string(i) + " is not finite or is 0");
    x.push_back(std::log(steps[i]));
    y.push_back(std::log(std::fabs(errors[i])));
  }
  if (std::all_of(x.begin(), x.end(), [&](double v) { return v == x.front(); }))
    throw std::invalid_argument("calcObservedOrder: the steps are all equal");
  return leastSquaresSlope(x, y);
}

}  // namespace crankcheck::validation
