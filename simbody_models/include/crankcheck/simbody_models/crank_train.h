#pragma once
/// @file
/// The elastic crank train of a scene's `[crankshaft]` in Simbody (docs/CONVENTIONS-crankcheck.md, "Torsion"), never using
/// the analytic formulas: each throw a crankshaft body of its own on a pin about Z from Ground (its cylinders' crank
/// pins, point masses and counterweights as KCrankModel's crankshaft, plus J_t as a disk), its cylinders' pistons and
/// rods closed on its pins as in KCrankModel; the front mass a disk on its own pin; the sections torsional springs and
/// dampers between neighbours (a Force::Custom on the pins' mobilities), the last one to the flywheel driven at
/// omega t; each throw's damping about omega; gravity and the gas (at the throw's own angle) as in KCrankModel.
///
/// The periodic steady state: started from the rigid motion at t = 0 (every pin at 0 turning at omega, the rods and
/// pistons assembled), integrated (RungeKuttaMerson, every probe and sample an integrated state) cycle by cycle by every
/// engine's one policy (crankcheck/solver/periodic_run.h): at 1000 x `accuracy` until the deviations psi_i - omega t and
/// their rates at a cycle's start change by less than 1000 x periodicity of the largest deviation over the cycle, then at
/// `accuracy` until they change by less than `periodicity`; from the 4th cycle at one accuracy on, the run is moved to
/// the extrapolated fixed point of its last cycle starts (the pins locked at the extrapolated angles and rates, the
/// pistons and rods assembled to them, as at t = 0); then one more cycle sampled at `samples` equal steps. Measured on
/// the gate's cases (tests/gate/torsion_test.cc): the example four at 6000 rpm 10 cycles, 7.7 s (22 cycles, 11.8 s run
/// out without the extrapolation, the accuracy staged a decade at a time); at 5450 rpm 10 cycles, 8.3 s (20, 11.0 s);
/// the marine six at 105 rpm, whose first mode is damped 2 %, 13 cycles, 5.1 s (69, 15.8 s). The cycle-to-cycle change at accuracy 1e-10
/// stops falling at about 1e-7 of the twist (the integration's own error per cycle, the example four at 6000 rpm), hence
/// `periodicity` 1e-6 by default; the twists then agree with the analytic engine's exact steady state to 1.4e-7 of the
/// twist scale.

#include <vector>

#include "crankcheck/solver/crank_train_run.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::simbody_models {

/// Simbody's defaults of CrankTrainRunOptions' fields left at 0.
inline constexpr double kCrankTrainAccuracy = 1e-10;     ///< the integrator's accuracy (relative error per step)
inline constexpr double kCrankTrainPeriodicity = 1e-6;   ///< the cycle-to-cycle change, relative to the twist
/// The work limit (CrankTrainRunOptions::max_steps): 3e5 integrator steps, about 2 min at 0.37 ms a step (the example
/// four), 16 x the gate's largest run (18492 steps, the four at 5450 rpm).
inline constexpr long long kCrankTrainMaxSteps = 300'000;

/// @throws std::invalid_argument if the scene has no [crankshaft] or speed, or is not one Simbody builds (a massless
///         rod, KCrankModel); std::runtime_error if the run has not become periodic in max_cycles cycles. Options at 0: the defaults
///         above.
CrankTrainRun simulateCrankTrainSteadyState(const Mechanism& m, const CrankTrainRunOptions& options = {});

}  // namespace crankcheck::simbody_models
