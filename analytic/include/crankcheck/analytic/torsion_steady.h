#pragma once
/// @file
/// The exact periodic steady state of the elastic crank train (docs/CONVENTIONS-crankcheck.md, "Exact"): the full nonlinear
/// equations of crank_train.h (each throw's variable inertia J_t + J_j(psi_j) and its J_j' psi_j'^2 term, the gas and
/// gravity torques at the throw's own angle, the sections' springs and dampers, the throws' absolute damping), the
/// flywheel driven at omega t, over one working cycle.
///
/// Method: shooting on the one-cycle map. With s = omega t and y = (x, dx/ds) the state at s = 0, P(y) is the state
/// after one cycle (Boost.Odeint's Dormand-Prince 5(4), error per step below `tolerance` relative and `tolerance` x
/// the twist scale absolute); Newton's method solves P(y) = y, the Jacobian dP/dy from the variational equations
/// integrated beside the state at 1e-5 (a Newton step needs it only roughly; the residual is always the accurate
/// map's) and kept while each step cuts the residual at least tenfold (computed anew at the current start otherwise).
/// Start: Holzer's response at s = 0 (torsion_forced.h). Converged when the periodicity residual is below 1000 x
/// `tolerance` of the twist scale (the largest deviation |x| of Holzer's response): the map's own
/// accuracy (measured on the example inline four at 6000 rpm: P at 1e-11 and at 1e-14 differ by 1e-9 of the scale).
/// Runge-Kutta-Fehlberg 7(8) was tried first and rejected: its error estimate vanishes on the part of the equations
/// that depends on time alone (the forcing), and its map at 1e-10 was off by 5e-6 of the scale.
/// The twist over the cycle then comes from `samples` equally spaced states of the periodic orbit (each reached by the
/// integrator exactly), expanded by FFT (order amplitudes) and its extremes refined on that series (crank_train.h):
/// from Newton's second iteration on, the run that measures the residual is that sampled run, so the converged
/// one is the orbit reported (about 0.8 x the time of integrating it again).

#include <vector>

#include <Eigen/Dense>

#include "crankcheck/analytic/crank_train.h"
#include "crankcheck/analytic/torsion_forced.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::analytic {

struct SteadyStateOptions {
  double tolerance = 1e-11;  ///< the integrator's error per step, relative (and absolute x the twist scale)
  /// States per cycle for the twist's series (even). The series of N samples aliases what lies above N / 2: measured on
  /// the example four at 3000 rpm, 2048 samples put a small section's peak-to-peak (the front's) 2.4e-7 off its value,
  /// 8192 within 1e-8 (16384 agrees).
  int samples = 8192;
  /// The work limit: evaluations of the train's equations in all (every cycle run, the Jacobians' variational runs,
  /// the error bound's run), past which the state is refused (std::runtime_error) instead of run unbounded. 1e8, about
  /// a minute: 175 x the most the example scenes take over the torsion part's speeds (5.7e5 on the four at 1500 rpm, tolerance
  /// 1e-11; 1.4e5 on the marine six at 105 rpm; at most 1.2e5 at the report's 1e-8), enough for the shafts too stiff
  /// for this route's cost and not stiff enough for the stiff limit's accuracy (the explicit steps follow the highest
  /// natural frequency: their cost grows as sqrt(K); the example four at 1e5 x its stiffness).
  long long max_evaluations = 100'000'000;
};

