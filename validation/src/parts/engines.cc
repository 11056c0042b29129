// Report part `engines`: which engine, at what cost, how exact. Cost per evaluation of every registered engine
// against its worst error over the campaign's cross-checks, with sentences read from the data.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <tuple>
#include <stdexcept>

#include "crankcheck/validation/commands/stepped.h"
#include "crankcheck/validation/crosscheck.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/parts.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/timing.h"
#include "crankcheck/validation/variants.h"

namespace crankcheck::validation {
namespace {

// engine_cost: one Google Benchmark run of every engine's evaluate() (every quantity at one angle) on the base scene's
// parts at k = 1 and k = 12.
struct EngineCostRow {
  std::string engine;
  int k = 1;
  double ns_per_eval = 0.0;  ///< [ns]
};
const Schema<EngineCostRow> kEngineCostTable{
    "engine_cost",
    {textField("engine", &EngineCostRow::engine), countField("k", &EngineCostRow::k),
     numberField("ns_per_eval", "ns", &EngineCostRow::ns_per_eval)}};

// engines (derived at rendering): per engine and quantity the worst error over every cross-checked case of the
// campaign, relative to the quantity's scale, against the analytic engine (the analytic engine's own row: case by case
// against the nearer of the other exact engines), with where it is and the engine's costs.
struct EngineRow {
  std::string engine, quantity;
  double worst_rel_error = 0.0;
  std::string where_case;
  double where_lambda = 0.0, where_phi_deg = 0.0, where_speed_rpm = 0.0;
  std::optional<double> ns_per_eval_k1, ns_per_eval_k12;  ///< [ns]; empty: not timed
};
const Schema<EngineRow> kEnginesTable{
    "engines",
    {textField("engine", &EngineRow::engine), textField("quantity", &EngineRow::quantity),
     numberField("worst_rel_error", "-", &EngineRow::worst_rel_error), textField("where_case", &EngineRow::where_case),
     numberField("where_lambda", "-", &EngineRow::where_lambda),
     numberField("where_phi_deg", "deg", &EngineRow::where_phi_deg),
     numberField("where_speed_rpm", "rpm", &EngineRow::where_speed_rpm),
     optionalField("ns_per_eval_k1", "ns", &EngineRow::ns_per_eval_k1),
     optionalField("ns_per_eval_k12", "ns", &EngineRow::ns_per_eval_k12)}};

// engines_league (derived): the figure's points, cost against the worst error over all quantities.
struct LeagueRow {
  std::string engine;
  int k = 1;
  double ns_per_eval = 0.0, worst_rel_error = 0.0;
};
const Schema<LeagueRow> kLeagueTable{
    "engines_league",
    {textField("engine", &LeagueRow::engine), countField("k", &LeagueRow::k),
     numberField("ns_per_eval", "ns", &LeagueRow::ns_per_eval),
     numberField("worst_rel_error", "-", &LeagueRow::worst_rel_error)}};

// The timed task: ns per evaluation of every registered engine at k = 1 and k = 12 (the base scene's parts, its
// stroke and speed, standing). Times itself on a core of its own (Task::measures_time).
Task buildEngineCostTask(const Mechanism& base, bool quick) {
  return {"engine_cost", true, [base, quick] {
            std::vector<std::pair<std::string, std::function<void()>>> timed;
            std::vector<std::pair<std::string, int>> keys;
            std::vector<double> angles;
            for (double d : anglesDeg(quick ? 30.0 : 5.0)) angles.push_back(radiansFromDegrees(d));
            for (int k : {1, 12}) {
              const Mechanism m = withGamma(withCylinders(base, k, base.machine.cycle), 90.0);
              for (const Engine& engine : listEngines()) {
                std::shared_ptr<EngineModel> model = engine.build(m);
                auto counter = std::make_shared<size_t>(0);
                const std::string name = engine.name + " k=" + std::to_string(k);
                keys.emplace_back(engine.name, k);
                timed.emplace_back(name, [model, counter, angles] {
                  benchmark::DoNotOptimize(model->evaluate(angles[(*counter)++ % angles.size()]));
                });
              }
            }
            const std::map<std::string, double> ns = measureNanosecondsPerCall(timed, getTimingSeconds(quick));
            std::vector<EngineCostRow> rows;
            for (const auto& [engine, k] : keys) {
              const auto it = ns.find(engine + " k=" + std::to_string(k));
              if (it != ns.end()) rows.push_back({engine, k, it->second});
            }
            return kEngineCostTable.tableSet(std::move(rows));
          }};
}

// The stepped engines' points of the league (from report part stepped_engines' tables, when it ran): each engine at its
// defaults and the finest step measured, labelled "NAME (DT s)", its cost per step against its worst error over every
// quantity it reports. A step is not an evaluation: a turn at that step costs the steps per turn times it.
std::vector<LeagueRow> findSteppedLeague(const TableSet& tables) {
  std::vector<LeagueRow> out;
  if (!tables.count(kSteppedErrorsTable.name()) || !tables.count(kSteppedCostTable.name())) return out;
  for (const Engine& e : listEngines(Route::kStepAtSpeed)) {
    double finest = 0.0, worst = -1.0, ns = 0.0;
    for (const SteppedCostRow& c : getRows(tables, kSteppedCostTable))
      if (c.engine == e.name && c.settings == "defaults" && (finest == 0.0 || c.dt < finest)) {
        finest = c.dt;
        ns = c.ns_per_step;
      }
    if (finest == 0.0) continue;
    for (const SteppedErrorRow& r : getRows(tables, kSteppedErrorsTable))
      if (r.engine == e.name && r.settings == "defaults" && r.dt == finest) worst = std::max(worst, r.worst_rel_error);
    if (worst >= 0.0) out.push_back({e.name + " (" + shortNumber(finest, 3) + " s)", 1, ns, worst});
  }
  return out;
}

// Adds (replaces) the derived tables `engines` and `engines_league` from `crosscheck` and `engine_cost`; nothing when
// either is missing.
void deriveEngineTables(TableSet& tables) {
  if (!tables.count(kCrossCheckTable.name()) || !tables.count(kEngineCostTable.name())) return;
  std::map<std::pair<std::string, std::string>, const CrossCheckRow*> worst;  // (engine, quantity)
  auto note = [&](const std::string& name, const CrossCheckRow& row) {
    const CrossCheckRow*& w = worst[{name, row.quantity}];
    if (!w || row.worst_rel_error > w->worst_rel_error) w = &row;
  };
  // The analytic engine's own error, case by case: its smaller disagreement with the other exact engines (each of
  // them is a reference with its own rounding: Simbody's grows like 1 / lambda on a very long rod, MuJoCo's does not).
  // Only what every other exact engine computes (not Simbody's second route to Q, "Q (virtual power)").
  struct Nearest {
    const CrossCheckRow* row = nullptr;
    size_t engines = 0;
  };
  std::map<std::tuple<std::string, std::string, std::string>, Nearest> analytic;  // (family, case, quantity)
  for (const CrossCheckRow& row : getRows(tables, kCrossCheckTable)) {
    note(row.engine, row);
    if (!findEngine(row.engine).gated) continue;
    Nearest& best = analytic[{row.family, row.case_name, row.quantity}];
    ++best.engines;
    if (!best.row || row.worst_rel_error < best.row->worst_rel_error) best.row = &row;
  }
  for (const auto& [key, best] : analytic)
    if (best.engines == listReferenceEngines().size()) note(getClosedFormEngine().name, *best.row);
  std::map<std::pair<std::string, int>, double> ns;
  for (const EngineCostRow& row : getRows(tables, kEngineCostTable)) ns[{row.engine, row.k}] = row.ns_per_eval;
  auto nsOf = [&](const std::string& name, int k) -> std::optional<double> {
    const auto it = ns.find({name, k});
    if (it == ns.end()) return std::nullopt;
    return it->second;
  };

  std::vector<EngineRow> engines;
  std::map<std::string, double> worst_of_engine;
  for (const auto& [key, w] : worst) {
    engines.push_back({key.first, key.second, w->worst_rel_error, w->case_name, w->lambda, w->where_phi_deg,
                       w->where_speed_rpm, nsOf(key.first, 1), nsOf(key.first, 12)});
    worst_of_engine[key.first] = std::max(worst_of_engine[key.first], w->worst_rel_error);
  }
  std::vector<LeagueRow> league;
  for (const auto& [key, value] : ns)
    if (worst_of_engine.count(key.first)) league.push_back({key.first, key.second, value, worst_of_engine[key.first]});
  for (LeagueRow& row : findSteppedLeague(tables)) league.push_back(std::move(row));
  tables.insert_or_assign(kEnginesTable.name(), kEnginesTable.table(std::move(engines)));
  tables.insert_or_assign(kLeagueTable.name(), kLeagueTable.table(std::move(league)));
}

// The part as the report shows it under `heading`: figure caption, sentences read from the data, the table; an empty
// heading when the tables are missing.
ReportPart describeEnginesPart(const TableSet& tables, const std::string& heading) {
  ReportPart part;
  const std::vector<EngineRow>& rows = getRows(tables, kEnginesTable);
  if (rows.empty()) return part;
  part.heading = heading;
  part.caption =
      "Cost per evaluation (every quantity at one crank angle; k = 1 filled, k = 12 open) against the worst error over "
      "every quantity and every cross-checked case of the campaign, relative to the quantity's scale: each engine "
      "against the analytic engine, the analytic engine against the nearer of the other exact engines, case by case; "
      "the physics engines people ship, labelled with a step: the cost of one step at their defaults and the finest "
      "step measured, against their worst error over a turn there. Down and left is better";

  // Per engine: the worst row over its quantities, and its costs.
  struct EngineSummary {
    double worst = -1.0;
    const EngineRow* row = nullptr;
    double ns1 = 0.0, ns12 = 0.0;
  };
  std::map<std::string, EngineSummary> by_engine;
  for (const EngineRow& row : rows) {
    EngineSummary& s = by_engine[row.engine];
    s.ns1 = row.ns_per_eval_k1.value_or(0.0);
    s.ns12 = row.ns_per_eval_k12.value_or(0.0);
    if (row.worst_rel_error > s.worst) {
      s.worst = row.worst_rel_error;
      s.row = &row;
    }
  }
  auto where = [&](const EngineRow& row) {
    return row.quantity + ", " + row.where_case + " (lambda " + shortNumber(row.where_lambda, 4) + "), phi " +
           formatNumber(row.where_phi_deg) + " deg, " + formatNumber(row.where_speed_rpm) + " rpm";
  };
  // Costs, cheapest first, at k = 1 and k = 12.
  std::vector<std::string> names;
  for (const Engine& e : listEngines())
    if (by_engine.count(e.name)) names.push_back(e.name);
  for (int k : {1, 12}) {
    std::vector<std::string> order = names;
    std::sort(order.begin(), order.end(), [&](const std::string& a, const std::string& b) {
      return (k == 1 ? by_engine[a].ns1 : by_engine[a].ns12) < (k == 1 ? by_engine[b].ns1 : by_engine[b].ns12);
    });
    std::string s = "Cost per evaluation at k = " + std::to_string(k) + ", cheapest first (one Google Benchmark run):";
    for (size_t i = 0; i < order.size(); ++i)
      s += std::string(i ? "," : "") + " " + order[i] + " " + shortNumber(k == 1 ? by_engine[order[i]].ns1 : by_engine[order[i]].ns12, 3) + " ns";
    part.paragraphs.push_back(s + ".");
  }
  // Which engine is cheapest at which accuracy.
  for (double accuracy : {1e-9, 1e-3}) {
    std::string best;
    for (const std::string& name : names)
      if (by_engine[name].worst <= accuracy && (best.empty() || by_engine[name].ns1 < by_engine[best].ns1)) best = name;
    std::string best_multibody;
    for (const std::string& name : names)
      if (!findEngine(name).closed_form && by_engine[name].worst <= accuracy &&
          (best_multibody.empty() || by_engine[name].ns1 < by_engine[best_multibody].ns1))
        best_multibody = name;
    std::string s = "Within " + shortNumber(accuracy) + " of the scale on every quantity: ";
    if (best.empty()) {
      s += "no engine.";
    } else {
      s += "the cheapest engine is " + best + " (" + shortNumber(by_engine[best].ns1, 3) + " ns at k = 1)";
      if (!best_multibody.empty() && best_multibody != best)
        s += "; the cheapest multibody engine is " + best_multibody + " (" + shortNumber(by_engine[best_multibody].ns1, 3) +
             " ns at k = 1, " + shortNumber(by_engine[best_multibody].ns1 / by_engine[best].ns1, 3) + " x " + best + ")";
      s += ".";
    }
    part.paragraphs.push_back(s);
  }
  // How far each engine is, and where it is worst.
  for (const Engine& e : listEngines()) {
    if (!by_engine.count(e.name)) continue;
    const EngineSummary& s = by_engine[e.name];
    part.paragraphs.push_back(e.name + (e.gated ? " (exact, gated)" : " (reported, not gated)") + ": worst error " +
                              shortNumber(s.worst) + " of the scale, at " + where(*s.row) + ". " + e.method + ".");
  }
  // The stepped engines' points (findSteppedLeague), in words.
  {
    std::string s;
    for (const LeagueRow& row : getRows(tables, kLeagueTable))
      if (row.engine.find(" (") != std::string::npos)
        s += (s.empty() ? "" : "; ") + row.engine + " " + shortNumber(row.worst_rel_error) + " of the scale at " +
             shortNumber(row.ns_per_eval, 3) + " ns a step";
    if (!s.empty())
      part.paragraphs.push_back("The physics engines people ship (part " + std::to_string(findPart("stepped_engines").number()) +
                                ") step the mechanism instead of evaluating it at an angle; their points are each "
                                "engine at its defaults and the finest step measured, the cost of one step (a turn at "
                                "that step costs the steps per turn times it) against the worst error over a turn: " + s + ".");
  }
  part.paragraphs.push_back(
      "The exact engines' numbers are rounding: the gate holds them to 64 eps x scale x conditioning. The soft "
      "engines' errors are MuJoCo's constraint solver as its users run it (one mj_forward from the exact state, the "
      "crank torque found so that the solver gives the crank zero acceleration): a finding, not a failure.");
  part.header = {"engine", "quantity", "worst error / scale [-]", "where", "ns per evaluation, k = 1", "ns per evaluation, k = 12"};
  for (const EngineRow& row : rows)
    part.rows.push_back({row.engine, row.quantity, shortNumber(row.worst_rel_error), where(row),
                         shortNumber(row.ns_per_eval_k1.value_or(0.0), 3), shortNumber(row.ns_per_eval_k12.value_or(0.0), 3)});
  return part;
}

class EnginesPart final : public Part {
 public:
  std::string key() const override { return "engines"; }
  std::string title() const override { return "Engines: which engine, at what cost, how exact"; }
  std::vector<Task> tasks(const PartContext& context) const override {
    return {buildEngineCostTask(context.base, context.quick)};
  }
  // From the cross-checks of every engine and their costs.
  void derive(TableSet& tables) const override { deriveEngineTables(tables); }
  ReportPart describe(const TableSet& tables) const override { return describeEnginesPart(tables, heading()); }
  std::vector<const TableSchema*> schemas() const override { return {&kEngineCostTable, &kEnginesTable, &kLeagueTable}; }
};

}  // namespace

namespace parts {
const Part& engines() {
  static const EnginesPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
