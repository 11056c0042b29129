#pragma once
/// @file
/// Every engine the harness knows, in one registry (validation/src/engines.cc), filtered by the route asked
/// (crankcheck::Route): the CLI's --engine, the gate, the campaign and the report loop over it. An engine is an Engine
/// (crankcheck/solver/engine.h) described by its own folder; adding one is that folder plus one registration line in
/// engines.cc (docs/contributing.md).

#include <cstddef>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "crankcheck/solver/engine.h"

namespace crankcheck::validation {

/// Engines of the registry, in its order: iterated, indexed and sized as a std::vector<Engine>, each element a
/// reference to the registry's engine (which lives as long as the program).
class EngineList {
 public:
  class const_iterator {
   public:
    using iterator_category = std::forward_iterator_tag;
    using value_type = Engine;
    using difference_type = std::ptrdiff_t;
    using pointer = const Engine*;
    using reference = const Engine&;
    const_iterator() = default;
    explicit const_iterator(std::vector<const Engine*>::const_iterator at) : at_(at) {}
    reference operator*() const { return **at_; }
    pointer operator->() const { return *at_; }
    const_iterator& operator++() { ++at_; return *this; }
    const_iterator operator++(int) { const_iterator before = *this; ++at_; return before; }
    bool operator==(const const_iterator& other) const { return at_ == other.at_; }
    bool operator!=(const const_iterator& other) const { return at_ != other.at_; }
   private:
    std::vector<const Engine*>::const_iterator at_{};
  };
  EngineList() = default;
  explicit EngineList(std::vector<const Engine*> engines) : engines_(std::move(engines)) {}
  const_iterator begin() const { return const_iterator(engines_.begin()); }
  const_iterator end() const { return const_iterator(engines_.end()); }
  size_t size() const { return engines_.size(); }
  bool empty() const { return engines_.empty(); }
  const Engine& operator[](size_t i) const { return *engines_[i]; }
  /// @throws std::out_of_range past the end.
  const Engine& at(size_t i) const { return *engines_.at(i); }
  const Engine& front() const { return *engines_.front(); }
  /// The place of `engine` in the list. @throws std::invalid_argument if it is not in it.
  size_t indexOf(const Engine& engine) const;

 private:
  std::vector<const Engine*> engines_;
};

/// The engines offering `route`, in the registry's order, less the engines a live SatOutScope leaves out. For
/// Route::kEvaluate: analytic, simbody, mujoco, mujoco-soft, mujoco-soft-stiff (the order of the report's tables);
/// for the stepped routes: ode, ode-quickstep, bullet, box2d.
const EngineList& listEngines(Route route = Route::kEvaluate);

/// The engine called `name` among those offering `route`. @throws std::invalid_argument naming those engines if there
/// is none ("no engine ..." for Route::kEvaluate, "no stepped engine ..." for the stepped routes).
const Engine& findEngine(const std::string& name, Route route = Route::kEvaluate);

/// The engine called `name` among those offering `route`, or null if there is none.
const Engine* findEngineOffering(const std::string& name, Route route);

/// The names of listEngines(route), joined by `separator`.
std::string joinEngineNames(const std::string& separator, Route route = Route::kEvaluate);

/// An engine that sits out of a piece of work on a scene: its build refuses the scene (a rule of its own, or an
/// accuracy it cannot hold there: Engine::build), and the engine's reason. The other engines answer without it.
struct SatOut {
  std::string engine;  ///< Engine::name
  std::string scene;   ///< Mechanism::name of the first scene it refuses
  std::string reason;  ///< the engine's own message
};

/// Builds every engine's model of every scene once, before any long work, and returns the engines that cannot build
/// one of them (each once, with the first scene it refuses), in the registry's order: they sit out of a campaign on
/// these scenes (SatOutScope). `paths[i]` names scenes[i] in a refusal.
/// @throws UsageError "PATH: --engine NAME: reason" (exit status 2) when the closed-form engine cannot build a scene
///         (the formulas under test), or when no reference engine can build them all (every reference's reason).
std::vector<SatOut> findSatOut(const std::vector<Mechanism>& scenes, const std::vector<std::string>& paths);

/// While it lives, listEngines() and every list built on it (findEngine, listReferenceEngines, the report's tables
/// with a column per engine) leave out the engines `sat_out` names: a campaign or a merge runs with the other engines.
/// Build it before the work starts and keep it until the report is written; one at a time.
/// @throws std::logic_error when another is alive; std::invalid_argument for a name that is no engine, or when it
///         would leave out the closed forms or every reference engine.
class SatOutScope {
 public:
  explicit SatOutScope(const std::vector<SatOut>& sat_out);
  ~SatOutScope();
  SatOutScope(const SatOutScope&) = delete;
  SatOutScope& operator=(const SatOutScope&) = delete;
};

/// The gated (exact) engines other than the closed forms: the references the analytic engine and graded programs are
/// compared with (simbody, mujoco), in the registry's order.
std::vector<const Engine*> listReferenceEngines();

/// The engines a user's choice names (`eval --engine`), in the registry's order: an engine's name, "all" (every
/// engine) or "both" (the closed forms and the first reference engine: listBothEngines); an unknown choice: none.
std::vector<const Engine*> selectEngines(const std::string& choice);

/// What "both" names: the closed-form engine and the first reference engine (analytic and simbody).
std::vector<const Engine*> listBothEngines();

/// The closed forms first, then every reference engine: the engines a part that shows each engine's values lists.
std::vector<const Engine*> listComparedEngines();

/// The engine of the closed forms under test (Engine::closed_form: "analytic"). @throws std::logic_error if the
/// registry has none.
const Engine& getClosedFormEngine();

/// A model for U and Q alone: the engine's reduced gravity model where it offers one (Engine::build_gravity), else its
/// full model of m at rest. @throws as Engine::build.
std::unique_ptr<EngineModel> buildGravityModel(const Engine& engine, const Mechanism& m);

/// The name of `engine`'s library without its version ("Simbody" of "Simbody 3.7.0"): how prose names the engine.
std::string getLibraryName(const Engine& engine);

/// getLibraryName of the first reference engine in play (listReferenceEngines): the engine a report's prose and
/// figures draw beside the closed forms.
std::string getReferenceName();

/// The libraries behind the engines other than the closed forms, each once, with their versions: "Simbody 3.7.0,
/// MuJoCo 2.2.2" (Engine::library), for a report's header.
std::string joinEngineLibraries();

/// Registers one more engine after the engine folders', with whatever routes it offers (a test build shows with it
/// that every engine-comparing part and the verdict take a new engine with no other change:
/// tests/validation/extra_engine_test.cc; a test's synthetic stepped engine). Call it before the first listEngines().
/// @throws std::logic_error once the registry is in use, or for a name it has already.
void registerExtraEngine(Engine engine);

}  // namespace crankcheck::validation
