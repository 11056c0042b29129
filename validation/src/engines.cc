#include "crankcheck/validation/engines.h"

#include <stdexcept>

#include "crankcheck/analytic/engine.h"
#include "crankcheck/mujoco_models/engine.h"
#include "crankcheck/simbody_models/engine.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/profile.h"

namespace crankcheck::validation {

const std::vector<Engine>& listEngines() {
  static const std::vector<Engine> engines = [] {
    std::vector<Engine> all;
    // One line per engine folder. A fourth engine (e.g. dart_models/) adds its line here.
    for (Engine& e : analytic::describeEngines()) all.push_back(std::move(e));
    for (Engine& e : simbody_models::describeEngines()) all.push_back(std::move(e));
    for (Engine& e : mujoco_models::describeEngines()) all.push_back(std::move(e));
    // Every build counted while profiling is on (profile.h); the engines' own models otherwise.
    for (Engine& e : all)
      e.build = [build = std::move(e.build), name = e.name](const Mechanism& m) { return buildCounted(build, name, m); };
    return all;
  }();
  return engines;
}

const Engine& findEngine(const std::string& name) {
  for (const Engine& e : listEngines())
    if (e.name == name) return e;
  throw std::invalid_argument("no engine \"" + name + "\"; the engines are " + joinEngineNames(", "));
}

std::string joinEngineNames(const std::string& separator) {
  std::string names;
  for (const Engine& e : listEngines()) names += (names.empty() ? "" : separator) + e.name;
  return names;
}

void checkEveryEngineBuilds(const Mechanism& m, const std::string& path) {
  for (const Engine& engine : listEngines()) {
    try {
      engine.build(m);
    } catch (const std::exception& e) {
      throw UsageError(path + ": --engine " + engine.name + ": " + e.what());
    }
  }
}

std::vector<const Engine*> listReferenceEngines() {
  std::vector<const Engine*> references;
  for (const Engine& e : listEngines())
    if (e.gated && e.name != "analytic") references.push_back(&e);
  return references;
}

}  // namespace crankcheck::validation
