#pragma once
/// @file
/// The scene and the results of one engine at one angle as JSON objects: what `crankcheck eval --format json`
/// prints, what `crankcheck grade` sends a graded program and reads back from it. SI units; names as in
/// docs/CONVENTIONS.md.

#include <nlohmann/json.hpp>

#include "crankcheck/scene/evaluation.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/balance.h"
#include "crankcheck/validation/commands/motion.h"

namespace crankcheck::validation {

/// The parsed scene in SI units, plus lambda.
nlohmann::ordered_json sceneToJson(const Mechanism& m);

/// One engine's result at one angle (phi_deg as the user gave it): {"engine", "phi_deg", the whole mechanism's
/// quantities in the catalogue's order (quantities.h), the dimensionless NAME_star of those that have one placed
/// after the numbers and before the vectors (null without a flywheel or at rest), "cylinders": [{each cylinder's
/// quantities}]} (docs/eval.md shows one). A quantity the scene does not define is left out (gas_force without [gas]); a component it does not define
/// is null (shaking_moment's X and Y unless the scene places its cylinders along the shaft).
nlohmann::ordered_json evaluationToJson(const Evaluation& ev, double phi_deg, const Mechanism& m);

/// The harmonics of calcBalance as `crankcheck balance --format json` prints them: one object per row, {"n",
/// "analytic" (the closed form with its exact zeros), one key per reference engine (its DFT), "vanishes_by_symmetry":
/// {"force", "moment_xy", "moment_z"} (null where not decided)}; each harmonic {"shaking_force": {"amplitude", "cos",
/// "sin"}, "shaking_moment": {"X", "Y", "Z": {"amplitude", "cos", "sin"}}}, X and Y null when `axial` is false (the
/// scene places no cylinder along the shaft).
/// One way's free run (commands/motion.h) as `crankcheck motion --json` and the Python module give it: delta with and
/// without gravity, omega's extremes and mean, and for a simulation its integrator, energy drift and steps.
nlohmann::ordered_json motionRunToJson(const MotionRun& run);

nlohmann::ordered_json balanceToJson(const std::vector<BalanceRow>& rows, bool axial);

/// The engines that sat out of a command's work, as its JSON prints them: [{"engine", "reason"}], empty when every
/// engine answered (balance, motion; CLI and Python).
nlohmann::ordered_json satOutToJson(const std::vector<SatOut>& sat_out);

/// What each engine's DFT resolves (calcBalanceResolution), as `balance --format json` prints it: {"force" [N],
/// "moment" [N m]}.
nlohmann::ordered_json balanceResolutionToJson(const BalanceResolution& resolution);

}  // namespace crankcheck::validation
