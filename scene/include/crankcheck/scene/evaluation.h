#pragma once
/// @file
/// What an engine reports for a mechanism at one crank angle. Every engine fills the same
/// struct so that the CLI, the tests and the reports compare like with like. Names, frames and signs are those
/// of docs/CONVENTIONS.md: global X horizontal, Y up, forces "ON b FROM a" in global components.

#include <array>
#include <string>
#include <vector>

namespace crankcheck {

/// A planar vector in global (X, Y) components.
using Vec2 = std::array<double, 2>;

/// Per-cylinder quantities.
struct CylinderEvaluation {
  double x_p = 0.0;             ///< [m] wrist pin position along the cylinder axis e, from the crank centre O
  double v_p = 0.0;             ///< [m/s] dx_p/dt at constant omega
  double a_p = 0.0;             ///< [m/s^2] d^2x_p/dt^2 at constant omega
  Vec2 crank_pin_force{};       ///< [N] crank on rod j at its crank pin B_j
  Vec2 wrist_pin_force{};       ///< [N] rod on piston j at its wrist pin A_j
  double wall_force = 0.0;      ///< [N] N_w: the wall pushes piston j with N_w n
  double gas_force = 0.0;       ///< [N] p A on piston j, positive toward the crank (0 without [gas])
  /// The rod's angle beta to the cylinder axis (sin beta = lambda sin theta; the rod from the wrist pin to the crank
  /// pin is l (-cos beta e + sin beta n)) [rad] and its time derivatives [rad/s, rad/s^2]. The rod body turns about +Z
  /// at -rod_omega.
  double rod_angle = 0.0, rod_omega = 0.0, rod_alpha = 0.0;
};

/// Whole-mechanism quantities at crank angle phi (of cylinder 0) and the scene's constant speed omega.
struct Evaluation {
  std::string engine;           ///< "analytic" or "simbody"
  double phi = 0.0;             ///< [rad]
  double U = 0.0;               ///< [J] V(phi) - V(0)
  double Q = 0.0;               ///< [N m] dU/dphi
  double drive_torque = 0.0;    ///< [N m] about +Z, keeps omega constant (= Q when omega = 0)
  Vec2 bearing_force{};         ///< [N] frame on crankshaft at O, all throws
  /// [N] the force the moving parts exert on the frame with gravity and gas off: -dP/dt, P the momentum of
  /// pistons, rods and crank throws (Norton's shaking force).
  Vec2 shaking_force{};
  /// [N m] -dH_O/dt about O (crank centre, z = 0), gravity and gas off, global X, Y, Z. Z is the rocking torque;
  /// X and Y come from axial spacing and are meaningful only when the scene places the cylinders along the shaft
  /// (hasAxialPositions); the CLI prints them as null otherwise.
  std::array<double, 3> shaking_moment{};
  std::vector<CylinderEvaluation> cylinders;
};

}  // namespace crankcheck
