#pragma once
/// @file
/// The seam of a stepped engine: a physics engine that advances the mechanism by fixed time steps with its own
/// constraint solver (ODE, Bullet, Box2D), as robotics and games run it. Such an engine answers no "value at crank
/// angle phi": it is driven at the scene's constant crank speed from the exact state at phi = 0, and each of its
/// steps reports the quantities it can read from its own API, each belonging to a stated instant of the step (a
/// position to the step's end, a solved force to its start, ...). validation/ measures those against the closed forms
/// at that instant (validation/stepped_errors.h). Plain values, no engine behind them.

#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "crankcheck/scene/evaluation.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/scene/quantities.h"
#include "crankcheck/solver/step_options.h"
#include "crankcheck/solver/trajectory.h"

namespace crankcheck {

/// [rad] The largest crank angle one step of a run may turn for the run to be measured: a quarter turn. Over a turn
/// of fewer than four steps the worst error is read at three instants or fewer (at 1 s and 3000 rpm every step lands
/// on the same angle, 50 turns on), the orders between such steps are of aliases, and a free run's extremes and
/// crossings, read by interpolation through six samples, would span more than a turn.
inline constexpr double kMaxStepAngle = std::numbers::pi / 2;

/// The start state from `exact`, an engine's Evaluation of m at phi = exact.phi and m's speed (validation/ hands in
/// the analytic engine's: the start is the run's input, not what is measured). Rigid-body kinematics only: the crank
/// pin from the crank's angle, the wrist pin x_p e + delta n, the rod from its angle beta (CylinderEvaluation::
/// rod_angle, the rod body turning at -rod_omega about +Z), each centre of mass's velocity v_A + w x (cm - A).
/// @throws std::invalid_argument if exact has not one cylinder per cylinder of m.
StartState calcStartState(const Mechanism& m, const Evaluation& exact);

/// The crankshaft as the stepped engines' models build it: one rigid body in the plane z = 0 lumping every throw's m_s
/// at r_s on its crank line and m_p at r_p opposite, at phi = 0 (the throws' axial spread only moves the bearing's
/// moments, which these models do not record). Scene data, not a closed form of the loop.
struct LumpedCrank {
  double mass = 0.0;              ///< [kg]
  Vec2 p_OBcm{};                  ///< [m] its centre of mass at phi = 0
  double inertia_about_o = 0.0;   ///< [kg m^2] about Z through O
  double inertia_about_cm = 0.0;  ///< [kg m^2] about Z through its centre of mass
};

/// m's crankshaft lumped (LumpedCrank).
/// @throws std::invalid_argument "LIBRARY cannot build this scene: [crank].mass ..." for a crank without mass, or
///         "... [crank].com_radius ..." for one without inertia about its centre of mass.
LumpedCrank calcLumpedCrank(const Mechanism& m, const std::string& library);

/// The refusals every stepped model shares, each naming its key: `[[balance_shaft]]` (no geared coupling in these
/// models), `[rod].mass` or `[piston].mass` of 0 (a body needs a mass), `[rod].inertia_about_wrist_pin` not above
/// m_k z_k^2 (a rod without inertia about its centre of mass).
/// @throws std::invalid_argument "LIBRARY cannot build this scene: KEY rule".
void checkSteppedScene(const Mechanism& m, const std::string& library);

/// [kg m^2] The rod's inertia about its centre of mass, I_o - m_k z_k^2 (Steiner).
double calcRodCentroidalInertia(const Mechanism& m);

/// An Evaluation of `cylinders` cylinders by `engine` with every quantity of the catalogue NaN (quantities.h): a stepped
/// engine's sample before it fills what it reports (Trajectory::values).
Evaluation makeUnreportedEvaluation(const std::string& engine, int cylinders);

}  // namespace crankcheck
