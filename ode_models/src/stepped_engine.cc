#include "crankcheck/ode_models/stepped_engine.h"

#include <ode/version.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "crankcheck/ode_models/constant_speed_run.h"
#include "crankcheck/ode_models/free_run.h"
#include "crankcheck/scene/quantities.h"

namespace crankcheck::ode_models {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const std::vector<std::string> kSettings{"defaults", "neutralised", "tightened"};

/// The tightened settings (stepped_engine.h), each chosen by measurement (tests/ode/ode_run_test.cc): ERP 1 (the whole
/// joint error corrected each step) has the smallest errors of 0.2, 0.5, 0.8, 0.9, 1 at every step from 1e-3 s down;
/// QuickStep's 100 iterations give dWorldStep's errors on the V8 at 1e-3 s (to 1e-5 of them), where 20 at ERP 1 leave
/// twice its crank-pin error.
/// ODE's CFM stays: 1e-12 changes no error by 1e-3 of itself.
constexpr double kTightenedErp = 1.0;
constexpr int kTightenedQuickStepIterations = 100;

/// Where each reported quantity belongs within a step (constant_speed_run.h explains why; tests/ode measures it).
const std::vector<QuantityInstant> kInstants{
    {QuantityId::kDriveTorque, 0.0},   {QuantityId::kBearingForce, 0.0},  {QuantityId::kPistonPosition, 1.0},
    {QuantityId::kPistonVelocity, 0.5}, {QuantityId::kPistonAcceleration, 0.0}, {QuantityId::kCrankPinForce, 0.0},
    {QuantityId::kWristPinForce, 0.0}, {QuantityId::kWallForce, 0.0}};
constexpr const char* kInstantsLine =
    "x_p at the step's end; v_p (the velocity after the step, which carries the positions from start to end) at its "
    "middle; a_p (the velocity change / dt), every solved force and the drive torque at its start (ODE solves them "
    "with the joints linearised at the start's positions)";

std::string shortValue(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

/// The run options of `settings` for `solver` (stepped_engine.h says what each name means; the tightened values are
/// justified by the measurements in tests/ode/ode_run_test.cc).
/// The driven and the free run share it: the motor's limit stays infinite (the free run has no motor).
template <class SeamOptions>
OdeRunOptions makeOptions(const std::string& engine, OdeSolver solver, const SeamOptions& s) {
  OdeRunOptions o;
  o.solver = solver;
  o.dt = s.dt;
  o.steps = s.steps;
  o.start = s.start;
  if (s.settings == "defaults") return o;
  if (s.settings != "neutralised" && s.settings != "tightened")
    throw std::invalid_argument(engine + " has no settings \"" + s.settings + "\"; its settings are defaults, neutralised, tightened");
  o.finite_rotation = true;
  if (s.settings == "tightened") {
    o.erp = kTightenedErp;
    o.quick_step_iterations = kTightenedQuickStepIterations;
  }
  return o;
}

/// An Evaluation of k cylinders with every field NaN.
Trajectory runStepped(const std::string& engine, OdeSolver solver, const Mechanism& m, const ConstantSpeedRunOptions& options) {
  if (!(std::fabs(m.machine.speed) > 0.0))
    throw std::invalid_argument(engine + ": [engine].speed_rpm must be != 0 (the run is driven at the scene's speed)");
  const OdeRun run = runOdeAtConstantSpeed(m, makeOptions(engine, solver, options));
  const int k = m.machine.cylinders;
  Trajectory out;
  out.reported = kInstants;
  out.seconds_per_step = run.seconds_per_step;
  const Evaluation blank = makeUnreportedEvaluation(engine, k);
  // The crank's speed after a step, as in the free run: its step's middle (ode_models/free_run.h).
  const double lag = (1.0 - kOdeFreeOmegaStepFraction) * options.dt;
  for (const OdeSample& s : run.samples) {
    out.time.push_back(s.t);
    out.phi.push_back(s.phi);
    out.omega.push_back(s.crank_speed);
    out.omega_time.push_back(s.t - lag);
    Evaluation& values = out.values.emplace_back(blank);
    double& loop_error = out.loop_error.emplace_back(s.bearing_error);
    values.phi = s.phi;
    values.drive_torque = s.drive_torque;
    values.bearing_force = {s.bearing_force[0], s.bearing_force[1]};
    for (int j = 0; j < k; ++j) {
      const OdeCylinderSample& c = s.cylinders[static_cast<size_t>(j)];
      CylinderEvaluation& e = values.cylinders[static_cast<size_t>(j)];
      e.x_p = c.x_p;
      e.v_p = c.v_p;
      e.a_p = c.a_p;
      e.crank_pin_force = {c.crank_pin.on_first[0], c.crank_pin.on_first[1]};  // on the rod from the crank
      e.wrist_pin_force = {c.wrist_pin.on_first[0], c.wrist_pin.on_first[1]};  // on the piston from the rod
      e.wall_force = c.wall_force;
      loop_error = std::max(loop_error, c.loop_error);
    }
  }
  return out;
}

Engine describe(const std::string& name, OdeSolver solver, const std::string& method) {
  Engine e;
  e.gated = false;  // measured, never gated
  e.name = name;
  e.library = std::string("ODE ") + dODE_VERSION;
  e.method = method;
  e.settings = kSettings;
  e.settings_meaning = {
      "ODE's own: ERP 0.2, CFM 1e-10, the default (non-finite) rotation update, QuickStep 20 iterations",
      "the defaults with the finite rotation mode on: a body turns by omega dt per step, not 2 atan(omega dt / 2)",
      "neutralised plus ERP " + shortValue(kTightenedErp) + " and QuickStep " + std::to_string(kTightenedQuickStepIterations) +
          " iterations, each chosen by measurement (ODE's CFM kept: tightening it changes nothing measurable)"};
  e.instants = kInstantsLine;
  e.cannot_build =
      "[[balance_shaft]] (no geared coupling), a massless rod, piston or crank, a rod without inertia about its centre "
      "of mass, speed 0";
  e.step_at_speed = [name, solver](const Mechanism& m, const ConstantSpeedRunOptions& o) { return runStepped(name, solver, m, o); };
  e.step_free = [name, solver](const Mechanism& m, const SteppedFreeRunOptions& o) {
    return runOdeFree(m, makeOptions(name, solver, o));
  };
  return e;
}

}  // namespace

std::vector<Engine> describeEngines() {
  return {describe("ode", OdeSolver::kStep,
                   "ODE's dWorldStep: the direct solve of every constraint force, semi-implicit Euler; the crank held "
                   "at the scene's speed by its hinge's motor"),
          describe("ode-quickstep", OdeSolver::kQuickStep,
                   "ODE's dWorldQuickStep: projected Gauss-Seidel on the constraint forces, warm-started, "
                   "semi-implicit Euler; the crank held at the scene's speed by its hinge's motor")};
}

}  // namespace crankcheck::ode_models
