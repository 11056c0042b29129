#pragma once
/// @file
/// What an engine's elastic crank train reports (Engine::simulate_crank_train, crankcheck/solver/engine.h): the periodic
/// steady state of a scene's `[crankshaft]` train (docs/CONVENTIONS-crankcheck.md, "Torsion"), the flywheel driven at the
/// scene's omega, sampled over one working cycle. Plain values, no engine behind them.

#include <vector>

namespace crankcheck {

/// How to run. Each field at 0 means the engine's own default (Engine::crank_train_method says what its accuracy
/// means and what it is by default).
struct CrankTrainRunOptions {
  double accuracy = 0.0;     ///< the integration's accuracy in the engine's sense (relative error per step)
  double periodicity = 0.0;  ///< the cycle-to-cycle change at which a run is periodic, relative to the twist
  /// Equally spaced samples of the cycle (even). 1024 give the twist over the cycle; a peak-to-peak read from them
  /// (through their Fourier series) carries their aliasing: 1e-5 of a small section's value on the example four at
  /// 3000 rpm, 2e-7 with 8192 (`crankcheck torsion` asks the exact routes for 8192). A soft route at a fixed step
  /// needs at least as many steps a cycle as samples.
  int samples = 1024;
  int max_cycles = 2000;     ///< refused beyond (a train too lightly damped to settle)
  /// The work limit: the integrator's steps in all, refused beyond (std::runtime_error naming it) instead of run
  /// unbounded (a shaft so stiff that the step falls with its fastest mode). 0: the engine's default (Simbody 3e5,
  /// MuJoCo 4e6: periodic_run.h kCrankTrainMaxSteps).
  long long max_steps = 0;
};

struct CrankTrainRun {
  /// Section i's twist [rad] (CONVENTIONS: psi_b - psi_a, the last omega t - psi_{n-1}) at t_k = t0 + k T / samples,
  /// k = 0 .. samples - 1, over one cycle of the periodic state (omega t0 a multiple of the cycle angle).
  std::vector<std::vector<double>> twists;
  int cycles = 0;             ///< cycles run before the sampled one (0 for a shooting method)
  double cycle_change = 0.0;  ///< the last cycle-to-cycle change (or periodicity residual), relative to the twist
  long long steps = 0;        ///< the integrator's steps in all
};

}  // namespace crankcheck
