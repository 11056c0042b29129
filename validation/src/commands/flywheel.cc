#include "crankcheck/validation/commands/flywheel.h"

#include <cstdio>
#include <stdexcept>
#include <string>

#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/scene/scene_file.h"

namespace crankcheck::validation {

FlywheelResult calcFlywheel(const Mechanism& m, double fluctuation) {
  if (!m.gas) throw std::invalid_argument("[gas]: missing table (flywheel sizing needs the working torque of a gas cycle)");
  if (!(m.machine.speed > 0.0)) throw std::invalid_argument("[engine].speed_rpm: must be > 0 (the mean speed)");
  FlywheelResult result;
  try {
    result.sizing = analytic::calcFlywheelSizing(m, fluctuation);
  } catch (const std::domain_error&) {
    throw;
  } catch (const std::runtime_error& e) {  // a root that does not converge: refused, not printed
    throw UncomputableError(e.what());
  }
  const analytic::FlywheelSizing& s = result.sizing;
  Mechanism with = m;
  with.flywheel_inertia = s.exact_inertia;
  // The flywheel the sizing found is a scene crankcheck made, not the user's: one past the format's limits (at 1e-6
  // rpm an inertia of 1.6e18 kg m^2) cannot be run by the engines, so the answer is refused, not blamed on a key.
  try {
    validateMechanism(with, m.name);
  } catch (const SceneError& e) {
    char inertia[32];
    std::snprintf(inertia, sizeof inertia, "%.3g", s.exact_inertia);
    throw UncomputableError("flywheel sizing: the exact flywheel, " + std::string(inertia) + " kg m^2, is outside what a scene holds (" + e.what() +
                            "), so the engines cannot run it to check the sizing; refused");
  }
  for (const Engine& engine : listEngines()) {
    if (!engine.simulate || !engine.simulates_loads) continue;
    FreeRunSettings run;
    run.integrator = engine.integrators.empty() ? std::string() : engine.integrators.front();
    run.accuracy = engine.default_accuracy;
    run.gas = true;
    run.load_torque = s.load_torque;
    run.revolutions = m.machine.cycle == Cycle::kFourStroke ? 2 : 1;  // one working cycle
    FreeRunResult r;
    try {
      r = engine.simulate(with, s.exact.omega0, run);
    } catch (const std::invalid_argument&) {
      throw;
    } catch (const std::runtime_error& e) {  // a run too stiff to finish: refused, not printed
      const std::string library = engine.library.substr(0, engine.library.find(' '));
      throw UncomputableError(library + "'s run with the exact flywheel: " + e.what());
    }
    result.runs.push_back({engine.name, engine.library, r.delta, r.energy_drift_per_revolution, r.omega_mean});
  }
  return result;
}

}  // namespace crankcheck::validation
