#pragma once
/// @file
/// Shaking force and moment (CONVENTIONS.md, "Layouts, axial positions, gas and shaking"): the loads the moving
/// parts put on the frame with gravity and gas off, F_s = -dP/dt and M_s = -dH_O/dt, P and H_O the momentum and
/// the angular momentum about O of pistons, rods and crank throws, at constant crank speed omega.
///
/// Per cylinder j in the plane z = z_j, with m a the mass times acceleration of each moving point or body (piston
/// m_o a_A, rod m_k a_G, throw masses m_s, m_p turning at omega) and p = (X, Y, z_j) its position:
///   dP/dt   = sum m a                                   (X, Y)
///   dH_O/dt = sum p x m a + I_G psi_ddot Z               (p x f = (-z f_Y, z f_X, X f_Y - Y f_X) for planar f)
/// with I_G = I_o - m_k z_k^2 the rod's central inertia and psi_ddot its angular acceleration. The throws' point
/// masses turn on circles: their p x m a has no Z part, but off the plane z = 0 it gives the rotating couple.

#include <array>

#include "crankcheck/scene/evaluation.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::analytic {

struct Shaking {
  Vec2 force{};                   ///< [N] F_s, global X, Y
  std::array<double, 3> moment{}; ///< [N m] M_s about O, global X, Y, Z
};

/// F_s and M_s at crank angle phi [rad] and the scene's omega; gravity and gas do not enter.
Shaking calcShaking(const Mechanism& m, double phi);

}  // namespace crankcheck::analytic
