#pragma once
/// @file
/// What the stepped engines' tests (tests/ode, tests/bullet, tests/box2d) share: the example scenes without what the
/// engines do not take, a registry engine's errors at a series of steps (validation/stepped_errors.h: each quantity
/// against the closed forms at its instant), one quantity's error and the order observed between two steps.

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "crankcheck/scene/scene_file.h"
#include "crankcheck/solver/stepped_run.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/stepped_errors.h"

namespace crankcheck::testing {

/// scenes/NAME (CRANKCHECK_SCENES_DIR, the test target's definition) with its [gas] and [[balance_shaft]] left out
/// when `drop_gas` (a model that refuses them).
inline Mechanism loadSteppedExample(const std::string& name, bool drop_gas = false) {
  Mechanism m = loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / name);
  if (drop_gas) m.gas.reset();
  m.balance_shafts.clear();
  return m;
}

/// The exact state of m at crank angle phi and m's speed (the analytic engine's evaluation): where a stepped run starts.
inline StartState calcExactStartState(const Mechanism& m, double phi = 0.0) {
  return calcStartState(m, validation::getClosedFormEngine().build(m)->evaluate(phi));
}

/// Where within its step a free run's omega belongs (0 its start, 1 its end), read off its first sample's omega_time
/// (Engine::step_free: time[i] = (i + 1) dt).
inline double findOmegaStepFraction(const Trajectory& run) {
  const double dt = run.time.at(1) - run.time.at(0);
  return 1.0 - (run.time.at(0) - run.omega_time.at(0)) / dt;
}

/// The engine called `name` of `engines` (a folder's describeEngines()). Fails the test if there is none.
inline const Engine& findStepped(const std::vector<Engine>& engines, const std::string& name) {
  for (const Engine& e : engines)
    if (e.name == name) return e;
  throw std::invalid_argument("no stepped engine " + name);
}

/// The error of `quantity` (a catalogue name or validation::kLoopErrorName) in `measure`. Throws if it is not there.
inline const validation::SteppedError& findSteppedError(const validation::SteppedMeasure& measure, const std::string& quantity) {
  for (const validation::SteppedError& e : measure.errors)
    if (e.quantity == quantity) return e;
  throw std::invalid_argument("the run reports no " + quantity);
}

/// measureSteppedRun at each of `steps` [s].
inline std::vector<validation::SteppedMeasure> measureAtSteps(const Engine& engine, const Mechanism& m,
                                                              const std::string& settings, const std::vector<double>& steps) {
  std::vector<validation::SteppedMeasure> out;
  for (double dt : steps) out.push_back(validation::measureSteppedRun(engine, m, settings, dt));
  return out;
}

/// The order of `quantity`'s error observed between the measures at steps dt1 and dt2.
inline double observedOrder(const validation::SteppedMeasure& a, double dt1, const validation::SteppedMeasure& b, double dt2,
                            const std::string& quantity) {
  return validation::calcObservedStepOrder(findSteppedError(a, quantity).worst_rel_error, dt1,
                                           findSteppedError(b, quantity).worst_rel_error, dt2);
}

}  // namespace crankcheck::testing
