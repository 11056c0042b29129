#include "crankcheck/validation/commands/motion.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "crankcheck/analytic/motion.h"
#include "crankcheck/solver/stepped_run.h"
#include "crankcheck/validation/engine_runs.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/run_measures.h"
#include "crankcheck/validation/variants.h"

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
  for (const Engine& engine : listEngines(Route::kStepFree)) {
    FreeRunSettings settings;
    settings.integrator = engine.settings.empty() ? "defaults" : engine.settings.front();
    settings.accuracy = kDefaultSteppedMotionStep;
    choices[engine.name] = settings;
  }
  return choices;
}

int chooseSteppedRun(FreeRunChoices& choices, const std::string& settings, double fraction) {
  int taken = 0;
  for (const Engine& engine : listEngines(Route::kStepFree)) {
    auto it = choices.find(engine.name);
    if (it == choices.end()) continue;
    it->second.accuracy = fraction;
    if (std::find(engine.settings.begin(), engine.settings.end(), settings) == engine.settings.end()) continue;
    it->second.integrator = settings;
    ++taken;
  }
  return taken;
}

namespace {
void addOnce(std::vector<std::string>& names, const std::vector<std::string>& more) {
  for (const std::string& n : more)
    if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
}
}  // namespace

std::vector<std::string> listIntegrators(bool gated) {
  std::vector<std::string> names;
  for (const Engine& engine : listEngines(Route::kSimulate))
    if (engine.gated == gated) addOnce(names, engine.integrators);
  return names;
}

std::vector<std::string> listSteppedSettings() {
  std::vector<std::string> names;
  for (const Engine& engine : listEngines(Route::kStepFree)) addOnce(names, engine.settings);
  return names;
}

int chooseIntegrator(FreeRunChoices& choices, const std::string& integrator, double accuracy) {
  int taken = 0;
  for (const Engine& engine : listEngines(Route::kSimulate)) {
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
  Mechanism free = m;  // no gas in a free run (the integrators' runs leave it out likewise: FreeRunSettings::gas)
  free.gas.reset();
  const Mechanism weightless = withLoads(m, false, true, false);
  for (const Engine& engine : listEngines(Route::kSimulate)) {
    if (!engine.build) continue;  // the sat-out check below needs a model
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
      // Read from the run as every engine's run is read (a stepped one's below): the first revolution, each speed at
      // its instant (findOmegaInstants), interpolated between the samples.
      const SpeedFluctuationOfRun g = calcSpeedFluctuation(free, findOmegaInstants(with.trajectory)).run;
      r.delta_gravity = g.delta;
      r.delta_no_gravity = calcSpeedFluctuation(weightless, findOmegaInstants(without.trajectory)).run.delta;
      r.omega_min = g.omega_min;
      r.omega_max = g.omega_max;
      r.omega_mean = g.omega_mean;
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
  // The engines that step free: released from the exact state at phi = 0 and w0.
  const double horizon = 2.0 * 2.0 * std::numbers::pi / analytic::calcFreeRun(m, w0).omega_mean;
  const StartState start = calcStartState(free, getClosedFormEngine().build(free)->evaluate(0.0));
  const StartState weightless_start = calcStartState(weightless, getClosedFormEngine().build(weightless)->evaluate(0.0));
  for (const Engine& engine : listEngines(Route::kStepFree)) {
    const auto chosen = choices.find(engine.name);
    const FreeRunSettings run = chosen != choices.end() ? chosen->second : defaults.at(engine.name);
    SteppedFreeRunOptions options;
    options.dt = run.accuracy * 2.0 * std::numbers::pi / w0;
    options.steps = static_cast<long>(std::ceil(1.1 * horizon / options.dt));  // a run that loses speed reaches it
    options.settings = run.integrator;
    MotionRun r;
    r.engine = engine.name;
    r.integrator = run.integrator;
    r.accuracy = options.dt;
    r.steps = static_cast<int>(options.steps);
    Trajectory with, without;
    try {
      options.start = start;
      with = engine.step_free(free, options);
      options.start = weightless_start;
      without = engine.step_free(weightless, options);
    } catch (const std::invalid_argument& e) {  // a scene it cannot build, or a step it refuses
      if (!sat_out) throw std::invalid_argument(engine.name + ": " + e.what());
      sat_out->push_back({engine.name, m.name, e.what()});
      continue;
    } catch (const std::runtime_error& e) {  // measured, never gated: its failure is its row, the others answer
      r.not_measured = engine.library + " could not run: " + e.what();
      runs.push_back(std::move(r));
      continue;
    }
    try {
      const Trajectory released = withRelease(with, 0.0, w0);
      const SpeedFluctuationOfRun g = calcSpeedFluctuation(free, released).run;
      r.delta_gravity = g.delta;
      r.delta_no_gravity = calcSpeedFluctuation(weightless, withRelease(without, 0.0, w0)).run.delta;
      r.omega_min = g.omega_min;
      r.omega_max = g.omega_max;
      r.omega_mean = g.omega_mean;
      // The closed forms' energy at each sample: its phi and its omega read at the sample's time.
      r.with_gravity.trajectory = released;
      r.with_gravity.energy = calcEnergyAtSamples(free, released);
      double drift = 0.0;
      for (double e : r.with_gravity.energy) drift = std::max(drift, std::fabs(e - r.with_gravity.energy.front()));
      r.energy_drift = drift / std::fabs(r.with_gravity.energy.front()) / 2.0;  // per revolution of the two
    } catch (const std::exception& e) {  // it stops turning, or falls short of a revolution (a speed cap, damping)
      r = MotionRun{engine.name, run.integrator, options.dt};
      r.steps = static_cast<int>(options.steps);
      r.not_measured = "its run at " + run.integrator + " does not turn as a free run does (" + e.what() + ")";
    }
    runs.push_back(std::move(r));
  }
  return runs;
}

}  // namespace crankcheck::validation
