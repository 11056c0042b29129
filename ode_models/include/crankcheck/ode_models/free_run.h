#pragma once
/// @file
/// The k-crank mechanism in ODE running free: the model of the constant-speed run (constant_speed_run.h: the same
/// bodies, joints and solver settings, one construction) without the crank's motor, the crank body carrying the
/// scene's flywheel (Mechanism::flywheel_inertia added to its inertia about Z), no gas (a scene's [gas] is not
/// applied: the free run is under gravity alone), released from the start state handed in (StartState: every body's
/// position and velocity, start.omega the crank's release speed) and stepped by ODE's own solver.
///
/// What each step records: the step's end time, the crank's angle at the step's end (the crank body's rotation about
/// Z, unwrapped, as the constant-speed run reads it) and the crank body's angular velocity about +Z after the step
/// (dBodyGetAngularVel). That velocity belongs to the step's MIDDLE (kOdeFreeOmegaStepFraction): ODE's step is
/// semi-implicit Euler, the velocity after the step is the one that carried the angle from the step's start to its
/// end (with the finite rotation mode phi_i - phi_{i-1} = dt omega_i exactly; tests/ode/ode_free_run_test.cc measures
/// it against the exact free run).

#include "crankcheck/ode_models/constant_speed_run.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/solver/stepped_run.h"

namespace crankcheck::ode_models {

/// Where within its step the free run's omega belongs (0 its start, 1 its end; the trajectory's omega_time): its middle.
inline constexpr double kOdeFreeOmegaStepFraction = 0.5;

/// Runs m free from o.start (o.start.omega the release speed, any finite value) for o.steps steps of o.dt with o's
/// solver settings; o.motor_max_torque does not apply. Every sample is read from ODE's API after the step.
/// @throws std::invalid_argument naming [flywheel].inertia when m has none, or as runOdeAtConstantSpeed for what ODE
///   cannot build and for a bad option (a scene of speed 0 is accepted: nothing is driven);
///   std::runtime_error when one of ODE's internal checks fails during the run.
Trajectory runOdeFree(const Mechanism& m, const OdeRunOptions& o);

}  // namespace crankcheck::ode_models
