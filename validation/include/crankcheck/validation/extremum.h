#pragma once
/// @file
/// The largest value of a periodic function over one crank turn, found so that it does not depend on the sampling
/// grid: the function is sampled at evenly spaced angles, and the best sampled local maxima are refined by Brent's
/// method (golden section with parabolic steps) on the two grid cells around each. Every "max over a turn" of the
/// report is found this way, for every engine alike (the parts error_vs_lambda, speed_vs_error, gravity_significance, errata, rod_models).

#include <functional>
#include <vector>

namespace crankcheck::validation {

/// A maximum over a turn.
struct TurnMaximum {
  double value = 0.0;  ///< the largest |f| found (>= every sample)
  double phi = 0.0;    ///< [rad] where, in [0, 2 pi)
};

/// Brent's angle tolerance [rad] of the full campaign: a smooth maximum's value exact to rounding.
inline constexpr double kFineAngleTolerance = 1e-10;

/// Brent's angle tolerance [rad] of a campaign: kFineAngleTolerance in the full one; 1e-6 in the quick one (a smoke
/// run), at 16-41 % fewer evaluations of the engines in the parts that refine (gravity_significance's engine max |Q|, the pin loads,
/// the pin offset, the rod models), a smooth maximum moving by at most 1e-13 relative, one at a kink by up to 3.1e-7
/// (bench/README.md, "The quick campaign's angle tolerance").
inline double getAngleTolerance(bool quick) { return quick ? 1e-6 : kFineAngleTolerance; }

/// max over phi in [0, 2 pi) of |f(phi)|, f 2 pi periodic. `samples` (>= 3) evenly spaced angles, then each of the
/// `refinements` largest sampled local maxima of |f| is refined by Brent's method on [phi_{i-1}, phi_{i+1}] to an
/// angle tolerance of `tolerance` [rad] (at 1e-10 the value of a smooth maximum is exact to rounding). The result does
/// not depend on the grid as long as the grid puts at least one sample on the hump that holds the maximum, i.e. has
/// at least 3 samples per period of the highest harmonic that matters. Costs samples + about 30 x refinements
/// evaluations of f (about 20 at 1e-6). @throws std::invalid_argument if samples < 3, refinements < 0 or
/// tolerance <= 0.
TurnMaximum findMaxAbsOverTurn(const std::function<double(double)>& f, int samples, int refinements = 4,
                               double tolerance = kFineAngleTolerance);

/// The same from samples already taken: values[i] = f(2 pi i / values.size()) (at least 3), so that a caller that
/// needs the samples anyway (a table over the turn) evaluates f only for the refinement.
TurnMaximum findMaxAbsOverTurn(const std::function<double(double)>& f, const std::vector<double>& values,
                               int refinements = 4, double tolerance = kFineAngleTolerance);

/// max |f| over [a, b] by Brent's method (f unimodal in |f| there), never below max(|f(a)|, |f(b)|).
/// Hand-written (Brent's localmin) rather than Boost.Math's brent_find_minima, measured on a full campaign: Boost caps
/// its stopping tolerance at half of double's digits (2^-25 of the angle), which moved the report's smooth maxima by up
/// to 2e-8 relative (Norton's x_p error) and 1.2e-9 (a bearing force); this one stops at `tolerance` [rad] and gives
/// them to rounding.
TurnMaximum refineMaxAbs(const std::function<double(double)>& f, double a, double b,
                         double tolerance = kFineAngleTolerance);

}  // namespace crankcheck::validation
