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
#include <stdexcept>
#include <vector>

#include "crankcheck/analytic/motion.h"
#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/validation/run_measures.h"

namespace crankcheck::validation {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

Mechanism loadSingle() {
  const Mechanism m = loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / "single_cylinder.toml");
  return withLoads(m, false, true, true);  // gravity alone: no gas (the scene has none), no drive
}

double accel(const Mechanism& m, double phi, double omega) {
  return analytic::calcCrankAcceleration(m, phi, omega, 0.0);
}

// Classical Runge-Kutta, `steps` steps of h from (0, omega0).
SteppedRun runRk4(const Mechanism& m, double omega0, double h, int steps) {
  SteppedRun run;
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
SteppedRun runSymplecticEuler(const Mechanism& m, double omega0, double h, int steps) {
  SteppedRun run;
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
SteppedRun runExact(const Mechanism& m, double omega0, int per_turn, int turns) {
  SteppedRun run;
  const double dphi = 2.0 * M_PI / per_turn;
  double t = 0.0, carry = 0.0;
  auto slowness = [&](double p) { return 1.0 / analytic::calcFreeRunSpeed(m, omega0, p); };
  for (int i = 0; i <= per_turn * turns; ++i) {
    const double phi = i * dphi;
    run.time.push_back(t + carry);
    run.phi.push_back(phi);
    run.omega.push_back(analytic::calcFreeRunSpeed(m, omega0, phi));
    const double cell = boost::math::quadrature::gauss<double, 20>::integrate(slowness, phi, phi + dphi);
    const double sum = t + cell;
    carry += std::fabs(t) >= std::fabs(cell) ? (t - sum) + cell : (cell - sum) + t;
    t = sum;
  }
  return run;
}

TEST(RunMeasuresTest, Explore) {
  const Mechanism m = loadSingle();
  const double omega0 = 40.0;
  const double period = 2.0 * M_PI / analytic::calcFreeRun(m, omega0).omega_mean;
  std::printf("period %.6g\n", period);
  std::vector<double> steps, trends, phases;
  for (int per_turn : {16, 24, 32, 48}) {
    const double h = period / per_turn;
    const SteppedRun run = runRk4(m, omega0, h, per_turn * 8);
    steps.push_back(h);
    trends.push_back(calcEnergyTrend(m, run));
    phases.push_back(calcPhaseError(m, run, run.time.back()));
    const auto f = calcSpeedFluctuation(m, run);
    std::printf("rk4 N %d trend %.3e phase %.3e delta %.6e exact %.6e dphimax %.3e\n", per_turn, trends.back(),
                phases.back(), f.run.delta, f.exact.delta, f.phi_max_error);
  }
  std::printf("orders %.3f %.3f\n", calcObservedOrder(steps, trends), calcObservedOrder(steps, phases));
  const SteppedRun exact = runExact(m, omega0, 1024, 4);
  const auto fe = calcSpeedFluctuation(m, exact);
  std::printf("exact trend %.3e phase %.3e ddelta %.3e dphimax %.3e dphimin %.3e delta %.3e\n",
              calcEnergyTrend(m, exact), calcPhaseError(m, exact, exact.time.back()), fe.delta_error,
              fe.phi_max_error, fe.phi_min_error, fe.exact.delta);
  std::printf("exact phase mid %.3e\n", calcPhaseError(m, exact, exact.time[1500]));
  const double w = m.machine.speed;
  const int n = static_cast<int>(std::round(10 * 2 * M_PI / w / 1e-4));
  SteppedRun se = runSymplecticEuler(m, w, 1e-4, n);
  double emin = 1e300, emax = -1e300, e0 = 0;
  for (size_t i = 1; i < se.time.size(); ++i) {
    const double e = 0.5 * analytic::calcReducedInertia(m, se.phi[i]).J * se.omega[i] * se.omega[i] +
                     analytic::calcPotentialEnergy(m, se.phi[i]);
    if (i == 1) e0 = e;
    emin = std::min(emin, e), emax = std::max(emax, e);
  }
  const auto fs = calcSpeedFluctuation(m, se);
  std::printf("se osc %.3e trend %.3e phase %.3e ddelta %.3e dphimax %.3e dphimin %.3e delta %.3e\n",
              (emax - emin) / e0, calcEnergyTrend(m, se), calcPhaseError(m, se, se.time.back()), fs.delta_error,
              fs.phi_max_error, fs.phi_min_error, fs.exact.delta);
  se.omega_half_step_behind = false;
  const auto fs2 = calcSpeedFluctuation(m, se);
  std::printf("se same-instant trend %.3e phase %.3e ddelta %.3e dphimax %.3e dphimin %.3e\n", calcEnergyTrend(m, se),
              calcPhaseError(m, se, se.time.back()), fs2.delta_error, fs2.phi_max_error, fs2.phi_min_error);
}

}  // namespace
}  // namespace crankcheck::validation
