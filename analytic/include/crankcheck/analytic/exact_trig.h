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

/// sin and cos of a + b from those of a and b (angle addition): no rounding of the sum a + b, so a throw's angle
/// phi + alpha_j stays as accurate as phi itself at any magnitude (phi = 1e6 rad), and exact zeros survive.
inline SinCos addAngles(const SinCos& a, const SinCos& b) {
  return {a.sin * b.cos + a.cos * b.sin, a.cos * b.cos - a.sin * b.sin};
}

/// sin and cos of throw j's crank angle theta_j = phi + alpha_j (CONVENTIONS.md).
inline SinCos calcThrowSinCos(double phi, double alpha) { return addAngles(calcSinCos(phi), calcSinCos(alpha)); }

}  // namespace crankcheck::analytic
