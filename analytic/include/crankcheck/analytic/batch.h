#pragma once
/// @file
/// Batch kernels: the analytic engine's quantities at many crank angles at once, with the same mathematics as the
/// scalar closed forms (calcGravityTorque, calcPotentialEnergy, calcPistonKinematics, calcReactions, calcShaking) and
/// the arithmetic arranged for SIMD throughput. What a sweep over millions of (k, lambda, gamma, phi) points calls.
///
/// Vectors and dispatch: the kernels are written once with Highway 1.0 and compiled for AVX-512 ("AVX3", 8 doubles),
/// AVX2 (4), SSE4 and SSSE3 (2) and the portable baseline ("SCALAR", plain C++, one lane); at the first call Highway
/// picks the widest the CPU has, so one binary runs on any x86-64. sin and cos of vectors come from SLEEF 3.5 (the
/// 1-ulp `_u10` sincos for the chosen width); the baseline uses the C library's sin and cos. getBatchTargetName()
/// says which path runs.
///
/// Arguments: every finite angle. SLEEF's u10 sincos reduces the argument exactly over the whole double range
/// (measured against glibc: within 0.5 eps up to |phi| = 1e300), so no range is refused. An angle that is NaN or
/// infinite makes the kernel throw std::invalid_argument after the pass (the outputs are then unspecified); on a grid,
/// phi0, step and the last angle are checked before anything is written.
///
/// Accuracy (tests/analytic/batch_test.cc, against the scalar functions angle by angle, on every angle the benchmark
/// times, on both the widest and the baseline path): within 4 eps times the quantity's physical scale
/// (validation/scales.h), times 1/(1 - lambda^2) near lambda = 1 (measured: at most 1.8 eps x scale for lambda <= 0.9;
/// at lambda = 0.999, where the bound is 2000, up to 121 for the pin forces, whose rod moment balance divides by the
/// rod's short projection on the cylinder axis, and 14 for the rest). Each throw's angle is phi rotated by alpha_j (addAngles, as calcThrowSinCos) and the
/// remaining arithmetic is the scalar functions' in the same order (with multiply-adds fused where the CPU has FMA;
/// the reactions also gather the throw's terms), so the difference is mostly what the vector sin/cos leave. The
/// kernels do not snap quarter turns: the scalar calcSinCos returns exact values for angles within 2 ulp of a multiple
/// of pi/2 (exact_trig.h), which moves its sin and cos by up to 2 eps |phi| there, so inside those
/// windows (measure zero; reached by random angles with probability ~1e-15) the two differ by up to that much.
/// On a uniform grid, sin and cos come from rotating each lane by Lanes() steps, re-anchored with an exact sincos of
/// the doubles phi0 + i step every 16 vectors: within 1e-13 of the scale (times 1/(1 - lambda^2)) for |phi| up to a
/// few hundred radians, beyond which the rounding of the scalar reference's own angle phi0 + i step dominates.
///
/// Layout: structure of arrays. Every output is one std::span<double> per quantity (per cylinder where the quantity is
/// per cylinder) with one entry per angle: the same size as phi, or, on a grid, the size that sets the number of
/// angles. Every layout the scalar functions accept is accepted (k cylinders, bank angles gamma_j, axial positions
/// z_j, explicit crank angles); with a [gas] table the reactions read the gas force from the scalar calcGasForce
/// angle by angle (correct, not vectorised).

#include <span>

#include "crankcheck/analytic/motion.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::analytic {

/// The piston kinematics of one cylinder (along its axis e_j, as calcPistonKinematics): one entry per angle.
struct PistonKinematicsSpans {
  std::span<double> x_p;  ///< [m]
  std::span<double> v_p;  ///< [m/s]
  std::span<double> a_p;  ///< [m/s^2]
};

/// The joint reactions of one cylinder (as CylinderReactions, global X, Y): one entry per angle.
struct CylinderReactionsSpans {
  std::span<double> crank_pin_force_X, crank_pin_force_Y;  ///< [N] crank on rod j at B_j
  std::span<double> wrist_pin_force_X, wrist_pin_force_Y;  ///< [N] rod on piston j at A_j
  std::span<double> wall_force;                            ///< [N] N_w along n_j
};

/// The reactions of the whole mechanism (as Reactions). `cylinders` is either empty (only the totals are computed)
/// or holds one entry per cylinder.
struct ReactionsSpans {
  std::span<double> drive_torque;                      ///< [N m] about +Z
  std::span<double> bearing_force_X, bearing_force_Y;  ///< [N] frame on crankshaft at O
  std::span<const CylinderReactionsSpans> cylinders;
};

