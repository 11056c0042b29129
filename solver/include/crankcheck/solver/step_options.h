#pragma once
/// @file
/// What a stepped route is asked (Engine::step_at_speed, Engine::step_free: crankcheck/solver/engine.h): the state a
/// run starts from and how to step. Plain values in C++17 (the Simbody folder, C++17, sees them through engine.h).

#include <string>
#include <vector>

#include "crankcheck/scene/evaluation.h"

namespace crankcheck {

/// One body's planar state in the global frame (docs/CONVENTIONS.md): its centre of mass, its angle about +Z, their
/// rates.
struct PlanarBodyState {
  Vec2 p_WBcm_W{};      ///< [m] centre of mass
  double angle = 0.0;   ///< [rad] the body's rotation about +Z from its pose at which the model is built
  Vec2 v_WBcm_W{};      ///< [m/s]
  double omega = 0.0;   ///< [rad/s] about +Z
};

/// Cylinder j's rod and piston and their pins at the start of a run.
struct CylinderStartState {
  Vec2 p_WB_W{};             ///< [m] the crank pin B_j
  Vec2 p_WA_W{};             ///< [m] the wrist pin A_j
  Vec2 e{}, n{};             ///< the cylinder's axis e_j and its normal n_j (CONVENTIONS)
  double x_p = 0.0;          ///< [m] A_j along e_j
  double v_p = 0.0;          ///< [m/s]
  /// The rod: its angle is the direction of A_j -> B_j about +Z (atan2), not measured from a built pose.
  PlanarBodyState rod;
  PlanarBodyState piston;    ///< its angle 0, its omega 0: the piston slides
};

/// The state a stepped run starts from: every body's position and velocity at phi = 0 and the scene's speed.
struct StartState {
  double phi = 0.0;          ///< [rad]
  double omega = 0.0;        ///< [rad/s] the crank's speed
  std::vector<CylinderStartState> cylinders;
};

/// How to run.
struct ConstantSpeedRunOptions {
  double dt = 1.0 / 240.0;   ///< [s] the step, > 0
  long steps = 0;            ///< steps to take, > 0
  /// One of Engine::settings: "defaults" (the library's own), or the engine's other named settings.
  std::string settings = "defaults";
  StartState start;          ///< the exact state at phi = 0 (calcStartState)
};

/// How to run free: no drive and no gas; the crank carries the scene's flywheel (Mechanism::flywheel_inertia about O,
/// added to the crank body's inertia), released from `start` (the exact state at phi = 0 and the release speed
/// start.omega) under the scene's gravity.
struct SteppedFreeRunOptions {
  double dt = 1.0 / 240.0;   ///< [s] the step, > 0
  long steps = 0;            ///< steps to take, > 0
  std::string settings = "defaults";  ///< one of Engine::settings
  StartState start;          ///< the exact state at phi = 0 and the release speed
};

}  // namespace crankcheck
