// Report part `flywheel`: flywheel sizing (Norton 13.9) judged: the exact energy integral's inertia against Norton's,
// the steady run's delta against the flywheel inertia confirmed by the reference engines' free runs with gas and load.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "crankcheck/analytic/flywheel.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/example_gas.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/variants.h"
#include "../flywheel_run.h"
#include "engine_fields.h"
#include "survey.h"

namespace crankcheck::validation {
namespace {

constexpr double kFluctuation = 0.01;

// flywheel: for each campaign scene with [gas], the steady run's delta against the flywheel inertia I_f, 0.3 to 3 times
// the exact inertia for C = 0.01: the exact energy integral's, and each loaded-run engine's where it ran (empty
// elsewhere). The key columns first: sorted, each series' rows come together, in order (reports/flywheel.gp draws
// them so).
struct FlywheelCurveRow {
  std::string scene;
  double flywheel_inertia = 0.0;  ///< [kg m^2]
  double exact_delta = 0.0;       ///< [-]
  /// [-] each engine's delta (listLoadedRunEngines' order); empty where it did not run.
  std::vector<std::optional<double>> engine_delta;
};

std::vector<Field<FlywheelCurveRow>> makeFlywheelCurveFields() {
  std::vector<Field<FlywheelCurveRow>> fields = {
      textField("scene", &FlywheelCurveRow::scene),
      numberField("flywheel_inertia", "kg m^2", &FlywheelCurveRow::flywheel_inertia),
      numberField("exact_delta", "-", &FlywheelCurveRow::exact_delta)};
  const std::vector<const Engine*> engines = listLoadedRunEngines();
  for (size_t i = 0; i < engines.size(); ++i) fields.push_back(elementField(engines[i]->name + "_delta", "-", &FlywheelCurveRow::engine_delta, i));
  return fields;
}

// The schema of `flywheel`: one delta column per engine in play whose free run takes loads (engine_fields.h).
const Schema<FlywheelCurveRow>& getFlywheelCurveTable() {
  return getEngineSchema<FlywheelCurveRow, makeFlywheelCurveFields>("flywheel");
}

// flywheel_sizing: the exact and Norton's I_f for C = 0.01 of the campaign's gas scenes.
struct FlywheelSizingRow {
  std::string scene, cycle;
  int k = 1;
  double speed_rpm = 0.0;       ///< [rpm]
  double exact_inertia = 0.0;   ///< [kg m^2]
  double norton_inertia = 0.0;  ///< [kg m^2]
  double norton_error = 0.0;    ///< [-] norton / exact - 1
  double norton_delta = 0.0;    ///< [-] the delta Norton's inertia really gives
};
const Schema<FlywheelSizingRow> kFlywheelSizingTable{
    "flywheel_sizing",
    {textField("scene", &FlywheelSizingRow::scene), textField("cycle", &FlywheelSizingRow::cycle),
     countField("k", &FlywheelSizingRow::k), numberField("speed_rpm", "rpm", &FlywheelSizingRow::speed_rpm),
     numberField("exact_inertia", "kg m^2", &FlywheelSizingRow::exact_inertia),
     numberField("norton_inertia", "kg m^2", &FlywheelSizingRow::norton_inertia),
     numberField("norton_error", "-", &FlywheelSizingRow::norton_error),
     numberField("norton_delta", "-", &FlywheelSizingRow::norton_delta)}};

// flywheel_norton: the same for the base scene's parts as an inline k-cylinder four-stroke with the example
// spark-ignition pressures (bore 2 r), k = 1, 2, 3, 4, 6, at 1500, 3000 and 6000 rpm (rows where no flywheel is needed
// for C = 0.01 are left out).
struct FlywheelNortonRow {
  double speed_rpm = 0.0;  ///< [rpm]
  int k = 1;
  double exact_inertia = 0.0;   ///< [kg m^2]
  double norton_inertia = 0.0;  ///< [kg m^2]
  double norton_error = 0.0;    ///< [-] norton / exact - 1
  double norton_delta = 0.0;    ///< [-] the delta Norton's inertia really gives
};
const Schema<FlywheelNortonRow> kFlywheelNortonTable{
    "flywheel_norton",
    {numberField("speed_rpm", "rpm", &FlywheelNortonRow::speed_rpm), countField("k", &FlywheelNortonRow::k),
     numberField("exact_inertia", "kg m^2", &FlywheelNortonRow::exact_inertia),
     numberField("norton_inertia", "kg m^2", &FlywheelNortonRow::norton_inertia),
     numberField("norton_error", "-", &FlywheelNortonRow::norton_error),
     numberField("norton_delta", "-", &FlywheelNortonRow::norton_delta)}};

// The part's three tables, each task's rows in its own (the campaign adds them up, appendTables): every task gives all
// three, empty or not.
TableSet makeFlywheelTables(std::vector<FlywheelCurveRow> curve, std::vector<FlywheelSizingRow> sizing,
                            std::vector<FlywheelNortonRow> sweep) {
  const Schema<FlywheelCurveRow>& curve_table = getFlywheelCurveTable();
  return {{curve_table.name(), curve_table.table(std::move(curve))},
          {kFlywheelSizingTable.name(), kFlywheelSizingTable.table(std::move(sizing))},
          {kFlywheelNortonTable.name(), kFlywheelNortonTable.table(std::move(sweep))}};
}

std::optional<analytic::FlywheelSizing> sized(const Mechanism& m) {
  try {
    return analytic::calcFlywheelSizing(m, kFluctuation);
  } catch (const std::domain_error&) {
    return std::nullopt;  // no flywheel needed (or possible) for this C
  }
}

// The points of the curve delta(I_f): 0.3 to 3 times the exact inertia, log spaced.
int calcPointCount(bool quick) { return quick ? 5 : 13; }

// A scene's sizing (sized) and the steady runs of its curve's points (calcSteadyRuns: the cycle's integrals once for
// all of them), computed once for all of the scene's tasks (SharedResult: with two or more workers the scene's first
// two tasks run side by side, so one of them waits for the other).
struct Curve {
  std::optional<analytic::FlywheelSizing> sizing;  // empty when the scene needs no flywheel for C (or none is possible)
  std::vector<double> inertias;                    // [kg m^2] 0.3 .. 3 times the exact inertia
  std::vector<analytic::SteadyRun> runs;           // at each of them
};
Curve calcCurve(const Mechanism& m, bool quick) {
  Curve c;
  c.sizing = sized(m);
  if (!c.sizing) return c;
  const int points = calcPointCount(quick);
  for (int i = 0; i < points; ++i)
    c.inertias.push_back(c.sizing->exact_inertia * std::pow(10.0, -0.5 + static_cast<double>(i) / (points - 1)));
  c.runs = analytic::calcSteadyRuns(m, c.inertias, c.sizing->load_torque);
  return c;
}

// The points of a scene's curve (`flywheel`) at which Simbody runs: every third of 13, the exact inertia among
// them; with `quick`, a smoke test of the run: the exact inertia's alone (10^0 of it), on the first scene with gas
// alone (the same route on every scene; the other scenes' runs were 0.8 of the quick part's cost, issue 28).
std::vector<int> listFlywheelRunPoints(bool quick, bool first_gas_scene) {
  if (quick) return first_gas_scene ? std::vector<int>{calcPointCount(quick) / 2} : std::vector<int>{};
  std::vector<int> runs;
  for (int i = 0; i < calcPointCount(quick); i += 3) runs.push_back(i);  // every third point, the middle among them
  return runs;
}

// The part's three tables with rows of one scene (none when it has no [gas] or needs no flywheel for C = 0.01):
// `point` < 0: its `flywheel_sizing` row and the curve's points Simbody does not run; else the curve's point `point`
// (one of `runs`, the scene's listFlywheelRunPoints) with Simbody's run.
TableSet calcFlywheelSceneTables(const Mechanism& m, bool quick, const std::vector<int>& runs, int point,
                                 SharedResult<Curve>& shared) {
  std::vector<FlywheelCurveRow> curve;
  std::vector<FlywheelSizingRow> sizing;
  if (!m.gas || !(m.machine.speed > 0.0)) return makeFlywheelTables({}, {}, {});
  const Curve& c = shared.get();
  const std::optional<analytic::FlywheelSizing>& s = c.sizing;
  if (!s) return makeFlywheelTables({}, {}, {});
  const analytic::FlywheelSizing& exact = *s;
  if (point < 0)
    sizing.push_back({m.name, toString(m.machine.cycle), m.machine.cylinders, m.speed_rpm, exact.exact_inertia,
                      exact.norton_inertia, exact.norton_inertia / exact.exact_inertia - 1.0, exact.norton.delta});
  for (int i = 0; i < calcPointCount(quick); ++i) {  // this task's points: the runs alone, the rest together
    const bool run_here = std::find(runs.begin(), runs.end(), i) != runs.end();
    if (point < 0 ? run_here : i != point) continue;
    const double I = c.inertias[static_cast<size_t>(i)];
    const analytic::SteadyRun& steady = c.runs[static_cast<size_t>(i)];
    const bool run = point >= 0;
    FlywheelCurveRow row{m.name, I, steady.delta, {}};
    for (const Engine* engine : listLoadedRunEngines()) {
      if (!run) {
        row.engine_delta.emplace_back();
        continue;
      }
      Mechanism with = m;
      with.flywheel_inertia = I;
      row.engine_delta.emplace_back(
          engine->simulate(with, steady.omega0, makeFlywheelRunSettings(*engine, true, exact.load_torque)).delta);
    }
    curve.push_back(std::move(row));
  }
  return makeFlywheelTables(std::move(curve), std::move(sizing), {});
}

// The part's three tables with the rows of the sweep on `parts` (`flywheel_norton`).
TableSet calcFlywheelNortonTables(const Mechanism& parts, bool quick) {
  std::vector<FlywheelNortonRow> sweep;
  const std::vector<int> ks = quick ? std::vector<int>{1, 4} : std::vector<int>{1, 2, 3, 4, 6};
  const std::vector<double> speeds = quick ? std::vector<double>{3000.0} : std::vector<double>{1500.0, 3000.0, 6000.0};
  Mechanism base = parts;
  base.machine.pin_offsets.clear();
  base.balance_shafts.clear();
  for (int k : ks)
    for (double rpm : speeds) {
      const Mechanism m = withSpeed(withGasAtDeadCentres(withGamma(withCylinders(base, k, Cycle::kFourStroke), 90.0),
                                                         makeExampleGas(Cycle::kFourStroke, 2.0 * base.crank.radius)),
                                    rpm);
      if (const std::optional<analytic::FlywheelSizing> s = sized(m))
        sweep.push_back({rpm, k, s->exact_inertia, s->norton_inertia, s->norton_inertia / s->exact_inertia - 1.0,
                         s->norton.delta});
    }
  return makeFlywheelTables({}, {}, std::move(sweep));
}

// The part as the report shows it under `heading`: figure caption, sentences read from the data; an empty heading
// without data.
ReportPart describeFlywheelPart(const TableSet& tables, const std::string& heading) {
  ReportPart part;
  const Schema<FlywheelCurveRow>& curve_table = getFlywheelCurveTable();
  if (!tables.count(kFlywheelSizingTable.name()) || !tables.count(kFlywheelNortonTable.name()) ||
      !tables.count(curve_table.name()))
    return part;
  part.heading = heading;
  std::vector<double> speeds;  // the right panel's, read from its table
  for (const FlywheelNortonRow& row : getRows(tables, kFlywheelNortonTable)) speeds.push_back(row.speed_rpm);
  part.caption =
      "Left: the steady run's speed fluctuation delta against the flywheel inertia for each scene with gas, at its own "
      "speed with its own [gas] (the exact energy integral as lines" +
      (listLoadedRunEngines().empty() ? std::string()
                                      : ", " + getLibraryName(*listLoadedRunEngines().front()) + "'s run over a working cycle as dots") +
      "), the "
      "exact inertia for delta = 0.01 marked by the dashed line. Right: the error of Norton's inertia (13.9) against "
      "the exact one, for C = 0.01, against the number of cylinders of an inline four-stroke on the base scene's parts "
      "with " + std::string(survey::kExampleGas) + ", one line per speed" +
      (speeds.empty() ? std::string() : ", " + survey::atSurveySpeeds(speeds));
  for (const FlywheelSizingRow& row : getRows(tables, kFlywheelSizingTable))
    part.paragraphs.push_back(row.scene + " at C = 0.01: the exact flywheel is " + shortNumber(row.exact_inertia, 4) +
                              " kg m^2, Norton's " + shortNumber(row.norton_inertia, 4) + " kg m^2 (" +
                              formatPercent(row.norton_error) + "), which really gives delta = " +
                              shortNumber(row.norton_delta, 4) + ".");
  const std::vector<FlywheelNortonRow>& sweep = getRows(tables, kFlywheelNortonTable);
  if (sweep.empty()) return part;
  double worst = 0.0, best = 1e300;
  std::string worst_at, best_at;
  for (const FlywheelNortonRow& row : sweep) {
    const double e = std::fabs(row.norton_error);
    const std::string at = "k = " + std::to_string(row.k) + ", " + shortNumber(row.speed_rpm, 5) + " rpm";
    if (e > worst) {
      worst = e;
      worst_at = at;
    }
    if (e < best) {
      best = e;
      best_at = at;
    }
  }
  part.paragraphs.push_back("On the base scene's parts as an inline four-stroke with gas, Norton's inertia is off by " +
                            formatPercent(best) + " at best (" + best_at + ") and " + formatPercent(worst) +
                            " at worst (" + worst_at +
                            "): his method takes the energy swing of the constant-speed torque, and leaves out that the "
                            "speed itself varies and that the mechanism's own inertia varies with the crank angle.");
  const std::vector<const Engine*> engines = listLoadedRunEngines();
  for (size_t i = 0; i < engines.size(); ++i) {
    double agreement = 0.0;
    for (const FlywheelCurveRow& row : getRows(tables, curve_table))
      if (i < row.engine_delta.size() && row.engine_delta[i])
        agreement = std::max(agreement, std::fabs(*row.engine_delta[i] / row.exact_delta - 1.0));
    part.paragraphs.push_back(engines[i]->library.substr(0, engines[i]->library.find(' ')) +
                              "'s run agrees with the exact energy integral's delta to " + shortNumber(agreement, 2) +
                              " (relative) at every point it was run.");
  }
  return part;
}

class FlywheelPart final : public Part {
 public:
  std::string key() const override { return "flywheel"; }
  std::string title() const override {
    const std::vector<const Engine*> runs = listLoadedRunEngines();  // none when Simbody sat out
    return "Flywheel sizing: the exact inertia, Norton's method" +
           (runs.empty() ? std::string() : ", " + getLibraryName(*runs.front()) + "'s run");
  }
  // One task per Simbody run and one per gas scene for the rest of its curve (listed with its runs), one for the
  // sweep on the base's parts: the tables add up.
  std::vector<Task> tasks(const PartContext& context) const override {
    std::vector<Task> out;
    const bool quick = context.quick;
    bool first_gas_scene = true;
    for (const Mechanism& m : context.scenes) {
      if (!m.gas) continue;
      auto sizing = std::make_shared<SharedResult<Curve>>([m, quick] { return calcCurve(m, quick); });
      const std::vector<int> runs = listFlywheelRunPoints(quick, first_gas_scene);
      first_gas_scene = false;
      out.push_back({"flywheel " + m.name, false,
                     [m, quick, runs, sizing] { return calcFlywheelSceneTables(m, quick, runs, -1, *sizing); },
                     task_cost::kFineCycleRun});
      for (int point : runs)
        out.push_back({"flywheel " + m.name + " run " + std::to_string(point), false,
                       [m, quick, runs, point, sizing] {
                         return calcFlywheelSceneTables(m, quick, runs, point, *sizing);
                       },
                       task_cost::kFineCycleRun});
    }
    out.push_back({"flywheel_norton", false, [base = context.base, quick] { return calcFlywheelNortonTables(base, quick); }});
    return out;
  }
  ReportPart describe(const TableSet& tables) const override { return describeFlywheelPart(tables, heading()); }
  std::vector<const TableSchema*> schemas() const override {
    return {&getFlywheelCurveTable(), &kFlywheelSizingTable, &kFlywheelNortonTable};
  }
};

}  // namespace

namespace parts {
const Part& flywheel() {
  static const FlywheelPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
