#include "crankcheck/validation/run_measures.h"

#include <algorithm>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <tuple>
#include <optional>
#include <memory>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include "crankcheck/analytic/gas_work.h"
#include "crankcheck/analytic/motion.h"
#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/solver/stepped_run.h"
#include "crankcheck/solver/trajectory.h"
#include "crankcheck/validation/extremum.h"

namespace crankcheck::validation {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;
constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

void checkRun(const Mechanism& m, const Trajectory& run, const RunLoad& load, const char* who) {
  if (run.phi.size() != run.time.size() || run.omega.size() != run.time.size())
    throw std::invalid_argument(std::string(who) + ": time, phi and omega must have as many samples (" +
                                std::to_string(run.time.size()) + ", " + std::to_string(run.phi.size()) + ", " +
                                std::to_string(run.omega.size()) + ")");
  if (run.time.size() < static_cast<size_t>(kMinRunSamples))
    throw std::invalid_argument(std::string(who) + ": too few samples (" + std::to_string(run.time.size()) +
                                "; at least " + std::to_string(kMinRunSamples) + ")");
  checkStrictlyIncreasing(run.time, "time", who);
  checkStrictlyIncreasing(run.phi, "phi", who);
  for (size_t i = 1; i < run.phi.size(); ++i)
    if (run.phi[i] - run.phi[i - 1] > kMaxStepAngle) {
      char line[96];
      std::snprintf(line, sizeof line, "%.4g deg", degreesFromRadians(run.phi[i] - run.phi[i - 1]));
      throw std::invalid_argument(std::string(who) + ": phi turns by " + line + " from sample " + std::to_string(i - 1) +
                                  " to " + std::to_string(i) + ", more than a quarter turn: the run is too coarse to be "
                                  "measured (its extremes and crossings are read by interpolation through six samples)");
    }
  for (size_t i = 0; i < run.omega.size(); ++i)
    if (!std::isfinite(run.omega[i]))
      throw std::invalid_argument(std::string(who) + ": omega[" + std::to_string(i) + "] is not finite");
  if (!m.flywheel_inertia)
    throw std::invalid_argument(std::string(who) + ": the scene needs the flywheel inertia [flywheel].inertia");
  if (m.gas && !load.gas)
    throw std::invalid_argument(std::string(who) + ": the scene has a [gas] table; a free run is judged under gravity "
                                "alone (RunLoad::gas for a run under gas)");
  if (load.gas && !m.gas) throw std::invalid_argument(std::string(who) + ": a run under gas needs the scene's [gas] table");
}

void checkOnePeriod(const Trajectory& run, double period, const char* who) {
  if (run.phi.back() - run.phi.front() < period)
    throw std::invalid_argument(std::string(who) + ": the run is shorter than one " +
                                (period > kTwoPi ? "working cycle" : "revolution") + " (" +
                                std::to_string(run.phi.back() - run.phi.front()) + " rad)");
}

}  // namespace

namespace {

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

double wrapAngle(double a, double period) {  // to (-period / 2, period / 2]
  a = std::remainder(a, period);
  return a <= -0.5 * period ? a + period : a;
}

// What the exact run conserves, and its period: a free run (gravity alone) conserves E = (1/2) J omega^2 + U over a
// revolution; a run under gas with the cycle-mean load conserves E - W(phi) + T_L phi (gas_work.h), periodic over the
// working cycle.
class RunInvariant {
 public:
  RunInvariant(const Mechanism& m, const RunLoad& load) : m_(m) {
    if (load.gas) gas_.emplace(m);
  }
  double getPeriod() const { return gas_ ? gas_->getCycle() : kTwoPi; }
  double getLoadTorque() const { return gas_ ? gas_->getMeanTorque() : 0.0; }
  /// The invariant's value at a state.
  double calcValue(double phi, double omega) const {
    const double e = 0.5 * analytic::calcReducedInertia(m_, phi).J * omega * omega + analytic::calcPotentialEnergy(m_, phi);
    return gas_ ? e - (gas_->calcWork(phi) - gas_->getMeanTorque() * phi) : e;
  }
  /// The exact run's speed at phi for the invariant's value `value`. @throws std::domain_error where it cannot turn.
  double calcSpeed(double phi, double value) const {
    const double potential = analytic::calcPotentialEnergy(m_, phi) -
                             (gas_ ? gas_->calcWork(phi) - gas_->getMeanTorque() * phi : 0.0);
    const double v2 = 2.0 * (value - potential) / analytic::calcReducedInertia(m_, phi).J;
    if (!(v2 > 0.0))
      throw std::domain_error("the exact run does not reach phi = " + std::to_string(phi) + " rad (it stops before)");
    return std::sqrt(v2);
  }
  const analytic::GasWork* getGasWork() const { return gas_ ? &*gas_ : nullptr; }

