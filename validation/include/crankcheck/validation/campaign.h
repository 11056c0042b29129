#pragma once
/// @file
/// The validation campaign behind `crankcheck validate`: a list of independent tasks (so that they can run on
/// several threads or be cut into shards), each producing rows of the report's tables.
///
/// Every maximum over a turn is found so that it does not depend on the grid (extremum.h: the exact harmonics or
/// Brent's method on the best samples), on the same grid in the quick and the full campaign; `resolved` = 0 marks a
/// number at rounding level (a bound, not a measured maximum).
///
/// Tables (CSV stems, columns in docs of reports/README.md):
///   crosscheck            family,engine,case,lambda,quantity,worst_rel_error,where_phi_deg,where_speed_rpm,tolerance_rel,
///                         pass (engine: the engine compared with the analytic one; pass: pass/FAIL for gated engines,
///                         reported for soft ones, which are measured, never gated)
///   every report part's tables: in the part's file, validation/src/parts/KEY.cc (Part::tables lists them)
///   scenes                family,scene,cylinders,cycle,acting,gamma_deg,speed_rpm,r,l,lambda,m_o,m_k,z_k,I_o,m_s,r_s,
///                         m_p,r_p,g,I_w (I_w empty: the scene has no flywheel)
///   notes                 note (what the campaign left out, and why; only when there is something to say)

#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "crankcheck/scene/mechanism.h"

namespace crankcheck::validation {

/// The unit of a text column (names, verdicts, flags): no unit, the CSV header names the column bare.
struct TextUnit {
  bool operator==(const TextUnit&) const = default;
};
/// A text column's unit: `Column{"engine", kText}`.
inline constexpr TextUnit kText{};

/// One column of a table: its name and its unit together. A number's unit is written in the CSV header,
/// "max_rel_error [-]": "-" for a dimensionless number (ratios, errors relative to a scale, counts, indices), "SI" where
/// the unit is the quantity's own (the row's quantity names it: J, N m, N, m, m/s, m/s^2, rad, ...), else the unit
/// ("N m", "deg", "rpm", "ns", ...). There is no column without a unit: a text column says kText.
struct Column {
  /// A number's column; `unit` must not be empty (Table refuses it).
  Column(std::string name, std::string unit) : name(std::move(name)), unit(std::move(unit)) {}
  /// A text column.
  Column(std::string name, TextUnit) : name(std::move(name)), text(true) {}

  std::string name;
  std::string unit;   ///< "" only for a text column
  bool text = false;  ///< a text column (kText): its header is the bare name

  bool operator==(const Column&) const = default;
};

/// One table of the report: its columns (each with its unit) and rows of already formatted fields (numbers by
/// formatNumber; a name may hold any character, the CSV writer quotes it).
class Table {
 public:
  Table() = default;
  /// @param name the table's name (the CSV stem), for the message only.
  /// @throws std::logic_error naming the table and the column for a number's column with an empty unit.
  Table(const std::string& name, std::vector<Column> columns);

  const std::vector<Column>& columns() const { return columns_; }
  /// The columns' names, in order.
  std::vector<std::string> names() const;

  std::vector<std::vector<std::string>> rows;

 private:
  std::vector<Column> columns_;
};
/// Tables by name (the CSV file stem).
using TableSet = std::map<std::string, Table>;

/// Appends `from`'s rows to `into`. @throws std::runtime_error if a table's columns differ.
void appendTables(TableSet& into, const TableSet& from);

/// Sorts every table's rows, column by column, numerically where both fields are numbers: the report is the
/// same whatever the order tasks ran in, on one thread, several, or in shards.
void sortTables(TableSet& tables);

struct CampaignOptions {
  bool quick = false;               ///< fewer lambdas, angles and methods: a smoke test of the whole report
  std::vector<Mechanism> scenes;    ///< the families to cross-check; empty = the built-in default campaign
  /// The keys of the report parts to run (`validate --parts`), each once; empty = every part. The cross-checks (the
  /// verdict) always run. @see checkPartKeys
  std::vector<std::string> parts;
};

/// One independent unit of work.
struct Task {
  std::string id;                   ///< e.g. "crosscheck inline4_four_gamma90 lambda=0.3"
  /// Times itself (Google Benchmark): run on a core of its own, never beside another such task (runner.h runTasks:
  /// on one worker while the others compute, when every worker has a core; else after the others).
  bool measures_time = false;
  std::function<TableSet()> run;
  double cost = 0.0;                ///< estimated, relative (part.h's task_cost): buildCampaign lists the largest first
};

/// The built-in scenes: a single cylinder (gamma 90, 0, 180, -90), inline 2, 3, 4, 6, 8, 12 in both strokes,
/// an inline four at gamma 0, 180, -90, a marine-size and a small-engine scale.
std::vector<Mechanism> buildDefaultScenes();

/// The example scenes, scenes/*.toml (the folder findScenesDir finds: install_paths.h), sorted by
/// file name: the scenes of report part pin_load_polar in the default campaign. @throws SceneError if one
/// does not load.
std::vector<Mechanism> loadExampleScenes();

/// The campaign: cross-checks of every family over lambda (its own and 0.1 .. 0.9), and the data of every report
/// figure. With options.scenes the first scene is the base of the lambda sweeps and figures.
std::vector<Task> buildCampaign(const CampaignOptions& options);

/// x in its shortest form that reads back to the same double (std::to_chars): 0.1, not 0.10000000000000001.
std::string formatNumber(double x);

/// x to `digits` significant digits (printf %g), for the sentences of the report: 0.012, 3.4e-15.
std::string shortNumber(double x, int digits = 2);

/// The index of the column `name` in t. @throws std::runtime_error if t has no such column (a report part read a
/// table it did not build: a programming error, never a user's).
size_t columnOf(const Table& t, const std::string& name);

}  // namespace crankcheck::validation
