#pragma once
/// @file
/// Joint reactions of the k-crank mechanism (any layout: each cylinder in its own bank gamma_j and plane z_j) at
/// constant crank speed, or at a state of an accelerating crank, with gravity: Newton-Euler of piston (a particle),
/// rod (a rigid body with its true inertia I_o about the wrist pin) and crank throw, per cylinder.
/// Names and signs: CONVENTIONS.md ("force ON b FROM a", global X, Y components).
///
/// Per cylinder, in the cylinder frame (e, n), with F_A = wrist_pin_force, F_B = crank_pin_force, G the rod's
/// centre of mass (a fixed fraction z_k / l of the way from A to B), psi the rod's angle about +Z:
///   piston, along e:      m_o a_p = F_A.e + m_o g.e - F_gas   (F_gas = p A toward the crank, gas.h)
///   piston, along n:      0 = F_A.n + N_w + m_o g.n
///   rod, forces:          m_k a_G = F_B - F_A + m_k g
///   rod, moments about A: I_o psi_ddot + m_k (G - A) x a_A = (B - A) x F_B + (G - A) x m_k g
///   crank throw, forces:  F_O,j = m_s a_s + m_p a_c - (m_s + m_p) g + F_B
///   crank throw, moments about the fixed O (the throw's point masses have angular momentum (m_s r_s^2 + m_p r_p^2)
///   omega about O, constant at constant omega):
///                         tau_j = B x F_B - P_s x m_s g - P_c x m_p g + (m_s r_s^2 + m_p r_p^2) alpha
/// bearing_force = sum_j F_O,j, drive_torque = sum_j tau_j + I_w alpha + the balance shafts' torque (balance_shafts.h).
/// At constant omega (calcReactions, calcEvaluation) alpha = 0; at a state (phi, omega, alpha) of an accelerating crank
/// (calcReactionsAtState, calcEvaluationAtState) the accelerations are those of calcCylinderMotion(m, j, phi, omega,
/// alpha) and the throw's masses have a_s = -omega^2 P_s + alpha Z x P_s (a_c likewise). The crankshaft's torsion
/// inertias ([crankshaft], mechanism.h) belong to the elastic train alone: the rigid shaft's are those of J (motion.h).

#include <vector>

#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/analytic/motion.h"
#include "crankcheck/scene/evaluation.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::analytic {

struct CylinderReactions {
  Vec2 crank_pin_force{};  ///< [N] crank on rod j at B_j
  Vec2 wrist_pin_force{};  ///< [N] rod on piston j at A_j
  double wall_force = 0.0; ///< [N] N_w, the wall pushes piston j with N_w n
};

struct Reactions {
  double drive_torque = 0.0;  ///< [N m] about +Z, to keep omega constant
  Vec2 bearing_force{};       ///< [N] frame on crankshaft at O, all throws
  std::vector<CylinderReactions> cylinders;
};

/// Reactions at crank angle phi [rad] and the scene's omega (m.machine.speed), with the rod as `rod` models it:
/// the rigid rod (kTrueInertia); the paper's two-mass rod with Delta_I (m_k1 at A, m_k3 at B, Delta_I = I_o - l z_k m_k
/// turning with the rod: the same mass, first moment and inertia about A, so the same reactions); or the common
/// two-mass rod without Delta_I, a body of mass m_k with its centre of mass at G and inertia m_k3 l^2 = m_k z_k l
/// about A, which engine programs use and which is wrong by Delta_I psi_ddot in the rod's moment balance.
Reactions calcReactions(const Mechanism& m, double phi, RodInertiaForm rod = RodInertiaForm::kTrueInertia);
/// The same from every cylinder's motion at phi (calcCylinderMotions), when it is already at hand.
Reactions calcReactions(const Mechanism& m, double phi, const std::vector<CylinderMotion>& motions,
                        RodInertiaForm rod = RodInertiaForm::kTrueInertia);

/// Reactions at a state of an accelerating crank: angle phi [rad], speed omega [rad/s], angular acceleration alpha
/// [rad/s^2] about +Z, with motions = calcCylinderMotions(m, phi, omega, alpha). drive_torque [N m] is the torque the
/// drive must apply to the crankshaft about +Z for that alpha: by Lagrange's equation (motion.h)
///   drive_torque = J(phi) alpha + (1/2) J'(phi) omega^2 + Q(phi) - calcGasTorque(m, phi)
/// (J with I_w and the balance shafts; the gas torque drives the shaft, so the drive gives less). The gas force is
/// the scene's at phi whatever omega. calcReactions(m, phi, motions, rod) is this at (m.machine.speed, 0), bit for bit.
Reactions calcReactionsAtState(const Mechanism& m, double phi, double omega, double alpha,
                               const std::vector<CylinderMotion>& motions,
                               RodInertiaForm rod = RodInertiaForm::kTrueInertia);

/// Everything the analytic engine reports at phi, in the struct every engine fills (engine = "analytic"):
/// U (eq 12), Q (eq 13), exact piston kinematics, calcReactions and calcShaking, each cylinder in its own bank.
/// calcEvaluationAtState(m, phi, m.machine.speed, 0.0).
Evaluation calcEvaluation(const Mechanism& m, double phi);

/// The same at a state of an accelerating crank: angle phi [rad], speed omega [rad/s], angular acceleration alpha
/// [rad/s^2] of the crank about +Z (any signs; omega = 0 allowed; e.g. a simulator's sample, alpha from its equation
/// of motion). U and Q depend on phi alone; v_p = x' omega, a_p = x'' omega^2 + x' alpha, rod_omega = beta' omega,
/// rod_alpha = beta'' omega^2 + beta' alpha (calcCylinderMotion); reactions and drive_torque by calcReactionsAtState
/// (the torque the drive applies for that alpha, flywheel I_w alpha included); shaking_force = -dP/dt with the
/// tangential accelerations; shaking_moment = -dH_O/dt, whose Z part then also has -(I_w + sum_j (m_s r_s^2 + m_p
/// r_p^2)) alpha, the crankshaft's own angular momentum rate (calcShaking). At omega = m.machine.speed and alpha = 0
/// it is calcEvaluation(m, phi), bit for bit.
Evaluation calcEvaluationAtState(const Mechanism& m, double phi, double omega, double alpha);

}  // namespace crankcheck::analytic
