#pragma once
/// @file
/// `crankcheck torsion SCENE [--speed RPM | --speeds FROM:TO:STEP] [--engine analytic,simbody] [--format table|json]`:
/// the torsional vibration of
/// the scene's elastic crank train ([crankshaft], docs/CONVENTIONS-crankcheck.md "Torsion"):
/// - each throw's constant inertia for Holzer's model, exact (the mean of J over a turn) beside the textbook's
///   shortcuts (half the reciprocating mass, with Norton's second-order term), analytic/torsion.h;
/// - the natural frequencies clamped at the flywheel, and the critical speeds rpm = 30 w_i / (pi n) of every order
///   n <= 24 (multiples of 1/2 four-stroke, of 1 two-stroke) that fall in the speeds asked (one speed: half to twice it);
/// - at each speed, each section's peak-to-peak twist by Holzer's summed orders (converged, and cut at order 24 as
///   often done) and by the exact periodic steady state of the variable-inertia train (analytic/torsion_steady.h),
///   with their difference; with `--engine simbody` also Simbody's elastic train run to its periodic state
///   (simbody_models/crank_train.h: about 11 s a speed on the example four, 25 s on the marine six). MuJoCo's
///   train is issue 30's next step: not claimed here.
/// A sweep shows a progress line on a terminal.

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

namespace crankcheck::app {

struct TorsionOptions {
  std::string scene_path;
  std::optional<std::string> speed;   ///< --speed as typed [rpm] (given empty: refused)
  std::optional<std::string> speeds;  ///< --speeds FROM:TO:STEP [rpm] as typed (given empty: refused)
  std::vector<std::string> engines{"analytic"};  ///< the exact steady states shown: engines with Engine::simulate_crank_train
  double work_limit = 600.0;  ///< --work-limit [s]: the longest estimated work started (validation/work_limit.h)
  std::string format = "table";
};

void addTorsionOptions(CLI::App& command, TorsionOptions& options);

/// @throws UsageError for a bad scene or flag, a scene without [crankshaft] or without a speed;
///         UncomputableError when a steady state cannot be found to its accuracy (refused, not printed).
std::string runTorsion(const TorsionOptions& options);

}  // namespace crankcheck::app
