#pragma once
/// @file
/// The free run in Simbody: the mechanism of KCrankModel with the crankshaft free (carrying the flywheel inertia
/// I_w), released at phi = 0 with speed omega0 and integrated by one of Simbody's integrators, with gravity on or
/// off. Nothing analytic enters: Simbody's own dynamics move the crank. No Simbody header here.

#include <string>
#include <vector>

#include "crankcheck/solver/free_run.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::simbody_models {

enum class IntegratorKind {
  kRungeKuttaMerson,    ///< explicit, 4th order with error control
  kCPodes,              ///< implicit multistep (BDF) with projection
  kSemiExplicitEuler2,  ///< first-order symplectic-like, with error control
};
std::string toString(IntegratorKind kind);  ///< "RungeKuttaMerson", "CPodes", "SemiExplicitEuler2"

struct FreeRunOptions {
  IntegratorKind integrator = IntegratorKind::kRungeKuttaMerson;
  double accuracy = 1e-10;            ///< the integrator's relative accuracy (Integrator::setAccuracy)
  int revolutions = 2;                ///< how far to integrate; every internal step is recorded
  bool gravity = true;
  /// The flywheel run (crankcheck flywheel): the scene's gas forces on the pistons and a constant load torque
  /// against the crank; delta and the energy's return are then measured over the first working cycle (720 degrees
  /// four-stroke, 360 two-stroke) instead of the first revolution, and `revolutions` must cover it.
  bool gas = false;
  double load_torque = 0.0;           ///< [N m]
  /// The most internal steps the integrator may take per revolution: a run that needs more is refused (a
  /// std::runtime_error naming the limit) rather than left to run for hours. The example scenes take about 400 per
  /// revolution at accuracy 1e-10; a scene whose masses or inertias differ by many orders (a 1e-12 kg piston on a
  /// 1e6 m rod) makes the system so stiff that the explicit integrators' steps shrink without end.
  int max_steps_per_revolution = 20000;
};

/// What the run found (crankcheck/solver/free_run.h: the same for every engine's free run).
using FreeRunResult = ::crankcheck::FreeRunResult;

/// @throws std::invalid_argument if omega0 <= 0, the scene has no flywheel inertia, or the rod is massless;
///         std::runtime_error if Simbody fails or the crank does not complete the revolutions.
FreeRunResult simulateFreeRun(const Mechanism& m, double omega0, const FreeRunOptions& options = {});

}  // namespace crankcheck::simbody_models
