#include "crankcheck/analytic/flywheel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "crankcheck/analytic/gas_work.h"
#include "crankcheck/analytic/motion.h"
#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/analytic/reactions.h"

namespace crankcheck::analytic {
namespace {

// What the steady run needs at each grid node, independent of I_f: J, W - T_L phi - U (T_L from W over the cycle).
struct CycleData {
  std::vector<double> phi, J, work;  // work = W(phi) - T_L phi - U(phi)
  double load_torque = 0.0;
  double cycle = 0.0;
};

CycleData calcCycleData(const Mechanism& m) {
  const GasWork gas(m);  // W at the cycle's grid (0.1 degree and every pressure-table corner)
  CycleData d;
  d.cycle = gas.getCycle();
  d.phi = gas.getGrid();
  d.load_torque = gas.getMeanTorque();
  Mechanism bare = m;
  bare.flywheel_inertia = 0.0;  // the flywheel is I_f, added below
  for (size_t i = 0; i < d.phi.size(); ++i) {
    d.J.push_back(calcReducedInertia(bare, d.phi[i]).J);
    d.work.push_back(gas.getNodeWork()[i] - d.load_torque * d.phi[i] - calcPotentialEnergy(m, d.phi[i]));
  }
  return d;
}

// phi_dot at the nodes for flywheel I and phi_dot(0) = w0; false where the kinetic energy would be negative.
bool speeds(const CycleData& d, double I, double w0, std::vector<double>& out) {
  out.resize(d.phi.size());
  const double E0 = 0.5 * (d.J[0] + I) * w0 * w0;
  for (size_t i = 0; i < d.phi.size(); ++i) {
    const double kinetic = E0 + d.work[i] - d.work[0];
    if (!(kinetic > 0.0)) return false;
    out[i] = std::sqrt(2.0 * kinetic / (d.J[i] + I));
  }
  return true;
}

// Cycle time by Simpson's rule on each pair of intervals (the trapezoid on a last odd one), with unequal steps.
double cycleTime(const CycleData& d, const std::vector<double>& w) {
  double t = 0.0;
  size_t i = 0;
  for (; i + 2 < d.phi.size(); i += 2) {
    const double h0 = d.phi[i + 1] - d.phi[i], h1 = d.phi[i + 2] - d.phi[i + 1];
    const double f0 = 1.0 / w[i], f1 = 1.0 / w[i + 1], f2 = 1.0 / w[i + 2];
    // Simpson for unequal intervals
    t += (h0 + h1) / 6.0 * ((2.0 - h1 / h0) * f0 + (h0 + h1) * (h0 + h1) / (h0 * h1) * f1 + (2.0 - h0 / h1) * f2);
  }
  if (i + 1 < d.phi.size()) t += 0.5 * (d.phi[i + 1] - d.phi[i]) * (1.0 / w[i] + 1.0 / w[i + 1]);
  return t;
}

// The extreme of samples f around index i by the parabola through it and its neighbours (cyclic): its value and
// where, in steps from i (the grid nearly uniform there).
struct Vertex {
  double value = 0.0, steps = 0.0;
};
Vertex refineExtreme(const std::vector<double>& f, size_t i) {
  const size_t n = f.size() - 1;  // the last node is the first again
  const double a = f[(i + n - 1) % n], b = f[i % n], c = f[(i + 1) % n];
  const double denominator = a - 2.0 * b + c;
  if (denominator == 0.0) return {b, 0.0};
  const double s = 0.5 * (a - c) / denominator;
  return {b - 0.25 * (a - c) * s, s};
}

// The angle [rad] of sample i moved by `steps` (a fraction of the neighbouring interval), in [0, cycle).
double angleAt(const CycleData& d, size_t i, double steps) {
  const size_t n = d.phi.size() - 1;
  const double h = steps >= 0.0 ? d.phi[i + 1] - d.phi[i] : d.phi[i] - (i == 0 ? d.phi[n - 1] - d.cycle : d.phi[i - 1]);
  const double phi = d.phi[i] + steps * h;
  return std::fmod(std::fmod(phi, d.cycle) + d.cycle, d.cycle);
}

SteadyRun steady(const CycleData& d, double I, double omega) {
  // phi_dot(0) for the mean speed omega: the secant method from omega and 1.01 omega.
  auto meanOf = [&](double w0, std::vector<double>& w) {
    if (!speeds(d, I, w0, w)) return -1.0;
    return d.cycle / cycleTime(d, w);
  };
  std::vector<double> w;
  double x0 = omega, x1 = 1.01 * omega;
  double f0 = meanOf(x0, w) - omega, f1 = meanOf(x1, w) - omega;
  for (int it = 0; it < 100 && std::fabs(f1) > 4.0 * std::numeric_limits<double>::epsilon() * omega && f1 != f0; ++it) {
    const double x2 = x1 - f1 * (x1 - x0) / (f1 - f0);
    x0 = x1;
    f0 = f1;
    x1 = x2;
    f1 = meanOf(x1, w) - omega;
  }
  if (meanOf(x1, w) < 0.0) throw std::domain_error("the energy integral leaves no positive speed: the flywheel is too small");
  SteadyRun r;
  r.omega0 = x1;
  r.omega_mean = d.cycle / cycleTime(d, w);
  const size_t imax = static_cast<size_t>(std::max_element(w.begin(), w.end() - 1) - w.begin());
  const size_t imin = static_cast<size_t>(std::min_element(w.begin(), w.end() - 1) - w.begin());
  const Vertex top = refineExtreme(w, imax), bottom = refineExtreme(w, imin);
  r.omega_max = std::max(w[imax], top.value);
  r.omega_min = std::min(w[imin], bottom.value);
  r.phi_at_omega_max = angleAt(d, imax, top.value > w[imax] ? top.steps : 0.0);
  r.phi_at_omega_min = angleAt(d, imin, bottom.value < w[imin] ? bottom.steps : 0.0);
  r.delta = (r.omega_max - r.omega_min) / r.omega_mean;
  return r;
}

// Norton 13.9: the energy swing of the integral of T - T_L at constant speed, T = minus the whole drive torque.
double calcNortonEnergy(const Mechanism& m, const CycleData& d) {
  double E = 0.0, lo = 0.0, hi = 0.0, previous = -calcReactions(m, 0.0).drive_torque - d.load_torque;
  for (size_t i = 1; i < d.phi.size(); ++i) {
    const double now = -calcReactions(m, d.phi[i]).drive_torque - d.load_torque;
    E += 0.5 * (d.phi[i] - d.phi[i - 1]) * (previous + now);
    previous = now;
    lo = std::min(lo, E);
    hi = std::max(hi, E);
  }
  return hi - lo;
}

void checkInputs(const Mechanism& m) {
  if (!m.gas) throw std::invalid_argument("[gas]: missing table (flywheel sizing needs the working torque of a gas cycle)");
  if (!(m.machine.speed > 0.0)) throw std::invalid_argument("[engine].speed_rpm: must be > 0 (the mean speed of the run)");
}

}  // namespace

SteadyRun calcSteadyRun(const Mechanism& m, double flywheel_inertia, double load_torque) {
  return calcSteadyRuns(m, {flywheel_inertia}, load_torque).front();
}

std::vector<SteadyRun> calcSteadyRuns(const Mechanism& m, const std::vector<double>& flywheel_inertias,
                                      double load_torque) {
  checkInputs(m);
  CycleData d = calcCycleData(m);
  for (size_t i = 0; i < d.phi.size(); ++i) d.work[i] += (d.load_torque - load_torque) * d.phi[i];
  d.load_torque = load_torque;
  std::vector<SteadyRun> out;
  for (double I : flywheel_inertias) out.push_back(steady(d, I, m.machine.speed));
  return out;
}

FlywheelFluctuation calcFlywheelFluctuation(const Mechanism& m, double flywheel_inertia) {
  checkInputs(m);
  if (!(flywheel_inertia > 0.0))
    throw std::invalid_argument("[flywheel].inertia: must be > 0 (got " + std::to_string(flywheel_inertia) + ")");
  const double omega = m.machine.speed;
  const CycleData d = calcCycleData(m);
  FlywheelFluctuation f;
  f.load_torque = d.load_torque;
  f.exact = steady(d, flywheel_inertia, omega);
  f.norton_energy = calcNortonEnergy(m, d);
  f.norton_delta = f.norton_energy / (flywheel_inertia * omega * omega);
  return f;
}

FlywheelSizing calcFlywheelSizing(const Mechanism& m, double fluctuation) {
  checkInputs(m);
  if (!(fluctuation > 0.0 && fluctuation < 1.0))
    throw std::invalid_argument("--fluctuation: must be in (0, 1) (got " + std::to_string(fluctuation) + ")");
  const double omega = m.machine.speed, C = fluctuation;
  const CycleData d = calcCycleData(m);
  FlywheelSizing s;
  s.load_torque = d.load_torque;
  s.norton_energy = calcNortonEnergy(m, d);
  s.norton_inertia = s.norton_energy / (C * omega * omega);
  s.norton = steady(d, s.norton_inertia, omega);
  // Without a flywheel the mechanism's own inertia may already hold the fluctuation below C: then there is no I_f.
  try {
    const double alone = steady(d, 0.0, omega).delta;
    if (alone <= C)
      throw std::domain_error("no flywheel is needed: the mechanism alone runs at delta = " + std::to_string(alone) +
                              " <= C");
  } catch (const std::domain_error& e) {
    if (std::string(e.what()).rfind("no flywheel", 0) == 0) throw;  // (a speed that cannot stay positive: sized below)
  }
  // The exact I_f: the secant method on delta against I_f from Norton's and a tenth more.
  auto deltaOf = [&](double I) { return steady(d, I, omega).delta - C; };
  double x0 = s.norton_inertia, x1 = 1.1 * s.norton_inertia;
  double f0 = s.norton.delta - C, f1 = deltaOf(x1);
  // delta is summed over ~1e4 grid intervals: its rounding is up to ~1e4 eps of C, the secant stops below that.
  for (int it = 0; it < 200 && std::fabs(f1) > 1e4 * std::numeric_limits<double>::epsilon() * C && f1 != f0; ++it) {
    double x2 = x1 - f1 * (x1 - x0) / (f1 - f0);
    if (!(x2 > 0.0)) x2 = 0.5 * std::min(x0, x1);
    x0 = x1;
    f0 = f1;
    x1 = x2;
    f1 = deltaOf(x1);
  }
  if (!(x1 > 0.0)) throw std::domain_error("no flywheel >= 0 gives this fluctuation: the mechanism alone runs steadier");
  s.exact_inertia = x1;
  s.exact = steady(d, x1, omega);
  if (!(std::fabs(s.exact.delta - C) <= 1e-9 * C)) {
    char text[200];
    std::snprintf(text, sizeof text, "the fluctuation reached %.3g for the %.3g asked, at I_f = %.3g kg m^2",
                  s.exact.delta, C, x1);
    throw std::runtime_error(std::string("flywheel sizing: the root in I_f did not converge (") + text + ")");
  }
  return s;
}

}  // namespace crankcheck::analytic
