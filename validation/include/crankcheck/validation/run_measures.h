#pragma once
/// @file
/// Measures of a time-stepped run of the crank train: a program steps the mechanism through time (a free run under
/// gravity alone: no gas, no drive, no load) and hands back its samples; these functions judge them against the exact
/// free run of analytic/motion.h (the energy integral (1/2) J(phi) phi_dot^2 + U(phi) = E).
/// The run is a Trajectory, read between its samples as solver/trajectory.h says.

#include <vector>

#include "crankcheck/scene/mechanism.h"
#include "crankcheck/solver/trajectory.h"

namespace crankcheck::validation {

/// What acts on the crank in the run besides gravity.
struct RunLoad {
  /// false: nothing (a free run; the scene must have no [gas]; the measures' period is a revolution). true: the scene's
  /// gas pressure on the pistons and a constant load torque against the crank equal to the gas torque's cycle mean
  /// (gas_work.h), so that the exact run is periodic over the working cycle (4 pi four-stroke, 2 pi two-stroke), the
  /// measures' period; its invariant is E - W(phi) + T_L phi.
  bool gas = false;
};

/// The fewest samples a run may have (the interpolation's six, and one more for a half-step-behind omega).
inline constexpr int kMinRunSamples = 8;
/// The most steps a time-stepped run may be asked to take (its smallest --dt over the run): 1e9, a thousand times the
/// default step of 100 revolutions (7.2e4), and seconds to minutes for a program at tens of nanoseconds a step.
inline constexpr double kMaxRunSteps = 1e9;

/// [1 / revolution] The energy's trend: E = (1/2) J(phi) omega^2 + U(phi) at each crossing of phi = phi(0) + 2 pi k
/// (k = 0, 1, ..., the run read at that phase and omega at the same instant), the least-squares slope of E_k against k,
/// relative to E_0. At a fixed phase the run's sampling (and a half-step-behind omega) does not show as an oscillation
/// of E; only the loss or gain per revolution does.
/// @throws std::invalid_argument if the run is malformed (sizes differ, fewer than kMinRunSamples, NaN, time or phi not
///         strictly increasing), the scene has no flywheel inertia, or the run is shorter than one revolution.
double calcEnergyTrend(const Mechanism& m, const Trajectory& run, const RunLoad& load = {});
/// The energies E_k [J] that calcEnergyTrend fits, k = 0, 1, ... (every crossing of phi(0) + 2 pi k within the run).
/// @throws std::invalid_argument as calcEnergyTrend.
std::vector<double> calcEnergyAtTurns(const Mechanism& m, const Trajectory& run, const RunLoad& load = {});
/// The energy E_i [J] at each sample (its phi and its omega read at the sample's time), the run under gravity alone:
/// what `crankcheck motion` reports the drift of for an engine that has no energy of its own.
/// @throws std::invalid_argument if the run is malformed (as calcEnergyTrend) or the scene has no flywheel inertia.
std::vector<double> calcEnergyAtSamples(const Mechanism& m, const Trajectory& run);

/// The speed's fluctuation over one revolution.
struct SpeedFluctuationOfRun {
  double delta = 0.0;             ///< (omega_max - omega_min) / omega_mean [-]
  double phi_at_omega_max = 0.0;  ///< [rad] in [0, 2 pi)
  double phi_at_omega_min = 0.0;  ///< [rad] in [0, 2 pi)
  double omega_min = 0.0, omega_max = 0.0;  ///< [rad/s] the extremes
  double omega_mean = 0.0;        ///< [rad/s] the revolution's angle over its duration
};

/// The run's fluctuation against the exact free run's.
struct SpeedFluctuationComparison {
  SpeedFluctuationOfRun run;    ///< over the run's first revolution, phi(0) to phi(0) + 2 pi: the extremes of the
                                ///< interpolated omega refined by Brent's method, omega_mean = 2 pi / its duration
  SpeedFluctuationOfRun exact;  ///< calcFreeRun released at phi = 0 with the run's omega at its first phi = 0 (mod 2 pi)
  double omega_at_zero = 0.0;   ///< [rad/s] that release speed
  double delta_error = 0.0;     ///< run.delta - exact.delta [-]
  /// [rad] run's - exact phi at omega_max, wrapped to (-pi, pi]: against the nearest phase where the exact run's speed
  /// has a local maximum within the run's own speed error of omega_max (the larger of |delta_error| x omega_mean and
  /// the run's change of speed over the revolution, at least 64 eps x omega_max): a centric standing single has two
  /// equal extremes, at phi and -phi, and a run that loses energy is fastest where it starts)
  double phi_max_error = 0.0;
  double phi_min_error = 0.0;   ///< [rad] the same for omega_min
};

/// The speed fluctuation of the run's first revolution and of the exact free run.
/// @throws std::invalid_argument as calcEnergyTrend; std::domain_error if the exact free run does not complete a
///         revolution at that release speed.
SpeedFluctuationComparison calcSpeedFluctuation(const Mechanism& m, const Trajectory& run, const RunLoad& load = {});

/// [rad] phi_run(horizon) - phi_exact(horizon): phi_run read at time `horizon` [s] (a time of the run, between its first
/// and its last sample), phi_exact the free run through the run's first state (phi(0), and omega read at time(0)),
/// from the energy integral t(phi) = integral of dphi / phi_dot(phi): one turn's time times the whole turns plus the
/// rest (Gauss-Kronrod quadrature), inverted by TOMS 748.
/// @throws std::invalid_argument if the run is malformed (as calcEnergyTrend), the scene has no flywheel inertia, or
///         horizon is outside [time.front(), time.back()]; std::domain_error if the exact run does not turn over.
double calcPhaseError(const Mechanism& m, const Trajectory& run, double horizon, const RunLoad& load = {});
/// calcPhaseError at each of `horizons` (the exact run's quadrature set up once).
std::vector<double> calcPhaseErrors(const Mechanism& m, const Trajectory& run, const std::vector<double>& horizons,
                                    const RunLoad& load = {});

/// The observed order of convergence: the least-squares slope of log|error| against log(step).
/// @throws std::invalid_argument if the sizes differ, there are fewer than 2 points, a step is not finite and > 0, an
///         error is not finite or is 0, or the steps are all equal.
double calcObservedOrder(const std::vector<double>& steps, const std::vector<double>& errors);

}  // namespace crankcheck::validation
