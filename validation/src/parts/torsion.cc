// Report part `torsion`: torsional vibration of the crank train, Holzer's constant inertia judged against the exact,
// variable-inertia train (docs/CONVENTIONS-crankcheck.md, "Torsion").
//
// The scenes: every campaign scene with a [crankshaft] table (the example inline four and marine six in the default
// campaign), each swept over speed from 0.25 to 1.25 times its own speed (17 speeds, and 3 around each of Holzer's
// critical speeds of the lowest major orders: listSweepSpeeds; --quick: 0.5 and 1).
// Accuracy of the sweep: Holzer's sum converged to 1e-6 of the largest peak-to-peak (HolzerOptions), the exact steady
// state integrated at 1e-8 (SteadyStateOptions; its error bound, at most 2e-5 of the largest peak-to-peak, is in the
// table): both far below the percent differences the part is about, at a third of the cost of `crankcheck torsion`'s
// 1e-8 / 1e-11. Its tables are declared below, each by its row type and schema (reports/README.md reads them).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>

#include "crankcheck/analytic/crank_train.h"
#include "crankcheck/analytic/torsion.h"
#include "crankcheck/analytic/torsion_forced.h"
#include "crankcheck/analytic/torsion_steady.h"
#include "crankcheck/validation/commands/torsion.h"  // kTextbookOrder
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/extremum.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/timing.h"
#include "crankcheck/validation/variants.h"
#include "../torsion_train.h"
#include "survey.h"

