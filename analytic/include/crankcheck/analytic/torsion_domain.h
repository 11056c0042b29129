#pragma once
/// @file
/// The domain in which the torsion analysis computes (docs/CONVENTIONS-crankcheck.md, "Torsion", "Domain"): a shaft
/// whose sections twist by at most kMaxShaftTwist. Beyond it the throws' phasing, which the firing order, Holzer's
/// linear model and the scene's crank angles all assume, is lost: the "crankshaft" is a chain of loose masses, not a
/// shaft, and its results are refused, never printed.

#include <string>

#include "crankcheck/analytic/torsion_forced.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::analytic {

/// [rad] The largest twist of a section, mean and oscillation together (0.1 rad, 5.7 deg): about ten times the twist
/// at which a steel crankshaft section (shear yield strain about 2e-3, throw length about three journal radii) yields,
/// so no real shaft is refused, and a tenth of the spacing of the firings of a twelve-cylinder four-stroke (60 deg),
/// so the throws keep their order and phasing to within a tenth of it.
inline constexpr double kMaxShaftTwist = 0.1;

/// The speed-free part of the domain, checked before any steady state: each section's static twist under the throws'
/// mean torque (the mean over a cycle of T_gas - Q: the power the gas delivers; gravity's and the inertia's means are
/// 0), K^-1 T_0 clamped at the flywheel, at most kMaxShaftTwist. A [crankshaft] without gas passes (no mean torque).
/// @throws std::invalid_argument "[crankshaft].stiffness[i]: ..." naming the first section beyond, its twist and the
///         stiffness it needs; as makeCrankTrain.
void checkTorsionDomain(const Mechanism& m);

/// The speed's part: every section's twist in Holzer's linear response (mean and every order: max |twist(tau)|) finite
/// and at most kMaxShaftTwist. `speed_rpm` only names the speed in the message.
/// @throws std::runtime_error naming the section, its twist and the bound (a valid scene whose shaft, at this speed,
///         twists beyond a crankshaft's: refused, not computed).
void checkHolzerTwist(const HolzerResponse& holzer, double speed_rpm);

}  // namespace crankcheck::analytic
