#pragma once
/// @file
/// A run of the crank through time, as samples: what every time-stepped run returns or hands in (a free run of an
/// engine, a stepped engine's run free or held at speed with the quantities it reports, a user's program's run in the
/// time-stepped grade), and how it is read between its samples. Plain values, no engine behind them; validation/run_measures.h judges a trajectory against the exact run.
///
/// The reading: local Lagrange interpolation of degree 5 (the six samples around the instant) of phi(t) and,
/// separately, of omega(t) at omega's own instants, so that a run's own integration error is measured rather than the
/// reading's: on a smooth run the reading's error falls as the step to the sixth power. A phase phi* is reached at the
/// time where the interpolated phi(t) equals phi* (TOMS 748 between the two samples that bracket it).
///
/// The start: a run that integrates from a state it is given returns the samples it made. An engine that simulates
/// (Engine::simulate) records its initial state, so its first sample is the release (t = 0). An engine that steps
/// (Engine::step_at_speed, Engine::step_free) returns one sample per step, the first at t = dt: the start was handed
/// in by the caller, who prepends it where a measure needs it (validation/engine_runs.h withRelease). A user's
/// program's run starts at its own first sample, which the time-stepped grade requires at t = 0.

#include <string>
#include <vector>

#include "crankcheck/scene/evaluation.h"
#include "crankcheck/scene/quantities.h"

namespace crankcheck {

/// Where within its step a stepped engine's value belongs: 0 the step's start, 1 its end, 0.5 its middle; outside
/// [0, 1] where the engine's value is best read there (Box2D's impulses: -0.5, half a step before the start).
struct QuantityInstant {
  QuantityId quantity;
  double step_fraction = 0.0;
};

/// A run, as samples.
struct Trajectory {
  std::vector<double> time;   ///< [s], strictly increasing
  std::vector<double> phi;    ///< [rad] the crank angle (the scene's convention), unwrapped and strictly increasing
  std::vector<double> omega;  ///< [rad/s] the crank speed
  /// true: omega[i] stands at time[i] - (time[i] - time[i-1]) / 2 (a backward difference, as many game and engine
  /// simulators store it; omega[0] is then not used), not at time[i].
  bool omega_half_step_behind = false;
  /// When not empty: the instant each omega stands at [s] (strictly increasing, as many as omega), in place of time and
  /// of omega_half_step_behind (a run that says at which time each value stands).
  std::vector<double> omega_time;
  double seconds_per_step = 0.0;  ///< [s] an engine's wall time of its stepping and reads, divided by its steps (0: untimed)

  /// A run that reports more than the crank's motion (a stepped engine's run held at its speed): the quantities it
  /// reports and where each belongs within its step, the same for every step (empty: only phi and omega).
  std::vector<QuantityInstant> reported;
  /// One per sample: the step that ends at sample i, its reported quantities in an Evaluation's fields (every other
  /// field NaN), each belonging to phi_start + step_fraction (phi[i] - phi_start), phi_start the previous sample's phi
  /// (for the first step, the run's start). Empty where `reported` is.
  std::vector<Evaluation> values;
  /// [m] One per sample where `values` is: the largest separation, at the step's end, of a joint the engine holds by
  /// constraint (a pin's anchor as each of its two bodies carries it, a piston off its line): how far the engine
  /// leaves the loops open. NaN: the engine closes them by construction.
  std::vector<double> loop_error;
};

/// A run read between its samples (the interpolation above). Keeps a reference to the run: the run must outlive it.
class TrajectoryReader {
 public:
  /// @throws std::invalid_argument if omega_time is given but is not as long as omega, finite and strictly increasing.
  explicit TrajectoryReader(const Trajectory& run);
  double findPhi(double t) const;    ///< [rad] phi at time t [s]
  double findOmega(double t) const;  ///< [rad/s] omega at time t, read at omega's own instants
  /// [s] The time at which phi reaches `phase` [rad] (within [phi.front(), phi.back()]; the first or last sample's time
  /// outside it).
  double findTimeAtPhase(double phase) const;
  double findOmegaAtPhase(double phase) const { return findOmega(findTimeAtPhase(phase)); }

 private:
  const Trajectory& run_;
  std::vector<double> omega_time_, omega_;
};

/// Checks that `v` is finite and strictly increasing.
/// @throws std::invalid_argument "WHO: WHAT[i] is not finite" or "WHO: WHAT is not strictly increasing at sample i".
void checkStrictlyIncreasing(const std::vector<double>& v, const char* what, const char* who);

}  // namespace crankcheck
