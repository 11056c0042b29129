// The scene sections' topic "Flywheel and torsion": the scene's speed fluctuation with its own flywheel at its own
// speed and gas (the exact energy integral, each engine's free run, Norton's method 13.9), and its crank train's
// critical speeds and twist at its speed (Holzer's constant inertia against the exact variable-inertia train).
#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "crankcheck/analytic/flywheel.h"
#include "crankcheck/analytic/motion.h"
#include "crankcheck/validation/commands/torsion.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/report_format.h"
#include "../flywheel_run.h"
#include "../torsion_train.h"
#include "topic.h"

namespace crankcheck::validation::your_engine {
namespace {

// your_engine_flywheel: the speed fluctuation of the scene with its own flywheel at its mean speed over a working cycle
// (720 degrees four-stroke with gas, 360 otherwise), one row per way: the exact energy integral ("analytic") and each
// engine's free run. With [gas]: against a constant load, the cycle mean of the gas torque (as the flywheel part);
// without: gravity alone, no load.
struct FlywheelRow {
  std::string scene, engine;
  int gated = 1;                    ///< 0: a soft way, measured beside
  int gas = 0;                      ///< 1: the scene's gas and the load; 0: gravity alone
  double flywheel_inertia = 0.0;    ///< [kg m^2] the scene's I_w
  double load_torque = 0.0;         ///< [N m]
  double omega0 = 0.0;              ///< [rad/s] the speed at phi = 0 of the periodic run (every engine's release)
  double omega_mean = 0.0, omega_min = 0.0, omega_max = 0.0;  ///< [rad/s]
  double delta = 0.0;               ///< [-] (omega_max - omega_min) / omega_mean
  double phi_deg_at_omega_max = 0.0, phi_deg_at_omega_min = 0.0;  ///< [deg] in the working cycle
  double accuracy = 0.0;            ///< the engine's accuracy in its own sense (0: the energy integral)
  std::string note;                 ///< why the row has no numbers (the way refused or failed); empty otherwise
};
const Schema<FlywheelRow> kFlywheelTable{
    "your_engine_flywheel",
    {textField("scene", &FlywheelRow::scene), textField("engine", &FlywheelRow::engine),
     countField("gated", &FlywheelRow::gated), countField("gas", &FlywheelRow::gas),
     numberField("flywheel_inertia", "kg m^2", &FlywheelRow::flywheel_inertia),
     numberField("load_torque", "N m", &FlywheelRow::load_torque), numberField("omega0", "rad/s", &FlywheelRow::omega0),
     numberField("omega_mean", "rad/s", &FlywheelRow::omega_mean), numberField("omega_min", "rad/s", &FlywheelRow::omega_min),
     numberField("omega_max", "rad/s", &FlywheelRow::omega_max), numberField("delta", "-", &FlywheelRow::delta),
     numberField("phi_deg_at_omega_max", "deg", &FlywheelRow::phi_deg_at_omega_max),
     numberField("phi_deg_at_omega_min", "deg", &FlywheelRow::phi_deg_at_omega_min),
     numberField("accuracy", "-", &FlywheelRow::accuracy), textField("note", &FlywheelRow::note)}};

// your_engine_critical: the critical speeds of the major orders within kCriticalRange of the scene's speed, Holzer's
// (J_eq) and the band of the variable-inertia train's (every throw at J_max .. every throw at J_min).
struct CriticalRow {
  std::string scene;
  int mode = 1;
  double order = 0.0;        ///< [-] a major order (a multiple of the firings per turn)
  double holzer_rpm = 0.0;   ///< [rpm] omega_mode / order
  double band_lo_rpm = 0.0, band_hi_rpm = 0.0;  ///< [rpm]
};
const Schema<CriticalRow> kCriticalTable{
    "your_engine_critical",
    {textField("scene", &CriticalRow::scene), countField("mode", &CriticalRow::mode),
     numberField("order", "-", &CriticalRow::order), numberField("holzer_rpm", "rpm", &CriticalRow::holzer_rpm),
     numberField("band_lo_rpm", "rpm", &CriticalRow::band_lo_rpm),
     numberField("band_hi_rpm", "rpm", &CriticalRow::band_hi_rpm)}};

// your_engine_twist: each section's peak-to-peak twist at the scene's speed: Holzer's (every order, and cut at order
// 24) and the exact steady state's (its error bound beside).
struct TwistRow {
  std::string scene;
  int section_index = 0;
  std::string section;
  double speed_rpm = 0.0;                                  ///< [rpm]
  double holzer = 0.0, holzer_order24 = 0.0, exact = 0.0;  ///< [rad]
  double error_bound = 0.0;                                ///< [rad] the exact state's
  double omega1 = 0.0;                                     ///< [rad/s] Holzer's first natural frequency
  double omega1_lo = 0.0, omega1_hi = 0.0;                 ///< [rad/s] the variable-inertia train's band
  std::string note;  ///< why the train was not computed (one row, no section): outside the model's domain; else empty
};
const Schema<TwistRow> kTwistTable{
    "your_engine_twist",
    {textField("scene", &TwistRow::scene), countField("section_index", &TwistRow::section_index),
     textField("section", &TwistRow::section), numberField("speed_rpm", "rpm", &TwistRow::speed_rpm),
     numberField("holzer", "rad", &TwistRow::holzer), numberField("holzer_order24", "rad", &TwistRow::holzer_order24),
     numberField("exact", "rad", &TwistRow::exact), numberField("error_bound", "rad", &TwistRow::error_bound),
     numberField("omega1", "rad/s", &TwistRow::omega1), numberField("omega1_lo", "rad/s", &TwistRow::omega1_lo),
     numberField("omega1_hi", "rad/s", &TwistRow::omega1_hi), textField("note", &TwistRow::note)}};

// The critical speeds listed: the major orders' within 0.25 .. 1.25 of the scene's speed (the torsion part's sweep).
constexpr double kCriticalLow = 0.25, kCriticalHigh = 1.25;

// The fitness table's rows of this topic: Norton's method from 100, Holzer's from 110.
constexpr int kNortonOrder = 100, kHolzerOrder = 110;
const std::string kNortonFlywheel = "Norton's flywheel method (13.9)";

// Every table a task of this topic writes, empty (a task gives them all, so that the section has each table).
TableSet makeTables() {
  return {{kFlywheelTable.name(), kFlywheelTable.table()},
          {kCriticalTable.name(), kCriticalTable.table()},
          {kTwistTable.name(), kTwistTable.table()},
          {kFitnessTable.name(), kFitnessTable.table()}};
}

// The working cycle [rad]: 720 degrees for a four-stroke with gas (its pressures repeat so), else a turn.
double cycleOf(const Mechanism& m) { return m.gas && m.machine.cycle == Cycle::kFourStroke ? 4.0 * M_PI : 2.0 * M_PI; }

// The exact run of the scene with its flywheel: the energy integral with the gas and its load (flywheel.h), or without
// gas the free run under gravity (motion.h) released at the speed whose mean is the scene's (the secant method on
// omega0, to rounding: the free run's mean speed is smooth and nearly proportional to omega0).
struct ExactRun {
  FlywheelRow row;
  double norton_delta = 0.0;  // with gas
};
ExactRun calcExactRun(const Mechanism& m) {
  ExactRun out;
  FlywheelRow& r = out.row;
  r.scene = m.name;
  r.engine = getClosedFormEngine().name;
  r.gas = m.gas ? 1 : 0;
  r.flywheel_inertia = *m.flywheel_inertia;
  try {
    if (m.gas) {
      const analytic::FlywheelFluctuation f = analytic::calcFlywheelFluctuation(m, *m.flywheel_inertia);
      r.load_torque = f.load_torque;
      r.omega0 = f.exact.omega0;
      r.omega_mean = f.exact.omega_mean;
      r.omega_min = f.exact.omega_min;
      r.omega_max = f.exact.omega_max;
      r.delta = f.exact.delta;
      r.phi_deg_at_omega_max = degreesFromRadians(f.exact.phi_at_omega_max);
      r.phi_deg_at_omega_min = degreesFromRadians(f.exact.phi_at_omega_min);
      out.norton_delta = f.norton_delta;
    } else {
      const double omega = m.machine.speed;
      if (!(omega > 0.0)) throw std::invalid_argument("[engine].speed_rpm: must be > 0 (the mean speed of the run)");
      double x0 = omega, x1 = 1.001 * omega;
      analytic::FreeRun run0 = analytic::calcFreeRun(m, x0), run1 = analytic::calcFreeRun(m, x1);
      for (int it = 0; it < 50 && std::fabs(run1.omega_mean - omega) > 4.0 * std::numeric_limits<double>::epsilon() * omega &&
                       run1.omega_mean != run0.omega_mean;
           ++it) {
        const double x2 = x1 - (run1.omega_mean - omega) * (x1 - x0) / (run1.omega_mean - run0.omega_mean);
        x0 = x1;
        run0 = run1;
        x1 = x2;
        run1 = analytic::calcFreeRun(m, x1);
      }
      r.omega0 = x1;
      r.omega_mean = run1.omega_mean;
      r.omega_min = run1.omega_min;
      r.omega_max = run1.omega_max;
      r.delta = run1.delta;
      r.phi_deg_at_omega_max = degreesFromRadians(run1.phi_at_omega_max);
      r.phi_deg_at_omega_min = degreesFromRadians(run1.phi_at_omega_min);
    }
  } catch (const std::exception& e) {
    r.note = e.what();
  }
  return out;
}

// The engines that run the scene's working cycle: with gas, those whose free run takes the gas and the load
// (Engine::simulates_loads, gated or not); without, every engine that simulates (the soft ways measured beside).
std::vector<const Engine*> listRunEngines(const Mechanism& m) {
  std::vector<const Engine*> out;
  for (const Engine& e : listEngines())
    if (e.simulate && !e.closed_form && (e.simulates_loads || !m.gas)) out.push_back(&e);
  return out;
}

// `engine`'s run released at the exact run's omega0 (the periodic state's speed at phi = 0), its delta over the
// working cycle as the engine measures it, the angles of its extremes among its steps; and, with gas, Norton's delta
// against it.
TableSet calcEngineRun(const Mechanism& m, const Engine& engine, SharedResult<ExactRun>& shared) {
  TableSet tables = makeTables();
  const ExactRun& exact = shared.get();
  if (!exact.row.note.empty()) return tables;  // the analytic row says why
  FlywheelRow r{m.name, engine.name, engine.gated ? 1 : 0, exact.row.gas, exact.row.flywheel_inertia,
                exact.row.load_torque, exact.row.omega0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, {}};
  const FreeRunSettings settings = makeFlywheelRunSettings(engine, m.gas.has_value(), exact.row.load_torque);
  r.accuracy = settings.accuracy;
  try {
    const FreeRunResult result = engine.simulate(m, exact.row.omega0, settings);
    const Trajectory& run = result.trajectory;
    r.omega_mean = result.omega_mean;
    r.omega_min = result.omega_min;
    r.omega_max = result.omega_max;
    r.delta = result.delta;
    const double cycle = cycleOf(m);
    size_t imax = 0, imin = 0;
    for (size_t i = 0; i < run.phi.size() && run.phi[i] - run.phi.front() < cycle; ++i) {
      if (run.omega[i] > run.omega[imax]) imax = i;
      if (run.omega[i] < run.omega[imin]) imin = i;
    }
    if (!run.phi.empty()) {
      r.phi_deg_at_omega_max = degreesFromRadians(std::fmod(run.phi[imax] - run.phi.front(), cycle));
      r.phi_deg_at_omega_min = degreesFromRadians(std::fmod(run.phi[imin] - run.phi.front(), cycle));
    }
    if (m.gas)
      tables.at(kFitnessTable.name())
          .getRows(kFitnessTable)
          .push_back({m.name, kNortonOrder + 1 + static_cast<int>(listEngines().indexOf(engine)), kNortonFlywheel, "delta",
                      engine.name, std::fabs(exact.norton_delta - result.delta) / result.delta,
                      "delta (" + engine.name + ")", result.delta, "-", std::nullopt, 1});
  } catch (const std::exception& e) {
    r.note = e.what();
  }
  tables.at(kFlywheelTable.name()).getRows(kFlywheelTable).push_back(std::move(r));
  return tables;
}

TableSet calcExactTables(const Mechanism& m, SharedResult<ExactRun>& shared) {
  TableSet tables = makeTables();
  const ExactRun& exact = shared.get();
  tables.at(kFlywheelTable.name()).getRows(kFlywheelTable).push_back(exact.row);
  if (m.gas && exact.row.note.empty())
    tables.at(kFitnessTable.name())
        .getRows(kFitnessTable)
        .push_back({m.name, kNortonOrder, kNortonFlywheel, "delta", exact.row.engine,
                    std::fabs(exact.norton_delta - exact.row.delta) / exact.row.delta, "delta (exact)", exact.row.delta,
                    "-", std::nullopt, 1});
  return tables;
}

TableSet calcTrainTablesOrThrow(const Mechanism& m);

// The crank train at the scene's speed: the critical speeds in range, each section's twist by Holzer and the exact
// steady state, Holzer's fitness (first natural frequency against the variable-inertia band, twist against the exact).
TableSet calcTrainTables(const Mechanism& m) {
  try {
    return calcTrainTablesOrThrow(m);
  } catch (const std::exception& e) {  // outside the model's domain (torsion_domain.h), or no periodic state
    TableSet tables = makeTables();
    TwistRow row;
    row.scene = m.name;
    row.speed_rpm = m.speed_rpm;
    row.note = e.what();
    tables.at(kTwistTable.name()).getRows(kTwistTable).push_back(std::move(row));
    return tables;
  }
}

TableSet calcTrainTablesOrThrow(const Mechanism& m) {
  TableSet tables = makeTables();
  const TorsionModeBand band = calcTorsionModeBand(m);
  const double lo = kCriticalLow * m.speed_rpm, hi = kCriticalHigh * m.speed_rpm;
  const double to_rpm = 30.0 / M_PI;
  auto& critical = tables.at(kCriticalTable.name()).getRows(kCriticalTable);
  for (int i = 0; i < band.holzer.frequencies.size(); ++i)
    for (double p : listMajorOrders(m, kTextbookOrder)) {
      const double rpm = band.holzer.frequencies(i) / p * to_rpm;
      if (rpm >= lo && rpm <= hi)
        critical.push_back({m.name, i + 1, p, rpm, band.at_max.frequencies(i) / p * to_rpm,
                            band.at_min.frequencies(i) / p * to_rpm});
    }
  const analytic::HolzerResponse holzer = analytic::calcHolzerResponse(m, makeTrainHolzerOptions());
  const analytic::ExactSteadyState exact = analytic::calcExactSteadyState(m, holzer, makeTrainSteadyStateOptions());
  const int n = static_cast<int>(exact.peak_to_peak.size());
  const double w1 = band.holzer.frequencies(0), w1_lo = band.at_max.frequencies(0), w1_hi = band.at_min.frequencies(0);
  double scale = 0.0, err = 0.0, err24 = 0.0;
  for (int i = 0; i < n; ++i) {
    tables.at(kTwistTable.name())
        .getRows(kTwistTable)
        .push_back({m.name, i, nameSection(m, i, n), m.speed_rpm, holzer.peak_to_peak[i], holzer.peak_to_peak_order24[i],
                    exact.peak_to_peak[i], exact.error_bound, w1, w1_lo, w1_hi, {}});
    scale = std::max(scale, exact.peak_to_peak[i]);
    err = std::max(err, std::fabs(holzer.peak_to_peak[i] - exact.peak_to_peak[i]));
    err24 = std::max(err24, std::fabs(holzer.peak_to_peak_order24[i] - exact.peak_to_peak[i]));
  }
  const std::string reference = getClosedFormEngine().name;
  auto& fitness = tables.at(kFitnessTable.name()).getRows(kFitnessTable);
  fitness.push_back({m.name, kHolzerOrder, "Holzer's constant inertia J_eq", "omega_1", reference,
                     std::max(w1 - w1_lo, w1_hi - w1) / w1, "omega_1 (Holzer)", w1, "rad/s", std::nullopt, 1});
  fitness.push_back({m.name, kHolzerOrder + 1, "Holzer's constant inertia J_eq", "twist (peak to peak)", reference,
                     err / scale, "max exact peak-to-peak", scale, "rad", std::nullopt, 1});
  fitness.push_back({m.name, kHolzerOrder + 2, "Holzer's constant inertia, orders <= 24", "twist (peak to peak)",
                     reference, err24 / scale, "max exact peak-to-peak", scale, "rad", std::nullopt, 1});
  return tables;
}

template <class Row>
std::vector<Row> rowsOfScene(const TableSet& tables, const Schema<Row>& schema, const std::string& scene) {
  std::vector<Row> out;
  for (const Row& row : getRows(tables, schema))
    if (row.scene == scene) out.push_back(row);
  return out;
}

std::string deg(double x) { return shortNumber(x, 4) + " deg"; }

std::vector<ReportBlock> describeFlywheel(const TableSet& tables, const SceneFactsRow& facts) {
  std::vector<ReportBlock> out;
  if (!facts.flywheel) {
    out.push_back({ReportBlock::kParagraph,
                   "No [flywheel] table: add one (its inertia I_w, docs/SCENE-FORMAT.md, [flywheel]) to see the speed "
                   "fluctuation over the working cycle at the scene's speed and Norton's flywheel method judged."});
    return out;
  }
  const std::vector<FlywheelRow> rows = rowsOfScene(tables, kFlywheelTable, facts.scene);
  const auto exact = std::find_if(rows.begin(), rows.end(), [](const FlywheelRow& r) { return r.engine == getClosedFormEngine().name; });
  if (exact == rows.end()) return out;
  if (!exact->note.empty()) {
    out.push_back({ReportBlock::kParagraph, "The speed fluctuation could not be computed: " + exact->note + "."});
    return out;
  }
  std::string text = "With its flywheel (I_w = " + shortNumber(exact->flywheel_inertia, 4) + " kg m^2) at its mean speed " +
                     shortNumber(facts.speed_rpm, 4) + " rpm, ";
  text += exact->gas ? "under its gas against a constant load equal to the cycle mean of the gas torque (" +
                           shortNumber(exact->load_torque, 4) + " N m, as the flywheel part: what the gas delivers to "
                           "the shaft, the negative of the mean of the loads' gas part; below 0 where the shaft drives "
                           "the machine), over 720 deg"
                     : "no [gas] table: gravity alone drives it (no load), over a turn";
  if (exact->gas && facts.cycle != "four-stroke") text.replace(text.rfind("720"), 3, "360");
  text += ": the exact energy integral gives delta = (omega_max - omega_min) / omega_mean = " + shortNumber(exact->delta, 4) +
          ", omega_max at " + deg(exact->phi_deg_at_omega_max) + " and omega_min at " + deg(exact->phi_deg_at_omega_min) +
          ".";
  for (const FlywheelRow& r : rows) {
    if (r.engine == exact->engine) continue;
    if (!r.note.empty()) {
      text += " " + r.engine + "'s run failed: " + r.note + ".";
      continue;
    }
    text += " " + r.engine + "'s free run" + (r.gated ? "" : " (a soft way, measured beside)") + " gives " +
            shortNumber(r.delta, 4) + " (" + formatPercent(r.delta / exact->delta - 1.0) + ").";
  }
  out.push_back({ReportBlock::kParagraph, text});
  if (exact->gas) {
    for (const FitnessRow& f : rowsOfScene(tables, kFitnessTable, facts.scene))
      if (f.order == kNortonOrder)
        out.push_back({ReportBlock::kParagraph,
                       kNortonFlywheel + " predicts delta = E / (I_w omega^2) for this flywheel: " +
                           formatFitness(f.max_error_rel, f.resolved) + " of the exact " + shortNumber(exact->delta, 4) +
                           " (the energy swing of the constant-speed torque; it leaves out that the speed and the "
                           "mechanism's own inertia vary)."});
  } else {
    out.push_back({ReportBlock::kParagraph,
                   "Norton's flywheel method sizes against the gas torque: add a [gas] table (docs/SCENE-FORMAT.md, Gas "
                   "pressure) to judge it on this scene."});
  }
  ReportBlock table{ReportBlock::kTable, {}, {"way", "delta", "omega_min [rad/s]", "omega_max [rad/s]", "at omega_max",
                                               "at omega_min"}};
  for (const FlywheelRow& r : rows)
    if (r.note.empty())
      table.rows.push_back({r.engine, shortNumber(r.delta, 4), shortNumber(r.omega_min, 6), shortNumber(r.omega_max, 6),
                            deg(r.phi_deg_at_omega_max), deg(r.phi_deg_at_omega_min)});
  out.push_back(std::move(table));
  if (rows.size() > 1)
    out.push_back({ReportBlock::kParagraph,
                   "An engine's angles are at its nearest step; where the firings are evenly spaced an extreme recurs "
                   "once per firing, so two ways may name different firings."});
  return out;
}

std::vector<ReportBlock> describeTorsion(const TableSet& tables, const SceneFactsRow& facts) {
  std::vector<ReportBlock> out;
  if (!facts.crankshaft) {
    out.push_back({ReportBlock::kParagraph, "No [crankshaft] table: add one to see the torsional vibration "
                                            "(docs/SCENE-FORMAT.md, Crankshaft (torsion))."});
    return out;
  }
  const std::vector<TwistRow> twist = rowsOfScene(tables, kTwistTable, facts.scene);
  if (twist.empty()) return out;
  if (!twist.front().note.empty()) {
    out.push_back({ReportBlock::kParagraph, "The torsional vibration at " + shortNumber(facts.speed_rpm, 4) +
                                                " rpm was not computed: " + twist.front().note + "."});
    return out;
  }
  const std::vector<CriticalRow> critical = rowsOfScene(tables, kCriticalTable, facts.scene);
  const TwistRow& first = twist.front();
  std::string text = "Holzer's first natural frequency is " + shortNumber(first.omega1 / (2 * M_PI), 4) +
                     " Hz; the variable-inertia train's lies between " + shortNumber(first.omega1_lo / (2 * M_PI), 4) +
                     " and " + shortNumber(first.omega1_hi / (2 * M_PI), 4) +
                     " Hz (every throw at its largest, at its smallest inertia over a turn). ";
  const double lo = kCriticalLow * facts.speed_rpm, hi = kCriticalHigh * facts.speed_rpm;
  if (critical.empty())
    text += "No critical speed of a major order falls within " + shortNumber(lo, 4) + " .. " + shortNumber(hi, 4) +
            " rpm (0.25 to 1.25 of its speed).";
  else
    text += "The critical speeds of the major orders within " + shortNumber(lo, 4) + " .. " + shortNumber(hi, 4) +
            " rpm (0.25 to 1.25 of its speed) are in the table, Holzer's and the band the variable inertia spreads "
            "them over.";
  out.push_back({ReportBlock::kParagraph, text});
  const TwistRow most = *std::max_element(twist.begin(), twist.end(),
                                          [](const TwistRow& a, const TwistRow& b) { return a.exact < b.exact; });
  out.push_back({ReportBlock::kParagraph,
                 "At " + shortNumber(facts.speed_rpm, 4) + " rpm the section " + most.section + " twists most: " +
                     shortNumber(most.exact, 4) + " rad peak to peak in the exact steady state (error bound " +
                     shortNumber(most.error_bound, 2) + " rad), " + shortNumber(most.holzer, 4) + " rad by Holzer (" +
                     formatPercent(most.holzer / most.exact - 1.0) +
                     "). The engines' own trains are compared in the torsion part (its first scene): a run of each here "
                     "would cost seconds."});
  if (!critical.empty()) {
    ReportBlock table{ReportBlock::kTable, {}, {"mode", "order", "Holzer [rpm]", "variable inertia [rpm]"}};
    for (const CriticalRow& c : critical)
      table.rows.push_back({std::to_string(c.mode), shortNumber(c.order, 3), shortNumber(c.holzer_rpm, 5),
                            shortNumber(c.band_lo_rpm, 5) + " .. " + shortNumber(c.band_hi_rpm, 5)});
    out.push_back(std::move(table));
  }
  return out;
}

class DynamicsTopic final : public SceneTopic {
 public:
  std::string title() const override { return "Flywheel and torsion"; }
  // One task for the exact flywheel run, one per engine's run (released at the exact run's speed, shared), one for
  // the crank train; each a few tenths of a second at most (task_cost::kShort). The quick campaign runs the same (the energy integral and the train have no grid to coarsen; the
  // engines' runs are the accuracy the flywheel part uses).
  std::vector<Task> tasks(const Mechanism& scene, bool quick) const override {
    (void)quick;
    std::vector<Task> out;
    if (scene.flywheel_inertia) {
      auto shared = std::make_shared<SharedResult<ExactRun>>([scene] { return calcExactRun(scene); });
      out.push_back({"your_engine dynamics " + scene.name + " flywheel", false,
                     [scene, shared] { return calcExactTables(scene, *shared); }, task_cost::kShort});
      for (const Engine* engine : listRunEngines(scene))
        out.push_back({"your_engine dynamics " + scene.name + " " + engine->name, false,
                       [scene, engine, shared] { return calcEngineRun(scene, *engine, *shared); },
                       task_cost::kShort});
    }
    if (scene.crankshaft && scene.machine.speed > 0.0)
      out.push_back({"your_engine dynamics " + scene.name + " torsion", false, [scene] { return calcTrainTables(scene); },
                     task_cost::kShort});
    return out;
  }
  std::vector<ReportBlock> describe(const TableSet& tables, const std::string& scene) const override {
    std::vector<ReportBlock> out;
    const std::optional<SceneFactsRow> facts = findSceneFacts(tables, scene);
    if (!facts) return out;
    out = describeFlywheel(tables, *facts);
    for (ReportBlock& b : describeTorsion(tables, *facts)) out.push_back(std::move(b));
    return out;
  }
  std::vector<const TableSchema*> schemas() const override {
    return {&kFlywheelTable, &kCriticalTable, &kTwistTable, &kFitnessTable};
  }
};

}  // namespace

namespace topics {
const SceneTopic& dynamics() {
  static const DynamicsTopic topic;
  return topic;
}
}  // namespace topics

}  // namespace crankcheck::validation::your_engine