struct ExactSteadyState {
  Eigen::VectorXd x0;        ///< [rad] the bodies' deviations at t = 0 on the periodic orbit
  Eigen::VectorXd x_dot0;    ///< [rad/s] their rates at t = 0
  std::vector<PeriodicSignal> bodies;  ///< body i's deviation over the cycle phase tau = 2 pi omega t / cycle
  std::vector<PeriodicSignal> twists;  ///< section i's twist [rad] over tau
  std::vector<double> peak_to_peak;    ///< [rad] per section
  int newton_iterations = 0;
  double residual = 0.0;     ///< max |P(y) - y| of the last step, in units of the twist scale
  double twist_scale = 0.0;  ///< [rad] the largest |x| of Holzer's response (the residual's unit)
  long steps = 0;            ///< the integrator's steps over the last cycle
  long long evaluations = 0; ///< of the train's equations, in all (SteadyStateOptions::max_evaluations)
  /// [rad] max over sections of |peak-to-peak reported - peak-to-peak of a run at 100 x `tolerance` from a start three
  /// times as far from the periodic orbit (y0 - 2 delta, delta the Newton step the last residual asks for)|: a bound on
  /// both the integration's part of the error (the looser run's; the accurate run is closer) and the periodicity's (to
  /// first order twice the reported orbit's). The looser run takes the steps its own error control chooses and reads
  /// the samples off its dense output (at step ends it took the samples' spacing wherever that was below its steps:
  /// the same computation as the accurate run, and from the same start the "bound" read 0 on the marine six).
  double error_bound = 0.0;
};

/// @throws std::invalid_argument as makeCrankTrain or calcHolzerResponse;
///         std::runtime_error (checkHolzerTwist, torsion_domain.h) if Holzer's response twists a section beyond
///         kMaxShaftTwist: outside the domain, not computed; std::runtime_error if Newton's method has not converged in 30 iterations (a steady state that does not
///         exist or is unstable: the shaft's twist running away, or the speed not kept).
ExactSteadyState calcExactSteadyState(const Mechanism& m, const SteadyStateOptions& options = {});

/// The same from Holzer's response already computed (calcHolzerResponse of m at any convergence: it starts Newton's
/// method and sets the twist scale), so that a caller who shows Holzer's response does not compute it twice.
/// @throws std::invalid_argument if `holzer` has another number of bodies; otherwise as above.
ExactSteadyState calcExactSteadyState(const Mechanism& m, const HolzerResponse& holzer,
                                      const SteadyStateOptions& options = {});

/// What calcExactSteadyState(m, holzer, options) costs, estimated before it (`crankcheck torsion`'s work limit,
/// validation/commands/torsion.h).
struct SteadyStateWork {
  /// The stiff-limit route answers: `seconds` and `evaluations` are its own, measured.
  bool stiff_limit = false;
  /// The accurate integrator's steps per cycle on the explicit route, from the probe (infinite when the probe's
  /// evaluations took no step: a damping or stiffness beyond any explicit step). The engines' own trains run the
  /// same equations by explicit integrators: their steps follow the same rates.
  double steps_per_cycle = 0.0;
  double evaluations = 0.0;  ///< of the train's equations in all, estimated
  double seconds = 0.0;      ///< [s] on this machine: evaluations x the probe's measured cost of one
};

/// The cycles' worth of the accurate run's evaluations a steady state takes by shooting: the Newton iterations' runs,
/// the Jacobian's variational run (dearer by the evaluation, fewer steps at its 1e-5) and the error bound's looser
/// run. Measured on the example four and the marine six at their speeds, and on the four with throw_damping 1e3 to
/// 1e6: 2.2 to 5.2 cycles in evaluations, 2.8 to 7.6 in time (the whole computation against the probe's cost of a
/// cycle; the Jacobian's evaluations cost more); 8 covers them (tests/analytic/torsion_steady_test.cc, SteadyStateWork).
inline constexpr double kShootingCycles = 8.0;

/// The work of calcExactSteadyState(m, holzer, options), estimated from a probe of the same equations: the accurate
/// integrator over four slices of 1/32 of the cycle each, spread over it, from Holzer's state at each slice's start,
/// at most 2e5 evaluations (a few ms; where they run out, the part of a slice covered counts), its evaluations per
/// cycle x kShootingCycles at its measured cost of one evaluation. On the stiff-limit route (where it answers) the
/// route itself is run and timed. An estimate, not a bound: a resonance that takes Newton more iterations costs more.
/// @throws std::invalid_argument as calcExactSteadyState for options or a Holzer response that do not fit the scene.
SteadyStateWork estimateExactSteadyStateWork(const Mechanism& m, const HolzerResponse& holzer,
                                             const SteadyStateOptions& options = {});

}  // namespace crankcheck::analytic