namespace crankcheck::validation {
namespace {

// The engines' trains in the report: a check of the figure's exact curve on the first scene at its own speed, not the
// gate (tests/gate/torsion_test.cc holds them to 2e-6 of the twist scale at their defaults on both example scenes and
// three speeds). At a cycle-to-cycle change of `periodicity` what is left of the transient is at most about that much
// of the twist scale: 1e-4 in the full campaign, 5e-2 in the quick one (a smoke test of the route). Samples of the
// cycle: 1024 in the full campaign; 256 in the quick one, whose peak-to-peaks then carry their aliasing, far below its
// periodicity. The gated routes' accuracy (their integrators' error per step): 1e-7 in the full campaign, which leaves
// their differences to the analytic orbit far below the periodicity and the part's percent differences, for less than
// the cost of 1e-8; 1e-5 in the quick one, whose differences it leaves at what the periodicity leaves. The soft routes
// (measured, not gated) at a fixed step of 1/1024 of a cycle in the full campaign (not run in the quick one; at least a
// step per sample): kSoftDefault's difference, its loops' give, is the same as at its default 1/4096; kSoftStiff's,
// its loops' time constant two steps, grows as the step squared yet stays a fiftieth of kSoftDefault's; at a quarter
// of the cost. The measurements behind each choice: bench/README.md (the accuracies each check needs, part torsion).
struct EngineRunSettings {
  double accuracy, periodicity;
  int samples;
  double soft_step;  // the soft routes' fixed step, a fraction of a cycle (their `accuracy`)
};
EngineRunSettings getEngineRunSettings(bool quick) {
  return quick ? EngineRunSettings{1e-5, 5e-2, 256, 0.0} : EngineRunSettings{1e-7, 1e-4, 1024, 1.0 / 1024};
}

// torsion: per scene and speed, the peak-to-peak twist of the section that twists most (exact), by Holzer (every order,
// and cut at order 24) and by the exact steady state; difference = exact / holzer - 1 there, worst_difference the
// largest |exact / holzer - 1| over the sections (signed).
struct SweepRow {
  std::string scene;
  double speed_rpm = 0.0;                                   ///< [rpm]
  double holzer = 0.0, holzer_order24 = 0.0, exact = 0.0;   ///< [rad]
  double difference = 0.0, worst_difference = 0.0;          ///< [-]
  std::string section, worst_section;
  double error_bound = 0.0;                                 ///< the exact state's [rad]
};
const Schema<SweepRow> kSweepTable{
    "torsion",
    {textField("scene", &SweepRow::scene), numberField("speed_rpm", "rpm", &SweepRow::speed_rpm),
     numberField("holzer", "rad", &SweepRow::holzer), numberField("holzer_order24", "rad", &SweepRow::holzer_order24),
     numberField("exact", "rad", &SweepRow::exact), numberField("difference", "-", &SweepRow::difference),
     numberField("worst_difference", "-", &SweepRow::worst_difference), textField("section", &SweepRow::section),
     textField("worst_section", &SweepRow::worst_section), numberField("error_bound", "rad", &SweepRow::error_bound)}};

// torsion_sections: every section at every speed.
struct SectionRow {
  std::string scene;
  double speed_rpm = 0.0;  ///< [rpm]
  int section_index = 0;
  std::string section;
  double holzer = 0.0, holzer_order24 = 0.0, exact = 0.0;  ///< [rad]
  double difference = 0.0;                                 ///< exact / holzer - 1 [-]
};
const Schema<SectionRow> kSectionsTable{
    "torsion_sections",
    {textField("scene", &SectionRow::scene), numberField("speed_rpm", "rpm", &SectionRow::speed_rpm),
     countField("section_index", &SectionRow::section_index), textField("section", &SectionRow::section),
     numberField("holzer", "rad", &SectionRow::holzer), numberField("holzer_order24", "rad", &SectionRow::holzer_order24),
     numberField("exact", "rad", &SectionRow::exact), numberField("difference", "-", &SectionRow::difference)}};

// torsion_orders: the order amplitudes of the section of `torsion`, up to order 24.
struct OrderRow {
  std::string scene;
  double speed_rpm = 0.0;            ///< [rpm]
  double order = 0.0;                ///< a multiple of the cycle's order step (1/2 four-stroke, 1 two-stroke)
  double holzer = 0.0, exact = 0.0;  ///< [rad]
};
const Schema<OrderRow> kOrdersTable{
    "torsion_orders",
    {textField("scene", &OrderRow::scene), numberField("speed_rpm", "rpm", &OrderRow::speed_rpm),
     numberField("order", "-", &OrderRow::order), numberField("holzer", "rad", &OrderRow::holzer),
     numberField("exact", "rad", &OrderRow::exact)}};

// torsion_modes: Holzer's natural frequencies (J_eq) and the chain's with every throw at J_t + min J_j and at
// J_t + max J_j over a turn (the spread over the cycle); the engine's major orders are the multiples of its firings per
// turn.
struct ModeRow {
  std::string scene;
  int mode = 1;
  double holzer_hz = 0.0, min_hz = 0.0, max_hz = 0.0;  ///< [Hz]
  double firings_per_turn = 0.0;
};
const Schema<ModeRow> kModesTable{
    "torsion_modes",
    {textField("scene", &ModeRow::scene), countField("mode", &ModeRow::mode),
     numberField("holzer_hz", "Hz", &ModeRow::holzer_hz), numberField("min_hz", "Hz", &ModeRow::min_hz),
     numberField("max_hz", "Hz", &ModeRow::max_hz), numberField("firings_per_turn", "-", &ModeRow::firings_per_turn)}};

// torsion_inertia: J_eq per throw, exact and by the textbook's shortcuts (torsion.h), with its range over a turn.
struct InertiaRow {
  std::string scene;
  int throw_index = 0;
  double exact_inertia = 0.0, min_inertia = 0.0, max_inertia = 0.0;  ///< [kg m^2]
  double half_reciprocating = 0.0, half_reciprocating_error = 0.0;    ///< [kg m^2], [-]
  double second_order = 0.0, second_order_error = 0.0;                ///< [kg m^2], [-]
};
const Schema<InertiaRow> kInertiaTable{
    "torsion_inertia",
    {textField("scene", &InertiaRow::scene), countField("throw", &InertiaRow::throw_index),
     numberField("exact_inertia", "kg m^2", &InertiaRow::exact_inertia),
     numberField("min_inertia", "kg m^2", &InertiaRow::min_inertia),
     numberField("max_inertia", "kg m^2", &InertiaRow::max_inertia),
     numberField("half_reciprocating", "kg m^2", &InertiaRow::half_reciprocating),
     numberField("half_reciprocating_error", "-", &InertiaRow::half_reciprocating_error),
     numberField("second_order", "kg m^2", &InertiaRow::second_order),
     numberField("second_order_error", "-", &InertiaRow::second_order_error)}};

// torsion_engines: each engine's own train (Engine::simulate_crank_train) on the first scene at its own speed against
// the analytic steady state, per section.
struct EngineTrainRow {
  std::string scene, engine;
  double speed_rpm = 0.0;  ///< [rpm]
  std::string section;
  double peak_to_peak = 0.0, exact = 0.0;  ///< [rad]
  double difference = 0.0;                 ///< (engine - analytic) / twist scale [-]
  int cycles = 0;
  double accuracy = 0.0;     ///< a gated route's error per step; a soft route's fixed step as a fraction of a cycle
  double periodicity = 0.0;  ///< the cycle-to-cycle change the run stopped at, relative to the twist
};
const Schema<EngineTrainRow> kEnginesTable{
    "torsion_engines",
    {textField("scene", &EngineTrainRow::scene), textField("engine", &EngineTrainRow::engine),
     numberField("speed_rpm", "rpm", &EngineTrainRow::speed_rpm), textField("section", &EngineTrainRow::section),
     numberField("peak_to_peak", "rad", &EngineTrainRow::peak_to_peak), numberField("exact", "rad", &EngineTrainRow::exact),
     numberField("difference", "-", &EngineTrainRow::difference), countField("cycles", &EngineTrainRow::cycles),
     numberField("accuracy", "-", &EngineTrainRow::accuracy),
     numberField("periodicity", "-", &EngineTrainRow::periodicity)}};

// torsion_ratio: the first scene's piston mass scaled, ratio = reciprocating / rotating inertia (torsion.h's textbook
// split), at Holzer's critical speed of mode 1 and the engine's lowest major order; exact and worst_difference empty
// where the train has no periodic state.
struct RatioRow {
  std::string scene;
  double piston_mass_factor = 0.0, ratio = 0.0, order = 0.0;
  double speed_rpm = 0.0;                              ///< [rpm]
  double holzer = 0.0;                                 ///< [rad]
  std::optional<double> exact;                         ///< [rad]
  std::optional<double> worst_difference;              ///< [-]
};
const Schema<RatioRow> kRatioTable{
    "torsion_ratio",
    {textField("scene", &RatioRow::scene), numberField("piston_mass_factor", "-", &RatioRow::piston_mass_factor),
     numberField("ratio", "-", &RatioRow::ratio), numberField("order", "-", &RatioRow::order),
     numberField("speed_rpm", "rpm", &RatioRow::speed_rpm), numberField("holzer", "rad", &RatioRow::holzer),
     optionalField("exact", "rad", &RatioRow::exact),
     optionalField("worst_difference", "-", &RatioRow::worst_difference)}};

// torsion_cost: wall time of each route's speed point in the campaign (other tasks run beside it: ratios, not
// benchmarks; bench/README.md "Torsion" has those).
struct CostRow {
  std::string scene, route;
  double speed_rpm = 0.0;  ///< [rpm]
  double seconds = 0.0;    ///< [s]
};
const Schema<CostRow> kCostTable{
    "torsion_cost",
    {textField("scene", &CostRow::scene), textField("route", &CostRow::route),
     numberField("speed_rpm", "rpm", &CostRow::speed_rpm), numberField("seconds", "s", &CostRow::seconds)}};

// torsion_resonances (derived): the local maxima of the `torsion` curves (route holzer or exact; a parabola through
// the grid's three points), the order whose amplitude rises most there, the mode nearest its frequency and Holzer's
// critical speed; mode and critical speed empty where no order near a mode rises.
struct ResonanceRow {
  std::string scene, route;
  double order = 0.0;
  std::optional<double> mode;          ///< 1-based
  double speed_rpm = 0.0;              ///< [rpm]
  double frequency_hz = 0.0;           ///< [Hz]
  std::optional<double> critical_rpm;  ///< [rpm]
  double twist = 0.0;                  ///< [rad]
};
const Schema<ResonanceRow> kResonancesTable{
    "torsion_resonances",
    {textField("scene", &ResonanceRow::scene), textField("route", &ResonanceRow::route),
     numberField("order", "-", &ResonanceRow::order), optionalField("mode", "-", &ResonanceRow::mode),
     numberField("speed_rpm", "rpm", &ResonanceRow::speed_rpm),
     numberField("frequency_hz", "Hz", &ResonanceRow::frequency_hz),
     optionalField("critical_rpm", "rpm", &ResonanceRow::critical_rpm),
     numberField("twist", "rad", &ResonanceRow::twist)}};

// The rows of `schema`'s table in `tables`, to append to (the table is there: makeEmptyTables).
template <class Row>
std::vector<Row>& rowsOf(TableSet& tables, const Schema<Row>& schema) {
  return tables.at(schema.name()).getRows(schema);
}

std::vector<const Mechanism*> listTrainScenes(const std::vector<Mechanism>& scenes) {
  std::vector<const Mechanism*> out;
  for (const Mechanism& m : scenes)
    if (m.crankshaft && m.machine.speed > 0.0) out.push_back(&m);
  return out;
}


// The sweep's speeds [rpm], ascending: 0.25 .. 1.25 of the scene's speed in 16 steps, and around each of Holzer's
// critical speeds of mode 1 and the four lowest major orders in that range (findMajorOrder) the speeds at 0.98, 1 and
// 1.02 of it, so that those resonances are located to about 1 % in both routes (a resonance of the example
// scenes is about 0.1 of its speed wide at half height). --quick: 0.5 and 1 of the scene's speed (a smoke test of
// both routes, which locates no resonance).
std::vector<double> listSweepSpeeds(const Mechanism& m, bool quick) {
  std::vector<double> out;
  if (quick) {
    for (double f : {0.5, 1.0}) out.push_back(f * m.speed_rpm);
    return out;
  }
  for (int i = 0; i <= 16; ++i) out.push_back(m.speed_rpm * (0.25 + i / 16.0));
  const double mode1 = analytic::calcTorsionModes(m).frequencies(0);
  const double firings = m.machine.cylinders * getOrderStep(m);
  int refined = 0;
  for (double p = firings; p <= kTextbookOrder + 1e-9 && refined < 4; p += firings) {
    const double critical = mode1 / p * 30.0 / M_PI;
    if (critical > 1.25 * m.speed_rpm || critical < 0.25 * m.speed_rpm) continue;
    for (double f : {0.98, 1.0, 1.02}) out.push_back(f * critical);
    ++refined;
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The engine's major orders are the multiples of its firings per turn (cylinders / 2 four-stroke, cylinders
// two-stroke): where the gas torques of evenly spaced firings add. The lowest one whose mode-1 critical speed is at
// most 1.25 x the scene's speed (the sweep's top), or the lowest at all.
double findMajorOrder(const Mechanism& m, double mode1) {
  const double firings = m.machine.cylinders * getOrderStep(m);
  for (double p = firings; p <= kTextbookOrder + 1e-9; p += firings)
    if (mode1 / p * 30.0 / M_PI <= 1.25 * m.speed_rpm) return p;
  return firings;
}

// Every table a task writes, empty: each task returns all of them, so that the report has each table (if only its
// header) whichever tasks ran.
TableSet makeEmptyTables() {
  TableSet t;
  t.emplace(kSweepTable.name(), kSweepTable.table());
  t.emplace(kSectionsTable.name(), kSectionsTable.table());
  t.emplace(kOrdersTable.name(), kOrdersTable.table());
  t.emplace(kModesTable.name(), kModesTable.table());
  t.emplace(kInertiaTable.name(), kInertiaTable.table());
  t.emplace(kEnginesTable.name(), kEnginesTable.table());
  t.emplace(kRatioTable.name(), kRatioTable.table());
  t.emplace(kCostTable.name(), kCostTable.table());
  return t;
}

// One speed point of a scene: Holzer and the exact steady state, every section, the orders of the section that twists
// most, and the cost of each route.
TableSet calcSpeedTables(const Mechanism& scene, double rpm, analytic::ThrowLoadOrders& load_orders) {
  TableSet tables = makeEmptyTables();
  const Mechanism m = withSpeed(scene, rpm);
  const analytic::HolzerOptions holzer_options = makeTrainHolzerOptions();
  auto start = std::chrono::steady_clock::now();
  const analytic::HolzerResponse holzer = analytic::calcHolzerResponse(m, holzer_options, load_orders);
  const double holzer_seconds = secondsSince(start);
  const analytic::SteadyStateOptions exact_options = makeTrainSteadyStateOptions();
  start = std::chrono::steady_clock::now();
  const analytic::ExactSteadyState exact = analytic::calcExactSteadyState(m, holzer, exact_options);
  const double exact_seconds = secondsSince(start);
  const int n = static_cast<int>(exact.peak_to_peak.size());
  int most = 0, worst = 0;
  auto differenceAt = [&](int i) { return exact.peak_to_peak[i] / holzer.peak_to_peak[i] - 1.0; };
  for (int i = 0; i < n; ++i) {
    if (exact.peak_to_peak[i] > exact.peak_to_peak[most]) most = i;
    if (std::fabs(differenceAt(i)) > std::fabs(differenceAt(worst))) worst = i;
    rowsOf(tables, kSectionsTable)
        .push_back({m.name, rpm, i, nameSection(m, i, n), holzer.peak_to_peak[i], holzer.peak_to_peak_order24[i],
                    exact.peak_to_peak[i], differenceAt(i)});
  }
  rowsOf(tables, kSweepTable)
      .push_back({m.name, rpm, holzer.peak_to_peak[most], holzer.peak_to_peak_order24[most], exact.peak_to_peak[most],
                  differenceAt(most), differenceAt(worst), nameSection(m, most, n), nameSection(m, worst, n),
                  exact.error_bound});
  // Order p of the cycle's harmonics h: p = h x step (crank_train.h's PeriodicSignal), up to order 24.
  const double step = getOrderStep(m);
  const auto& hc = holzer.twists[most].coefficients;
  const auto& ec = exact.twists[most].coefficients;
  for (size_t h = 1; h * step <= kTextbookOrder + 1e-9; ++h)
    rowsOf(tables, kOrdersTable)
        .push_back({m.name, rpm, h * step, h < hc.size() ? std::abs(hc[h]) : 0.0, h < ec.size() ? std::abs(ec[h]) : 0.0});
  rowsOf(tables, kCostTable).push_back({m.name, "holzer", rpm, holzer_seconds});
  rowsOf(tables, kCostTable).push_back({m.name, getClosedFormEngine().name, rpm, exact_seconds});
  return tables;
}

// The scene's inertias and modes: J_eq and its shortcuts per throw, and the frequencies at J_eq, J_min and J_max.
TableSet calcModeTables(const Mechanism& m) {
  TableSet tables = makeEmptyTables();
  const TorsionModeBand band = calcTorsionModeBand(m);
  const analytic::TorsionModes& modes = band.holzer;
  for (int j = 0; j < static_cast<int>(band.inertias.size()); ++j) {
    const analytic::ThrowInertia& inertia = band.inertias[static_cast<size_t>(j)];
    const auto [jmin, jmax] = band.ranges[static_cast<size_t>(j)];
    rowsOf(tables, kInertiaTable)
        .push_back({m.name, j, inertia.exact, jmin, jmax, inertia.half_reciprocating,
                    inertia.half_reciprocating / inertia.exact - 1.0, inertia.second_order,
                    inertia.second_order / inertia.exact - 1.0});
  }
  const analytic::TorsionModes& at_min = band.at_min;
  const analytic::TorsionModes& at_max = band.at_max;
  for (int i = 0; i < modes.frequencies.size(); ++i)
    rowsOf(tables, kModesTable)
        .push_back({m.name, i + 1, modes.frequencies(i) / (2 * M_PI), at_max.frequencies(i) / (2 * M_PI),
                    at_min.frequencies(i) / (2 * M_PI), m.machine.cylinders * getOrderStep(m)});
  return tables;
}

// The analytic steady state at the first scene's own speed, which every engine's train is held against: computed once
// for the engines' tasks, by the first that needs it (each asks after its own run, so the others rarely wait).
using SharedSteadyState = SharedResult<analytic::ExactSteadyState>;
analytic::ExactSteadyState calcTrainReference(const Mechanism& m) {
  const analytic::SteadyStateOptions exact_options = makeTrainSteadyStateOptions();
  return analytic::calcExactSteadyState(m, exact_options);
}

// An exact engine's train at the scene's own speed against the analytic steady state.
TableSet calcEngineTables(const Mechanism& m, const Engine& engine, bool quick, SharedSteadyState& analytic_state) {
  TableSet tables = makeEmptyTables();
  CrankTrainRunOptions options;
  // A gated route's accuracy is its integrator's error per step; a soft route's is its own (MuJoCo's: the fixed time
  // step as a fraction of a cycle, Engine::crank_train_method).
  const EngineRunSettings settings = getEngineRunSettings(quick);
  options.accuracy = engine.crank_train_gated ? settings.accuracy : settings.soft_step;
  options.periodicity = settings.periodicity;
  options.samples = settings.samples;
  const auto start = std::chrono::steady_clock::now();
  const CrankTrainRun run = engine.simulate_crank_train(m, options);
  const double run_seconds = secondsSince(start);
  const analytic::ExactSteadyState& exact = analytic_state.get();
  const int n = static_cast<int>(run.twists.size());
  for (int i = 0; i < n; ++i) {
    const double p2p = analytic::findSignalExtremes(analytic::calcSignalFromSamples(run.twists[i])).peakToPeak();
    rowsOf(tables, kEnginesTable)
        .push_back({m.name, engine.name, m.speed_rpm, nameSection(m, i, n), p2p, exact.peak_to_peak[i],
                    (p2p - exact.peak_to_peak[i]) / exact.twist_scale, run.cycles, options.accuracy,
                    options.periodicity});
  }
  rowsOf(tables, kCostTable).push_back({m.name, engine.name, m.speed_rpm, run_seconds});
  return tables;
}

// Throw 0's reciprocating and rotating inertia in the textbook's split (torsion.h, ThrowInertia::half_reciprocating):
// J_rec = sum of (1/2) m_rec r^2 over its cylinders, m_rec = m_o + m_k (l - z_k) / l; J_rot the rest of that J_eq.
double calcReciprocatingRatio(const Mechanism& m) {
  const double m_rec = m.piston.mass + m.rod.mass * (m.rod.length - m.rod.com_from_wrist_pin) / m.rod.length;
  const double cylinders = static_cast<double>(findThrows(m).front().size());
  const double j_rec = cylinders * 0.5 * m_rec * m.crank.radius * m.crank.radius;
  return j_rec / (analytic::calcThrowInertia(m, 0).half_reciprocating - j_rec);
}

// One point of the ratio sweep: the piston mass times `factor`, at Holzer's critical speed of mode 1 and the major
// order; the exact state refused (runtime_error: no periodic state) leaves its cells empty.
TableSet calcRatioTables(const Mechanism& scene, double factor) {
  TableSet tables = makeEmptyTables();
  Mechanism m = scene;
  m.piston.mass *= factor;
  const analytic::TorsionModes modes = analytic::calcTorsionModes(m);
  const double order = findMajorOrder(scene, analytic::calcTorsionModes(scene).frequencies(0));
  const double rpm = modes.frequencies(0) / order * 30.0 / M_PI;
  m = withSpeed(m, rpm);
  const analytic::HolzerOptions holzer_options = makeTrainHolzerOptions();
  const analytic::HolzerResponse holzer = analytic::calcHolzerResponse(m, holzer_options);
  const size_t most_holzer = static_cast<size_t>(
      std::max_element(holzer.peak_to_peak.begin(), holzer.peak_to_peak.end()) - holzer.peak_to_peak.begin());
  RatioRow row{scene.name, factor, calcReciprocatingRatio(m), order, rpm, holzer.peak_to_peak[most_holzer], {}, {}};
  try {
    const analytic::SteadyStateOptions exact_options = makeTrainSteadyStateOptions();
    const analytic::ExactSteadyState exact = analytic::calcExactSteadyState(m, holzer, exact_options);
    size_t worst = 0;
    for (size_t i = 0; i < exact.peak_to_peak.size(); ++i)
      if (std::fabs(exact.peak_to_peak[i] / holzer.peak_to_peak[i] - 1.0) >
          std::fabs(exact.peak_to_peak[worst] / holzer.peak_to_peak[worst] - 1.0))
        worst = i;
    row.exact = exact.peak_to_peak[most_holzer];
    row.worst_difference = exact.peak_to_peak[worst] / holzer.peak_to_peak[worst] - 1.0;
  } catch (const std::runtime_error&) {
    // no periodic steady state (Newton did not converge): the constant-inertia model broke; exact stays empty
  }
  rowsOf(tables, kRatioTable).push_back(std::move(row));
  return tables;
}

std::vector<double> listRatioFactors(bool quick) {
  return quick ? std::vector<double>{1.0} : std::vector<double>{0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0};
}

// ---- derive: the resonances of the sweep ----

// Local maxima of one route's curve (interior grid points 1 % above both neighbours), each placed by the parabola through
// the three points; its order the one whose amplitude rises most there (above the mean of its neighbours') among the
// orders within 25 % of a natural frequency, its mode the nearest (mode and critical speed empty when no such order
// rises: the order that rises most, no resonance).
void addResonances(std::vector<ResonanceRow>& out, const std::string& scene, const std::string& route,
                   const std::vector<const SweepRow*>& sweep,
                   const std::map<double, std::map<double, double>>& amplitudes, const std::vector<double>& modes_hz) {
  const bool exact = route != "holzer";
  auto value = [&](size_t i) { return exact ? sweep[i]->exact : sweep[i]->holzer; };
  for (size_t i = 1; i + 1 < sweep.size(); ++i) {
    // A resonance stands out: at least 1 % above both neighbours (the example scenes' stand 7 % to 86 % above them on
    // this grid; what is below are ripples of the sum's shoulders, 0.04 % on the example four).
    if (!(value(i) > 1.01 * value(i - 1) && value(i) > 1.01 * value(i + 1))) continue;
    // The vertex of the parabola through (x_{i-1}, y_{i-1}), (x_i, y_i), (x_{i+1}, y_{i+1}).
    const double x0 = sweep[i - 1]->speed_rpm, x1 = sweep[i]->speed_rpm, x2 = sweep[i + 1]->speed_rpm;
    const double y0 = value(i - 1), y1 = value(i), y2 = value(i + 1);
    const double rpm = x1 - 0.5 * ((x1 - x0) * (x1 - x0) * (y1 - y2) - (x1 - x2) * (x1 - x2) * (y1 - y0)) /
                                ((x1 - x0) * (y1 - y2) - (x1 - x2) * (y1 - y0));
    const auto at = amplitudes.find(x1), before = amplitudes.find(x0), after = amplitudes.find(x2);
    if (at == amplitudes.end() || before == amplitudes.end() || after == amplitudes.end()) continue;
    // The candidates: orders whose frequency at the peak is within 25 % of a natural frequency (a resonance); the
    // one that rises most. None rising: the order that rises most of all, with no mode.
    auto nearestMode = [&](double p) {
      size_t mode = 0;
      for (size_t k = 1; k < modes_hz.size(); ++k)
        if (std::fabs(modes_hz[k] - p * rpm / 60.0) < std::fabs(modes_hz[mode] - p * rpm / 60.0)) mode = k;
      return mode;
    };
    auto nearAMode = [&](double p) { return std::fabs(p * rpm / 60.0 / modes_hz[nearestMode(p)] - 1.0) <= 0.25; };
    double order = 0.0, rise = -1e300, any_order = 0.0, any_rise = -1e300;
    for (const auto& [p, a] : at->second) {
      const double r = a - 0.5 * (before->second.at(p) + after->second.at(p));
      if (r > any_rise) {
        any_rise = r;
        any_order = p;
      }
      if (nearAMode(p) && r > rise) {
        rise = r;
        order = p;
      }
    }
    const bool resonant = rise > 0.0;
    if (!resonant) order = any_order;
    const double hz = order * rpm / 60.0;
    const size_t mode = nearestMode(order);
    out.push_back({scene, route, order, resonant ? std::optional<double>(mode + 1) : std::nullopt, rpm, hz,
                   resonant ? std::optional<double>(modes_hz[mode] * 60.0 / order) : std::nullopt, y1});
  }
}

void deriveTorsion(TableSet& tables) {
  for (const TableSchema* needed : {static_cast<const TableSchema*>(&kSweepTable), static_cast<const TableSchema*>(&kOrdersTable),
                                    static_cast<const TableSchema*>(&kModesTable)})
    if (!tables.count(needed->name())) return;
  std::map<std::string, std::vector<const SweepRow*>> sweeps;  // rows are sorted: by scene, then speed
  for (const SweepRow& row : getRows(tables, kSweepTable)) sweeps[row.scene].push_back(&row);
  // scene -> speed -> order -> amplitude
  std::map<std::string, std::map<double, std::map<double, double>>> holzer_orders, exact_orders;
  for (const OrderRow& row : getRows(tables, kOrdersTable)) {
    holzer_orders[row.scene][row.speed_rpm][row.order] = row.holzer;
    exact_orders[row.scene][row.speed_rpm][row.order] = row.exact;
  }
  std::map<std::string, std::vector<double>> modes;
  for (const ModeRow& row : getRows(tables, kModesTable)) modes[row.scene].push_back(row.holzer_hz);
  std::vector<ResonanceRow> resonances;
  for (const auto& [scene, sweep] : sweeps) {
    if (!modes.count(scene)) continue;
    addResonances(resonances, scene, "holzer", sweep, holzer_orders[scene], modes[scene]);
    addResonances(resonances, scene, "exact", sweep, exact_orders[scene], modes[scene]);
  }
  tables.insert_or_assign(kResonancesTable.name(), kResonancesTable.table(std::move(resonances)));
}

// ---- describe ----

// An order of the engine (a multiple of 1/2 up to 24) as the sentences and tables write it.
std::string formatOrder(double order) { return shortNumber(order, 4); }

void describeSweeps(const TableSet& tables, ReportPart& part) {
  std::map<std::string, std::vector<const SweepRow*>> by_scene;
  for (const SweepRow& row : getRows(tables, kSweepTable)) by_scene[row.scene].push_back(&row);
  for (const auto& [scene, rows] : by_scene) {
    int within = 0, beyond = 0;
    const SweepRow* worst = rows.front();
    double cut = 0.0;
    std::string cut_at;
    for (const SweepRow* row : rows) {
      const double d = std::fabs(row->worst_difference);
      within += d <= 0.01;
      beyond += d > 0.10;
      if (d > std::fabs(worst->worst_difference)) worst = row;
      const double c = std::fabs(row->holzer_order24 / row->holzer - 1.0);
      if (c > cut) {
        cut = c;
        cut_at = shortNumber(row->speed_rpm, 4);
      }
    }
    part.paragraphs.push_back(
        scene + ", " + std::to_string(rows.size()) + " speeds from " + shortNumber(rows.front()->speed_rpm, 4) + " to " +
        shortNumber(rows.back()->speed_rpm, 4) + " rpm: Holzer's peak-to-peak twist (every order summed) is within 1 % "
        "of the exact steady state's on every section at " + std::to_string(within) + " of them and off by more than "
        "10 % on some section at " + std::to_string(beyond) + "; at worst " + formatPercent(worst->worst_difference) +
        " (" + worst->worst_section + ", " + shortNumber(worst->speed_rpm, 4) + " rpm). The textbook's sum cut at order "
        "24 differs from the converged sum by up to " + formatPercent(cut) + " (at " + cut_at + " rpm).");
  }
}

void describeResonances(const TableSet& tables, ReportPart& part) {
  std::map<std::string, std::vector<const ResonanceRow*>> exact, holzer;
  for (const ResonanceRow& row : getRows(tables, kResonancesTable))
    (row.route == "holzer" ? holzer : exact)[row.scene].push_back(&row);
  auto join = [](std::string& list, const std::string& item) { list += (list.empty() ? "" : ", ") + item; };
  for (const auto& [scene, peaks] : exact) {
    std::string found, missed;
    for (const ResonanceRow* peak : peaks) {
      const double rpm = peak->speed_rpm;
      std::string what = "order " + formatOrder(peak->order) + " at " + shortNumber(rpm, 4) + " rpm";
      if (!peak->mode || !peak->critical_rpm) {
        what += " (no mode near its frequency)";
      } else {
        const double critical = *peak->critical_rpm;
        what += " (mode " + std::to_string(static_cast<int>(*peak->mode)) + "; Holzer's critical speed " +
                shortNumber(critical, 4) + " rpm, " + (rpm >= critical ? "+" : "") + formatPercent(rpm / critical - 1.0) +
                ")";
      }
      bool matched = false;
      for (const ResonanceRow* h : holzer[scene])
        if (h->order == peak->order && std::fabs(h->speed_rpm / rpm - 1.0) < 0.05) matched = true;
      join(matched ? found : missed, what);
    }
    std::string sentence = scene + ": the exact steady state peaks at ";
    if (!found.empty()) sentence += found + ", where Holzer's sum peaks too (within 5 %)" + (missed.empty() ? "; it misses none of them" : "");
    if (!missed.empty())
      sentence += (found.empty() ? "" : "; and at ") + missed +
                  ", where Holzer's sum has no peak within 5 %: a resonance the constant-inertia model misses or moves";
    sentence += ". (Peaks: the parabola through three points of the sweep, whose grid is refined to 2 % of the speed "
                "around Holzer's critical speeds of the lowest major orders.)";
    part.paragraphs.push_back(sentence);
  }
}

void describeModes(const TableSet& tables, ReportPart& part) {
  for (const ModeRow& row : getRows(tables, kModesTable)) {
    if (row.mode != 1) continue;
    const double h = row.holzer_hz, lo = row.min_hz, hi = row.max_hz;
    part.paragraphs.push_back(row.scene + ": mode 1 is at " + shortNumber(h, 4) + " Hz with Holzer's J_eq; with every "
                              "throw at its lightest and at its heaviest over a turn it would be at " +
                              shortNumber(hi, 4) + " and " + shortNumber(lo, 4) + " Hz: a spread of " +
                              formatPercent((hi - lo) / h) + " that the constant inertia cannot show.");
  }
}

void describeRatio(const TableSet& tables, ReportPart& part) {
  const std::vector<RatioRow>& rows = getRows(tables, kRatioTable);
  if (rows.empty()) return;
  std::vector<const RatioRow*> points;
  for (const RatioRow& row : rows) points.push_back(&row);
  std::stable_sort(points.begin(), points.end(), [](const RatioRow* a, const RatioRow* b) { return a->ratio < b->ratio; });
  const std::string range = points.size() == 1 ? "is " + shortNumber(points.front()->ratio, 3) + " times the rotating one"
                                                : "runs from " + shortNumber(points.front()->ratio, 3) + " to " +
                                                      shortNumber(points.back()->ratio, 3) + " times the rotating one";
  std::string sentence = rows.front().scene + ", its piston mass scaled so that the reciprocating inertia " + range +
                         ", at Holzer's critical speed of mode 1 and order " + formatOrder(rows.front().order) +
                         ": Holzer's worst section is off by ";
  std::string list;
  std::optional<double> breaks;
  for (const RatioRow* point : points) {
    const std::optional<double>& d = point->worst_difference;
    list += (list.empty() ? "" : ", ") + (d ? formatPercent(*d) : std::string("no periodic state")) + " at " +
            shortNumber(point->ratio, 3);
    if (!breaks && (!d || std::fabs(*d) > 0.10)) breaks = point->ratio;
  }
  sentence += list + ". ";
  sentence += breaks ? "The constant-inertia model is off by more than 10 % from a ratio of " + shortNumber(*breaks, 3) +
                           " on."
                     : "It stays within 10 % over the whole sweep.";
  part.paragraphs.push_back(sentence);
}

void describeEnginesAndCost(const TableSet& tables, ReportPart& part) {
  if (tables.count(kEnginesTable.name())) {
    std::map<std::string, double> worst;
    std::map<std::string, std::string> where;
    auto isGated = [](const std::string& engine) {
      for (const Engine& known : listEngines())
        if (known.name == engine) return known.crank_train_gated;
      return true;
    };
    for (const EngineTrainRow& row : getRows(tables, kEnginesTable)) {
      worst[row.engine] = std::max(worst[row.engine], std::fabs(row.difference));
      // A soft route's accuracy is its fixed step as a fraction of a cycle.
      std::string how = "its default step";
      if (row.accuracy > 0.0)
        how = isGated(row.engine) ? "accuracy " + shortNumber(row.accuracy, 1)
                                  : "a fixed step of 1/" + shortNumber(1.0 / row.accuracy, 6) + " of a cycle";
      where[row.engine] = row.scene + " at " + shortNumber(row.speed_rpm, 4) + " rpm (" + how +
                          ", run until the cycle-to-cycle change is below " + shortNumber(row.periodicity, 1) +
                          " of the twist)";
    }
    for (const auto& [engine, w] : worst) {
      const bool gated = isGated(engine);
      part.paragraphs.push_back(engine + "'s own elastic train " +
                                (gated ? "agrees with the analytic steady state's peak-to-peak twists to "
                                       : "(a soft solver: measured, not gated) differs from the analytic steady state's "
                                         "peak-to-peak twists by up to ") +
                                shortNumber(w, 2) + " of the twist scale on " + where[engine] + ".");
    }
  }
  if (!tables.count(kCostTable.name())) return;
  std::map<std::string, std::pair<double, int>> mean;  // route -> (sum of seconds, points)
  for (const CostRow& row : getRows(tables, kCostTable)) {
    mean[row.route].first += row.seconds;
    ++mean[row.route].second;
  }
  std::string list;
  for (const auto& [route, s] : mean)
    list += (list.empty() ? "" : ", ") + route + " " + shortNumber(s.first / s.second, 2) + " s (" +
            std::to_string(s.second) + (s.second == 1 ? " point)" : " points)");
  part.paragraphs.push_back("Cost of a speed point in this campaign (mean wall time, other work beside it): " + list +
                            ".");
}

ReportPart describeTorsionPart(const TableSet& tables, const std::string& heading) {
  ReportPart part;
  for (const TableSchema* needed : {static_cast<const TableSchema*>(&kSweepTable), static_cast<const TableSchema*>(&kModesTable),
                                    static_cast<const TableSchema*>(&kInertiaTable)})
    if (!tables.count(needed->name())) return part;
  if (getRows(tables, kSweepTable).empty()) return part;
  part.heading = heading;
  ReportBlock figure;
  figure.kind = ReportBlock::kFigure;
  figure.figure = "torsion";
  figure.text =
      "Top: Campbell diagrams, Holzer's natural frequencies (lines, the band from every throw at its lightest to its "
      "heaviest), the engine orders as rays from the origin (the major ones bold), the peaks of the exact steady state "
      "(filled) and of Holzer's sum (open) on their order's ray. Bottom left and middle: the peak-to-peak twist of the "
      "section that twists most against speed, Holzer's sum of every order (line) and the exact steady state (dots). "
      "Right: exact / Holzer - 1 of the worst section against speed (top), and against the ratio of reciprocating to "
      "rotating inertia at the major order's critical speed (bottom). Each scene with [crankshaft] as given, with its "
      "own [gas], swept over speed from 0.25 to 1.25 times its own speed (the sweep's other speeds are " +
      std::string(survey::kNotSceneSpeed) + "); the ratio sweep scales the first such scene's piston mass and runs at "
      "Holzer's critical speed";
  ReportPart sentences;
  describeSweeps(tables, sentences);
  describeResonances(tables, sentences);
  describeModes(tables, sentences);
  describeRatio(tables, sentences);
  describeEnginesAndCost(tables, sentences);
  part.blocks.push_back(figure);
  for (const std::string& p : sentences.paragraphs) part.blocks.push_back({ReportBlock::kParagraph, p});
  ReportBlock inertia;
  inertia.kind = ReportBlock::kTable;
  inertia.header = {"scene", "throw", "J_eq exact [kg m^2]", "J min", "J max", "half reciprocating", "error",
                    "second order", "error"};
  for (const InertiaRow& row : getRows(tables, kInertiaTable))
    inertia.rows.push_back({row.scene, std::to_string(row.throw_index), shortNumber(row.exact_inertia, 4),
                            shortNumber(row.min_inertia, 4), shortNumber(row.max_inertia, 4),
                            shortNumber(row.half_reciprocating, 4), shortNumber(row.half_reciprocating_error, 4),
                            shortNumber(row.second_order, 4), shortNumber(row.second_order_error, 4)});
  part.blocks.push_back(inertia);
  const std::vector<ResonanceRow>& resonances = getRows(tables, kResonancesTable);
  if (!resonances.empty()) {
    ReportBlock peaks;
    peaks.kind = ReportBlock::kTable;
    peaks.header = {"scene", "route", "order", "mode", "peak [rpm]", "frequency [Hz]", "Holzer critical [rpm]",
                    "twist [rad]"};
    for (const ResonanceRow& row : resonances)
      peaks.rows.push_back({row.scene, row.route, formatOrder(row.order),
                            row.mode ? std::to_string(static_cast<int>(*row.mode)) : "", shortNumber(row.speed_rpm, 4),
                            shortNumber(row.frequency_hz, 4), row.critical_rpm ? shortNumber(*row.critical_rpm, 4) : "",
                            shortNumber(row.twist, 4)});
    part.blocks.push_back(peaks);
  }
  return part;
}

// The notes' tag of this part's own lines ("Part N (torsion): "): a refused route's (calcOrNote), which derive looks
// for. The notes are the campaign's table of sentences (no key column), so the tag is how this part knows its lines.
std::string getNoteTag(const Part& part) { return "Part " + std::to_string(part.number()) + " (" + part.key() + ")"; }

// A task whose route is refused for its scene (outside the small-twist domain at one of the sweep's speeds, past a
// work limit): its reason in the report's notes, tagged `tag`, and no numbers (crankcheck torsion refuses the same
// with status 1). The part then leaves its figure and tables out (derive), rather than draw a sweep with holes; the
// other parts go on. A logic error still ends the campaign.
template <class Calc>
TableSet calcOrNote(const std::string& tag, const std::string& what, Calc calc) {
  try {
    return calc();
  } catch (const std::runtime_error& e) {
    return kNotesTable.tableSet({{tag + ": " + what + " not computed: " + formatOneLine(e.what())}});
  }
}

class TorsionPart final : public Part {
 public:
  std::string key() const override { return "torsion"; }
  std::string title() const override {
    return "Torsional vibration: Holzer's constant inertia against the exact crank train";
  }
  // One task per speed point of each scene with [crankshaft], one for its modes, one per engine's own train on the
  // first scene, one per point of the ratio sweep on the first scene. --quick (a smoke test of the part): the gated
  // engines' trains alone (the soft chains' route has its own test: tests/mujoco/crank_train_test.cc).
  std::vector<Task> tasks(const PartContext& context) const override {
    std::vector<Task> out;
    const std::string tag = getNoteTag(*this);
    const std::vector<const Mechanism*> scenes = listTrainScenes(context.scenes);
    for (size_t s = 0; s < scenes.size(); ++s) {
      const Mechanism& m = *scenes[s];
      out.push_back({"torsion modes " + m.name, false, [m] { return calcModeTables(m); }});
      // The throws' speed-free torque orders, computed once for the scene's speed points (torsion_forced.h).
      const auto load_orders = std::make_shared<analytic::ThrowLoadOrders>();
      for (double rpm : listSweepSpeeds(m, context.quick))
        out.push_back({"torsion " + m.name + " " + formatNumber(rpm) + " rpm", false,
                       [m, rpm, load_orders, tag] {
                         return calcOrNote(tag, m.name + " at " + shortNumber(rpm, 4) + " rpm",
                                           [&] { return calcSpeedTables(m, rpm, *load_orders); });
                       },
                       task_cost::kShort});
      if (s > 0) continue;
      const auto analytic_state = std::make_shared<SharedSteadyState>([m] { return calcTrainReference(m); });
      for (const Engine& engine : listEngines())
        if (engine.simulate_crank_train && !engine.closed_form && (engine.crank_train_gated || !context.quick))
          out.push_back({"torsion " + m.name + " " + engine.name, false,
                         [m, &engine, quick = context.quick, analytic_state, tag] {
                           return calcOrNote(tag, m.name + " by " + engine.name,
                                             [&] { return calcEngineTables(m, engine, quick, *analytic_state); });
                         },
                         task_cost::kFineCycleRun});
    }
    if (!scenes.empty())
      for (double factor : listRatioFactors(context.quick))
        out.push_back({"torsion ratio " + formatNumber(factor), false,
                       [m = *scenes.front(), factor, tag] {
                         return calcOrNote(tag, m.name + " at the inertia ratio's factor " + shortNumber(factor, 4),
                                           [&] { return calcRatioTables(m, factor); });
                       },
                       task_cost::kShort});
    return out;
  }
  std::string findOmission(const PartContext& context) const override {
    if (!listTrainScenes(context.scenes).empty()) return {};
    std::string names;
    for (const Mechanism& m : context.scenes) names += (names.empty() ? "" : ", ") + m.name;
    return "no scene (" + names + ") has a [crankshaft] table with [engine].speed_rpm > 0, the elastic crank train "
           "it analyses. Give a scene one (docs/SCENE-FORMAT.md, \"[crankshaft]\") to get it.";
  }
  void derive(TableSet& tables) const override {
    // A route refused (calcOrNote): the part's tables out, its notes say why and which.
    const std::string tag = getNoteTag(*this) + ": ";
    const std::vector<NoteRow>& notes = getRows(tables, kNotesTable);
    if (std::any_of(notes.begin(), notes.end(),
                    [&](const NoteRow& row) { return row.note.compare(0, tag.size(), tag) == 0; })) {
      for (const TableSchema* schema : schemas()) tables.erase(schema->name());
      addRows(tables, kNotesTable,
              {{getNoteTag(*this) + " is left out: the routes these notes name could not be computed, and a sweep "
                "with holes is not drawn. crankcheck torsion on each scene shows the rest."}});
      return;
    }
    deriveTorsion(tables);
  }
  ReportPart describe(const TableSet& tables) const override { return describeTorsionPart(tables, heading()); }
  std::vector<const TableSchema*> schemas() const override {
    return {&kSweepTable,   &kSectionsTable, &kOrdersTable, &kModesTable,      &kInertiaTable,
            &kEnginesTable, &kRatioTable,    &kCostTable,   &kResonancesTable};
  }
};

}  // namespace

namespace parts {
const Part& torsion() {
  static const TorsionPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