/// The shaking force and moment (as Shaking): one entry per angle.
struct ShakingSpans {
  std::span<double> force_X, force_Y;              ///< [N]
  std::span<double> moment_X, moment_Y, moment_Z;  ///< [N m] about O
};

// Every kernel below is written for centric cylinders without balance shafts: each throws std::invalid_argument for a
// mechanism with pin offsets (hasPinOffsets) or [[balance_shaft]]s, whose values the scalar functions
// (calcEvaluation) give angle by angle.

/// Q [N m] (Stanczak eq 13, calcGravityTorque) at each angle phi[i] [rad].
/// @throws std::invalid_argument if the spans differ in size or an angle is not finite.
void calcGravityTorqueBatch(const Mechanism& m, std::span<const double> phi, std::span<double> Q);
/// Q [N m] on the uniform grid phi_i = phi0 + i step, i = 0 .. Q.size() - 1.
/// @throws std::invalid_argument if phi0, step or the last angle is not finite.
void calcGravityTorqueOnGrid(const Mechanism& m, double phi0, double step, std::span<double> Q);

/// U [J] (eqs 3, 12, calcPotentialEnergy: zero at phi = 0) at each angle phi[i] [rad].
/// @throws std::invalid_argument if the spans differ in size or an angle is not finite.
void calcPotentialEnergyBatch(const Mechanism& m, std::span<const double> phi, std::span<double> U);
/// U [J] on the uniform grid phi_i = phi0 + i step, i = 0 .. U.size() - 1.
/// @throws std::invalid_argument if phi0, step or the last angle is not finite.
void calcPotentialEnergyOnGrid(const Mechanism& m, double phi0, double step, std::span<double> U);

/// Exact piston kinematics of every cylinder j at theta_j = phi[i] + alpha_j (calcPistonKinematics, Norton 13.1d and
/// its derivatives at the scene's omega). `cylinders` has one entry per cylinder.
/// @throws std::invalid_argument if cylinders.size() != k, a span differs in size from phi, or an angle is not finite.
void calcPistonKinematicsBatch(const Mechanism& m, std::span<const double> phi,
                               std::span<const PistonKinematicsSpans> cylinders);
/// The same on the uniform grid phi_i = phi0 + i step; the spans' common size is the number of angles.
/// @throws std::invalid_argument if cylinders.size() != k, the spans differ in size, or an angle is not finite.
void calcPistonKinematicsOnGrid(const Mechanism& m, double phi0, double step,
                                std::span<const PistonKinematicsSpans> cylinders);

/// Joint reactions and drive torque (calcReactions: Newton-Euler per cylinder, each in its own bank, with gravity
/// and, with [gas], the gas force) at each angle phi[i] [rad] and the scene's omega.
/// @throws std::invalid_argument if out.cylinders is neither empty nor of size k, a span differs in size from phi,
/// or an angle is not finite.
void calcReactionsBatch(const Mechanism& m, std::span<const double> phi, const ReactionsSpans& out,
                        RodInertiaForm rod = RodInertiaForm::kTrueInertia);
/// The same on the uniform grid phi_i = phi0 + i step; out.drive_torque's size is the number of angles.
/// @throws std::invalid_argument as calcReactionsBatch, or if phi0, step or the last angle is not finite.
void calcReactionsOnGrid(const Mechanism& m, double phi0, double step, const ReactionsSpans& out,
                         RodInertiaForm rod = RodInertiaForm::kTrueInertia);

/// Shaking force and moment about O (calcShaking: gravity and gas off) at each angle phi[i] [rad].
/// @throws std::invalid_argument if a span differs in size from phi or an angle is not finite.
void calcShakingBatch(const Mechanism& m, std::span<const double> phi, const ShakingSpans& out);
/// The same on the uniform grid phi_i = phi0 + i step; out.force_X's size is the number of angles.
/// @throws std::invalid_argument if the spans differ in size, or phi0, step or the last angle is not finite.
void calcShakingOnGrid(const Mechanism& m, double phi0, double step, const ShakingSpans& out);

/// The instruction set the batch kernels run on in this process: "AVX3" (AVX-512), "AVX2", "SSE4", "SSSE3" or
/// "SCALAR" (the portable baseline). Tests force the baseline with hwy::SetSupportedTargetsForTest(HWY_SCALAR).
const char* getBatchTargetName();

}  // namespace crankcheck::analytic
