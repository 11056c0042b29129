// Report part `integrator_pareto`: the exact engines' integrators (Simbody's), cost against error in the free run. Needs
// the base scene's flywheel: without one the part is left out (campaign.cc's notes say so).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <exception>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "../part_math.h"
#include "crankcheck/analytic/motion.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/balance.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/campaign_scenes.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/table.h"
#include "crankcheck/validation/task.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/validation/timing.h"
#include "crankcheck/validation/variants.h"
#include "survey.h"

namespace crankcheck::validation {
namespace {

// integrator_pareto: the free run of each simulating reference engine by each integrator and accuracy: cost per
// simulated revolution (one Google Benchmark run) against the error of delta and the energy drift, the analytic energy
// integral as reference. A run that failed has NaN in its numbers.
struct IntegratorParetoRow {
  std::string integrator;
  double accuracy = 0.0;           ///< [-] the integrator's accuracy setting
  double ns_per_revolution = 0.0;  ///< [ns] per simulated revolution
  double delta_error = 0.0;        ///< [-] |delta - exact delta| / exact delta
  double energy_drift = 0.0;       ///< [-] relative energy drift per revolution
  std::string status;              ///< "ok" or "failed"
  std::string engine;
};
const Schema<IntegratorParetoRow> kIntegratorParetoTable{
    "integrator_pareto",
    {textField("integrator", &IntegratorParetoRow::integrator),
     numberField("accuracy", "-", &IntegratorParetoRow::accuracy),
     numberField("ns_per_revolution", "ns", &IntegratorParetoRow::ns_per_revolution),
     numberField("delta_error", "-", &IntegratorParetoRow::delta_error),
     numberField("energy_drift", "-", &IntegratorParetoRow::energy_drift),
     textField("status", &IntegratorParetoRow::status), textField("engine", &IntegratorParetoRow::engine)}};

TableSet calcIntegratorParetoTables(const Mechanism& base, bool quick) {
  const Mechanism m = withSpeed(base, 300.0);
  const analytic::FreeRun exact = analytic::calcFreeRun(m, m.machine.speed, true);
  // Every gated reference engine that simulates (Engine::simulate: Simbody's), by each of its integrators.
  struct Run {
    const Engine* engine;
    FreeRunSettings settings;
    std::string name;
  };
  std::vector<Run> runs;
  // --quick: two of them, a decade either side of the middle (1e-7: the first-order integrator is skipped there, whose
  // 1e-4 run cost as much as the other four runs; issue 28).
  const std::vector<double> accuracies = quick ? std::vector<double>{1e-3, 1e-7} : std::vector<double>{1e-3, 1e-4, 1e-6, 1e-8, 1e-10};
  for (const Engine* engine : listReferenceEngines()) {
    if (!engine->simulate) continue;
    for (size_t i = 0; i < engine->integrators.size(); ++i)
      for (double accuracy : accuracies) {
        // A first-order integrator below 1e-6 needs millions of steps per revolution.
        if (i < engine->integrator_orders.size() && engine->integrator_orders[i] == 1 && accuracy < 1e-6) continue;
        FreeRunSettings settings;
        settings.integrator = engine->integrators[i];
        settings.accuracy = accuracy;
        char name[96];
        std::snprintf(name, sizeof name, "%s %s %.0e", engine->name.c_str(), settings.integrator.c_str(), accuracy);
        runs.push_back({engine, settings, name});
      }
  }
  // Each run is timed by Google Benchmark and keeps its last result, so that no run is integrated twice just for
  // its error (a run that fails is reported as failed).
  std::vector<std::pair<std::string, std::function<void()>>> timed;
  std::map<std::string, std::shared_ptr<FreeRunResult>> results;
  std::map<std::string, std::shared_ptr<std::string>> failures;
  for (const Run& run : runs) {
    auto result = results[run.name] = std::make_shared<FreeRunResult>();
    auto failure = failures[run.name] = std::make_shared<std::string>();
    timed.emplace_back(run.name, [m, engine = run.engine, settings = run.settings, result, failure] {
      if (!failure->empty()) return;
      try {
        *result = engine->simulate(m, m.machine.speed, settings);
      } catch (const std::exception& e) {
        *failure = e.what();
      }
      benchmark::DoNotOptimize(result->delta);
    });
  }
  const std::map<std::string, double> ns = measureNanosecondsPerCall(timed, 0.01);
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::vector<IntegratorParetoRow> rows;
  for (const Run& run : runs) {
    const std::string& integrator = run.settings.integrator;
    const FreeRunResult& result = *results[run.name];
    const auto time = ns.find(run.name);
    if (!failures[run.name]->empty() || time == ns.end()) {
      rows.push_back({integrator, run.settings.accuracy, kNaN, kNaN, kNaN, "failed", run.engine->name});
      continue;
    }
    rows.push_back({integrator, run.settings.accuracy, time->second / run.settings.revolutions,
                    std::fabs(result.delta - exact.delta) / exact.delta, result.energy_drift_per_revolution, "ok",
                    run.engine->name});
  }
  return kIntegratorParetoTable.tableSet(std::move(rows));
}

// The first reference engine in play that runs free (Simbody); null when none does (Simbody sat out).
const Engine* findFreeRunReference() {
  for (const Engine* engine : listReferenceEngines())
    if (engine->simulate) return engine;
  return nullptr;
}

class IntegratorParetoPart final : public Part {
 public:
  std::string key() const override { return "integrator_pareto"; }
  std::string title() const override {
    const Engine* engine = findFreeRunReference();
    return (engine ? getLibraryName(*engine) : std::string("An exact engine")) + "'s integrators";
  }
  // One task that times: on a core of its own (Task::measures_time); none without the base scene's flywheel or
  // without an exact engine that runs free.
  std::vector<Task> tasks(const PartContext& context) const override {
    if (!context.base.flywheel_inertia || !findFreeRunReference()) return {};
    return {{"integrator_pareto", true,
             [base = context.base, quick = context.quick] { return calcIntegratorParetoTables(base, quick); }}};
  }
  ReportPart describe(const TableSet& tables) const override {
    ReportPart part;
    if (!tables.count(kIntegratorParetoTable.name())) return part;
    part.heading = heading();
    const Engine* engine = findFreeRunReference();
    std::string integrators;
    for (size_t i = 0; engine && i < engine->integrators.size(); ++i)
      integrators += (i == 0 ? "" : i + 1 == engine->integrators.size() ? " and " : ", ") + engine->integrators[i];
    part.caption =
        (engine ? getLibraryName(*engine) : std::string("-")) + "'s free run by " + integrators + " at accuracies 1e-3 to 1e-10: cost per "
        "simulated revolution (one Google Benchmark run) against the relative error of delta and the energy drift per "
        "revolution, the analytic energy integral as reference; the free run of the base scene released at 300 rpm (" +
        std::string(survey::kNotSceneSpeed) + "), without gas";
    part.header = {"integrator", "accuracy [-]", "time per revolution [ns]", "delta error [-]", "energy drift [-]", "status"};
    for (const IntegratorParetoRow& row : getRows(tables, kIntegratorParetoTable))
      part.rows.push_back({row.integrator, shortNumber(row.accuracy, 4), shortNumber(row.ns_per_revolution, 4),
                           shortNumber(row.delta_error, 4), shortNumber(row.energy_drift, 4), row.status});
    return part;
  }
  std::vector<const TableSchema*> schemas() const override { return {&kIntegratorParetoTable}; }
  std::string findOmission(const PartContext& context) const override {
    if (!context.base.flywheel_inertia || findFreeRunReference()) return {};  // the campaign's note says the first
    return "no exact engine in play runs free: the one that does sat out of this campaign (see its note).";
  }
};

}  // namespace

namespace parts {
const Part& integratorPareto() {
  static const IntegratorParetoPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
