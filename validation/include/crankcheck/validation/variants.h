#pragma once
/// @file
/// Variants of a mechanism that the campaigns sweep over (validate's cross-check, grade): the same engine with
/// another crank ratio, speed, cylinder count or orientation, and the crank-angle grids.

#include <string>
#include <vector>

#include "crankcheck/scene/mechanism.h"

namespace crankcheck::validation {

/// The same mechanism with crank ratio lambda = r / l: the rod is lengthened or shortened (r fixed), its centre of
/// mass stays at the same fraction of its length and its radius of gyration scales with it.
Mechanism withLambda(const Mechanism& base, double lambda);

/// The same mechanism turning at `rpm` [rev/min] (speed_rpm and omega [rad/s] together).
Mechanism withSpeed(const Mechanism& base, double rpm);

/// The same parts as an inline engine of k single-acting cylinders in one bank and one plane, phase angles of
/// eqs (8)-(11), without gas (a [gas] table needs a firing angle for each of the new cylinders).
Mechanism withCylinders(const Mechanism& base, int k, Cycle cycle);

/// The same engine turned as a whole so that cylinder 0's bank is at gamma_deg (every bank turns with it).
Mechanism withGamma(const Mechanism& base, double gamma_deg);

/// 0, step, 2 step, ... below 360 [deg].
std::vector<double> anglesDeg(double step);

/// "gamma90", "gammam90" (minus), the tag of a bank angle in case names.
std::string gammaTag(double gamma_deg);

}  // namespace crankcheck::validation
