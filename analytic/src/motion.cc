#include "crankcheck/analytic/motion.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <utility>
#include <vector>

#include <boost/math/tools/toms748_solve.hpp>

#include "crankcheck/analytic/balance_shafts.h"
#include "crankcheck/analytic/exact_trig.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/analytic/potential_energy.h"
#include "cylinder_terms.h"

namespace crankcheck::analytic {

Mechanism makeUnitSpeedCopy(const Mechanism& m) {
  Mechanism unit;
  unit.crank = m.crank;
  unit.rod = m.rod;
  unit.machine.speed = 1.0;
  return unit;
}

void addCylinderInertia(const Mechanism& m, const Mechanism& unit, int j, const SinCos& t, RodInertiaForm form,
                        ReducedInertia& out) {
  const double r = m.crank.radius, l = m.rod.length, z = m.rod.com_from_wrist_pin, mu = z / l;
  const double m_o = m.piston.mass, m_k = m.rod.mass, I_o = m.rod.inertia_about_wrist_pin;
  const PistonKinematics p = calcPistonKinematics(unit, t, getPinOffset(m, j));   // v_p = x', a_p = x''
  const RodKinematics rod = calcRodRates(unit, t, getPinOffset(m, j));            // beta', beta''
  const double crank = m.crank.mass * m.crank.com_radius * m.crank.com_radius +
                       m.crank.counterweight_mass * m.crank.counterweight_radius * m.crank.counterweight_radius;
  out.J += crank;
  switch (form) {
    case RodInertiaForm::kTrueInertia: {
      // G' = (1 - mu) A' + mu B' in the cylinder frame; B' = r (-sin, cos), B'' = -r (cos, sin).
      const double Ge = (1 - mu) * p.v_p - mu * r * t.sin, Gn = mu * r * t.cos;
      const double Gee = (1 - mu) * p.a_p - mu * r * t.cos, Gnn = -mu * r * t.sin;
      const double I_G = I_o - m_k * z * z;
      out.J += m_o * p.v_p * p.v_p + m_k * (Ge * Ge + Gn * Gn) + I_G * rod.beta_dot * rod.beta_dot;
      out.dJ += 2.0 * (m_o * p.v_p * p.a_p + m_k * (Ge * Gee + Gn * Gnn) + I_G * rod.beta_dot * rod.beta_ddot);
      break;
    }
    case RodInertiaForm::kTwoMassWithDeltaI:
    case RodInertiaForm::kTwoMassWithoutDeltaI: {
      // Eq (2): m_k1 = m_k (l - z_k)/l at A, m_k3 = m_k z_k / l at B (moving at r per radian), Delta_I = I_o - l z_k m_k.
      const double m_k1 = m_k * (l - z) / l, m_k3 = m_k * z / l;
      const double delta_I = form == RodInertiaForm::kTwoMassWithDeltaI ? I_o - l * z * m_k : 0.0;
      out.J += (m_o + m_k1) * p.v_p * p.v_p + m_k3 * r * r + delta_I * rod.beta_dot * rod.beta_dot;
      out.dJ += 2.0 * ((m_o + m_k1) * p.v_p * p.a_p + delta_I * rod.beta_dot * rod.beta_ddot);
      break;
    }
  }
}

ReducedInertia calcReducedInertia(const Mechanism& m, double phi, RodInertiaForm form) {
  // Time derivatives at unit crank speed are the derivatives with respect to theta. The kinematics read r, l and omega
  // alone: a light copy of those (not of m's tables: the crank train calls this at every integration step).
  const Mechanism unit = makeUnitSpeedCopy(m);
  ReducedInertia out;
  out.J = m.flywheel_inertia.value_or(0.0) + calcBalanceShaftLoads(m, phi).inertia;  // shafts: m rho^2 ratio^2 each
  for (int j = 0; j < m.machine.cylinders; ++j)
    addCylinderInertia(m, unit, j, calcThrowSinCos(phi, m.machine.crank_angles[static_cast<size_t>(j)]), form, out);
  return out;
}

double calcGasTorque(const Mechanism& m, double phi) {
  if (!m.gas) return 0.0;
  if (!(m.machine.speed > 0.0))
    throw std::invalid_argument("calcGasTorque: the crank speed must be > 0 (dx_p/dphi is read as v_p / omega)");
  double torque = 0.0;
  for (int c = 0; c < m.machine.cylinders; ++c) {
    // The gas pushes piston c with -p A e_c: its power -p A x_p' phi', so its torque on the shaft is -p A x_p'.
    const double dx_dphi = calcPistonKinematics(m, phi + m.machine.crank_angles[static_cast<size_t>(c)],
                                                getPinOffset(m, c)).v_p / m.machine.speed;
    torque -= calcGasForce(m, c, phi) * dx_dphi;
  }
  return torque;
}

double calcCrankAcceleration(const Mechanism& m, double phi, double phi_dot, double net_torque, bool gravity) {
  const ReducedInertia inertia = calcReducedInertia(m, phi);
  const double Q = gravity ? calcGravityTorque(m, phi) : 0.0;
  return (net_torque - Q - 0.5 * inertia.dJ * phi_dot * phi_dot) / inertia.J;
}

namespace {

double energyOf(const Mechanism& m, double omega0) { return 0.5 * calcReducedInertia(m, 0.0).J * omega0 * omega0; }

void checkFreeRun(const Mechanism& m, double omega0) {
  if (!(omega0 > 0.0)) throw std::invalid_argument("free run: the release speed must be > 0 ([engine].speed_rpm)");
  if (!m.flywheel_inertia) throw std::invalid_argument("free run: the scene needs the flywheel inertia [flywheel].inertia");
}

// phi_dot^2 at phi and its derivative d(phi_dot^2)/dphi = 2 (-Q J - (E - U) J') / J^2.
struct SpeedSquared {
  double value, slope;
};
SpeedSquared speedSquared(const Mechanism& m, double E, double phi, bool gravity) {
  const ReducedInertia inertia = calcReducedInertia(m, phi);
  const double U = gravity ? calcPotentialEnergy(m, phi) : 0.0, Q = gravity ? calcGravityTorque(m, phi) : 0.0;
  return {2.0 * (E - U) / inertia.J, 2.0 * (-Q * inertia.J - (E - U) * inertia.dJ) / (inertia.J * inertia.J)};
}

}  // namespace

double calcFreeRunSpeed(const Mechanism& m, double omega0, double phi, bool gravity) {
  checkFreeRun(m, omega0);
  const double v2 = speedSquared(m, energyOf(m, omega0), phi, gravity).value;
  if (!(v2 > 0.0)) throw std::domain_error("free run: the crank stops before this angle (released too slowly)");
  return std::sqrt(v2);
}

FreeRun calcFreeRun(const Mechanism& m, double omega0, bool gravity) {
  checkFreeRun(m, omega0);
  FreeRun run;
  run.energy = energyOf(m, omega0);
  const double E = run.energy;
  // Sample one revolution; J and U are 2 pi periodic in phi.
  const int n = 2048;
  const double h = 2.0 * M_PI / n;
  std::vector<double> v2(n), slope(n);
  for (int i = 0; i < n; ++i) {
    const SpeedSquared s = speedSquared(m, E, i * h, gravity);
    if (!(s.value > 0.0))
      throw std::domain_error("free run: the crank does not complete a revolution (released too slowly against gravity)");
    v2[i] = s.value;
    slope[i] = s.slope;
  }
  // Mean speed: T = integral of dphi / phi_dot over a period. The integrand is smooth and periodic, so the
  // trapezoidal rule converges geometrically; 2048 points agree with 1024 to double precision (tests/analytic/motion_test.cc).
  double period = 0.0;
  for (int i = 0; i < n; ++i) period += h / std::sqrt(v2[i]);
  run.omega_mean = 2.0 * M_PI / period;
  // Extremes: the zeros of the slope of phi_dot^2, bracketed by sign changes between samples, refined by TOMS 748
  // (Boost.Math) to the bracket's rounding (about 6 evaluations where bisection took 50).
  double vmax = v2[0], vmin = v2[0], phi_max = 0.0, phi_min = 0.0;
  auto keep = [&](double v, double phi) {
    if (v > vmax) vmax = v, phi_max = phi;
    if (v < vmin) vmin = v, phi_min = phi;
  };
  for (int i = 0; i < n; ++i) {
    keep(v2[i], i * h);
    const int j = (i + 1) % n;
    if ((slope[i] > 0.0) == (slope[j] > 0.0) || slope[i] == 0.0) continue;
    const double a = i * h, b = (i + 1) * h;
    std::pair<double, double> root{a, b};
    if (slope[j] != 0.0) {
      std::uintmax_t iterations = 60;
      root = boost::math::tools::toms748_solve([&](double phi) { return speedSquared(m, E, phi, gravity).slope; }, a,
                                               b, slope[i], slope[j], boost::math::tools::eps_tolerance<double>(52),
                                               iterations);
    } else {
      root = {b, b};
    }
    const double phi = 0.5 * (root.first + root.second);
    keep(speedSquared(m, E, phi, gravity).value, std::fmod(phi, 2.0 * M_PI));
  }
  run.omega_max = std::sqrt(vmax);
  run.omega_min = std::sqrt(vmin);
  run.phi_at_omega_max = phi_max;
  run.phi_at_omega_min = phi_min;
  run.delta = (run.omega_max - run.omega_min) / run.omega_mean;
  return run;
}

}  // namespace crankcheck::analytic
