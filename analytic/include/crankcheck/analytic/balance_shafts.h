#pragma once
/// @file
/// The balance shafts of a scene ([[balance_shaft]], scene/mechanism.h): eccentric point masses m at radius rho on
/// shafts parallel to Z through (x, y), in the plane z, turning at ratio x the crank speed, at psi = ratio phi + phase
/// from +X. The coupling is an ideal gear: a torque between the shafts, no force on the crank's main bearing.
/// Their exact share of each quantity, at crank angle phi and the scene's constant omega (Omega = ratio omega):
///   U = sum m g rho (sin psi(phi) - sin psi(0)),          Q = dU/dphi = sum m g rho ratio cos psi,
///   drive torque = sum ratio m g rho cos psi (at constant speed a shaft needs only its gravity torque),
///   F_s = -sum m a = sum m rho Omega^2 (cos psi, sin psi),
///   M_s = -sum p x m a = sum m rho Omega^2 (-z sin psi, z cos psi, x sin psi - y cos psi),
///   J (reduced inertia of the free run) = sum m rho^2 ratio^2.
/// A shaft with a whole-number ratio s adds to harmonic |s| of the shaking (calcBalanceShaftHarmonic).

#include <array>
#include <vector>

#include "crankcheck/scene/evaluation.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::analytic {

struct BalanceShaftLoads {
  double U = 0.0;             ///< [J] relative to phi = 0
  double Q = 0.0;             ///< [N m]
  double drive_torque = 0.0;  ///< [N m] what the crank must give the shafts (with gravity; 0 without shafts)
  Vec2 shaking_force{};       ///< [N]
  std::array<double, 3> shaking_moment{};  ///< [N m] about O
  double inertia = 0.0;       ///< [kg m^2] their share of J, constant
};
/// The sum over every shaft of m, at the scene's constant omega: calcBalanceShaftLoads(m, phi, m.machine.speed, 0.0).
BalanceShaftLoads calcBalanceShaftLoads(const Mechanism& m, double phi);
/// The same at a state of an accelerating crank (speed omega [rad/s], acceleration alpha [rad/s^2]): a shaft's mass
/// then also has the tangential acceleration rho Omega_dot (-sin psi, cos psi), Omega_dot = ratio alpha, so
///   drive torque += m rho^2 ratio^2 alpha (the shafts' share of J, times alpha),
///   F_s += m rho Omega_dot (sin psi, -cos psi),  M_s += m rho Omega_dot (z cos psi, z sin psi, -(x cos psi + y sin psi + rho)).
/// At omega = m.machine.speed and alpha = 0 the same operations as at constant speed.
BalanceShaftLoads calcBalanceShaftLoads(const Mechanism& m, double phi, double omega, double alpha);

/// Shaft `b`'s share of harmonic n of F_s and M_s (n = |ratio|: F = c cos(n phi) + s sin(n phi)); zeros for another
/// n. @throws std::invalid_argument if its ratio is not a whole number (its shaking is then not periodic in phi).
struct ShaftHarmonic {
  Vec2 force_cos{}, force_sin{};
  std::array<double, 3> moment_cos{}, moment_sin{};
};
ShaftHarmonic calcBalanceShaftHarmonic(const Mechanism& m, const BalanceShaftParams& b, int n);

}  // namespace crankcheck::analytic
