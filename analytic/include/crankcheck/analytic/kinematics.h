#pragma once
/// @file
/// Kinematics of one slider-crank at constant crank speed omega: exact closed forms, centric or with the piston pin
/// offset by delta along n (desaxe); Norton's two-term approximation (Design of Machinery, 13.3c-e) and the Fourier
/// series of any order with exact coefficients (both centric: the textbook's forms).
///
/// theta is the crank angle of this cylinder [rad] (theta = 0: crank pin on +e, the outer dead centre when centric),
/// x_p is measured from the crank centre O along the cylinder axis e (CONVENTIONS.md); the wrist pin is at
/// A = x_p e + delta n. With s = sin(beta) = lambda sin(theta) - delta / l:
///   x_p = r cos(theta) + l sqrt(1 - s^2)   (delta = 0: Norton 13.1d).
/// Time derivatives are at the scene's constant omega = m.machine.speed: v_p = omega dx_p/dtheta, etc.; the cylinder's
/// whole motion (calcCylinderMotion) also at any state (phi, omega, alpha) of an accelerating crank.

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "crankcheck/analytic/exact_trig.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::analytic {

/// Position and its time derivatives along the cylinder axis e.
struct PistonKinematics {
  double x_p = 0.0;  ///< [m]
  double v_p = 0.0;  ///< [m/s]
  double a_p = 0.0;  ///< [m/s^2]
  double j_p = 0.0;  ///< [m/s^3] jerk
};

/// The rod's angle beta to the cylinder axis, sin(beta) = lambda sin(theta) - delta / l, |beta| < pi/2, and its time
/// derivatives. The vector from wrist pin A to crank pin B is l (-cos(beta) e + sin(beta) n), so the rod body
/// turns about +Z with angular velocity -beta_dot and angular acceleration -beta_ddot.
struct RodKinematics {
  double beta = 0.0;       ///< [rad]
  double beta_dot = 0.0;   ///< [rad/s]
  double beta_ddot = 0.0;  ///< [rad/s^2]
};

/// The moving points of cylinder j at crank angle phi, in its own cylinder frame (e_j, n_j) (a planar frame in the
/// plane z = z_j, right-handed about +Z, so planar cross products equal global ones): wrist pin A, crank pin B, the
/// rod's centre of mass G, their accelerations (at constant omega, or at a state (phi, omega, alpha) of an accelerating
/// crank) and the rod's angular acceleration.
struct CylinderMotion {
  SinCos gamma;                ///< bank angle gamma_j: e_j = (cos, sin), n_j = (-sin, cos) in global X, Y
  SinCos theta;                ///< theta_j = phi + alpha_j
  double z = 0.0;              ///< [m] z_j
  PistonKinematics piston;     ///< x_p, v_p, a_p, j_p along e_j
  RodKinematics rod;           ///< beta and its derivatives
  Eigen::Vector2d p_OA, p_OB, p_OG;  ///< [m] (e, n) components
  Eigen::Vector2d a_A, a_B, a_G;     ///< [m/s^2] (e, n) components
  double psi_ddot = 0.0;       ///< [rad/s^2] the rod's angular acceleration about +Z (= -beta_ddot)
};
/// At the scene's constant omega = m.machine.speed: calcCylinderMotion(m, j, phi, m.machine.speed, 0.0).
/// @throws std::out_of_range if j is not a cylinder of m.
CylinderMotion calcCylinderMotion(const Mechanism& m, int j, double phi);
/// calcCylinderMotion of every cylinder, in order: computed once where several quantities need it (calcEvaluation).
std::vector<CylinderMotion> calcCylinderMotions(const Mechanism& m, double phi);
/// The motion at a state of an accelerating crank: angle phi [rad], speed omega [rad/s] and angular acceleration
/// alpha [rad/s^2] of the crank about +Z (any signs; omega = 0 allowed). With ' = d/dtheta (the forms per radian of
/// calcPistonKinematics and calcRodKinematics), the constant-speed part at omega plus alpha times the first derivative:
///   v_p = x' omega,  a_p = x'' omega^2 + x' alpha,  j_p = x''' omega^3 + 3 x'' omega alpha  (the jerk at constant alpha),
///   beta_dot = beta' omega,  beta_ddot = beta'' omega^2 + beta' alpha,  psi_ddot = -beta_ddot,
///   a_B = -omega^2 p_OB + alpha Z x p_OB,  a_A = a_p e,  a_G = (1 - mu) a_A + mu a_B.
/// At omega = m.machine.speed and alpha = 0 it is the constant-speed motion, bit for bit (the same operations: the
/// alpha terms are not formed at alpha = 0).
/// @throws std::out_of_range if j is not a cylinder of m.
CylinderMotion calcCylinderMotion(const Mechanism& m, int j, double phi, double omega, double alpha);
/// calcCylinderMotion at (phi, omega, alpha) of every cylinder, in order.
std::vector<CylinderMotion> calcCylinderMotions(const Mechanism& m, double phi, double omega, double alpha);

