#pragma once
// What the report parts' computations (parts/*.cc) share: maxima over a turn from Q's exact harmonics (found so that
// they do not depend on the grid: extremum.h), the resolution rule of a maximum at rounding level, the sampling of a
// turn, the built-in marine scene.

#include <vector>

#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/campaign_scenes.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/table.h"
#include "crankcheck/validation/task.h"
#include "crankcheck/validation/extremum.h"

namespace crankcheck::validation {

/// [-] The crank ratio lambda = r / l of m's parts.
double lambdaOf(const Mechanism& m);

/// Q's harmonics [N m] with exact Lambda_n up to order 200: the tail beyond is below q^100 ~ 1e-28 of Q up to
/// lambda = 0.95 (q = (lambda / (1 + sqrt(1 - lambda^2)))^2, fourier_series.h).
std::vector<analytic::TorqueHarmonic> exactHarmonics(const Mechanism& m,
                                                     analytic::Eq5Form form = analytic::Eq5Form::kDerived);

/// The harmonics above `order`: minus the error of the series truncated there (no cancellation: each term is its own
/// size, so the error is exact to rounding however small).
std::vector<analytic::TorqueHarmonic> harmonicsAbove(const std::vector<analytic::TorqueHarmonic>& h, int order);

/// a - b, harmonic by harmonic.
std::vector<analytic::TorqueHarmonic> harmonicsMinus(const std::vector<analytic::TorqueHarmonic>& a,
                                                     const std::vector<analytic::TorqueHarmonic>& b);

/// The maximum of |sum of harmonics| over a turn (in the harmonics' unit), found so that it does not depend on the grid
/// (extremum.h: every hump refined, findMaxAbsOfHarmonics); 0 for no harmonics.
double maxAbsOfHarmonics(std::vector<analytic::TorqueHarmonic> h);
/// The same with where it is: the largest |sum of harmonics| over a turn and its angle [rad] in [0, 2 pi); {0, 0} for
/// no harmonics (or all zero). `refinements`: how many of the best sampled humps are refined (extremum.h); 0 (the
/// default): every hump, 2 x the highest order that matters + 2. A truncation's remainder has many humps of nearly one
/// height (its first harmonic's, moved by a few percent by the next), and 8 samples a period read a hump up to 8 %
/// low, so the 4 best sampled need not hold the largest (refining 4 found an order-12 remainder up to 0.7 % low).
TurnMaximum findMaxAbsOfHarmonics(std::vector<analytic::TorqueHarmonic> h, int refinements = 0);

/// A maximum of a difference computed in double carries an error up to the agreement tolerance (64 eps x scale x
/// conditioning, the worst rounding either engine shows); it is known to 1 % only above 100 times that.
/// @param rel_value [-] the maximum relative to its scale. @return false: the number is a bound, not a measured maximum.
bool resolvedToOnePercent(double rel_value, double conditioning = 1.0);

/// The samples of a turn for quantities that hold harmonics up to about n: 6 per period (3 per hump of |f|), at least 48.
int samplesForOrder(int n);

/// The built-in marine engine (buildDefaultScenes): the second engine of the torque split and rod model parts.
Mechanism findMarineScene();

}  // namespace crankcheck::validation
