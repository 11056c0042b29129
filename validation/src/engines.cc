#include "crankcheck/validation/engines.h"

#include <algorithm>
#include <array>
#include <iterator>
#include <memory>
#include <stdexcept>

#include "crankcheck/analytic/engine.h"
#include "crankcheck/box2d_models/stepped_engine.h"
#include "crankcheck/bullet_models/stepped_engine.h"
#include "crankcheck/mujoco_models/engine.h"
#include "crankcheck/ode_models/stepped_engine.h"
#include "crankcheck/simbody_models/engine.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/profile.h"
#include "crankcheck/validation/variants.h"

namespace crankcheck::validation {

namespace {

// The engines registerExtraEngine added, and whether the registry has been built (after which none may be added).
std::vector<Engine>& extraEngines() {
  static std::vector<Engine> extra;
  return extra;
}
bool engine_registry_built = false;

constexpr Route kRoutes[] = {Route::kEvaluate, Route::kSimulate, Route::kStepAtSpeed, Route::kStepFree, Route::kCrankTrain};
constexpr size_t kRouteCount = std::size(kRoutes);

// One list per route, of `engines` (in their order) offering it.
std::array<EngineList, kRouteCount> listByRoute(const std::vector<const Engine*>& engines) {
  std::array<EngineList, kRouteCount> lists;
  for (size_t r = 0; r < kRouteCount; ++r) {
    std::vector<const Engine*> offering;
    for (const Engine* e : engines)
      if (offersRoute(*e, kRoutes[r])) offering.push_back(e);
    lists[r] = EngineList(std::move(offering));
  }
  return lists;
}

// Every registered engine, built on first use.
const std::vector<Engine>& listRegisteredEngines() {
  static const std::vector<Engine> engines = [] {
    engine_registry_built = true;
    std::vector<Engine> all;
    // One line per engine folder. A further engine (e.g. dart_models/) adds its line here.
    for (Engine& e : analytic::describeEngines()) all.push_back(std::move(e));
    for (Engine& e : simbody_models::describeEngines()) all.push_back(std::move(e));
    for (Engine& e : mujoco_models::describeEngines()) all.push_back(std::move(e));
    for (Engine& e : ode_models::describeEngines()) all.push_back(std::move(e));
    for (Engine& e : bullet_models::describeEngines()) all.push_back(std::move(e));
    for (Engine& e : box2d_models::describeEngines()) all.push_back(std::move(e));
    for (const Engine& e : extraEngines()) {  // a test build's (registerExtraEngine)
      for (const Engine& known : all)
        if (known.name == e.name) throw std::logic_error("registerExtraEngine: engine \"" + e.name + "\" twice");
      all.push_back(e);
    }
    // Every build counted while profiling is on (profile.h); the engines' own models otherwise.
    for (Engine& e : all) {
      if (e.build)
        e.build = [build = std::move(e.build), name = e.name](const Mechanism& m) { return buildCounted(build, name, m); };
      if (e.build_gravity)
        e.build_gravity = [build = std::move(e.build_gravity), name = e.name](const Mechanism& m) {
          return buildCounted(build, name, m);
        };
    }
    return all;
  }();
  return engines;
}

// The registry's lists by route.
const std::array<EngineList, kRouteCount>& listRegisteredByRoute() {
  static const std::array<EngineList, kRouteCount> lists = [] {
    std::vector<const Engine*> all;
    for (const Engine& e : listRegisteredEngines()) all.push_back(&e);
    return listByRoute(all);
  }();
  return lists;
}

// The lists by route less the engines a live SatOutScope leaves out; null when none is alive. Set and cleared only by
// SatOutScope, before and after the work whose threads read it.
std::unique_ptr<const std::array<EngineList, kRouteCount>> engines_in_play;

size_t routeIndex(Route route) { return static_cast<size_t>(std::find(std::begin(kRoutes), std::end(kRoutes), route) - std::begin(kRoutes)); }

}  // namespace

void registerExtraEngine(Engine engine) {
  if (engine_registry_built) throw std::logic_error("registerExtraEngine: the engine registry is already in use");
  for (const Engine& e : extraEngines())
    if (e.name == engine.name) throw std::logic_error("registerExtraEngine: engine \"" + engine.name + "\" twice");
  extraEngines().push_back(std::move(engine));
}

size_t EngineList::indexOf(const Engine& engine) const {
  for (size_t i = 0; i < engines_.size(); ++i)
    if (engines_[i] == &engine) return i;
  throw std::invalid_argument("engine \"" + engine.name + "\" is not in this list");
}

const EngineList& listEngines(Route route) {
  return (engines_in_play ? *engines_in_play : listRegisteredByRoute())[routeIndex(route)];
}

SatOutScope::SatOutScope(const std::vector<SatOut>& sat_out) {
  if (engines_in_play) throw std::logic_error("SatOutScope: another one is alive");
  for (const SatOut& s : sat_out)
    if (std::none_of(listRegisteredEngines().begin(), listRegisteredEngines().end(),
                     [&](const Engine& e) { return e.name == s.engine; }))
      throw std::invalid_argument("no engine \"" + s.engine + "\"");
  std::vector<const Engine*> in_play;
  for (const Engine& e : listRegisteredEngines())
    if (std::none_of(sat_out.begin(), sat_out.end(), [&](const SatOut& s) { return s.engine == e.name; }))
      in_play.push_back(&e);
  const bool closed_form = std::any_of(in_play.begin(), in_play.end(), [](const Engine* e) { return e->closed_form; });
  const bool reference = std::any_of(in_play.begin(), in_play.end(), [](const Engine* e) { return e->gated && !e->closed_form; });
  if (!closed_form || !reference)
    throw std::invalid_argument("it leaves out " + std::string(closed_form ? "every reference engine" : "the closed forms"));
  engines_in_play = std::make_unique<const std::array<EngineList, kRouteCount>>(listByRoute(in_play));
}

SatOutScope::~SatOutScope() { engines_in_play.reset(); }

const Engine* findEngineOffering(const std::string& name, Route route) {
  for (const Engine& e : listEngines(route))
    if (e.name == name) return &e;
  return nullptr;
}

const Engine& findEngine(const std::string& name, Route route) {
  for (const Engine& e : listEngines(route))
    if (e.name == name) return e;
  const bool stepped = route == Route::kStepAtSpeed || route == Route::kStepFree;
  throw std::invalid_argument(std::string(stepped ? "no stepped engine \"" : "no engine \"") + name + "\"; the " +
                              (stepped ? "stepped engines" : "engines") + " are " + joinEngineNames(", ", route));
}

std::string joinEngineNames(const std::string& separator, Route route) {
  std::string names;
  for (const Engine& e : listEngines(route)) names += (names.empty() ? "" : separator) + e.name;
  return names;
}

std::vector<SatOut> findSatOut(const std::vector<Mechanism>& scenes, const std::vector<std::string>& paths) {
  std::vector<SatOut> sat_out;
  std::string references_refused;  // "PATH: --engine NAME: reason; ..." of every reference that sits out
  bool reference_left = false;
  for (const Engine& engine : listEngines()) {
    for (size_t i = 0; i < scenes.size(); ++i) {
      try {
        engine.build(scenes[i]);
        continue;
      } catch (const std::exception& e) {
        if (engine.closed_form) throw UsageError(paths.at(i) + ": --engine " + engine.name + ": " + e.what());
        sat_out.push_back({engine.name, scenes[i].name, e.what()});
        if (engine.gated)
          references_refused += (references_refused.empty() ? "" : "; ") + paths.at(i) + ": --engine " + engine.name + ": " + e.what();
      }
      break;
    }
    const bool sits_out = !sat_out.empty() && sat_out.back().engine == engine.name;
    if (engine.gated && !engine.closed_form && !sits_out) reference_left = true;
  }
  if (!reference_left) throw UsageError(references_refused + " (no exact engine is left to compare the formulas with)");
  return sat_out;
}

std::vector<const Engine*> listReferenceEngines() {
  std::vector<const Engine*> references;
  for (const Engine& e : listEngines())
    if (e.gated && !e.closed_form) references.push_back(&e);
  return references;
}

std::string getLibraryName(const Engine& engine) { return engine.library.substr(0, engine.library.find(' ')); }

std::string getReferenceName() { return getLibraryName(*listReferenceEngines().front()); }

std::string joinEngineLibraries() {
  std::vector<std::string> seen;
  std::string out;
  for (const Engine& e : listEngines()) {
    if (e.closed_form || std::find(seen.begin(), seen.end(), e.library) != seen.end()) continue;
    seen.push_back(e.library);
    out += (out.empty() ? "" : ", ") + e.library;
  }
  return out;
}

std::vector<const Engine*> listComparedEngines() {
  std::vector<const Engine*> engines = {&getClosedFormEngine()};
  for (const Engine* e : listReferenceEngines()) engines.push_back(e);
  return engines;
}

std::vector<const Engine*> listBothEngines() {
  std::vector<const Engine*> both = {&getClosedFormEngine()};
  const std::vector<const Engine*> references = listReferenceEngines();
  if (!references.empty()) both.push_back(references.front());
  return both;
}

std::vector<const Engine*> selectEngines(const std::string& choice) {
  const std::vector<const Engine*> both = listBothEngines();
  std::vector<const Engine*> selected;
  for (const Engine& e : listEngines())
    if (choice == "all" || e.name == choice || (choice == "both" && std::find(both.begin(), both.end(), &e) != both.end()))
      selected.push_back(&e);
  return selected;
}

const Engine& getClosedFormEngine() {
  for (const Engine& e : listEngines())
    if (e.closed_form) return e;
  throw std::logic_error("the engine registry has no closed-form engine");
}

std::unique_ptr<EngineModel> buildGravityModel(const Engine& engine, const Mechanism& m) {
  if (engine.build_gravity) return engine.build_gravity(m);
  return engine.build(withSpeed(m, 0.0));
}

}  // namespace crankcheck::validation
