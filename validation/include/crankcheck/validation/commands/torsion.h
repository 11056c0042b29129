#pragma once
/// @file
/// The computation of `crankcheck torsion`: the elastic crank train of a scene with [crankshaft] (analytic/torsion.h,
/// torsion_forced.h, torsion_steady.h) at one or more speeds: each throw's inertia for Holzer's model, the natural
/// frequencies and the critical speeds in the range, and at each speed each section's peak-to-peak twist by Holzer's
/// summed orders, by the exact periodic steady state and by every engine asked for that runs the train
/// (Engine::simulate_crank_train).

#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "crankcheck/analytic/torsion.h"
#include "crankcheck/analytic/torsion_forced.h"
#include "crankcheck/analytic/torsion_steady.h"
#include "crankcheck/solver/engine.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/work_limit.h"

namespace crankcheck::validation {

/// The highest order whose critical speeds are listed, and the order the textbook cuts Holzer's sum at.
constexpr double kTextbookOrder = 24.0;

/// A critical speed: mode `mode` (1 = the lowest) excited by order `order` at `rpm`.
struct CriticalSpeed {
  int mode = 0;
  double order = 0.0;
  double rpm = 0.0;
};

/// The train at one speed.
struct TorsionSpeed {
  double rpm = 0.0;
  analytic::HolzerResponse holzer;
  analytic::ExactSteadyState exact;
  std::vector<std::vector<double>> trains;  ///< each engine's peak-to-peak twist per section [rad]
  std::vector<int> train_cycles;            ///< the cycles each engine ran before its sampled one
};

struct TorsionResult {
  std::vector<analytic::ThrowInertia> inertias;  ///< per throw
  analytic::TorsionModes modes;
  double range_lo = 0.0, range_hi = 0.0;          ///< [rpm] the critical speeds' range (one speed: half to twice it)
  std::vector<CriticalSpeed> critical;            ///< every order n <= 24 of every mode in the range, by speed
  std::vector<TorsionSpeed> speeds;               ///< one per speed asked, in order
};

/// A steady state that could not be found at one speed (exit status 1, as UncomputableError).
class TorsionSpeedError : public UncomputableError {
 public:
  TorsionSpeedError(double rpm, const std::string& what) : UncomputableError(what), rpm(rpm) {}
  double rpm;  ///< [rpm] the speed
};

/// How an engine's train runs: to every section's peak-to-peak within about 1e-6 of its value (measured on the example
/// four at 3000 rpm, where the front section twists a tenth of the most): an exact route (Engine::crank_train_gated)
/// at accuracy 1e-11, periodic to 1e-7 of the twist, sampled 8192 times (CrankTrainRunOptions::samples: aliasing);
/// the exact route's defaults (1e-10, 1e-6, 1024) leave 1e-5 of that section's value. A soft route at its own defaults
/// (its step is its accuracy).
CrankTrainRunOptions makeTrainOptions(const Engine& engine);

/// The speeds a sweep's estimate probes: every one of a sweep of at most 8, else 8 spread evenly over it (the first and
/// the last among them). A train's cost falls with the speed where a fast rate sets its steps (a cycle lasts longer in
/// the rate's time) and varies slowly otherwise: the probed speeds' mean stands for every speed.
inline constexpr size_t kProbedSpeeds = 8;
/// The steps of an engine's first probe (against a run of one step: its build), 4 x more while it stays below 50 ms.
inline constexpr long long kEngineProbeSteps = 64;
/// The cycles an engine's train runs at a speed, for its estimate: the example four's exact trains run 10 cycles from
/// the rigid motion to periodic at 6000 rpm (5 at 1000 rpm), and the sampled one (its steps at least the samples).
inline constexpr double kEngineCycles = 11.0;

/// The work calcTorsion is estimated to take, before it.
struct TorsionWorkEstimate {
  double seconds = 0.0;  ///< [s] on this machine
  std::string how;       ///< how it was estimated, for the refusal: "N speeds at the mean of K probed: ..."
  std::string smaller;   ///< how to ask for less, by the dearest part: "fewer --speeds", "without --engine simbody", ...
};

/// The work of calcTorsion(scene, rpms, engines), estimated before it: at each speed probed (kProbedSpeeds), Holzer's
/// response (timed) and the exact steady state's estimate (analytic::estimateExactSteadyStateWork), the probed speeds'
/// mean taken for every speed; each engine's train: kEngineCycles x the probed speeds' mean steps a cycle (or the
/// samples, if more, for the sampled cycle) at its cost of a step measured by capped runs (kEngineProbeSteps) at the
/// speed of the most steps a cycle, for every speed.
/// `holzer` (optional) receives the probed speeds' Holzer responses by index, for the sweep to reuse.
/// @throws std::invalid_argument as calcTorsion; TorsionSpeedError at a probed speed outside the small-twist domain
///         (analytic::checkHolzerTwist) or whose Holzer response cannot be computed.
TorsionWorkEstimate estimateTorsionWork(const Mechanism& scene, const std::vector<double>& rpms,
                                        const std::vector<const Engine*>& engines,
                                        std::map<size_t, analytic::HolzerResponse>* holzer = nullptr);

/// The torsion of `scene` at `rpms` (each > 0, increasing) with the trains of `engines` (each offering
/// simulate_crank_train); `on_speed(i)` is called before speed i is computed (a progress line). The work is estimated
/// first (estimateTorsionWork) and refused past `work_limit_seconds` (checkWorkLimit, `--work-limit`), nothing run.
/// @throws std::invalid_argument "[crankshaft]: rule" or "KEY: rule" for a scene outside the model's domain
///         (analytic/torsion_domain.h), "[crankshaft]: missing table ..." without one, or an engine's refusal;
///         UsageError for work estimated past the limit; UncomputableError when the modes cannot be computed;
///         TorsionSpeedError when a steady state cannot be found at a speed.
TorsionResult calcTorsion(const Mechanism& scene, const std::vector<double>& rpms, const std::vector<const Engine*>& engines,
                          double work_limit_seconds = kDefaultWorkLimitSeconds,
                          const std::function<void(size_t)>& on_speed = {});

}  // namespace crankcheck::validation
