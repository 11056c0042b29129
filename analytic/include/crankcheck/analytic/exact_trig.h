#pragma once
/// @file
/// sin and cos that are exact at quarter turns. Angles the user gives as exact multiples of 90 degrees
/// arrive as n * M_PI_2 (see radiansFromDegrees); std::sin(M_PI) is 1.2e-16, not 0, which would put a
/// spurious residue into every quantity that physically vanishes at a dead centre.

namespace crankcheck::analytic {

struct SinCos {
  double sin = 0.0;
  double cos = 1.0;
};

/// sin and cos of `angle` [rad]. When `angle` lies within two units in the last place of a nonzero multiple
/// n pi/2 (the doubles that mean "exactly n quarter turns"), returns the exact values (0, +-1); otherwise
/// std::sin and std::cos.
SinCos calcSinCos(double angle);

}  // namespace crankcheck::analytic
