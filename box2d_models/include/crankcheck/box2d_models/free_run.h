#pragma once
/// @file
/// The Box2D model's free run: the model of constant_speed_run.h (the same construction) with the crank joint's motor
/// off and the scene's flywheel (Mechanism::flywheel_inertia about O) added to the crank body's inertia, no gas (a
/// scene's [gas] is left out: the free run is under gravity alone), released from a start state and stepped by
/// Box2D's own solver. Box2D stays inside src/: this header includes no Box2D header.
///
/// The instants: phi is the crank body's angle after the step (b2Body::GetAngle, continuous over turns, a float);
/// omega its angular velocity after the step (GetAngularVelocity). Box2D's step updates the velocities (gravity, then
/// the joints' velocity solve, which makes them tangent to the step's start configuration), moves every body by dt
/// times its new velocity, then corrects positions only. The position pass, closing the loop that the straight move
/// along the start's tangent opened, turns the crank too: measured, phi_i - phi_{i-1} = dt omega_i + (1/2) dt^2 alpha,
/// so omega_i acts as the speed at the step's start (its omega_time the step's start; tests/box2d/box2d_free_run_test.cc,
/// OmegaBelongsToTheStepsStart, at 1e-4 s; at 1/240..1e-3 s Box2D's 5 mm slop shifts it toward 0.1 of the step).
///
/// The run loses energy at first order in dt: each step's velocity solve projects the velocities onto the joints'
/// tangent (an inelastic projection), so the crank falls behind the exact free run, its phase error first order
/// (measured in the test).
///
/// Box2D's b2_maxRotation caps a body's turn per step (pi/2): the run refuses a step at which the release speed
/// would reach it, and throws std::runtime_error if the crank's speed reaches the cap during the run.

#include "crankcheck/box2d_models/constant_speed_run.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/solver/stepped_run.h"

namespace crankcheck::box2d_models {

/// Runs m free at o's step, steps, iterations and warm starting, released from o.start (o.start.omega the crank's
/// release speed [rad/s], != 0).
/// @throws std::invalid_argument "[flywheel].inertia ..." if m has none (or not > 0), and as runBox2dAtConstantSpeed
///   for a scene Box2D cannot build, a step it would cap at the release speed or a bad option (the scene's speed
///   itself is not used); std::runtime_error if the crank's speed reaches Box2D's cap during the run.
Trajectory runBox2dFree(const Mechanism& m, const Box2dRunOptions& o);

}  // namespace crankcheck::box2d_models
