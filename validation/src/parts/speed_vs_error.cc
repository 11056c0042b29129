// Report part `speed_vs_error`: cost per evaluation of Q against its error, every method timed in one run on this
// machine.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "../part_math.h"
#include "crankcheck/analytic/batch.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/balance.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/campaign_scenes.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/table.h"
#include "crankcheck/validation/task.h"
#include "crankcheck/validation/extremum.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/validation/timing.h"
#include "crankcheck/validation/variants.h"

namespace crankcheck::validation {
namespace {

using analytic::LambdaSource;

// speed_vs_error: cost per evaluation of Q against its error, every method measured in one Google Benchmark run.
struct SpeedVsErrorRow {
  std::string method;
  double ns_per_eval = 0.0;    ///< [ns] per angle
  double max_rel_error = 0.0;  ///< [-] relative to the energy scale
  std::string resolved;        ///< "1", or "0": at rounding level, a bound (resolvedToOnePercent)
};
const Schema<SpeedVsErrorRow> kSpeedVsErrorTable{
    "speed_vs_error",
    {textField("method", &SpeedVsErrorRow::method), numberField("ns_per_eval", "ns", &SpeedVsErrorRow::ns_per_eval),
     numberField("max_rel_error", "-", &SpeedVsErrorRow::max_rel_error),
     textField("resolved", &SpeedVsErrorRow::resolved)}};

TableSet calcSpeedVsErrorTables(const Mechanism& base, bool quick) {
  const Mechanism m = withSpeed(base, 0.0);
  const double E = calcEnergyScale(m);
  const std::vector<double> angles = [&] {
    std::vector<double> v;
    for (double d : anglesDeg(quick ? 30.0 : 5.0)) v.push_back(radiansFromDegrees(d));
    return v;
  }();

  struct Method {
    std::string name;
    std::function<double(double)> eval;  // Q at phi
    int fourier_order = 0;               // a Fourier series of this order; 0: another method
  };
  std::vector<Method> methods;
  const std::vector<const Engine*> references = listReferenceEngines();
  // Each reference engine's routes to Q (engine.h): its reduced gravity model, its full model at several constraint
  // accuracies where it offers them, else its full model as it is.
  for (const Engine* engine : references) {
    if (engine->build_gravity) {
      std::shared_ptr<EngineModel> reduced = engine->build_gravity(m);
      methods.push_back({engine->name + "_reduced", [reduced](double phi) { return reduced->calcQ(phi); }});
    }
  }
  methods.push_back({"exact_closed_form", [m](double phi) { return analytic::calcGravityTorque(m, phi); }});
  for (int order : {2, 4, 6, 8, 12}) {
    auto harmonics = std::make_shared<std::vector<analytic::TorqueHarmonic>>(analytic::calcGravityTorqueHarmonics(m, order));
    methods.push_back({"fourier_order_" + std::to_string(order),
                       [harmonics](double phi) { return analytic::evaluateTorqueHarmonics(*harmonics, phi); }, order});
  }
  auto printed = std::make_shared<std::vector<analytic::TorqueHarmonic>>(
      analytic::calcGravityTorqueHarmonics(m, 12, LambdaSource::kAsPrinted));
  methods.push_back({"paper_eq15_printed", [printed](double phi) { return analytic::evaluateTorqueHarmonics(*printed, phi); }});
  for (const Engine* engine : references) {
    if (!engine->build_at_accuracy) {
      std::shared_ptr<EngineModel> model = engine->build(m);
      methods.push_back({engine->name, [model](double phi) { return model->calcQ(phi); }});
      continue;
    }
    for (double tol : quick ? std::vector<double>{1e-4, 1e-12} : std::vector<double>{1e-4, 1e-6, 1e-8, 1e-10, 1e-12}) {
      std::shared_ptr<EngineModel> model = engine->build_at_accuracy(m, tol);
      char name[96];
      std::snprintf(name, sizeof name, "%s_tol_%.0e", engine->name.c_str(), tol);
      methods.push_back({name, [model](double phi) { return model->calcQ(phi); }});
    }
  }

  // Errors against the exact closed form (the closed form's own error against the first reference engine): the maximum
  // over the turn, the same in the quick and the full campaign: the Fourier series' from the exact harmonics they
  // leave out, the others by refining the best of 72 samples (extremum.h). resolved = 0: at rounding level, a bound.
  std::map<std::string, std::pair<double, bool>> errors;
  const std::unique_ptr<EngineModel> reference = references.front()->build(m);
  const auto exact_harmonics = exactHarmonics(m);
  for (const Method& method : methods) {
    double worst = 0.0;
    bool resolved = true;
    if (method.fourier_order > 0) {
      worst = maxAbsOfHarmonics(harmonicsAbove(exact_harmonics, method.fourier_order));
    } else if (method.name == "paper_eq15_printed") {
      worst = maxAbsOfHarmonics(harmonicsMinus(*printed, exact_harmonics));
      resolved = resolvedToOnePercent(worst / E);
    } else {
      const bool closed_form = method.name == "exact_closed_form";
      worst = findMaxAbsOverTurn([&](double phi) {
                return method.eval(phi) - (closed_form ? reference->calcQ(phi) : analytic::calcGravityTorque(m, phi));
              }, 72).value;
      resolved = resolvedToOnePercent(worst / E, calcScales(m).conditioning);
    }
    errors[method.name] = {worst / E, resolved};
  }
  std::vector<std::pair<std::string, std::function<void()>>> timed;
  for (const Method& method : methods) {
    auto counter = std::make_shared<size_t>(0);
    timed.emplace_back(method.name, [method, counter, angles] {
      const double phi = angles[(*counter)++ % angles.size()];
      benchmark::DoNotOptimize(method.eval(phi));
    });
  }
  // The same methods where they also have a batch form (issue 14): the SIMD kernels on arbitrary angles and on a
  // uniform grid (batch.h), and Simbody over a grid by superposing one-cylinder models (grid_sweep.h). Each call
  // evaluates a whole batch; the table gives ns per angle.
  constexpr size_t kBatch = 4096;
  const size_t engine_grid = quick ? 72 : 360;
  auto batch_angles = std::make_shared<std::vector<double>>(kBatch);
  for (size_t i = 0; i < kBatch; ++i)  // the same turn, not a grid: each angle nudged off the sample
    (*batch_angles)[i] = angles[i % angles.size()] + 1e-3 * static_cast<double>(i / angles.size());
  auto batch_out = std::make_shared<std::vector<double>>(kBatch);
  const double grid_step = 2.0 * M_PI / static_cast<double>(kBatch);
  struct BatchMethod {
    std::string name;
    size_t angles_per_call;
    std::function<void()> run;  // fills *batch_out (Simbody: its own grid)
  };
  const std::vector<BatchMethod> kernel_methods = {
      {"exact_closed_form_batch", kBatch, [m, batch_angles, batch_out] {
         analytic::calcGravityTorqueBatch(m, *batch_angles, *batch_out);
         benchmark::DoNotOptimize(batch_out->data());
       }},
      {"exact_closed_form_grid", kBatch, [m, batch_out, grid_step] {
         analytic::calcGravityTorqueOnGrid(m, 0.0, grid_step, *batch_out);
         benchmark::DoNotOptimize(batch_out->data());
       }},
  };
  std::vector<BatchMethod> batch_methods = kernel_methods;
  {
    // Their errors: the kernels against the scalar closed form (rounding: a bound), the engines' grids against it.
    std::vector<double> batch(kBatch), grid(kBatch);
    analytic::calcGravityTorqueBatch(m, *batch_angles, batch);
    analytic::calcGravityTorqueOnGrid(m, 0.0, grid_step, grid);
    double worst_batch = 0.0, worst_grid = 0.0;
    for (size_t i = 0; i < kBatch; ++i) {
      worst_batch = std::max(worst_batch, std::fabs(batch[i] - analytic::calcGravityTorque(m, (*batch_angles)[i])));
      worst_grid = std::max(worst_grid, std::fabs(grid[i] - analytic::calcGravityTorque(m, static_cast<double>(i) * grid_step)));
    }
    errors["exact_closed_form_batch"] = {worst_batch / E, false};
    errors["exact_closed_form_grid"] = {worst_grid / E, false};
  }
  // Each reference engine's route over a whole grid (Engine::calc_q_on_grid: Simbody's superposition of one-cylinder
  // models, grid_sweep.h).
  for (const Engine* engine : references) {
    if (!engine->calc_q_on_grid) continue;
    const double step = 2.0 * M_PI / static_cast<double>(engine_grid);
    const std::string name = engine->name + "_grid_superposition";
    batch_methods.push_back({name, engine_grid, [m, engine, engine_grid, step] {
                               benchmark::DoNotOptimize(engine->calc_q_on_grid(m, 0.0, step, engine_grid));
                             }});
    const std::vector<double> sweep = engine->calc_q_on_grid(m, 0.0, step, engine_grid);
    double worst_sweep = 0.0;
    for (size_t i = 0; i < engine_grid; ++i)
      worst_sweep = std::max(worst_sweep, std::fabs(sweep[i] - analytic::calcGravityTorque(m, 2.0 * M_PI * static_cast<double>(i) /
                                                                                               static_cast<double>(engine_grid))));
    errors[name] = {worst_sweep / E, resolvedToOnePercent(worst_sweep / E, calcScales(m).conditioning)};
  }
  for (const BatchMethod& b : batch_methods) timed.emplace_back(b.name, b.run);
  const std::map<std::string, double> ns = measureNanosecondsPerCall(timed, getTimingSeconds(quick));
  std::vector<SpeedVsErrorRow> rows;
  for (const Method& method : methods) {
    const auto it = ns.find(method.name);
    if (it != ns.end())
      rows.push_back({method.name, it->second, errors[method.name].first, errors[method.name].second ? "1" : "0"});
  }
  for (const BatchMethod& b : batch_methods) {
    const auto it = ns.find(b.name);
    if (it != ns.end())
      rows.push_back({b.name, it->second / static_cast<double>(b.angles_per_call), errors[b.name].first,
                      errors[b.name].second ? "1" : "0"});
  }
  return kSpeedVsErrorTable.tableSet(std::move(rows));
}

// Each reference engine's routes to Q, as calcSpeedVsErrorTables takes them: "Simbody at several projection
// tolerances and by its reduced gravity model, MuJoCo by its model".
std::string listReferenceRoutes() {
  std::string out;
  for (const Engine* e : listReferenceEngines()) {
    std::string routes = e->build_at_accuracy ? "at several projection tolerances" : "by its model";
    if (e->build_gravity) routes += " and by its reduced gravity model";
    out += (out.empty() ? "" : ", ") + getLibraryName(*e) + " " + routes;
  }
  return out;
}

class SpeedVsErrorPart final : public Part {
 public:
  std::string key() const override { return "speed_vs_error"; }
  std::string title() const override { return "Speed against error"; }
  // One task that times: on a core of its own (Task::measures_time).
  std::vector<Task> tasks(const PartContext& context) const override {
    return {{"speed_vs_error", true, [base = context.base, quick = context.quick] { return calcSpeedVsErrorTables(base, quick); }}};
  }
  ReportPart describe(const TableSet& tables) const override {
    ReportPart part;
    if (!tables.count(kSpeedVsErrorTable.name())) return part;
    part.heading = heading();
    part.blocks.push_back({ReportBlock::kFigure,
                           "Cost per evaluation of Q against its error, all measured in one run on this machine: the "
                           "exact closed form, Fourier orders, the printed eq (15), each reference engine by each of its "
                           "routes to Q (" + listReferenceRoutes() + "); the Pareto front joined",
                           {}, {}, key()});
    ReportBlock table{ReportBlock::kTable, "", {"method", "time per evaluation [ns]", "max error / energy scale [-]", "resolved"}};
    for (const SpeedVsErrorRow& row : getRows(tables, kSpeedVsErrorTable))
      table.rows.push_back({row.method, shortNumber(row.ns_per_eval, 4), shortNumber(row.max_rel_error, 4), row.resolved});
    part.blocks.push_back(std::move(table));
    part.blocks.push_back({ReportBlock::kParagraph,
                           "Each error is the maximum over the turn (the Fourier series' from the exact harmonics they "
                           "leave out, the others refined from 72 samples by Brent's method). resolved = 0: the error is "
                           "at rounding level (below 100 x 64 eps of the energy scale), the number is a bound, not a "
                           "measured maximum."});
    return part;
  }
  std::vector<const TableSchema*> schemas() const override { return {&kSpeedVsErrorTable}; }
  std::vector<ReportedMaximum> maxima() const override {
    return {{"speed_vs_error", {"method"}, {"max_rel_error"}, "resolved", "0"}};
  }
};

}  // namespace

namespace parts {
const Part& speedVsError() {
  static const SpeedVsErrorPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
