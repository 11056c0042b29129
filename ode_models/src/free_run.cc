#include "crankcheck/ode_models/free_run.h"

#include <ode/ode.h>

#include <chrono>

#include "ode_model.h"

namespace crankcheck::ode_models {

Trajectory runOdeFree(const Mechanism& m, const OdeRunOptions& o) {
  OdeModel model;
  buildOdeModel(model, m, o, CrankDrive::kFreeWithFlywheel);
  Trajectory run;
  const double lag = (1.0 - kOdeFreeOmegaStepFraction) * o.dt;  // omega belongs to the step's middle
  const auto n = static_cast<std::size_t>(o.steps);
  run.time.reserve(n);
  run.phi.reserve(n);
  run.omega.reserve(n);
  run.omega_time.reserve(n);
  double phi = o.start.phi;
  const auto started = std::chrono::steady_clock::now();
  for (long i = 0; i < o.steps; ++i) {
    stepOdeModel(model, o);
    phi = readCrankAngle(model, phi);
    run.time.push_back(static_cast<double>(i + 1) * o.dt);
    run.phi.push_back(phi);
    run.omega.push_back(dBodyGetAngularVel(model.crank)[2]);
    run.omega_time.push_back(run.time.back() - lag);
  }
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - started;
  run.seconds_per_step = elapsed.count() / static_cast<double>(o.steps);
  return run;
}

}  // namespace crankcheck::ode_models
