// Report part `engines` (13): which engine, at what cost, how exact. Cost per evaluation of every registered engine
// against its worst error over the campaign's cross-checks, with sentences read from the data.
//
// Tables (CSV stems, columns; reports/README.md):
//   engine_cost     engine,k,ns_per_eval                      one Google Benchmark run of every engine's evaluate()
//                                                             (every quantity at one angle) on the base scene's parts
//                                                             at k = 1 and k = 12
//   engines         engine,quantity,worst_rel_error,where_case,where_lambda,where_phi_deg,where_speed_rpm,
//                   ns_per_eval_k1,ns_per_eval_k12            derived at rendering: per engine variant and quantity the
//                                                             worst error over every cross-checked case of the
//                                                             campaign, relative to the quantity's scale, against the
//                                                             analytic engine (the analytic engine's own row: case by
//                                                             case against the nearer of the other exact engines)
//   engines_league  engine,k,ns_per_eval,worst_rel_error      derived: the figure's points (cost against the worst
//                                                             error over all quantities)

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <tuple>
#include <stdexcept>

#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/timing.h"
#include "crankcheck/validation/variants.h"

namespace crankcheck::validation {
namespace {

double toDouble(const std::string& s) { return s.empty() ? 0.0 : std::stod(s); }

struct Worst {
  double rel = -1.0;
  std::string kase, lambda, phi, rpm;
};

// The timed task: ns per evaluation of every registered engine at k = 1 and k = 12 (the base scene's parts, its
// stroke and speed, standing). Times itself on a core of its own (Task::measures_time).
Task buildEngineCostTask(const Mechanism& base, bool quick) {
  return {"engine_cost", true, [base, quick] {
            std::vector<std::pair<std::string, std::function<void()>>> timed;
            std::vector<std::pair<std::string, int>> keys;
            std::vector<double> angles;
            for (double d : anglesDeg(quick ? 30.0 : 5.0)) angles.push_back(radiansFromDegrees(d));
            for (int k : {1, 12}) {
              const Mechanism m = withGamma(withCylinders(base, k, base.engine.cycle), 90.0);
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
            Table t("engine_cost", {{"engine", kText}, {"k", "-"}, {"ns_per_eval", "ns"}});
            for (const auto& [engine, k] : keys) {
              const auto it = ns.find(engine + " k=" + std::to_string(k));
              if (it != ns.end()) t.rows.push_back({engine, std::to_string(k), formatNumber(it->second)});
            }
            return TableSet{{"engine_cost", t}};
          }};
}

// Adds (replaces) the derived tables `engines` and `engines_league` from `crosscheck` and `engine_cost`; nothing when
// either is missing.
void deriveEngineTables(TableSet& tables) {
  const auto cross = tables.find("crosscheck");
  const auto cost = tables.find("engine_cost");
  if (cross == tables.end() || cost == tables.end()) return;
  const Table& c = cross->second;
  const size_t engine = columnOf(c, "engine"), quantity = columnOf(c, "quantity"), rel = columnOf(c, "worst_rel_error"),
               kase = columnOf(c, "case"), lambda = columnOf(c, "lambda"), phi = columnOf(c, "where_phi_deg"),
               rpm = columnOf(c, "where_speed_rpm");
  std::map<std::pair<std::string, std::string>, Worst> worst;  // (engine, quantity)
  auto note = [&](const std::string& name, const std::vector<std::string>& row) {
    Worst& w = worst[{name, row[quantity]}];
    const double r = toDouble(row[rel]);
    if (r > w.rel) w = {r, row[kase], row[lambda], row[phi], row[rpm]};
  };
  // The analytic engine's own error, case by case: its smaller disagreement with the other exact engines (each of
  // them is a reference with its own rounding: Simbody's grows like 1 / lambda on a very long rod, MuJoCo's does not).
  // Only what every other exact engine computes (not Simbody's second route to Q, "Q (virtual power)").
  struct Nearest {
    std::vector<std::string> row;
    size_t engines = 0;
  };
  std::map<std::tuple<std::string, std::string, std::string>, Nearest> analytic;  // (family, case, quantity)
  const size_t family = columnOf(c, "family");
  for (const auto& row : c.rows) {
    note(row[engine], row);
    if (!findEngine(row[engine]).gated) continue;
    Nearest& best = analytic[{row[family], row[kase], row[quantity]}];
    ++best.engines;
    if (best.row.empty() || toDouble(row[rel]) < toDouble(best.row[rel])) best.row = row;
  }
  for (const auto& [key, best] : analytic)
    if (best.engines == listReferenceEngines().size()) note(getClosedFormEngine().name, best.row);
  std::map<std::pair<std::string, int>, double> ns;
  const Table& t = cost->second;
  const size_t ce = columnOf(t, "engine"), ck = columnOf(t, "k"), cns = columnOf(t, "ns_per_eval");
  for (const auto& row : t.rows) ns[{row[ce], std::stoi(row[ck])}] = toDouble(row[cns]);
  auto nsOf = [&](const std::string& name, int k) {
    const auto it = ns.find({name, k});
    return it == ns.end() ? std::string() : formatNumber(it->second);
  };

  Table engines("engines", {{"engine", kText}, {"quantity", kText}, {"worst_rel_error", "-"}, {"where_case", kText},
                            {"where_lambda", "-"}, {"where_phi_deg", "deg"}, {"where_speed_rpm", "rpm"},
                            {"ns_per_eval_k1", "ns"}, {"ns_per_eval_k12", "ns"}});
  std::map<std::string, double> worst_of_engine;
  for (const auto& [key, w] : worst) {
    engines.rows.push_back({key.first, key.second, formatNumber(w.rel), w.kase, w.lambda, w.phi, w.rpm,
                            nsOf(key.first, 1), nsOf(key.first, 12)});
    worst_of_engine[key.first] = std::max(worst_of_engine[key.first], w.rel);
  }
  Table league("engines_league", {{"engine", kText}, {"k", "-"}, {"ns_per_eval", "ns"}, {"worst_rel_error", "-"}});
  for (const auto& [key, value] : ns)
    if (worst_of_engine.count(key.first))
      league.rows.push_back({key.first, std::to_string(key.second), formatNumber(value), formatNumber(worst_of_engine[key.first])});
  tables["engines"] = engines;
  tables["engines_league"] = league;
}

// The part as the report shows it under `heading`: figure caption, sentences read from the data, the table; an empty
// heading when the tables are missing.
ReportPart describeEnginesPart(const TableSet& tables, const std::string& heading) {
  ReportPart part;
  const auto it = tables.find("engines");
  if (it == tables.end() || it->second.rows.empty()) return part;
  const Table& t = it->second;
  const size_t engine = columnOf(t, "engine"), quantity = columnOf(t, "quantity"), rel = columnOf(t, "worst_rel_error"),
               kase = columnOf(t, "where_case"), lambda = columnOf(t, "where_lambda"), phi = columnOf(t, "where_phi_deg"),
               rpm = columnOf(t, "where_speed_rpm"), ns1 = columnOf(t, "ns_per_eval_k1"), ns12 = columnOf(t, "ns_per_eval_k12");
  part.heading = heading;
  part.caption =
      "Cost per evaluation (every quantity at one crank angle; k = 1 filled, k = 12 open) against the worst error over "
      "every quantity and every cross-checked case of the campaign, relative to the quantity's scale: each engine "
      "against the analytic engine, the analytic engine against the nearer of the other exact engines, case by case. "
      "Down and left is better";

  // Per engine: the worst row over its quantities, and its costs.
  struct EngineSummary {
    double worst = -1.0;
    std::vector<std::string> row;
    double ns1 = 0.0, ns12 = 0.0;
  };
  std::map<std::string, EngineSummary> by_engine;
  for (const auto& row : t.rows) {
    EngineSummary& s = by_engine[row[engine]];
    s.ns1 = toDouble(row[ns1]);
    s.ns12 = toDouble(row[ns12]);
    const double r = toDouble(row[rel]);
    if (r > s.worst) {
      s.worst = r;
      s.row = row;
    }
  }
  auto where = [&](const std::vector<std::string>& row) {
    return row[quantity] + ", " + row[kase] + " (lambda " + shortNumber(toDouble(row[lambda]), 4) + "), phi " +
           row[phi] + " deg, " + row[rpm] + " rpm";
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
                              shortNumber(s.worst) + " of the scale, at " + where(s.row) + ". " + e.method + ".");
  }
  part.paragraphs.push_back(
      "The exact engines' numbers are rounding: the gate holds them to 64 eps x scale x conditioning. The soft "
      "engines' errors are MuJoCo's constraint solver as its users run it (one mj_forward from the exact state, the "
      "crank torque found so that the solver gives the crank zero acceleration): a finding, not a failure.");
  part.header = {"engine", "quantity", "worst error / scale [-]", "where", "ns per evaluation, k = 1", "ns per evaluation, k = 12"};
  for (const auto& row : t.rows)
    part.rows.push_back({row[engine], row[quantity], shortNumber(toDouble(row[rel])), where(row), shortNumber(toDouble(row[ns1]), 3),
                         shortNumber(toDouble(row[ns12]), 3)});
  return part;
}

class EnginesPart final : public Part {
 public:
  std::string key() const override { return "engines"; }
  int number() const override { return 13; }
  std::string title() const override { return "Engines: which engine, at what cost, how exact"; }
  std::vector<Task> tasks(const PartContext& context) const override {
    return {buildEngineCostTask(context.base, context.quick)};
  }
  // From the cross-checks of every engine and their costs.
  void derive(TableSet& tables) const override { deriveEngineTables(tables); }
  ReportPart describe(const TableSet& tables) const override { return describeEnginesPart(tables, heading()); }
  std::vector<std::string> tables() const override { return {"engine_cost", "engines", "engines_league"}; }
};

}  // namespace

namespace parts {
const Part& engines() {
  static const EnginesPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
