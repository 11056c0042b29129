#include "part_math.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/campaign_scenes.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/table.h"
#include "crankcheck/validation/task.h"
#include "crankcheck/validation/extremum.h"
#include "crankcheck/validation/scales.h"

namespace crankcheck::validation {

using analytic::Eq5Form;
using analytic::LambdaSource;

// The crank ratio (part_math.h).
double lambdaOf(const Mechanism& m) { return calcCrankRatio(m); }

// ------------------------------------------------------------------------------------------------------------
// The helpers of the parts' computations (part_math.h): maxima over a turn that do not depend on the grid
// (extremum.h), from the exact harmonics where Q is concerned.

// Q's harmonics with exact Lambda_n up to this order: the tail beyond is below q^100 ~ 1e-28 of Q up to lambda = 0.95
// (q = (lambda / (1 + sqrt(1 - lambda^2)))^2, fourier_series.h).
constexpr int kExactOrder = 200;

std::vector<analytic::TorqueHarmonic> exactHarmonics(const Mechanism& m, Eq5Form form) {
  return analytic::calcGravityTorqueHarmonics(m, kExactOrder, LambdaSource::kExact, form);
}

// The harmonics above `order`: minus the error of the series truncated there (no cancellation: each term is its own
// size, so the error is exact to rounding however small).
std::vector<analytic::TorqueHarmonic> harmonicsAbove(const std::vector<analytic::TorqueHarmonic>& h, int order) {
  std::vector<analytic::TorqueHarmonic> out;
  for (const analytic::TorqueHarmonic& x : h)
    if (x.n > order) out.push_back(x);
  return out;
}

// a - b, harmonic by harmonic.
std::vector<analytic::TorqueHarmonic> harmonicsMinus(const std::vector<analytic::TorqueHarmonic>& a,
                                                     const std::vector<analytic::TorqueHarmonic>& b) {
  std::map<int, analytic::TorqueHarmonic> by_n;
  for (const auto& x : a) by_n[x.n] = x;
  for (const auto& x : b) {
    analytic::TorqueHarmonic& y = by_n[x.n];
    y.n = x.n;
    y.cos_coefficient -= x.cos_coefficient;
    y.sin_coefficient -= x.sin_coefficient;
  }
  std::vector<analytic::TorqueHarmonic> out;
  for (const auto& [n, x] : by_n) out.push_back(x);
  return out;
}

namespace {

// The highest order of a sum of harmonics that is at least 1e-3 of the largest (a hump of a smaller one cannot move the
// maximum by more than its own size); samples enough for its maximum: 8 per period of that order, at least 72 (5 deg).
int findHighestOrder(const std::vector<analytic::TorqueHarmonic>& h) {
  double largest = 0.0;
  for (const auto& x : h) largest = std::max(largest, std::hypot(x.cos_coefficient, x.sin_coefficient));
  int highest = 1;
  for (const auto& x : h)
    if (std::hypot(x.cos_coefficient, x.sin_coefficient) >= 1e-3 * largest) highest = std::max(highest, x.n);
  return highest;
}
int samplesFor(const std::vector<analytic::TorqueHarmonic>& h) { return std::max(72, 8 * findHighestOrder(h)); }

}  // namespace

double maxAbsOfHarmonics(std::vector<analytic::TorqueHarmonic> h) { return findMaxAbsOfHarmonics(std::move(h)).value; }

TurnMaximum findMaxAbsOfHarmonics(std::vector<analytic::TorqueHarmonic> h, int refinements) {
  // Harmonics below 1e-18 of the largest cannot move the maximum above rounding (at most 100 of them): left out.
  double largest = 0.0;
  for (const auto& x : h) largest = std::max(largest, std::hypot(x.cos_coefficient, x.sin_coefficient));
  std::erase_if(h, [&](const analytic::TorqueHarmonic& x) { return !(std::hypot(x.cos_coefficient, x.sin_coefficient) >= 1e-18 * largest); });
  if (h.empty() || largest == 0.0) return {};
  if (refinements <= 0) refinements = 2 * findHighestOrder(h) + 2;  // every hump of |sum|
  return findMaxAbsOverTurn([&h](double phi) { return analytic::evaluateTorqueHarmonics(h, phi); }, samplesFor(h),
                            refinements);
}

// A maximum of a difference computed in double carries an error up to the agreement tolerance (64 eps x scale x
// conditioning, the worst rounding either engine shows); it is known to 1 % only above 100 times that. Below, the
// number is a bound (the quantity is at rounding level), not a measured maximum.
bool resolvedToOnePercent(double rel_value, double conditioning) {
  return rel_value > 100.0 * kAgreementMultiple * kEps * conditioning;
}

// The samples of a turn for quantities that hold harmonics up to about n: 6 per period (3 per hump of |f|), at least 48.
int samplesForOrder(int n) { return std::max(48, 6 * n); }

Mechanism findMarineScene() {
  for (const Mechanism& m : buildDefaultScenes())
    if (m.name.rfind("marine", 0) == 0) return m;
  throw std::logic_error("campaign: no built-in marine scene");
}

}  // namespace crankcheck::validation
