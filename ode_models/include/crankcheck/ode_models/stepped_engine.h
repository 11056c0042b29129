#pragma once
/// @file
/// ODE's two stepped engines for the registry (crankcheck/solver/engine.h: Engine, its stepped routes): "ode" (dWorldStep, the
/// direct solve of the constraint forces) and "ode-quickstep" (dWorldQuickStep, projected Gauss-Seidel), each run by
/// runOdeAtConstantSpeed (constant_speed_run.h) and run free by runOdeFree (free_run.h: the same model without the
/// motor, carrying the scene's flywheel; its speed belongs to the step's middle) at one of three named settings,
/// the same for both runs (the motor's limit does not apply to the free run):
/// - "defaults": ODE's own (ERP 0.2, CFM 1e-10 in double precision, the default rotation update, QuickStep's 20
///   iterations);
/// - "neutralised": the defaults with the one that changes the physics turned off: the finite rotation mode, so a
///   body turns by omega dt per step and not 2 atan(omega dt / 2) (the default update's crank falls behind its own
///   speed: 12 % at 3000 rpm and 1/240 s). ODE's other defaults that could change the physics are off already
///   (linear and angular damping 0, no angular speed cap, no auto-disable: tests/ode verifies them);
/// - "tightened": neutralised plus what a careful user would tighten, each value chosen by measurement
///   (tests/ode/ode_run_test.cc holds the numbers): ERP 1 (the smallest errors at every step from 1e-3 s down, up to
///   6 times below ERP 0.2's at 1e-4 s; at 1/240 s, where every setting is tens of percent off, it is worse) and
///   QuickStep's 100 iterations (dWorldStep's errors on the V8 at 1e-3 s, where 20 at ERP 1 leave twice its
///   crank-pin error). ODE's CFM
///   stays 1e-10: 1e-12 changes no error measurably, 0 makes the solve of these redundant 3-D joints singular.

#include <vector>

#include "crankcheck/solver/engine.h"

namespace crankcheck::ode_models {

/// "ode" and "ode-quickstep", in that order. Their library reads ODE's version from its header (ode/version.h).
/// Their step_at_speed throws std::invalid_argument for an unknown settings name (naming it and the engine's settings) and for
/// a scene of speed 0, and as runOdeAtConstantSpeed otherwise; their step_free for an unknown settings name, and as
/// runOdeFree otherwise (a scene without [flywheel].inertia).
std::vector<Engine> describeEngines();

}  // namespace crankcheck::ode_models
