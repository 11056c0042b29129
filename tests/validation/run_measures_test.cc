// The measures of a time-stepped run (run_measures.h) on runs made here by the test's own integrators of Lagrange's
// equation J phi'' + (1/2) J' phi'^2 + Q = 0 (calcCrankAcceleration as the right-hand side: the dynamics, not the
// measure): a classical Runge-Kutta run at several steps, a semi-implicit Euler run storing its velocity half a step
// behind, and the exact run (t(phi) by the test's own Gauss-Legendre quadrature, cell by cell), on the standing single
// (scenes/single_cylinder.toml, no [gas]).

#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/quadrature/gauss.hpp>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <string>
#include <stdexcept>
#include <vector>

#include "crankcheck/analytic/flywheel.h"
#include "crankcheck/analytic/gas_work.h"
#include "crankcheck/analytic/motion.h"
#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/validation/engine_runs.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/run_measures.h"
#include "../support/test_numbers.h"

namespace crankcheck::validation {
namespace {

using testing::kEps;

Mechanism loadSingle() {
  const Mechanism m = loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / "single_cylinder.toml");
  return withLoads(m, false, true, true);  // gravity alone: no gas (the scene has none), no drive
}

double accel(const Mechanism& m, double phi, double omega) {
  return analytic::calcCrankAcceleration(m, phi, omega, 0.0);
}

// Classical Runge-Kutta, `steps` steps of h from (0, omega0).
Trajectory runRk4(const Mechanism& m, double omega0, double h, int steps) {
  Trajectory run;
  double phi = 0.0, omega = omega0;
  for (int i = 0; i <= steps; ++i) {
    run.time.push_back(i * h);
    run.phi.push_back(phi);
    run.omega.push_back(omega);
    const double k1p = omega, k1w = accel(m, phi, omega);
    const double k2p = omega + 0.5 * h * k1w, k2w = accel(m, phi + 0.5 * h * k1p, k2p);
    const double k3p = omega + 0.5 * h * k2w, k3w = accel(m, phi + 0.5 * h * k2p, k3p);
    const double k4p = omega + h * k3w, k4w = accel(m, phi + h * k3p, k4p);
    phi += h / 6.0 * (k1p + 2.0 * k2p + 2.0 * k3p + k4p);
    omega += h / 6.0 * (k1w + 2.0 * k2w + 2.0 * k3w + k4w);
  }
  return run;
}

// Semi-implicit (symplectic) Euler as game and engine simulators step: omega += h a(phi, omega); phi += h omega. The
// stored omega[i] (i >= 1) is the speed over the step that ended at time[i]: it stands half a step behind.
Trajectory runSymplecticEuler(const Mechanism& m, double omega0, double h, int steps) {
  Trajectory run;
  run.omega_half_step_behind = true;
  double phi = 0.0, omega = omega0;
  for (int i = 0; i <= steps; ++i) {
    run.time.push_back(i * h);
    run.phi.push_back(phi);
    run.omega.push_back(omega);
    omega += h * accel(m, phi, omega);
    phi += h * omega;
  }
  return run;
}

// The exact run sampled at phi = 2 pi i / per_turn: omega from the energy integral, time by Gauss-Legendre (20
// points) over each cell of 1 / phi_dot, summed with Neumaier's compensation.
Trajectory runExact(const Mechanism& m, double omega0, int per_turn, int turns) {
  Trajectory run;
  const double dphi = 2.0 * M_PI / per_turn;
  double t = 0.0, carry = 0.0;
  auto slowness = [&](double p) { return 1.0 / analytic::calcFreeRunSpeed(m, omega0, p); };
  for (int i = 0; i <= per_turn * turns; ++i) {
    const double phi = i * dphi;
    run.time.push_back(t + carry);
    run.phi.push_back(phi);
    run.omega.push_back(analytic::calcFreeRunSpeed(m, omega0, phi));
    const double cell = boost::math::quadrature::gauss<double, 20>::integrate(slowness, phi, (i + 1) * dphi);
    const double sum = t + cell;
    carry += std::fabs(t) >= std::fabs(cell) ? (t - sum) + cell : (cell - sum) + t;
    t = sum;
  }
  return run;
}

const double kOmegaSlow = 40.0;  // [rad/s] a slow release: gravity's share of the fluctuation is large

double periodOf(const Mechanism& m, double omega0) { return 2.0 * M_PI / analytic::calcFreeRun(m, omega0).omega_mean; }

// Classical Runge-Kutta at 16 to 48 steps a turn over 8 turns. Its phase error falls at order 4 (measured 4.18). Its
// energy's drift at fixed phase falls one order faster (measured 4.96): the phase error lies along the orbit, where E
// does not change, and the leading transverse term returns to zero over each turn in this one-degree-of-freedom system
// (as on the harmonic oscillator, whose energy factor per step is 1 - (omega h)^6 / 72: order 5 per unit time).
// Within 0.3 of the order is the brief's margin for a fit over 3:1 in step.
TEST(RunMeasuresTest, RungeKuttaConvergesAtItsOrder) {
  const Mechanism m = loadSingle();
  const double period = periodOf(m, kOmegaSlow);
  std::vector<double> steps, trends, phases;
  for (int per_turn : {16, 24, 32, 48}) {
    const double h = period / per_turn;
    const Trajectory run = runRk4(m, kOmegaSlow, h, per_turn * 8);
    steps.push_back(h);
    trends.push_back(calcEnergyTrend(m, run));
    phases.push_back(calcPhaseError(m, run, run.time.back()));
  }
  EXPECT_NEAR(calcObservedOrder(steps, phases), 4.0, 0.3);
  EXPECT_NEAR(calcObservedOrder(steps, trends), 5.0, 0.3);
  // The coarsest run's errors stand well above the reading's rounding, so the fit measures the integrator.
  EXPECT_GT(std::fabs(trends.front()), 1e6 * kEps);
  EXPECT_GT(std::fabs(phases.front()), 1e6 * kEps * 8.0 * 2.0 * M_PI);
}

// The exact run, 1024 samples a turn over 4 turns: every measure at rounding. Scales and multiples: E_k holds J (16 eps,
// tests/analytic/motion_test.cc), omega^2 and U, and the slope of 5 points; so 16 eps of E_0. The phase: t(phi) by two
// quadratures each at rounding (the test's compensated sum, the measure's Gauss-Kronrod and TOMS 748 to 2 eps), 16 eps
// of phi at the horizon. delta = (omega_max - omega_min) / omega_mean with omega / omega_mean about 1: each extreme to
// a few eps relative (degree-5 interpolation at 1024 samples a turn errs by about (2 pi / 1024)^6, below rounding),
// 16 eps. The phase of omega_max: Brent's angle tolerance (1e-10 rad) on both sides, 1e-9 rad.
TEST(RunMeasuresTest, ExactRunMeasuresAtRounding) {
  const Mechanism m = loadSingle();
  const Trajectory exact = runExact(m, kOmegaSlow, 1024, 4);
  EXPECT_LE(std::fabs(calcEnergyTrend(m, exact)), 16.0 * kEps);
  for (size_t i : {size_t{1500}, size_t{3072}, exact.time.size() - 1})
    EXPECT_LE(std::fabs(calcPhaseError(m, exact, exact.time[i])), 16.0 * kEps * exact.phi[i]) << i;
  // Between samples the reading interpolates phi(t): still at rounding.
  const double between = 0.5 * (exact.time[2500] + exact.time[2501]);
  EXPECT_LE(std::fabs(calcPhaseError(m, exact, between)), 16.0 * kEps * exact.phi[2501]);
  const SpeedFluctuationComparison f = calcSpeedFluctuation(m, exact);
  EXPECT_EQ(f.omega_at_zero, kOmegaSlow);  // the run starts at phi = 0: its first sample, read exactly
  EXPECT_GT(f.exact.delta, 1e-3);          // a fluctuation to measure
  EXPECT_LE(std::fabs(f.delta_error), 16.0 * kEps);
  EXPECT_LE(std::fabs(f.phi_max_error), 1e-9);
}

// The centric standing single turns with omega(phi) = omega(-phi) (J and U are even in phi): its two minima of speed
// are equal, and which one a run finds lowest is decided by the run's own error. A run whose speed is lowered by 1e-9
// of omega near the mirror of the exact run's minimum has its minimum there: its phase is judged against the nearest
// equal extreme, not the one the exact run's root finder happened to land on, and is within the bump's width.
TEST(RunMeasuresTest, EqualExtremesAreEither) {
  const Mechanism m = loadSingle();
  Trajectory run = runExact(m, kOmegaSlow, 1024, 2);
  const analytic::FreeRun exact = analytic::calcFreeRun(m, kOmegaSlow);
  ASSERT_GT(exact.phi_at_omega_min, 0.1);  // not at 0 or pi: a pair phi, 2 pi - phi
  const double mirror = 2.0 * M_PI - exact.phi_at_omega_min, width = 0.05;
  for (size_t i = 0; i < run.phi.size(); ++i) {
    const double d = std::remainder(run.phi[i] - mirror, 2.0 * M_PI) / width;
    run.omega[i] -= 1e-9 * kOmegaSlow * std::exp(-d * d);
  }
  const SpeedFluctuationComparison f = calcSpeedFluctuation(m, run);
  EXPECT_NEAR(f.run.phi_at_omega_min, mirror, width);  // the run's minimum is at the mirror
  EXPECT_LT(std::fabs(f.phi_min_error), width);        // and that is an extreme of the exact run
}

// Semi-implicit Euler at 10 kHz from the scene's speed over 10 turns, its omega half a step behind. E sample by sample
// oscillates with the step (the speed read half a step off the angle); at fixed phase that does not show and the trend
// is far smaller (measured 2.7e-6 per turn against an oscillation of 3.0e-4: at least 10 times). The flag matters:
// read as same-instant, omega is put half a step late, so omega_max appears omega h / 2 further on (within 5 %:
// omega varies by delta = 0.4 %), while read at its own instants the phase of omega_max is 100 times closer.
TEST(RunMeasuresTest, HalfStepBehindRunAtFixedPhase) {
  const Mechanism m = loadSingle();
  const double omega0 = m.machine.speed, h = 1e-4;
  Trajectory run = runSymplecticEuler(m, omega0, h, static_cast<int>(std::round(10.0 * periodOf(m, omega0) / h)));
  double e_min = std::numeric_limits<double>::infinity(), e_max = -e_min;
  for (size_t i = 1; i < run.time.size(); ++i) {
    const double e = 0.5 * analytic::calcReducedInertia(m, run.phi[i]).J * run.omega[i] * run.omega[i] +
                     analytic::calcPotentialEnergy(m, run.phi[i]);
    e_min = std::min(e_min, e);
    e_max = std::max(e_max, e);
  }
  const double oscillation = (e_max - e_min) / e_max;
  const double trend = calcEnergyTrend(m, run);
  EXPECT_LT(std::fabs(trend), oscillation / 10.0) << trend << " " << oscillation;
  const SpeedFluctuationComparison own = calcSpeedFluctuation(m, run);
  run.omega_half_step_behind = false;
  const SpeedFluctuationComparison same = calcSpeedFluctuation(m, run);
  EXPECT_NEAR(same.phi_max_error, 0.5 * omega0 * h, 0.05 * 0.5 * omega0 * h);
  EXPECT_LT(std::fabs(own.phi_max_error), std::fabs(same.phi_max_error) / 100.0);
}

// Each omega's own instant, given sample by sample (protocol 2's omega_t), reads omega as the half-step flag does: the
// same samples at the same instants (to an ulp of t), so the same interpolation.
TEST(RunMeasuresTest, OmegaInstantsGivenSampleBySample) {
  const Mechanism m = loadSingle();
  const double omega0 = m.machine.speed, h = 2e-4;
  const Trajectory flagged = runSymplecticEuler(m, omega0, h, static_cast<int>(std::round(3.0 * periodOf(m, omega0) / h)));
  Trajectory timed = flagged;
  timed.omega_half_step_behind = false;
  timed.time.erase(timed.time.begin());  // omega[0] stands at no half step: the sample is dropped, as the flag drops it
  timed.phi.erase(timed.phi.begin());
  timed.omega.erase(timed.omega.begin());
  for (double t : timed.time) timed.omega_time.push_back(t - 0.5 * h);
  // The flag computes t_i - (t_i - t_{i-1}) / 2, the instants above t_i - h / 2: they agree to an ulp of t, so the
  // readings agree to the interpolation's conditioning times that (a few ulps of omega).
  const TrajectoryReader a(flagged), b(timed);
  for (double t = 0.01; t < 2.0 * periodOf(m, omega0); t += 0.0137)
    EXPECT_NEAR(a.findOmega(t), b.findOmega(t), 64.0 * kEps * omega0) << t;
  timed.omega_time.pop_back();
  EXPECT_THROW(TrajectoryReader{timed}, std::invalid_argument);
}

// A power law's order, exactly.
TEST(RunMeasuresTest, ObservedOrderOfAPowerLaw) {
  const std::vector<double> steps{1e-2, 5e-3, 2e-3, 1e-3};
  std::vector<double> errors;
  for (double h : steps) errors.push_back(-3.0 * std::pow(h, 4));
  EXPECT_NEAR(calcObservedOrder(steps, errors), 4.0, 64.0 * kEps);  // logs of size 28, a few roundings each
}

template <typename F>
void expectRefusal(F&& f, const std::string& words) {
  try {
    f();
    ADD_FAILURE() << "no exception; expected one naming '" << words << "'";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

// Each malformed run and argument is refused by each measure, naming what is wrong.
TEST(RunMeasuresTest, Refusals) {
  const Mechanism m = loadSingle();
  const Trajectory good = runExact(m, kOmegaSlow, 16, 2);
  auto all = [&](const Trajectory& run, const std::string& words) {
    expectRefusal([&] { calcEnergyTrend(m, run); }, words);
    expectRefusal([&] { calcSpeedFluctuation(m, run); }, words);
    expectRefusal([&] { calcPhaseError(m, run, run.time.empty() ? 0.0 : run.time.back()); }, words);
  };
  Trajectory r = good;
  r.omega.pop_back();
  all(r, "as many samples");
  r = good;
  r.time.resize(7), r.phi.resize(7), r.omega.resize(7);
  all(r, "too few samples");
  for (auto member : {&Trajectory::time, &Trajectory::phi, &Trajectory::omega}) {
    r = good;
    (r.*member)[5] = std::nan("");
    all(r, "is not finite");
  }
  r = good;
  r.time[5] = r.time[4];
  all(r, "time is not strictly increasing");
  r = good;
  r.phi[5] = r.phi[4] - 1e-3;
  all(r, "phi is not strictly increasing");
  r = good;  // 16 samples a turn (22.5 deg apart), then a jump of a quarter turn more: 112.5 deg between two samples
  for (size_t i = 5; i < r.phi.size(); ++i) r.phi[i] += std::numbers::pi / 2;
  all(r, "phi turns by 112.5 deg from sample 4 to 5, more than a quarter turn");
  Mechanism no_flywheel = m;
  no_flywheel.flywheel_inertia.reset();
  expectRefusal([&] { calcEnergyTrend(no_flywheel, good); }, "flywheel");
  expectRefusal([&] { calcSpeedFluctuation(no_flywheel, good); }, "flywheel");
  expectRefusal([&] { calcPhaseError(no_flywheel, good, good.time.back()); }, "flywheel");
  // A scene with gas is not a free run under gravity alone: refused, not judged against the wrong reference.
  const Mechanism with_gas = loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / "inline4_four_stroke.toml");
  expectRefusal([&] { calcEnergyTrend(with_gas, good); }, "[gas]");
  expectRefusal([&] { calcPhaseError(with_gas, good, good.time.back()); }, "[gas]");
  r = runExact(m, kOmegaSlow, 16, 1);
  for (int i = 0; i < 2; ++i) r.time.pop_back(), r.phi.pop_back(), r.omega.pop_back();  // short of a whole turn
  expectRefusal([&] { calcEnergyTrend(m, r); }, "shorter than one revolution");
  expectRefusal([&] { calcSpeedFluctuation(m, r); }, "shorter than one revolution");
  expectRefusal([&] { calcPhaseError(m, good, good.time.back() * 1.01); }, "outside the run's time");
  expectRefusal([&] { calcPhaseError(m, good, -1e-3); }, "outside the run's time");
  expectRefusal([&] { calcObservedOrder({1e-3, 2e-3}, {1.0}); }, "2 steps but 1 errors");
  expectRefusal([&] { calcObservedOrder({1e-3}, {1.0}); }, "too few points");
  expectRefusal([&] { calcObservedOrder({1e-3, 0.0}, {1.0, 2.0}); }, "step 1 is not finite and > 0");
  expectRefusal([&] { calcObservedOrder({1e-3, 2e-3}, {1.0, 0.0}); }, "error 1 is not finite or is 0");
  expectRefusal([&] { calcObservedOrder({1e-3, 2e-3}, {1.0, std::nan("")}); }, "error 1 is not finite or is 0");
  expectRefusal([&] { calcObservedOrder({1e-3, 1e-3}, {1.0, 2.0}); }, "all equal");
}

}  // namespace
}  // namespace crankcheck::validation

