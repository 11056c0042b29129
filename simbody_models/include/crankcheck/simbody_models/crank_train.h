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
/// pistons assembled), integrated (RungeKuttaMerson) cycle by cycle, first at 1000 x `accuracy`, then a decade tighter
/// each time the deviations psi_i - omega t and their rates at the start of a cycle change by less than
/// periodicity / accuracy times the accuracy in use (of the largest deviation seen over that cycle), down to `accuracy`,
/// until they change by less than `periodicity`; then one more cycle sampled at `samples` equal steps. The stages keep
/// the run's own error per cycle (about 1000 x its accuracy) a tenth of the change it measures, at a fraction of the
/// cost of the whole transient at `accuracy`: the marine six 15.7 s against 24.8 s with one loose stage (and 40.7 s
/// with none), the agreement with the analytic steady state 4e-8 of the twist scale (1.1e-7 on the example four). The
/// time of the transient is the shaft's lightest damping's: about 1 / (zeta w) per mode. At accuracy 1e-10 the
/// cycle-to-cycle change stops falling at about 1e-7 of the twist (the integration's own error per cycle, measured on
/// the example four at 6000 rpm), hence `periodicity` 1e-6 by default: 22 cycles there, about 11 s; the peak-to-peak
/// twists then agree with the analytic engine's exact
/// steady state to 4e-7 (tests/gate/torsion_test.cc).

#include <vector>

#include "crankcheck/scene/crank_train_run.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::simbody_models {

/// Simbody's defaults of CrankTrainRunOptions' fields left at 0.
inline constexpr double kCrankTrainAccuracy = 1e-10;     ///< the integrator's accuracy (relative error per step)
inline constexpr double kCrankTrainPeriodicity = 1e-6;   ///< the cycle-to-cycle change, relative to the twist

/// @throws std::invalid_argument if the scene has no [crankshaft] or speed, or is not one Simbody builds (a massless
///         rod, KCrankModel); std::runtime_error if the run has not become periodic in max_cycles cycles. Options at 0: the defaults
///         above.
CrankTrainRun simulateCrankTrainSteadyState(const Mechanism& m, const CrankTrainRunOptions& options = {});

}  // namespace crankcheck::simbody_models
