#pragma once
/// @file
/// The elastic crank train of a scene's `[crankshaft]` in Simbody (../shared/CONVENTIONS.md, "Torsion"), never using
/// the analytic formulas: each throw a crankshaft body of its own on a pin about Z from Ground (its cylinders' crank
/// pins, point masses and counterweights as KCrankModel's crankshaft, plus J_t as a disk), its cylinders' pistons and
/// rods closed on its pins as in KCrankModel; the front mass a disk on its own pin; the sections torsional springs and
/// dampers between neighbours (a Force::Custom on the pins' mobilities), the last one to the flywheel driven at
/// omega t; each throw's damping about omega; gravity and the gas (at the throw's own angle) as in KCrankModel.
///
/// The periodic steady state: started from the rigid motion at t = 0 (every pin at 0 turning at omega, the rods and
/// pistons assembled), integrated (RungeKuttaMerson) cycle by cycle, at 1000 x `accuracy` until the deviations
/// psi_i - omega t and their rates at the start of a cycle change by less than 1000 x `periodicity` of the largest
/// deviation seen over that cycle, then at `accuracy` until they change by less than `periodicity`; then one more
/// cycle sampled at `samples` equal steps (the loose start halves the cost; the agreement with the analytic steady
/// state stays 1.3e-7 of the twist scale). The time of the transient is the shaft's lightest
/// damping's: about 1 / (zeta w) per mode. At accuracy 1e-10 the cycle-to-cycle change stops falling at about 1e-7 of
/// the twist (the integration's own error per cycle, measured on the example four at 6000 rpm), hence `periodicity`
/// 1e-6 by default: 16 cycles there, about 11 s; the peak-to-peak twists then agree with the analytic engine's exact
/// steady state to 4e-7 (tests/gate/torsion_test.cc).

#include <vector>

#include "crankcheck/scene/mechanism.h"

namespace crankcheck::simbody_models {

struct CrankTrainRunOptions {
  double accuracy = 1e-10;     ///< the integrator's accuracy (relative error per step)
  double periodicity = 1e-6;   ///< the cycle-to-cycle change at which the run is periodic, relative to the twist
  int samples = 1024;          ///< equally spaced samples of the last cycle (even)
  int max_cycles = 2000;       ///< refused beyond (a train too lightly damped to settle)
};

struct CrankTrainRun {
  /// Section i's twist [rad] (CONVENTIONS: psi_b - psi_a, the last omega t - psi_{n-1}) at t_k = t0 + k T / samples,
  /// k = 0 .. samples - 1, over the last cycle (t0 a whole number of cycles: omega t0 a multiple of the cycle angle).
  std::vector<std::vector<double>> twists;
  int cycles = 0;              ///< cycles run before the sampled one
  double cycle_change = 0.0;   ///< the last cycle-to-cycle change, relative to the largest deviation
  long long steps = 0;         ///< the integrator's steps in all
};

/// @throws std::invalid_argument if the scene has no [crankshaft] or speed, or is not one Simbody builds (a massless
///         rod, KCrankModel); std::runtime_error if the run has not become periodic in max_cycles cycles.
CrankTrainRun simulateCrankTrainSteadyState(const Mechanism& m, const CrankTrainRunOptions& options = {});

}  // namespace crankcheck::simbody_models
