#pragma once
/// @file
/// The one notion of an engine the harness has: a named way of computing the Evaluation of a Mechanism at a crank
/// angle. Each engine folder (analytic/, simbody_models/, mujoco_models/) describes its engines with this plain
/// interface; validation/src/engines.cc lists them (one registration line per folder), and the CLI, the gate, the
/// campaign and the report loop over that list. Header only, no engine library behind it.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "crankcheck/scene/evaluation.h"
#include "crankcheck/scene/free_run.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck {

/// One engine's model of one mechanism, built once and evaluated at many crank angles. Not thread-safe: one object
/// per thread (engines keep warm starts and scratch space).
class EngineModel {
 public:
  virtual ~EngineModel() = default;
  /// Everything of Evaluation at crank angle phi [rad] of cylinder 0 and the mechanism's constant speed omega
  /// (engine.speed [rad/s]). Units and signs: CONVENTIONS.md.
  /// @throws std::invalid_argument if phi is not finite; std::runtime_error if the engine fails at phi.
  virtual Evaluation evaluate(double phi) = 0;
};

/// An engine, or one way of evaluating with an engine ("mujoco" and "mujoco-soft" are two ways of one library).
struct Engine {
  std::string name;         ///< as on the command line and in JSON: "analytic", "simbody", "mujoco", ...
  std::string library;      ///< the library that computes, with its version: "Simbody 3.7.0", "MuJoCo 2.2.2"
  std::string method;       ///< one line: how it computes (for --help, the README and the report)
  /// True when the engine claims exactness: the gate holds it to the agreement rule (64 eps x scale x conditioning)
  /// against every other gated engine. False: its errors are measured and reported, never gated (a soft solver).
  bool gated = true;
  /// Builds the engine's model of m.
  /// @throws std::invalid_argument if the engine cannot build m (the message names the scene key and the rule);
  ///         std::runtime_error if the engine's library fails.
  using BuildFunction = std::function<std::unique_ptr<EngineModel>(const Mechanism& m)>;
  BuildFunction build;

  /// The free run (`crankcheck motion`), for engines that simulate; empty `integrators`: none.
  std::vector<std::string> integrators;  ///< the names FreeRunSettings::integrator takes; the first is the default
  std::string accuracy_meaning;          ///< what FreeRunSettings::accuracy means for this engine, and its default
  double default_accuracy = 0.0;
  /// @throws std::invalid_argument for a mechanism without flywheel, omega0 <= 0 or an unknown integrator;
  ///         std::runtime_error if the run fails or the crank does not complete the revolutions.
  std::function<FreeRunResult(const Mechanism& m, double omega0, const FreeRunSettings& settings)> simulate;
};

}  // namespace crankcheck
