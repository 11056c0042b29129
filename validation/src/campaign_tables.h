#pragma once
// The computations of report parts 1-8 (campaign.cc), for their part files (parts/*.cc). Each returns the rows of its
// tables from one task; the campaign adds the tasks' tables up (appendTables). Tables and columns: campaign.h.

#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/campaign.h"

namespace crankcheck::validation {

/// error_vs_lambda at one lambda: every method's max error over the turn on the base's parts at `lambda`.
TableSet calcErrorVsLambdaTables(const Mechanism& base, double lambda);
/// speed_vs_error: ns per evaluation of Q against its error, one Google Benchmark run (run alone: it times).
TableSet calcSpeedVsErrorTables(const Mechanism& base, bool quick);
/// harmonics of Q of one cycle, k = 1..12 (Simbody's DFT, the analytic prediction, the paper's table).
TableSet calcHarmonicsTables(const Mechanism& base, Cycle cycle);
/// gravity_significance of one cycle, k = 1..12: max |Q| exact and by Simbody.
TableSet calcGravitySignificanceTables(const Mechanism& base, Cycle cycle);
/// norton_fig13_8: piston x, v, a over two turns, exact and two-term.
TableSet calcNortonFigureTables(const Mechanism& base);
/// errata, eq5_layouts, eq15_coefficients, eq15_engines: the sources as printed against the exact values.
TableSet calcErrataTables(const Mechanism& base);
/// delta_vs_k of one cycle: the free run's speed fluctuation with and without gravity (needs base's flywheel).
TableSet calcDeltaVsKTables(const Mechanism& base, Cycle cycle, bool quick);
/// integrator_pareto: Simbody's integrators' cost against their error (run alone: it times; needs base's flywheel).
TableSet calcIntegratorParetoTables(const Mechanism& base, bool quick);

/// The built-in marine engine (buildDefaultScenes): the second engine of parts 10 and 11.
Mechanism findMarineScene();

}  // namespace crankcheck::validation
