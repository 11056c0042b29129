#pragma once
/// @file
/// The computation of `crankcheck torsion`: the elastic crank train of a scene with [crankshaft] (analytic/torsion.h,
/// torsion_forced.h, torsion_steady.h) at one or more speeds: each throw's inertia for Holzer's model, the natural
/// frequencies and the critical speeds in the range, and at each speed each section's peak-to-peak twist by Holzer's
/// summed orders, by the exact periodic steady state and by every engine asked for that runs the train
/// (Engine::simulate_crank_train).

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "crankcheck/analytic/torsion.h"
#include "crankcheck/analytic/torsion_forced.h"
#include "crankcheck/analytic/torsion_steady.h"
#include "crankcheck/solver/engine.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/errors.h"

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

/// The torsion of `scene` at `rpms` (each > 0, increasing) with the trains of `engines` (each offering
/// simulate_crank_train); `on_speed(i)` is called before speed i is computed (a progress line).
/// @throws std::invalid_argument "[crankshaft]: rule" or "KEY: rule" for a scene outside the model's domain
///         (analytic/torsion_domain.h), "[crankshaft]: missing table ..." without one, or an engine's refusal;
///         UncomputableError when the modes cannot be computed; TorsionSpeedError when a steady state cannot be
///         found at a speed.
TorsionResult calcTorsion(const Mechanism& scene, const std::vector<double>& rpms, const std::vector<const Engine*>& engines,
                          const std::function<void(size_t)>& on_speed = {});

}  // namespace crankcheck::validation
