#pragma once
/// @file
/// A Mechanism written as a scene file (docs/SCENE-FORMAT.md) that parseScene accepts: what `crankcheck grade`
/// sends a graded program (`scene_toml`) and writes beside a failing case, so that `crankcheck eval FILE` reproduces
/// it.
///
/// Numbers are written in their shortest form that reads back to the same double (std::to_chars). Lengths, masses,
/// speeds and pressures read back exactly; angles pass through degrees (SI radians inside, degrees in the file),
/// so an angle may come back one rounding away: a caller that needs the file and the value to be the same
/// mechanism uses the parsed file's Mechanism (as grade does).

#include <string>

#include "crankcheck/scene/mechanism.h"

namespace crankcheck {

/// The scene text of `m`: the inline form (cylinder_angle_deg, crank_angles_deg only when they are not eqs
/// (8)-(11)'s, cylinder_spacing when the axial positions are j x spacing, firing_order with [gas]) when `m` has
/// one bank and such a form holds it; otherwise one [[cylinder]] table per cylinder. `m.name` is not written (a
/// scene's name is its file's stem).
std::string formatSceneToml(const Mechanism& m);

/// x in the shortest decimal form that reads back to the same double ("0.1", "1e-06", "-0.35"); "nan", "inf" and
/// "-inf" as TOML writes them.
std::string formatShortest(double x);

}  // namespace crankcheck
