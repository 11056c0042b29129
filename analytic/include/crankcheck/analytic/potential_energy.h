#pragma once
/// @file
/// Gravitational potential energy of the k-crank inline mechanism (Stanczak eqs 2, 3, 5, 6, 12).
///
/// Per cylinder, with the rod reduced to two point masses (eq 2: m_k1 = m_k (l - z_k)/l at the wrist pin,
/// m_k3 = m_k z_k / l at the crank pin; exact for potential energy), the height of the moving masses gives
///   V_j(theta) = U1 sin(gamma) x_p(theta) / r + U2 sin(theta + gamma) + const,
///   U1 = g r (m_o + m_k1),   U2 = g (m_k3 r + m_s r_s - m_p r_p)            [J]
/// which is eq (3) with eq (5)'s abbreviations in dimensional form (the paper divides them by I_w omega^2).
/// U(phi) = sum_j V_j(phi + alpha_j) - V_j(alpha_j): zero at phi = 0 (CONVENTIONS.md). Eq (12) as printed
/// refers every cylinder to its own outer dead centre instead; the two differ by a constant only.

#include "crankcheck/scene/mechanism.h"

namespace crankcheck::analytic {

/// Which form of eq (5) to use for the coefficients U1, U2.
enum class Eq5Form {
  /// Derived from eq (2) with z_k measured from the wrist pin: U1 carries (l - z_k)/l of the rod, U2 z_k / l.
  kDerived,
  /// Eq (5) as printed: U1 = M_t + l_z M_z with l_z = z_k / l, U2 = M_s - M_sp + l_z* M_z with
  /// l_z* = (l - z_k) / l, i.e. the rod's split swapped relative to eq (2). Equal to kDerived when z_k = l/2.
  kAsPrinted,
};

/// The coefficients of eq (5) in joules (dimensional: multiply the paper's by I_w omega^2).
struct GravityCoefficients {
  double U1 = 0.0;  ///< [J] weight moving with the wrist pin, times r
  double U2 = 0.0;  ///< [J] first moment of the weights turning with the crank pin
};

GravityCoefficients calcGravityCoefficients(const Mechanism& m, Eq5Form form = Eq5Form::kDerived);

/// U(phi) [J], eqs (3), (12), relative to phi = 0. Evaluated in forms free of cancellation:
/// sin(a + phi) - sin(a) = 2 sin(phi/2) cos(a + phi/2), and the radical's difference as a quotient.
double calcPotentialEnergy(const Mechanism& m, double phi, Eq5Form form = Eq5Form::kDerived);

/// I_w omega^2 [J], the paper's unit of energy and torque (eqs 4, 6): U* = U / (I_w omega^2).
/// @throws std::invalid_argument if the scene has no flywheel inertia or omega = 0.
double calcDimensionlessUnit(const Mechanism& m);

}  // namespace crankcheck::analytic
