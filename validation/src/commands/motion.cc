#include "crankcheck/validation/commands/motion.h"

#include <algorithm>
#include <stdexcept>

#include "crankcheck/analytic/motion.h"
#include "crankcheck/validation/engines.h"

namespace crankcheck::validation {

FreeRunChoices getDefaultFreeRunSettings() {
  FreeRunChoices choices;
  for (const Engine& engine : listEngines()) {
    if (!engine.simulate || engine.integrators.empty()) continue;
    FreeRunSettings settings;
    settings.integrator = engine.integrators.front();
    settings.accuracy = engine.default_accuracy;
    choices[engine.name] = settings;
  }
  return choices;
}

int chooseIntegrator(FreeRunChoices& choices, const std::string& integrator, double accuracy) {
  int taken = 0;
  for (const Engine& engine : listEngines()) {
    if (!engine.simulate) continue;
    if (std::find(engine.integrators.begin(), engine.integrators.end(), integrator) == engine.integrators.end()) continue;
    FreeRunSettings& settings = choices[engine.name];
    settings.integrator = integrator;
    settings.accuracy = accuracy;
    ++taken;
  }
  return taken;
}

std::vector<MotionRun> calcMotion(const Mechanism& m, const FreeRunChoices& choices, std::vector<SatOut>* sat_out) {
  if (!m.flywheel_inertia)
    throw std::invalid_argument("[flywheel].inertia: missing key (the free run needs the flywheel inertia)");
  if (!(m.machine.speed > 0.0)) throw std::invalid_argument("[engine].speed_rpm: must be > 0 for the free run (the release speed)");
  const double w0 = m.machine.speed;
  std::vector<MotionRun> runs;
  try {
    const analytic::FreeRun with = analytic::calcFreeRun(m, w0, true), without = analytic::calcFreeRun(m, w0, false);
    MotionRun a;
    a.engine = getClosedFormEngine().name;  // the closed forms' free run (motion.h)
    a.delta_gravity = with.delta;
    a.delta_no_gravity = without.delta;
    a.omega_min = with.omega_min;
    a.omega_max = with.omega_max;
    a.omega_mean = with.omega_mean;
    runs.push_back(std::move(a));
  } catch (const std::domain_error& e) {
    throw std::invalid_argument(std::string("[engine].speed_rpm: ") + e.what());
  }
  const FreeRunChoices defaults = getDefaultFreeRunSettings();
  for (const Engine& engine : listEngines()) {
    if (!engine.simulate) continue;
    const auto chosen = choices.find(engine.name);
    FreeRunSettings run = chosen != choices.end() ? chosen->second : defaults.at(engine.name);
    try {
      (void)engine.build(m);  // an engine that cannot hold its accuracy on m is found out before it runs
    } catch (const std::invalid_argument& e) {
      if (!sat_out) throw std::invalid_argument(engine.name + ": " + e.what());
      sat_out->push_back({engine.name, m.name, e.what()});
      continue;
    }
    try {
      run.gravity = true;
      FreeRunResult with = engine.simulate(m, w0, run);
      run.gravity = false;
      const FreeRunResult without = engine.simulate(m, w0, run);
      MotionRun r;
      r.engine = engine.name;
      r.integrator = run.integrator;
      r.accuracy = run.accuracy;
      r.delta_gravity = with.delta;
      r.delta_no_gravity = without.delta;
      r.omega_min = with.omega_min;
      r.omega_max = with.omega_max;
      r.omega_mean = with.omega_mean;
      r.energy_drift = with.energy_drift_per_revolution;
      r.steps = with.steps;
      r.with_gravity = std::move(with);
      runs.push_back(std::move(r));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(engine.name + ": " + e.what());
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(engine.name + ": " + engine.library + " could not run: " + e.what());
    }
  }
  return runs;
}

}  // namespace crankcheck::validation
