#pragma once
/// @file
/// Report part `balance_shafts` (16): what balance shafts designed by `crankcheck balance --design N` cancel, by every
/// exact engine. Everything of the part is here: its task's tables and its sentences; report.cc only places it.
///
/// The cases: the base scene's parts at 6000 rpm as a standing single cylinder with the shafts that cancel its primary
/// force (design 1: a shaft turning with the crank and one against it, the second the primary balancer, ratio -1),
/// as an inline four with the pair that cancels its secondary force (design 2: a Lanchester pair, ratios 2 and -2),
/// and each campaign scene that carries `[[balance_shaft]]` tables as it is (the example offset four with its pair),
/// each beside the same engine without shafts.
/// Table (CSV stem, columns; reports/README.md):
///   balance_shafts  case,shafts,engine,n,force_amplitude,force_relative
///                   case: the engine and what was designed; shafts "none" | "with"; n = 1..6; engine: "analytic"
///                   (the closed form, its exact zeros as 0) and each other exact engine (a DFT of its own shaking
///                   force over a revolution); the amplitude of harmonic n of the shaking force [N] and relative to the
///                   force scale (scales.h) of the engine without shafts

#include <string>
#include <vector>

#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/report_part.h"

namespace crankcheck::validation {

/// The part's table on `parts` (its crank, rod and piston) and the `scenes` with balance shafts.
/// @throws std::runtime_error if an engine fails.
TableSet calcBalanceShaftTables(const Mechanism& parts, const std::vector<Mechanism>& scenes);

/// The part as the report shows it: heading, figure caption, sentences read from the data; an empty heading
/// without data.
ReportPart describeBalanceShaftPart(const TableSet& tables);

}  // namespace crankcheck::validation
