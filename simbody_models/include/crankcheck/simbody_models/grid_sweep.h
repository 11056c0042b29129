#pragma once
/// @file
/// Simbody's U and Q over a uniform grid of crank angles by superposition: with the crankshaft rigid and its angle
/// prescribed, cylinder j's parts (piston, rod, its throw's masses) feel gravity and the frame only, so cylinder j
/// contributes to Q and U what a one-cylinder mechanism in the same bank gamma_j contributes at its own crank angle
/// theta_j = phi + alpha_j, and the k-cylinder values are sums of one-cylinder values at shifted angles. The sweep
/// builds one KCrankModel of one cylinder per distinct cylinder (same bank; every cylinder has the same crank, rod and
/// piston) and evaluates it once per distinct angle the k cylinders need, then sums. No formula of the analytic engine
/// is used: every value is Simbody's (calcHoldingTorque, calcPotentialEnergy of the one-cylinder model). The gate
/// (tests/gate/grid_sweep_test.cc) checks the sums against the k-cylinder KCrankModel itself.
///
/// Which angles are shared: when alpha_j is a whole number a_j of steps (to 8 eps of the larger of |alpha_j| and
/// 2 pi), cylinder j reads the one-cylinder values on the same grid shifted by a_j; when the step divides a turn (2 pi
/// / |step| a whole number P, to 8 eps), indices are taken modulo P, so a grid of n >= P angles costs P one-cylinder
/// evaluations for any k in one bank. Cylinders whose alpha_j is not a whole number of steps get their own grid
/// (offset alpha_j): the cost then grows with the number of such offsets, up to k one-cylinder sweeps.
///
/// Gas is not part of U or Q (CONVENTIONS.md: Q is gravity's alone), so a scene's [gas] table is ignored here.

#include <cstddef>
#include <vector>

#include "crankcheck/scene/mechanism.h"
#include "crankcheck/simbody_models/k_crank_model.h"

namespace crankcheck::simbody_models {

/// What the sweep evaluated: the one-cylinder models and angles it needed.
struct GridSweepStats {
  int models = 0;             ///< one-cylinder models built (distinct bank and grid offset)
  size_t evaluations = 0;     ///< one-cylinder evaluations in all
};

/// Q [N m] (the static holding torque, KCrankModel::calcHoldingTorque) at phi_i = phi0 + i step, i = 0 .. n - 1.
/// @throws std::invalid_argument if phi0 or step is not finite, step = 0, or the mechanism is invalid (as KCrankModel).
/// @throws std::runtime_error if Simbody fails (as KCrankModel).
std::vector<double> calcHoldingTorqueOnGrid(const Mechanism& m, double phi0, double step, size_t n,
                                            ModelOptions options = {}, GridSweepStats* stats = nullptr);

/// U [J] = V(phi) - V(0) (KCrankModel::calcPotentialEnergy) at phi_i = phi0 + i step: the sum over cylinders of the
/// one-cylinder U_1(theta_j) - U_1(alpha_j). @throws as calcHoldingTorqueOnGrid.
std::vector<double> calcPotentialEnergyOnGrid(const Mechanism& m, double phi0, double step, size_t n,
                                              ModelOptions options = {}, GridSweepStats* stats = nullptr);

}  // namespace crankcheck::simbody_models