 private:
  const Mechanism& m_;
  std::optional<analytic::GasWork> gas_;
};

// The exact run through a state, over its period: its speed at any phase, its extremes and mean speed, and the time it
// takes from phi = 0 to any phase.
struct ExactRun {
  double period = 0.0;
  std::function<double(double)> speed;    // [rad/s] at phi
  double omega_max = 0.0, omega_min = 0.0, omega_mean = 0.0;
  double phi_at_omega_max = 0.0, phi_at_omega_min = 0.0;  // in [0, period)
  std::function<double(double)> elapsed;  // [s] from phi = 0 (monotone)
};

// The free run (analytic/motion.h) with speed omega_zero at phi = 0: its extremes to double precision, its time by
// Gauss-Kronrod over whole turns and the rest (the turn's time by the same quadrature, so that t(phi) has no step).
ExactRun makeFreeRun(const Mechanism& m, double omega_zero) {
  const analytic::FreeRun turn = analytic::calcFreeRun(m, omega_zero);  // throws if it does not turn over
  ExactRun out;
  out.period = kTwoPi;
  out.speed = [&m, omega_zero](double p) { return analytic::calcFreeRunSpeed(m, omega_zero, p); };
  out.omega_max = turn.omega_max;
  out.omega_min = turn.omega_min;
  out.omega_mean = turn.omega_mean;
  out.phi_at_omega_max = turn.phi_at_omega_max;
  out.phi_at_omega_min = turn.phi_at_omega_min;
  auto integral = [&m, omega_zero](double to) {
    auto slowness = [&](double p) { return 1.0 / analytic::calcFreeRunSpeed(m, omega_zero, p); };
    return to > 0.0 ? boost::math::quadrature::gauss_kronrod<double, 61>::integrate(slowness, 0.0, to, 10, 1e-11) : 0.0;
  };
  const double period_time = integral(kTwoPi);
  out.elapsed = [integral, period_time](double p) {
    const double turns = std::floor(p / kTwoPi);
    return turns * period_time + integral(p - turns * kTwoPi);
  };
  return out;
}

// The run under gas with the cycle-mean load through invariant value `value`: periodic over the working cycle. Its
// time by 8-point Gauss-Legendre on every interval of the gas work's grid (0.1 degree and every pressure corner: the
// speed is smooth between them), its extremes from the grid's nodes refined by Brent's method on the two intervals
// around the best.
ExactRun makeGasRun(const RunInvariant& invariant, double value) {
  static const double kNodes[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                                   0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
  static const double kWeights[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                                     0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
  const analytic::GasWork& gas = *invariant.getGasWork();
  const std::vector<double>& grid = gas.getGrid();
  auto speed = [&invariant, value](double p) { return invariant.calcSpeed(p, value); };
  auto cellTime = [speed](double a, double b) {
    const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
    double sum = 0.0;
    for (int q = 0; q < 8; ++q) sum += kWeights[q] / speed(mid + half * kNodes[q]);
    return half * sum;
  };
  auto times = std::make_shared<std::vector<double>>(grid.size(), 0.0);
  std::vector<double> node_speed(grid.size());
  for (size_t i = 0; i < grid.size(); ++i) {
    node_speed[i] = speed(grid[i]);
    if (i > 0) (*times)[i] = (*times)[i - 1] + cellTime(grid[i - 1], grid[i]);
  }
  ExactRun out;
  out.period = gas.getCycle();
  out.speed = speed;
  out.omega_mean = out.period / times->back();
  const size_t n = grid.size() - 1;  // grid[n] = the cycle = grid[0] + cycle
  auto refine = [&](size_t i, double sign) {
    const double a = i == 0 ? grid[n - 1] - out.period : grid[i - 1], b = grid[i + 1];  // i < n: the last node is the first
    const double lift = 2.0 * *std::max_element(node_speed.begin(), node_speed.end());
    const TurnMaximum best = refineMaxAbs([&](double p) { return lift + sign * speed(p); }, a, b);
    return std::pair{sign * (best.value - lift), std::fmod(std::fmod(best.phi, out.period) + out.period, out.period)};
  };
  const size_t imax = static_cast<size_t>(std::max_element(node_speed.begin(), node_speed.end() - 1) - node_speed.begin());
  const size_t imin = static_cast<size_t>(std::min_element(node_speed.begin(), node_speed.end() - 1) - node_speed.begin());
  std::tie(out.omega_max, out.phi_at_omega_max) = refine(imax, 1.0);
  std::tie(out.omega_min, out.phi_at_omega_min) = refine(imin, -1.0);
  out.omega_max = std::max(out.omega_max, node_speed[imax]);
  out.omega_min = std::min(out.omega_min, node_speed[imin]);
  const double cycle_time = times->back(), cycle = out.period;
  out.elapsed = [grid, times, cellTime, cycle_time, cycle](double p) {
    const double cycles = std::floor(p / cycle);
    const double rest = p - cycles * cycle;
    const size_t i = std::min(static_cast<size_t>(std::upper_bound(grid.begin(), grid.end(), rest) - grid.begin()) - 1,
                              grid.size() - 2);
    return cycles * cycle_time + (*times)[i] + cellTime(grid[i], rest);
  };
  return out;
}

// The exact run with speed omega at phase phi (for a free run: released at phi = 0 with the same energy).
ExactRun makeExactRun(const Mechanism& m, const RunInvariant& invariant, double phi, double omega) {
  const double value = invariant.calcValue(phi, omega);
  if (invariant.getGasWork()) return makeGasRun(invariant, value);
  // U(0) = 0 by the convention of potential_energy.h: the release speed at phi = 0 with energy `value`.
  const double v2 = 2.0 * value / analytic::calcReducedInertia(m, 0.0).J;
  if (!(v2 > 0.0)) throw std::domain_error("the exact free run does not reach phi = 0 (its energy is not > 0)");
  return makeFreeRun(m, std::sqrt(v2));
}

}  // namespace

std::vector<double> calcEnergyAtTurns(const Mechanism& m, const Trajectory& run, const RunLoad& load) {
  constexpr const char* kWho = "calcEnergyAtTurns";
  checkRun(m, run, load, kWho);
  const RunInvariant invariant(m, load);
  const double period = invariant.getPeriod();
  checkOnePeriod(run, period, kWho);
  const TrajectoryReader reader(run);
  const double phi0 = run.phi.front();
  const int turns = static_cast<int>(std::floor((run.phi.back() - phi0) / period));
  std::vector<double> energy;
  for (int i = 0; i <= turns; ++i) {
    const double phase = phi0 + period * i;
    if (phase > run.phi.back()) break;
    energy.push_back(invariant.calcValue(phase, reader.findOmegaAtPhase(phase)));
  }
  return energy;
}

std::vector<double> calcEnergyAtSamples(const Mechanism& m, const Trajectory& run) {
  checkRun(m, run, {}, "calcEnergyAtSamples");
  const RunInvariant invariant(m, {});
  const TrajectoryReader reader(run);
  std::vector<double> energy;
  for (size_t i = 0; i < run.time.size(); ++i) energy.push_back(invariant.calcValue(run.phi[i], reader.findOmega(run.time[i])));
  return energy;
}

double calcEnergyTrend(const Mechanism& m, const Trajectory& run, const RunLoad& load) {
  const std::vector<double> energy = calcEnergyAtTurns(m, run, load);
  std::vector<double> k;
  for (size_t i = 0; i < energy.size(); ++i) k.push_back(static_cast<double>(i));
  const TrajectoryReader reader(run);
  // Relative to the kinetic and potential energy at the start (the invariant's value there, less the gas terms).
  const double phi0 = run.phi.front(), omega0 = reader.findOmegaAtPhase(phi0);
  const double start = 0.5 * analytic::calcReducedInertia(m, phi0).J * omega0 * omega0 + analytic::calcPotentialEnergy(m, phi0);
  return leastSquaresSlope(k, energy) / (load.gas ? start : energy.front());
}

SpeedFluctuationComparison calcSpeedFluctuation(const Mechanism& m, const Trajectory& run, const RunLoad& load) {
  constexpr const char* kWho = "calcSpeedFluctuation";
  checkRun(m, run, load, kWho);
  const RunInvariant invariant(m, load);
  const double period = invariant.getPeriod();
  checkOnePeriod(run, period, kWho);
  const TrajectoryReader reader(run);
  const double phi0 = run.phi.front(), phi1 = phi0 + period;
  // omega against phase over the first period: the samples in it and its end, then the extremes refined.
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
  const double omega_mean = period / (reader.findTimeAtPhase(phi1) - run.time.front());

  SpeedFluctuationComparison out;
  out.run.delta = (omega_max - omega_min) / omega_mean;
  out.run.phi_at_omega_max = std::fmod(std::fmod(phi_max, period) + period, period);
  out.run.phi_at_omega_min = std::fmod(std::fmod(phi_min, period) + period, period);
  out.run.omega_min = omega_min;
  out.run.omega_max = omega_max;
  out.run.omega_mean = omega_mean;
  // The exact run through the run's state at its first phi = 0 (mod the period).
  const double zero = period * std::ceil(phi0 / period);
  out.omega_at_zero = reader.findOmegaAtPhase(zero);
  const ExactRun exact = makeExactRun(m, invariant, zero, out.omega_at_zero);
  out.exact = {(exact.omega_max - exact.omega_min) / exact.omega_mean, exact.phi_at_omega_max, exact.phi_at_omega_min,
               exact.omega_min, exact.omega_max, exact.omega_mean};
  if (!load.gas) out.exact.delta = analytic::calcFreeRun(m, out.omega_at_zero).delta;  // the analytic engine's own
  out.delta_error = out.run.delta - out.exact.delta;
  // An extreme can be reached at several phases with speeds the run cannot tell apart (a centric standing single:
  // omega(phi) = omega(-phi), two equal minima; an inline four: two equal humps a turn): the run's phase is compared
  // with the nearest of the exact run's local extremes whose speed is within the run's own speed error of the extreme:
  // |delta error| x omega_mean, or the run's change of speed over the period (a run that loses energy is fastest
  // where it starts), at least rounding.
  const double drift = std::fabs(reader.findOmegaAtPhase(phi1) - reader.findOmegaAtPhase(phi0));  // 0 on the exact run
  const double speed_error =
      std::max({std::fabs(out.delta_error) * omega_mean, drift, 64.0 * kEpsilon * exact.omega_max});
  const int samples = static_cast<int>(std::lround(720.0 * period / kTwoPi));
  auto nearest = [&](double run_phase, double exact_phase, double extreme, double sign) {
    double best = wrapAngle(run_phase - exact_phase, period);
    auto v = [&](double p) { return sign * exact.speed(p); };
    std::vector<double> values(static_cast<size_t>(samples));
    for (int i = 0; i < samples; ++i) values[static_cast<size_t>(i)] = v(period * i / samples);
    for (int i = 0; i < samples; ++i) {
      const double here = values[static_cast<size_t>(i)];
      if (!(here >= values[static_cast<size_t>((i + samples - 1) % samples)] &&
            here >= values[static_cast<size_t>((i + 1) % samples)]))
        continue;  // not a local extreme of the samples
      const TurnMaximum local = refineMaxAbs([&](double p) { return v(p) + 2.0 * exact.omega_max; },
                                             period * (i - 1) / samples, period * (i + 1) / samples);
      if (std::fabs(local.value - 2.0 * exact.omega_max - sign * extreme) > speed_error) continue;
      const double error = wrapAngle(run_phase - local.phi, period);
      if (std::fabs(error) < std::fabs(best)) best = error;
    }
    return best;
  };
  out.phi_max_error = nearest(out.run.phi_at_omega_max, out.exact.phi_at_omega_max, exact.omega_max, 1.0);
  out.phi_min_error = nearest(out.run.phi_at_omega_min, out.exact.phi_at_omega_min, exact.omega_min, -1.0);
  return out;
}

std::vector<double> calcPhaseErrors(const Mechanism& m, const Trajectory& run, const std::vector<double>& horizons,
                                    const RunLoad& load) {
  constexpr const char* kWho = "calcPhaseError";
  checkRun(m, run, load, kWho);
  for (double horizon : horizons)
    if (!(horizon >= run.time.front() && horizon <= run.time.back()))
      throw std::invalid_argument(std::string(kWho) + ": the horizon " + std::to_string(horizon) +
                                  " s is outside the run's time [" + std::to_string(run.time.front()) + ", " +
                                  std::to_string(run.time.back()) + "] s");
  const TrajectoryReader reader(run);
  const double t0 = run.time.front(), phi0 = run.phi.front();
  const RunInvariant invariant(m, load);
  const ExactRun exact = makeExactRun(m, invariant, phi0, reader.findOmega(t0));  // throws if it does not turn over
  const double start = exact.elapsed(phi0);
  std::vector<double> out;
  for (double horizon : horizons) {
    const double dt = horizon - t0;
    if (dt == 0.0) {
      out.push_back(reader.findPhi(horizon) - phi0);
      continue;
    }
    const double target = start + dt;
    auto g = [&](double p) { return exact.elapsed(p) - target; };
    // phi advances at least omega_min and at most omega_max per second.
    double a = phi0 + exact.omega_min * dt, b = phi0 + exact.omega_max * dt;
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

double calcPhaseError(const Mechanism& m, const Trajectory& run, double horizon, const RunLoad& load) {
  return calcPhaseErrors(m, run, {horizon}, load).front();
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
