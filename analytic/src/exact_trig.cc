#include "crankcheck/analytic/exact_trig.h"

#include <cmath>
#include <limits>

namespace crankcheck::analytic {

SinCos calcSinCos(double angle) {
  if (std::isfinite(angle) && angle != 0.0) {
    const double quarter_turns = std::nearbyint(angle / M_PI_2);
    const double nearest = quarter_turns * M_PI_2;
    // Two ulps of the angle: the distance between n pi/2 rounded once and the sum of two such roundings.
    if (quarter_turns != 0.0 && std::fabs(angle - nearest) <= 2.0 * std::numeric_limits<double>::epsilon() *
                                                                  std::fabs(nearest)) {
      switch (static_cast<int>(std::fmod(std::fabs(quarter_turns), 4.0)) * (quarter_turns < 0 ? -1 : 1)) {
        case 0: return {0.0, 1.0};
        case 1: case -3: return {1.0, 0.0};
        case 2: case -2: return {0.0, -1.0};
        case 3: case -1: return {-1.0, 0.0};
      }
    }
  }
  return {std::sin(angle), std::cos(angle)};
}

}  // namespace crankcheck::analytic
