#include "crankcheck/analytic/kinematics.h"

#include <cmath>
#include <stdexcept>

#include "crankcheck/analytic/exact_trig.h"
#include "crankcheck/analytic/fourier_series.h"

namespace crankcheck::analytic {

PistonKinematics calcPistonKinematics(const Mechanism& m, double theta, double pin_offset) {
  return calcPistonKinematics(m, calcSinCos(theta), pin_offset);
}

PistonKinematics calcPistonKinematics(const Mechanism& m, const SinCos& theta, double pin_offset) {
  const double r = m.crank.radius, l = m.rod.length, w = m.engine.speed;
  const double lambda = r / l;
  const auto [s1, c1] = theta;
  const double s = lambda * s1 - pin_offset / l;       // sin(beta)
  const double c = std::sqrt((1.0 - s) * (1.0 + s));   // cos(beta), no cancellation
  const double c3 = c * c * c, c5 = c3 * c * c;
  const double t = s / c;                              // tan(beta)
  PistonKinematics k;
  k.x_p = r * c1 + l * c;  // Norton 13.1d (centric); the wrist pin on x_p e + delta n
  k.v_p = -r * w * (s1 + c1 * t);
  if (pin_offset == 0.0) {
    // The centric forms in sin 2theta, cos 2theta (the batch kernels compute the same expressions):
    // d2x/dtheta2 = -r (cos + lambda cos2 / root + lambda^3 sin^2 2 / (4 root^3)),
    // d3x/dtheta3 = r (sin + 2 lambda sin2 / root - (3/2) lambda^3 sin2 cos2 / root^3 - (3/8) lambda^5 sin^3 2 / root^5).
    const double s2 = 2.0 * s1 * c1, c2 = (c1 - s1) * (c1 + s1);
    const double l3 = lambda * lambda * lambda, l5 = l3 * lambda * lambda;
    k.v_p = -r * w * (s1 + lambda * s2 / (2.0 * c));
    k.a_p = -r * w * w * (c1 + lambda * c2 / c + l3 * s2 * s2 / (4.0 * c3));
    k.j_p = r * w * w * w * (s1 + 2.0 * lambda * s2 / c - 1.5 * l3 * s2 * c2 / c3 - 0.375 * l5 * s2 * s2 * s2 / c5);
    return k;
  }
  k.a_p = r * w * w * (-c1 + s1 * t - lambda * c1 * c1 / c3);
  k.j_p = r * w * w * w * (s1 + c1 * t + 3.0 * lambda * s1 * c1 / c3 - 3.0 * lambda * lambda * s * c1 * c1 * c1 / c5);
  return k;
}

RodKinematics calcRodKinematics(const Mechanism& m, double theta, double pin_offset) {
  return calcRodKinematics(m, calcSinCos(theta), pin_offset);
}

RodKinematics calcRodKinematics(const Mechanism& m, const SinCos& theta, double pin_offset) {
  const double lambda = m.crank.radius / m.rod.length, w = m.engine.speed;
  const auto [s1, c1] = theta;
  const double s = lambda * s1 - pin_offset / m.rod.length;
  const double cos_beta = std::sqrt((1.0 - s) * (1.0 + s));
  const double cos3 = cos_beta * cos_beta * cos_beta;
  RodKinematics k;
  k.beta = std::asin(s);
  k.beta_dot = w * lambda * c1 / cos_beta;
  if (pin_offset == 0.0)  // centric: the two terms in one, -lambda (1 - lambda^2) sin / c^3
    k.beta_ddot = -w * w * lambda * (1.0 - lambda) * (1.0 + lambda) * s1 / cos3;
  else
    k.beta_ddot = w * w * lambda * (-s1 / cos_beta + lambda * s * c1 * c1 / cos3);
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
  const double r = m.crank.radius, w = m.engine.speed, mu = m.rod.com_from_wrist_pin / m.rod.length;
  CylinderMotion c;
  c.gamma = calcSinCos(getBankAngle(m, j));
  c.theta = calcThrowSinCos(phi, m.engine.crank_angles.at(static_cast<size_t>(j)));
  c.z = getAxialPosition(m, j);
  const double delta = getPinOffset(m, j);
  c.piston = calcPistonKinematics(m, c.theta, delta);
  c.rod = calcRodKinematics(m, c.theta, delta);
  c.psi_ddot = -c.rod.beta_ddot;  // the rod turns about +Z by -beta
  c.p_OA = {c.piston.x_p, delta};  // the wrist pin on x_p e + delta n
  c.p_OB = {r * c.theta.cos, r * c.theta.sin};
  c.p_OG = c.p_OA + mu * (c.p_OB - c.p_OA);
  c.a_A = {c.piston.a_p, 0.0};
  c.a_B = -w * w * c.p_OB;  // the crank pin turns at constant omega
  c.a_G = (1.0 - mu) * c.a_A + mu * c.a_B;
  return c;
}

std::vector<CylinderMotion> calcCylinderMotions(const Mechanism& m, double phi) {
  std::vector<CylinderMotion> motions;
  for (int j = 0; j < m.engine.cylinders; ++j) motions.push_back(calcCylinderMotion(m, j, phi));
  return motions;
}

PistonKinematics calcPistonKinematicsNorton(const Mechanism& m, double theta) {
  const double r = m.crank.radius, l = m.rod.length, w = m.engine.speed;
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
  const double r = m.crank.radius, l = m.rod.length, w = m.engine.speed;
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
