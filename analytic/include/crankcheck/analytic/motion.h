#pragma once
/// @file
/// The motion of the single degree of freedom: reduced moment of inertia J(phi), the Lagrange equation, and the free
/// run under gravity alone (Stanczak's purpose: how much gravity makes the crank speed fluctuate).
///
/// Kinetic energy T = (1/2) J(phi) phi_dot^2 with, per cylinder (theta = phi + alpha_j, ' = d/dtheta),
///   J_j = m_o x'^2 + m_k |G'|^2 + I_G beta'^2 + m_s r_s^2 + m_p r_p^2,   I_G = I_o - m_k z_k^2,
/// plus I_w (shaft and flywheel). Lagrange's equation for phi (Q = dU/dphi):
///   J phi'' + (1/2) J' phi'^2 + Q = T_drive - T_load.

#include "crankcheck/scene/mechanism.h"

namespace crankcheck::analytic {

/// How the rod's inertia enters J.
enum class RodInertiaForm {
  kTrueInertia,           ///< the rigid rod: mass m_k at G, I_G about G
  kTwoMassWithDeltaI,     ///< the paper's reduction (eqs 1-2): m_k1 at A, m_k3 at B, and Delta_I = I_o - l z_k m_k
                          ///< turning with the rod; dynamically equivalent to the true rod (same mass, first moment
                          ///< and inertia about A), so J is the same
  kTwoMassWithoutDeltaI,  ///< the common shortcut that drops Delta_I: exact for potential energy, not for inertia
};

struct ReducedInertia {
  double J = 0.0;   ///< [kg m^2], including I_w (0 if the scene has none)
  double dJ = 0.0;  ///< dJ/dphi [kg m^2 / rad]
};

ReducedInertia calcReducedInertia(const Mechanism& m, double phi, RodInertiaForm form = RodInertiaForm::kTrueInertia);

/// [N m] The gas forces' torque on the crankshaft about +Z at crank angle phi: their power per unit crank speed,
/// -sum_j F_gas,j dx_p,j/dphi (virtual work; the same as minus the drive torque of the gas alone, reactions.h, held
/// to it in tests/analytic/motion_test.cc). 0 without [gas]. The one formula of the flywheel's work (flywheel.h) and of
/// each throw's gas torque in the crank train (crank_train.h).
/// @throws std::invalid_argument if the scene's crank speed is not > 0 (dx_p/dphi is read as v_p / omega).
double calcGasTorque(const Mechanism& m, double phi);

/// phi'' [rad/s^2] from Lagrange's equation at (phi, phi_dot) with a net external torque T_drive - T_load [N m].
double calcCrankAcceleration(const Mechanism& m, double phi, double phi_dot, double net_torque, bool gravity = true);

/// Free running with gravity only (no drive, no load), released at phi = 0 with speed omega0:
/// (1/2) J(phi) phi_dot^2 + U(phi) = E = (1/2) J(0) omega0^2, so phi_dot(phi) = sqrt(2 (E - U(phi)) / J(phi)).
struct FreeRun {
  double omega_min = 0.0;   ///< [rad/s] over a revolution
  double omega_max = 0.0;   ///< [rad/s]
  double omega_mean = 0.0;  ///< [rad/s] 2 pi / (time of one revolution)
  double delta = 0.0;       ///< (omega_max - omega_min) / omega_mean, the coefficient of speed fluctuation
  double energy = 0.0;      ///< E [J]
  double phi_at_omega_min = 0.0, phi_at_omega_max = 0.0;  ///< [rad] where, in [0, 2 pi)
};

/// phi_dot [rad/s] of the free run at phi. @throws std::domain_error if the crank cannot reach phi (E < U).
double calcFreeRunSpeed(const Mechanism& m, double omega0, double phi, bool gravity = true);

/// The free run's extremes (found as zeros of d(phi_dot^2)/dphi to double precision) and mean speed (trapezoidal
/// rule on the periodic 1 / phi_dot, converged to double precision).
/// @throws std::invalid_argument if omega0 <= 0 or the scene has no flywheel inertia; std::domain_error if the
///         crank does not complete a revolution (released too slowly against gravity).
FreeRun calcFreeRun(const Mechanism& m, double omega0, bool gravity = true);

}  // namespace crankcheck::analytic
