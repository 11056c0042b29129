#pragma once
/// @file
/// Report part `engines`: which engine, at what cost, how exact. Everything of the part is here: its timed task,
/// the table it derives from the campaign's cross-checks, its sentences; report.cc only places it.
///
/// Tables (CSV stems, columns; reports/README.md):
///   engine_cost     engine,k,ns_per_eval                      one Google Benchmark run of every engine's evaluate()
///                                                             (every quantity at one angle) on the base scene's parts
///                                                             at k = 1 and k = 12
///   engines         engine,quantity,worst_rel_error,where_case,where_lambda,where_phi_deg,where_speed_rpm,
///                   ns_per_eval_k1,ns_per_eval_k12            derived at rendering: per engine variant and quantity the
///                                                             worst error over every cross-checked case of the
///                                                             campaign, relative to the quantity's scale, against the
///                                                             analytic engine (the analytic engine's own row: case by
///                                                             case against the nearer of the other exact engines)
///   engines_league  engine,k,ns_per_eval,worst_rel_error      derived: the figure's points (cost against the worst
///                                                             error over all quantities)

#include <string>
#include <vector>

#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/report_part.h"

namespace crankcheck::validation {

/// The timed task: ns per evaluation of every registered engine at k = 1 and k = 12 (the base scene's parts, its
/// stroke and speed, standing). Runs alone (Task::measures_time).
Task buildEngineCostTask(const Mechanism& base, bool quick);

/// Adds (replaces) the derived tables `engines` and `engines_league` from `crosscheck` and `engine_cost`; nothing when
/// either is missing.
void deriveEngineTables(TableSet& tables);

/// The part as the report shows it: heading, figure caption, sentences read from the data, the table.
/// @return an empty heading when the tables are missing.
ReportPart describeEnginesPart(const TableSet& tables);

}  // namespace crankcheck::validation