/// Exact piston kinematics (Norton 13.1d and its derivatives; closed forms, no series), with the pin offset
/// pin_offset = delta [m] (|delta| < l - r; 0: centric). Per radian of crank, c = cos(beta) = sqrt(1 - s^2):
///   x' = -r (sin + cos s / c),  x'' = -r cos + r sin s / c - r lambda cos^2 / c^3,
///   x''' = r sin + r cos s / c + 3 r lambda sin cos / c^3 - 3 r lambda^2 s cos^3 / c^5.
PistonKinematics calcPistonKinematics(const Mechanism& m, double theta, double pin_offset = 0.0);
/// The same from sin and cos of theta (e.g. calcThrowSinCos(phi, alpha_j)). Inline: the crank train's integration
/// (torsion_steady.h) asks for it at every step of every throw and reads v_p and a_p alone, so the compiler drops the
/// rest (the jerk's divisions); the same operations wherever it is inlined (bit for bit while the build contracts no
/// multiply-adds: the project sets no -march, and x86-64's baseline has no FMA).
inline PistonKinematics calcPistonKinematics(const Mechanism& m, const SinCos& theta, double pin_offset = 0.0) {
  const double r = m.crank.radius, l = m.rod.length, w = m.machine.speed;
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

/// Exact rod angle and its derivatives (per radian of crank; times omega, omega^2): beta' = lambda cos / cos(beta),
/// beta'' = -lambda sin / cos(beta) + lambda^2 sin(beta) cos^2 / cos^3(beta); centric: -lambda (1 - lambda^2) sin /
/// cos^3(beta).
RodKinematics calcRodKinematics(const Mechanism& m, double theta, double pin_offset = 0.0);
RodKinematics calcRodKinematics(const Mechanism& m, const SinCos& theta, double pin_offset = 0.0);
/// sin(beta) = lambda sin(theta) - delta / l: the rod's angle (calcRodKinematics) and its rates read the same one.
inline double calcRodSine(const Mechanism& m, const SinCos& theta, double pin_offset) {
  return m.crank.radius / m.rod.length * theta.sin - pin_offset / m.rod.length;
}
/// beta_dot and beta_ddot alone (beta left 0: no asin), the same operations as calcRodKinematics: for a caller that
/// reads the rates only (the reduced inertia, at every step of the crank train's integration).
inline RodKinematics calcRodRates(const Mechanism& m, const SinCos& theta, double pin_offset = 0.0) {
  const double lambda = m.crank.radius / m.rod.length, w = m.machine.speed;
  const auto [s1, c1] = theta;
  const double s = calcRodSine(m, theta, pin_offset);
  const double cos_beta = std::sqrt((1.0 - s) * (1.0 + s));
  const double cos3 = cos_beta * cos_beta * cos_beta;
  RodKinematics k;
  k.beta_dot = w * lambda * c1 / cos_beta;
  if (pin_offset == 0.0)  // centric: the two terms in one, -lambda (1 - lambda^2) sin / c^3
    k.beta_ddot = -w * w * lambda * (1.0 - lambda) * (1.0 + lambda) * s1 / cos3;
  else
    k.beta_ddot = w * w * lambda * (-s1 / cos_beta + lambda * s * c1 * c1 / cos3);
  return k;
}

/// The dead centres of a cylinder with pin offset delta: the crank angles theta at which the piston reverses (crank
/// and rod in line: sin(theta_outer) = delta / (l + r), theta_inner = pi + asin(delta / (l - r))), and the stroke
/// x_p(theta_outer) - x_p(theta_inner) = sqrt((l + r)^2 - delta^2) - sqrt((l - r)^2 - delta^2) (2 r when centric).
struct DeadCentres {
  double outer = 0.0, inner = 0.0;  ///< [rad] theta of the outer (farthest) and inner dead centre, in (-pi, pi]
  double stroke = 0.0;              ///< [m]
};
DeadCentres calcDeadCentres(const Mechanism& m, double pin_offset);

/// Norton's two-term approximation (centric, whatever the scene's pin offset: the textbook's shortcut):
/// x = l - r^2/(4l) + r (cos + (r/4l) cos 2theta)   (13.3c),
/// v = -r omega (sin + (r/2l) sin 2theta)   (13.3d), a = -r omega^2 (cos + (r/l) cos 2theta)   (13.3e),
/// and j, the time derivative of (13.3e).
PistonKinematics calcPistonKinematicsNorton(const Mechanism& m, double theta);

/// The Fourier series of the centric x_p truncated after harmonic `order` (>= 1), with the exact coefficients of
/// fourier_series.h, and its term-by-term time derivatives.
/// @throws std::invalid_argument if order < 1.
PistonKinematics calcPistonKinematicsFourier(const Mechanism& m, double theta, int order);

}  // namespace crankcheck::analytic