namespace crankcheck::validation {
namespace {

// A run under gas at the cycle-mean load (RunLoad::gas), held against two references the measures did not produce:
// Simbody's own loaded free run (its multibody model, its integrator at 1e-10, the gas as forces on its pistons)
// released from the steady run's speed, and the flywheel's steady run (analytic/flywheel.h: Simpson's rule on the
// cycle's grid, extremes by a parabola through the best node). The inline four, four-stroke: the working cycle is 4 pi.
TEST(RunMeasuresTest, LoadedRunAgainstSimbodyAndTheFlywheelsSteadyRun) {
  const Mechanism m = loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / "inline4_four_stroke.toml");
  ASSERT_TRUE(m.gas && m.flywheel_inertia);
  const analytic::GasWork gas(m);
  const analytic::SteadyRun steady = analytic::calcSteadyRun(m, *m.flywheel_inertia, gas.getMeanTorque());
  FreeRunSettings settings;
  settings.integrator = "RungeKuttaMerson";
  settings.accuracy = 1e-10;
  settings.revolutions = 4;  // two working cycles
  settings.gas = true;
  settings.load_torque = gas.getMeanTorque();
  const Trajectory run = findOmegaInstants(findEngine("simbody").simulate(m, steady.omega0, settings).trajectory);
  const RunLoad load{true};
  // Simbody at 1e-10 relative per step keeps the invariant E - W + T_L phi to about its steps times 1e-10 a cycle
  // (about 3000 steps a cycle: 3e-7 at most; measured far below): 1e-6 per cycle bounds it.
  EXPECT_LT(std::fabs(calcEnergyTrend(m, run, load)), 1e-6);
  const SpeedFluctuationComparison f = calcSpeedFluctuation(m, run, load);
  // The exact periodic run through Simbody's state at phi = 0 is the steady run: the same delta as the flywheel's to
  // its parabola's accuracy (the extremes of a 0.1-degree grid refined by a parabola: 1e-6 of delta).
  EXPECT_NEAR(f.exact.delta, steady.delta, 1e-6 * steady.delta);
  EXPECT_NEAR(f.exact.phi_at_omega_max, steady.phi_at_omega_max, 1e-3);
  EXPECT_NEAR(f.exact.phi_at_omega_min, steady.phi_at_omega_min, 1e-3);
  // Simbody's run and the exact run agree on delta to its accuracy: 1e-6 relative as the flywheel part holds its runs.
  EXPECT_LT(std::fabs(f.delta_error), 1e-6 * f.exact.delta);
  EXPECT_LT(std::fabs(f.phi_max_error), 1e-3);
  EXPECT_LT(std::fabs(f.phi_min_error), 1e-3);
  // The phase after two cycles: each step's speed error at most 1e-10 relative, summed over the steps, times the
  // angle run (as EngineRunsTest bounds Simbody's free run).
  const double horizon = run.time.back();
  EXPECT_LT(std::fabs(calcPhaseError(m, run, horizon, load)), 1e-10 * static_cast<double>(run.time.size()) * run.phi.back());
  // A loaded run needs the scene's gas, and a free run refuses it.
  Mechanism no_gas = m;
  no_gas.gas.reset();
  EXPECT_THROW(calcEnergyTrend(no_gas, run, load), std::invalid_argument);
  EXPECT_THROW(calcEnergyTrend(m, run), std::invalid_argument);
}

// The gas work W(phi) (gas_work.h) against the gas torque it integrates: W' = T_gas by a central difference, and
// W(phi + cycle) = W(phi) + W(cycle).
TEST(RunMeasuresTest, GasWorkIntegratesTheGasTorque) {
  const Mechanism m = loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / "inline4_four_stroke.toml");
  const analytic::GasWork gas(m);
  double peak = 0.0;
  for (double p = 0.0; p < gas.getCycle(); p += 0.01) peak = std::max(peak, std::fabs(analytic::calcGasTorque(m, p)));
  const double h = 1e-4;
  for (double p : {0.3, 1.7, 3.3, 5.1, 7.9, 11.0}) {
    const double derivative = (gas.calcWork(p + h) - gas.calcWork(p - h)) / (2.0 * h);
    // Central difference: h^2 / 6 |T''| with |T''| at most about peak x 1e3 across the combustion peak, plus the
    // rounding of W (cycle work x eps / h): 1e-5 of the peak holds both.
    EXPECT_NEAR(derivative, analytic::calcGasTorque(m, p), 1e-5 * peak) << p;
    EXPECT_NEAR(gas.calcWork(p + gas.getCycle()), gas.calcWork(p) + gas.getCycleWork(), 64.0 * kEps * peak * gas.getCycle());
  }
}

}  // namespace
}  // namespace crankcheck::validation
