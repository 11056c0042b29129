#pragma once
/// @file
/// `crankcheck balance SCENE [--order N] [--format table|json]`: the shaking force and the three shaking-moment
/// components harmonic by harmonic, n = 1..N, in closed form and from a DFT of Simbody's over one revolution, side by
/// side; a harmonic that vanishes exactly by the layout's symmetry is printed as 0 with the reason. `--design N`: the
/// [[balance_shaft]] tables that cancel harmonic N of the shaking force (validation/balance.h, designBalanceShafts),
/// ready to paste into the scene, then every harmonic with them, from every engine (the residual).

#include <CLI/CLI.hpp>
#include <string>

namespace crankcheck::app {

struct BalanceOptions {
  std::string scene_path;
  int order = 8;
  std::string format = "table";
  int design = 0;  ///< > 0: design the balance shafts that cancel this harmonic of the shaking force
};

void addBalanceOptions(CLI::App& command, BalanceOptions& options);

/// @throws UsageError for a bad scene or flag (a massless rod: Simbody's mass matrix is singular).
std::string runBalance(const BalanceOptions& options);

}  // namespace crankcheck::app
