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
#include <vector>

#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/scene/evaluation.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::analytic {

struct Shaking {
  Vec2 force{};                   ///< [N] F_s, global X, Y
  std::array<double, 3> moment{}; ///< [N m] M_s about O, global X, Y, Z
};

/// F_s and M_s at crank angle phi [rad] and the scene's omega; gravity and gas do not enter.
Shaking calcShaking(const Mechanism& m, double phi);
/// The same from every cylinder's motion at crank angle phi (calcCylinderMotions), when it is already at hand; the
/// balance shafts' share (balance_shafts.h) from phi.
Shaking calcShaking(const Mechanism& m, const std::vector<CylinderMotion>& motions, double phi);
/// The same at a state of an accelerating crank (speed omega [rad/s], acceleration alpha [rad/s^2]), motions =
/// calcCylinderMotions(m, phi, omega, alpha): the throws' masses also have alpha Z x p, so F_s gains -alpha Z x (the
/// throw's first moment), and M_s's Z part -(I_w + sum_j (m_s r_s^2 + m_p r_p^2)) alpha (the crankshaft's own angular
/// momentum rate: its throws' point masses and the flywheel, motion.h's J); the shafts' share at (omega, alpha).
/// calcShaking(m, motions, phi) is this at (m.machine.speed, 0), bit for bit.
Shaking calcShaking(const Mechanism& m, const std::vector<CylinderMotion>& motions, double phi, double omega,
                    double alpha);

}  // namespace crankcheck::analytic

namespace crankcheck::analytic {

/// Harmonic n of the shaking force and moment at constant speed:
///   F_s(phi) = sum_n force_cos cos(n phi) + force_sin sin(n phi), the same for each component of M_s.
struct ShakingHarmonic {
  int n = 0;
  Vec2 force_cos{}, force_sin{};                     ///< [N] X, Y
  std::array<double, 3> moment_cos{}, moment_sin{};  ///< [N m] X, Y, Z about O
  /// [N] the largest |F_n(phi)| over the turn: the force of one harmonic traces an ellipse, this is its semi-major
  /// axis (the sum of the magnitudes of its forward- and backward-turning parts).
  double calcForceAmplitude() const;
  /// [N m] hypot(cos, sin) of moment component `axis` (0: X, 1: Y, 2: Z).
  double calcMomentAmplitude(int axis) const;
};

/// Harmonics n = 1..order of F_s and M_s in closed form, per cylinder, from the exact Fourier coefficients A_n of
/// the radical and B_n of its inverse (fourier_series.h), each cylinder at its own phase theta_j = phi + alpha_j, in
/// its own bank and plane. In cylinder j's frame (mu = z_k / l, M_t = (m_s r_s - m_p r_p) / r, I_G = I_o - m_k z_k^2):
///   force along e:  -omega^2 [ (m_o + m_k + M_t) r cos(theta) + (m_o + (1 - mu) m_k) l sum_h h^2 A_h cos(h theta) ]
///   force along n:  -omega^2 (mu m_k + M_t) r sin(theta)
///   moment about Z: m_k (1 - mu) mu r l omega^2 sin(theta) sum_h (1 - h^2) A_h cos(h theta)
///                   - I_G omega^2 sum_h h C_h sin(h theta),  C_1 = lambda (B_0 + B_2 / 2), C_h = lambda (B_{h-1} + B_{h+1}) / 2
/// (the mass times acceleration of piston, rod and throw; the rod's angular velocity per radian of crank is
/// sum_h C_h cos(h theta)), negated; the X and Y moments are z_j times the force's Y and -X parts.
/// With pin offsets the motion has sine terms too: the harmonics are then those of the exact F_s and M_s (calcShaking)
/// by a DFT whose number of samples N is doubled until harmonics N/4 and N/4 + 1 are below 4 eps of the largest value
/// (they decay geometrically, so what the DFT folds onto harmonics up to N/4 is then below rounding).
/// @throws std::invalid_argument if order < 1; std::runtime_error if an offset motion's DFT does not converge.
std::vector<ShakingHarmonic> calcShakingHarmonics(const Mechanism& m, int order);

/// Which parts of harmonic n vanish exactly because of the layout's symmetry, whatever the masses: with every bank
/// and throw angle a whole number of eighths of a degree and every axial position a whole number of nanometres, the
/// sums over the cylinders that carry harmonic n are sums of 2880th roots of unity with integer weights, decided
/// exactly (isZeroSumOfRootsOfUnity):
///   force:           sum_j e^{i (n beta_j - (n - 1) gamma_j)} = 0 and sum_j e^{i ((n + 1) gamma_j - n beta_j)} = 0
///                    (the forward- and backward-turning parts);
///   moment X and Y:  the same sums weighted by z_j;
///   moment Z:        sum_j e^{i n alpha_j} = 0.
/// Apart from the phases, what a centric cylinder cannot carry at all (every pin offset 0, no balance shaft turning at
/// n; whatever the angles): its force has orders 1 and even only (the piston's acceleration is cos(theta) and the even
/// cosines of the radical's series, the rod's centre moves sideways as sin(theta)), so neither force nor moments X, Y
/// at odd n >= 3; its moment Z odd orders only (the rod's swing is odd in theta), so none at even n. And at n >= 2 the
/// force of any cylinder, with a pin offset too, lies along its axis (the sideways part is order 1 alone): with every
/// cylinder's axis along Y (banks at 90 or 270 degrees) or along X (0 or 180: lying, a boxer) and no balance shaft at
/// n, the force has no X (or no Y) component there, so no moment about Y (or X).
struct HarmonicSymmetry {
  bool decided = false;  ///< false when an angle is not a whole 1/8 degree or a position not a whole nanometre, or
                         ///< the cylinders' pin offsets differ
  bool force_cancels = false, moment_xy_cancels = false, moment_z_cancels = false;
  bool force_order_absent = false;     ///< centric cylinders and odd n >= 3: force and moments X, Y are 0 exactly
  bool moment_z_order_absent = false;  ///< centric cylinders and even n: moment Z is 0 exactly
  /// Every axis along Y (X), n >= 2, no shaft at n: the force has no X (Y) part, moment Y (X) is 0 exactly.
  bool moment_x_direction_absent = false, moment_y_direction_absent = false;
};
HarmonicSymmetry findHarmonicSymmetry(const Mechanism& m, int n);

/// Exactly whether sum_j weights[j] e^{2 pi i exponents[j] / parts_per_turn} = 0 (integer exponents of any sign,
/// integer weights), for parts_per_turn = 2^a 3^b 5^c with a, b, c >= 1 (360: degrees; 2880: eighths of a degree).
/// Such an N has radical 30, so its cyclotomic polynomial is Phi_30(x^(N/30)) and 1, z, ..., z^(N/30 - 1) are a basis
/// of Q(z) over Q(z^(N/30)): the sum is zero exactly when, for each residue r mod N/30, the polynomial of the terms
/// with exponent = r (mod N/30) in y = x^(N/30) is divisible by Phi_30(y) = y^8 + y^7 - y^5 - y^4 - y^3 + y + 1.
/// Integer arithmetic throughout. @throws std::invalid_argument if the spans differ in length or N is not such.
bool isZeroSumOfRootsOfUnity(const std::vector<long long>& exponents, const std::vector<long long>& weights,
                             long long parts_per_turn = 360);

}  // namespace crankcheck::analytic
