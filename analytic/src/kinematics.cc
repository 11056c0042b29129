#include "crankcheck/analytic/kinematics.h"

#include <cmath>
#include <optional>
#include <stdexcept>

#include "crankcheck/analytic/exact_trig.h"
#include "crankcheck/analytic/fourier_series.h"
#include "cylinder_terms.h"

namespace crankcheck::analytic {

PistonKinematics calcPistonKinematics(const Mechanism& m, double theta, double pin_offset) {
  return calcPistonKinematics(m, calcSinCos(theta), pin_offset);
}

RodKinematics calcRodKinematics(const Mechanism& m, double theta, double pin_offset) {
  return calcRodKinematics(m, calcSinCos(theta), pin_offset);
}

RodKinematics calcRodKinematics(const Mechanism& m, const SinCos& theta, double pin_offset) {
  RodKinematics k = calcRodRates(m, theta, pin_offset);
  k.beta = std::asin(calcRodSine(m, theta, pin_offset));
  return k;
}

DeadCentres calcDeadCentres(const Mechanism& m, double pin_offset) {
  const double r = m.crank.radius, l = m.rod.length;
  DeadCentres d;
  d.outer = std::asin(pin_offset / (l + r));                                     // crank and rod stretched out
  d.inner = std::remainder(M_PI + std::asin(pin_offset / (l - r)), 2.0 * M_PI);  // crank folded back under the rod
  d.stroke = std::sqrt((l + r - pin_offset) * (l + r + pin_offset)) - std::sqrt((l - r - pin_offset) * (l - r + pin_offset));
  return d;
}

CylinderMotion calcCylinderMotion(const Mechanism& m, int j, double phi) {
  return calcCylinderMotion(m, j, phi, m.machine.speed, 0.0);
}

std::vector<CylinderMotion> calcCylinderMotions(const Mechanism& m, double phi) {
  return calcCylinderMotions(m, phi, m.machine.speed, 0.0);
}

CylinderMotion calcCylinderMotion(const Mechanism& m, int j, double phi, double omega, double alpha) {
  const double r = m.crank.radius, w = omega, mu = m.rod.com_from_wrist_pin / m.rod.length;
  // The constant-speed kinematics read r, l and m.machine.speed: at another omega, a light copy of those.
  std::optional<Mechanism> at_omega;
  if (omega != m.machine.speed) {
    at_omega = makeUnitSpeedCopy(m);
    at_omega->machine.speed = omega;
  }
  const Mechanism& k = at_omega ? *at_omega : m;
  CylinderMotion c;
  c.gamma = calcSinCos(getBankAngle(m, j));
  c.theta = calcThrowSinCos(phi, m.machine.crank_angles.at(static_cast<size_t>(j)));
  c.z = getAxialPosition(m, j);
  const double delta = getPinOffset(m, j);
  c.piston = calcPistonKinematics(k, c.theta, delta);
  c.rod = calcRodKinematics(k, c.theta, delta);
  c.p_OA = {c.piston.x_p, delta};  // the wrist pin on x_p e + delta n
  c.p_OB = {r * c.theta.cos, r * c.theta.sin};
  c.p_OG = c.p_OA + mu * (c.p_OB - c.p_OA);
  c.a_B = -w * w * c.p_OB;  // the crank pin's centripetal part (all of it at constant omega)
  if (alpha != 0.0) {
    // The crank's acceleration adds alpha times the derivatives per radian (the kinematics at unit speed: v_p = x',
    // a_p = x'', beta_dot = beta'), and the crank pin's tangential part alpha Z x p_OB.
    const Mechanism unit = makeUnitSpeedCopy(m);
    const PistonKinematics per_radian = calcPistonKinematics(unit, c.theta, delta);
    const RodKinematics rod_per_radian = calcRodRates(unit, c.theta, delta);
    c.piston.a_p += per_radian.v_p * alpha;
    c.piston.j_p += 3.0 * per_radian.a_p * omega * alpha;
    c.rod.beta_ddot += rod_per_radian.beta_dot * alpha;
    c.a_B += alpha * Eigen::Vector2d{-c.p_OB.y(), c.p_OB.x()};
  }
  c.psi_ddot = -c.rod.beta_ddot;  // the rod turns about +Z by -beta
  c.a_A = {c.piston.a_p, 0.0};
  c.a_G = (1.0 - mu) * c.a_A + mu * c.a_B;
  return c;
}

std::vector<CylinderMotion> calcCylinderMotions(const Mechanism& m, double phi, double omega, double alpha) {
  std::vector<CylinderMotion> motions;
  for (int j = 0; j < m.machine.cylinders; ++j) motions.push_back(calcCylinderMotion(m, j, phi, omega, alpha));
  return motions;
}

PistonKinematics calcPistonKinematicsNorton(const Mechanism& m, double theta) {
  const double r = m.crank.radius, l = m.rod.length, w = m.machine.speed;
  const auto [s1, c1] = calcSinCos(theta);
  const double s2 = 2.0 * s1 * c1, c2 = (c1 - s1) * (c1 + s1);
  PistonKinematics k;
  k.x_p = l - r * r / (4.0 * l) + r * (c1 + r / (4.0 * l) * c2);  // 13.3c
  k.v_p = -r * w * (s1 + r / (2.0 * l) * s2);                    // 13.3d
  k.a_p = -r * w * w * (c1 + r / l * c2);                        // 13.3e
  k.j_p = r * w * w * w * (s1 + 2.0 * r / l * s2);               // d/dt of 13.3e
  return k;
}

PistonKinematics calcPistonKinematicsFourier(const Mechanism& m, double theta, int order) {
  if (order < 1) throw std::invalid_argument("calcPistonKinematicsFourier: order must be >= 1");
  const double r = m.crank.radius, l = m.rod.length, w = m.machine.speed;
  const std::vector<double> a = calcRadicalFourierCoefficients(r / l, order);
  const auto [s1, c1] = calcSinCos(theta);
  PistonKinematics k;
  // x = r cos + l (A_0 + sum A_n cos n theta); derivatives term by term.
  k.x_p = r * c1 + l * a[0];
  k.v_p = -r * w * s1;
  k.a_p = -r * w * w * c1;
  k.j_p = r * w * w * w * s1;
  for (int n = 2; n <= order; n += 2) {
    const auto [sn, cn] = calcSinCos(n * theta);
    const double la = l * a[n];
    k.x_p += la * cn;
    k.v_p -= la * n * w * sn;
    k.a_p -= la * n * n * w * w * cn;
    k.j_p += la * n * n * n * w * w * w * sn;
  }
  return k;
}

}  // namespace crankcheck::analytic
