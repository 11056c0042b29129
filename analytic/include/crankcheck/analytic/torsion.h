#pragma once
/// @file
/// Torsional vibration of the crank train, Holzer's (textbook) model (docs/CONVENTIONS-crankcheck.md, "Torsion"): each
/// throw a constant inertia J_eq,j, the sections springs, the train clamped at the flywheel (driven at omega t).
///
/// Bodies, front first: the front mass F (when [crankshaft].front_inertia > 0), then the throws of findThrows
/// (scene/mechanism.h). Section i joins body i and body i + 1; the last section joins the last throw and the flywheel W,
/// which is clamped. So n bodies have n sections, and
///   K_ii = K_{i-1} + K_i (K_{-1} = 0),  K_{i,i+1} = K_{i+1,i} = -K_i,  J = diag(J_F, J_eq,0, ..., J_eq,k-1),
///   K x = w^2 J x   (the free vibration of (K - w^2 J) x = 0, CONVENTIONS "Holzer's model").

#include <vector>

#include <Eigen/Dense>

#include "crankcheck/scene/mechanism.h"

namespace crankcheck::analytic {

/// J_j(psi) [kg m^2]: the reduced inertia of the cylinders on throw `throw_index` (findThrows) at shaft angle psi [rad]
/// (psi in place of phi in their crank angles, theta_c = psi + alpha_c): crank point masses, counterweight, rod and
/// piston, the J(phi) of motion.h (calcReducedInertia) of those cylinders alone, without [crankshaft].throw_inertia,
/// the flywheel or balance shafts.
/// @throws std::out_of_range if there is no such throw.
double calcThrowReducedInertia(const Mechanism& m, int throw_index, double psi);

/// Throw j's constant inertia for Holzer's model: exact (to rounding) and by the textbook's shortcuts.
struct ThrowInertia {
  /// [kg m^2] J_t + the mean of J_j over a turn, (1 / 2 pi) integral of J_j dpsi: the trapezoidal sum over N equally
  /// spaced angles (the exact mean of a smooth periodic function up to its Fourier terms of order N, 2N, ...: geometric
  /// convergence), N doubled from 16 until two sums differ by at most 4 eps of the mean; compensated sums. Accuracy:
  /// a few eps relative.
  double exact = 0.0;
  int samples = 0;  ///< N of the last sum
  /// [kg m^2] the two-mass rod (eq 2, Norton 13.4): m_k3 = m_k z_k / l rotating at the crank pin, m_k1 = m_k (l - z_k) / l
  /// reciprocating with the piston, Delta_I dropped; the reciprocating m_rec = m_o + m_k1 counted with half its mass,
  /// J_t + sum over the throw's cylinders of (m_s r_s^2 + m_p r_p^2 + m_k3 r^2 + (1/2) m_rec r^2): the mean of
  /// m_rec x'^2 with x' = -r sin(theta), the first term of Norton's series 13.3 (Den Hartog, Mechanical Vibrations,
  /// torsional vibration of reciprocating engines: "half the reciprocating mass").
  double half_reciprocating = 0.0;
  /// [kg m^2] as half_reciprocating with Norton's two-term velocity x' = -r (sin(theta) + (lambda / 2) sin(2 theta)),
  /// whose square averages r^2 (1/2 + lambda^2 / 8): (1/2) m_rec r^2 (1 + lambda^2 / 4).
  double second_order = 0.0;
};

/// Throw `throw_index`'s inertias, J_t = [crankshaft].throw_inertia (0 without the table). Pin offsets enter the exact
/// mean only (the shortcuts are for centric cylinders).
/// @throws std::out_of_range if there is no such throw;
///         std::runtime_error if the sum has not converged at N = 2^20 (lambda within about 1e-5 of 1).
ThrowInertia calcThrowInertia(const Mechanism& m, int throw_index);

/// The natural frequencies and mode shapes of a chain clamped at its end.
struct TorsionModes {
  std::vector<double> inertias;   ///< J [kg m^2] of the bodies, front first
  std::vector<double> stiffness;  ///< K_i [N m/rad], section i between body i and body i + 1 (the last: the clamp)
  Eigen::VectorXd frequencies;    ///< w_i [rad/s], ascending
  /// Column i: mode i, the bodies' amplitudes [rad] scaled so that the largest |x| is 1 and that entry positive
  /// (the first such entry where two tie).
  Eigen::MatrixXd shapes;
};

/// K x = w^2 J x for bodies `inertias` joined by `stiffness` (section i between body i and body i + 1, the last one
/// to the clamp), by Eigen's GeneralizedSelfAdjointEigenSolver (Cholesky of J; normwise backward stable: each w^2
/// within a few n eps of the largest w^2).
/// @throws std::invalid_argument if the lists are empty or of different lengths, or a value is not positive and finite.
TorsionModes calcChainModes(const std::vector<double>& inertias, const std::vector<double>& stiffness);

/// Holzer's model of the scene's [crankshaft]: the front mass (if any) and every throw's ThrowInertia::exact,
/// the scene's stiffnesses, clamped at the flywheel.
/// @throws std::invalid_argument if the scene has no [crankshaft] or a throw has no inertia (J_eq = 0: massless parts
///         and throw_inertia 0); as calcThrowInertia.
TorsionModes calcTorsionModes(const Mechanism& m);

}  // namespace crankcheck::analytic
