#pragma once
/// @file
/// The engine layouts of the balance table and of the gate's layout sweep: inline 1-6, 8, 12; V6 at 60 and 90
/// degrees; V8 cross-plane and flat-plane; V12; boxer 4 and 6; a 45 degree V-twin; a five-cylinder radial. Each is
/// built on one passenger-car cylinder (the campaign's base parts), with its textbook crank arrangement, its
/// cylinders spaced along the shaft (throws 0.1 m apart, the two cylinders of a shared pin 0.02 m apart; the crank
/// centre O at the middle, so that moments about O are the couples of the balance tables), and
/// turned as a whole by `rotation_deg` (0: as built, V bisectors and inline banks vertical; 90: lying; 180: hanging).
/// Angles follow docs/CONVENTIONS.md "Layouts": bank gamma_j, throw beta_j, theta_j = phi + beta_j - gamma_j.

#include <optional>
#include <string>
#include <vector>

#include "crankcheck/scene/mechanism.h"

namespace crankcheck::validation {

/// One cylinder of a layout, in degrees and metres as a scene file gives it.
struct CylinderPlace {
  double bank_deg = 90.0;
  double throw_deg = 0.0;
  double axial_position = 0.0;
};

/// What the textbook balance tables say of a layout (two-term piston motion, both cylinders of a shared pin in one
/// plane, couples about the engine's middle): true = vanishes, false = does not, empty = the tables say nothing.
/// F1, F2: primary and secondary shaking force; M1, M2: primary and secondary couple (moments about X and Y).
struct TextbookBalance {
  std::optional<bool> F1, F2, M1, M2;
};

/// A named layout.
struct Layout {
  std::string name;              ///< e.g. "V8_cross_plane"
  std::string description;       ///< e.g. "V8, 90 deg, cross-plane crank (throws 0, 90, 270, 180)"
  std::vector<CylinderPlace> cylinders;
  TextbookBalance textbook;      ///< the claim the balance table checks (typed in: it is the source's, not ours)
};

/// Every layout of the balance table, as built (rotation 0). The textbook claims are those of the standard balance
/// tables (e.g. Taylor, The Internal-Combustion Engine in Theory and Practice, vol. 2, ch. 8; Norton, Design of
/// Machinery, ch. 14).
std::vector<Layout> getBalanceLayouts();

/// The mechanism of `layout` turned by rotation_deg, on `parts` (its crank, rod, piston, flywheel, speed and gravity;
/// its engine layout is replaced; centric, without gas), named "<layout>_rot<deg>". Four-stroke.
Mechanism makeLayoutMechanism(const Layout& layout, const Mechanism& parts, double rotation_deg = 0.0);

}  // namespace crankcheck::validation
