#include "crankcheck/analytic/potential_energy.h"

#include "crankcheck/analytic/balance_shafts.h"

#include <cmath>
#include <stdexcept>

#include "crankcheck/analytic/exact_trig.h"

namespace crankcheck::analytic {

GravityCoefficients calcGravityCoefficients(const Mechanism& m, Eq5Form form) {
  const double g = m.machine.gravity, r = m.crank.radius, l = m.rod.length, z = m.rod.com_from_wrist_pin;
  // Eq (2): the rod's share at the wrist pin and at the crank pin.
  const double wrist_share = (form == Eq5Form::kDerived) ? (l - z) / l : z / l;  // printed eq (5): l_z = z_k / l
  const double crank_share = (form == Eq5Form::kDerived) ? z / l : (l - z) / l;  // printed eq (5): l_z* = (l - z_k) / l
  GravityCoefficients c;
  c.U1 = g * r * (m.piston.mass + m.rod.mass * wrist_share);
  c.U2 = g * (m.rod.mass * crank_share * r + m.crank.mass * m.crank.com_radius -
              m.crank.counterweight_mass * m.crank.counterweight_radius);
  return c;
}

double calcPotentialEnergy(const Mechanism& m, double phi, Eq5Form form) {
  const auto [U1, U2] = calcGravityCoefficients(m, form);
  const double lambda = m.crank.radius / m.rod.length;
  const SinCos half = calcSinCos(0.5 * phi);
  const double sin_phi = 2.0 * half.sin * half.cos;
  double U = 0.0;
  for (int j = 0; j < m.machine.cylinders; ++j) {
    const double alpha = m.machine.crank_angles[j];
    const SinCos gamma = calcSinCos(getBankAngle(m, j));  // eq (3) per cylinder: each in its own bank
    // x = alpha + phi/2, the mean of the two crank angles theta = alpha + phi and alpha.
    const SinCos a = calcSinCos(alpha);
    const SinCos x = addAngles(a, half);              // angle addition: no rounding of alpha + phi/2
    const SinCos theta = addAngles(x, half);
    // s = sin(beta) = lambda sin - delta / l (pin offset delta: the wrist pin on x_p e + delta n, whose height
    // delta cos(gamma) is the same at every angle and drops out of U).
    const double epsilon = getPinOffset(m, j) / m.rod.length;
    const double s_theta = lambda * theta.sin - epsilon, s_alpha = lambda * a.sin - epsilon;
    const double root_theta = std::sqrt((1.0 - s_theta) * (1.0 + s_theta));
    const double root_alpha = std::sqrt((1.0 - s_alpha) * (1.0 + s_alpha));
    // U2 [sin(theta + gamma) - sin(alpha + gamma)] = U2 2 sin(phi/2) cos(x + gamma)
    const double crank_term = U2 * 2.0 * half.sin * (x.cos * gamma.cos - x.sin * gamma.sin);
    // [x_p(theta) - x_p(alpha)] / r = cos theta - cos alpha + (root_theta - root_alpha) / lambda, and
    // root_theta - root_alpha = (s_alpha - s_theta)(s_alpha + s_theta) / (root_theta + root_alpha) with
    // s_alpha - s_theta = -2 lambda cos(x) sin(phi/2) (delta cancels):
    //   = -2 sin(x) sin(phi/2) - 2 cos(x) sin(phi/2) (s_alpha + s_theta) / (root_theta + root_alpha);
    // centric, s_alpha + s_theta = 2 lambda sin(x) cos(phi/2): -lambda sin(phi) sin(2x) / (root_theta + root_alpha).
    const double stroke =
        epsilon == 0.0 ? -2.0 * x.sin * half.sin - lambda * sin_phi * 2.0 * x.sin * x.cos / (root_theta + root_alpha)
                       : -2.0 * half.sin * (x.sin + x.cos * (s_alpha + s_theta) / (root_theta + root_alpha));
    U += crank_term + U1 * gamma.sin * stroke;
  }
  return U + calcBalanceShaftLoads(m, phi).U;  // the balance shafts' masses (balance_shafts.h)
}

double calcDimensionlessUnit(const Mechanism& m) {
  if (!m.flywheel_inertia)
    throw std::invalid_argument("dimensionless values need the flywheel inertia I_w ([flywheel].inertia)");
  if (m.machine.speed == 0.0)
    throw std::invalid_argument("dimensionless values need a nonzero speed ([engine].speed_rpm)");
  return *m.flywheel_inertia * m.machine.speed * m.machine.speed;
}

}  // namespace crankcheck::analytic
