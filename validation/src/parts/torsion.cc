// Report part `torsion` (17): torsional vibration of the crank train, Holzer's constant inertia judged against the
// exact, variable-inertia train (docs/CONVENTIONS-crankcheck.md, "Torsion"; docs/CONVENTIONS-crankcheck.md).
//
// The scenes: every campaign scene with a [crankshaft] table (the example inline four and marine six in the default
// campaign), each swept over speed from 0.25 to 1.25 times its own speed (17 speeds, and 3 around each of Holzer's
// critical speeds of the lowest major orders: listSweepSpeeds; --quick: 0.5 and 1).
// Accuracy of the sweep: Holzer's sum converged to 1e-6 of the largest peak-to-peak (HolzerOptions), the exact steady
// state integrated at 1e-8 (SteadyStateOptions; its error bound, at most 2e-5 of the largest peak-to-peak, is in the
// table): both far below the percent differences the part is about, at a third of the cost of `crankcheck torsion`'s
// 1e-8 / 1e-11.
//
// Tables (CSV stems, columns; reports/README.md):
//   torsion           scene,speed_rpm,holzer,holzer_order24,exact,difference,worst_difference,section,worst_section,
//                     error_bound: the peak-to-peak twist [rad] of the section that twists most (exact), by Holzer
//                     (every order, and cut at order 24) and by the exact steady state; difference = exact / holzer - 1
//                     there, worst_difference the largest |exact / holzer - 1| over the sections (signed)
//   torsion_sections  scene,speed_rpm,section_index,section,holzer,holzer_order24,exact,difference: every section
//   torsion_orders    scene,speed_rpm,order,holzer,exact: the order amplitudes [rad] of the section of `torsion`
//   torsion_modes     scene,mode,holzer_hz,min_hz,max_hz,firings_per_turn: Holzer's natural frequencies (J_eq) and the
//                     chain's with every throw at J_t + min J_j and at J_t + max J_j over a turn (the spread over the
//                     cycle); firings per turn: the engine's major orders are its multiples
//   torsion_inertia   scene,throw,exact_inertia,min_inertia,max_inertia,half_reciprocating,half_reciprocating_error,
//                     second_order,second_order_error: J_eq exact and by the textbook's shortcuts (torsion.h)
//   torsion_resonances scene,route,order,mode,speed_rpm,frequency_hz,critical_rpm,twist: the local maxima of the
//                     `torsion` curves (route holzer or exact; a parabola through the grid's three points), the order
//                     whose amplitude rises most there, the mode nearest its frequency and Holzer's critical speed
//   torsion_engines   scene,engine,speed_rpm,section,peak_to_peak,exact,difference,cycles,accuracy,periodicity: each
//                     engine's own train (Engine::simulate_crank_train) on the first scene at its own speed against
//                     the analytic steady state, difference = (engine - analytic) / twist scale
//   torsion_ratio     scene,piston_mass_factor,ratio,order,speed_rpm,holzer,exact,worst_difference: the first scene's
//                     piston mass scaled, ratio = reciprocating / rotating inertia (torsion.h's textbook split), at
//                     Holzer's critical speed of mode 1 and the engine's lowest major order; exact empty where the
//                     train has no periodic state
//   torsion_cost      scene,route,speed_rpm,seconds: wall time of each route's speed point in the campaign (other
//                     tasks run beside it: ratios, not benchmarks; bench/README.md "Torsion" has those)

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
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/extremum.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/variants.h"

namespace crankcheck::validation {
namespace {

constexpr double kHolzerConvergence = 1e-6;
constexpr double kExactTolerance = 1e-8;
constexpr int kExactSamples = 2048;  // the series' aliasing, a few 1e-7 of a small section's value, is below the part's
                                     // percent differences (torsion_steady.h)
constexpr double kTextbookOrder = 24.0;
// The engines' trains in the report: a check of the figure's exact curve on the first scene at its own speed, not the
// gate (tests/gate/torsion_test.cc holds them to 2e-6 of the twist scale at their defaults on both example scenes and
// three speeds). At a cycle-to-cycle change of `periodicity` what is left of the transient is at most about that much
// of the twist scale: 1e-4 in the full campaign, 5e-2 in the quick one (a smoke test of the route: on the example four
// both trains stop after 4 cycles, at a change of 0.049, with differences to the exact orbit of 2.1e-3 of the twist
// scale; at 1e-2 they ran a fifth cycle, 15 % of Simbody's run, for 8e-4 and 1e-3; 2026-11-26). Samples of the cycle:
// 1024 in the full campaign; 256 in the quick one, whose peak-to-peaks then carry their aliasing, about 1e-4 of the
// twist scale on the example four (1e-5 at 1024), far below its periodicity (every sample a step end: at 1024 the
// sampled cycle was half of Simbody's quick run). The gated routes' accuracy (their integrators' error per step): 1e-7
// in the full campaign, which leaves their differences to the analytic orbit at 8e-6 (Simbody) and 5e-7 (MuJoCo) of the
// twist scale on the example four, far below the periodicity and the part's percent differences, at 0.81 and 0.61 of
// the cost of 1e-8 (9e-7 and 3e-7; 2026-11-26, bench/README.md "Ninth session"); 1e-5 in the quick one, whose
// differences it leaves at what the periodicity leaves (at 1e-2: 5e-4 to 1e-3 of the twist scale at 1e-6 and at 1e-5
// alike), at 0.7 of the cost of 1e-6. The soft routes (measured, not gated) at a fixed step of 1/1024 of a cycle in the
// full campaign (not run in the quick one; at least a step per sample): kSoftDefault's difference, its loops' give
// (0.12 of the twist scale), is the same as at its default 1/4096; kSoftStiff's, its loops' time constant two steps,
// 1.7e-3 instead of 9e-5 (3.9e-4 at 1/2048), still a fiftieth of kSoftDefault's; at a quarter of the cost.
struct EngineRunSettings {
  double accuracy, periodicity;
  int samples;
  double soft_step;  // the soft routes' fixed step, a fraction of a cycle (their `accuracy`)
};
EngineRunSettings getEngineRunSettings(bool quick) {
  return quick ? EngineRunSettings{1e-5, 5e-2, 256, 0.0} : EngineRunSettings{1e-7, 1e-4, 1024, 1.0 / 1024};
}

std::string num(double x) { return formatNumber(x); }

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

std::vector<const Mechanism*> listTrainScenes(const std::vector<Mechanism>& scenes) {
  std::vector<const Mechanism*> out;
  for (const Mechanism& m : scenes)
    if (m.crankshaft && m.engine.speed > 0.0) out.push_back(&m);
  return out;
}

// The working cycle's order step: 1/2 (four-stroke), 1 (two-stroke).
double getOrderStep(const Mechanism& m) { return m.engine.cycle == Cycle::kFourStroke ? 0.5 : 1.0; }

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
  const double firings = m.engine.cylinders * getOrderStep(m);
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
  const double firings = m.engine.cylinders * getOrderStep(m);
  for (double p = firings; p <= kTextbookOrder + 1e-9; p += firings)
    if (mode1 / p * 30.0 / M_PI <= 1.25 * m.speed_rpm) return p;
  return firings;
}

// Section i's name as a bare word: front-throw0, throw0-throw1, ..., throw3-flywheel.
std::string nameSection(const Mechanism& m, int i, int bodies) {
  const bool front = m.crankshaft->front_inertia > 0.0;
  auto body = [&](int b) {
    if (b >= bodies) return std::string("flywheel");
    if (front && b == 0) return std::string("front");
    return "throw" + std::to_string(b - (front ? 1 : 0));
  };
  return body(i) + "-" + body(i + 1);
}

TableSet makeEmptyTables() {
  TableSet t;
  t["torsion"] = Table("torsion", {{"scene", kText}, {"speed_rpm", "rpm"}, {"holzer", "rad"}, {"holzer_order24", "rad"},
                                   {"exact", "rad"}, {"difference", "-"}, {"worst_difference", "-"}, {"section", kText},
                                   {"worst_section", kText}, {"error_bound", "rad"}});
  t["torsion_sections"] = Table("torsion_sections", {{"scene", kText}, {"speed_rpm", "rpm"}, {"section_index", "-"},
                                                     {"section", kText}, {"holzer", "rad"}, {"holzer_order24", "rad"},
                                                     {"exact", "rad"}, {"difference", "-"}});
  t["torsion_orders"] = Table("torsion_orders", {{"scene", kText}, {"speed_rpm", "rpm"}, {"order", "-"},
                                                 {"holzer", "rad"}, {"exact", "rad"}});
  t["torsion_modes"] = Table("torsion_modes", {{"scene", kText}, {"mode", "-"}, {"holzer_hz", "Hz"}, {"min_hz", "Hz"},
                                               {"max_hz", "Hz"}, {"firings_per_turn", "-"}});
  t["torsion_inertia"] = Table("torsion_inertia", {{"scene", kText}, {"throw", "-"}, {"exact_inertia", "kg m^2"},
                                                   {"min_inertia", "kg m^2"}, {"max_inertia", "kg m^2"},
                                                   {"half_reciprocating", "kg m^2"}, {"half_reciprocating_error", "-"},
                                                   {"second_order", "kg m^2"}, {"second_order_error", "-"}});
  t["torsion_engines"] = Table("torsion_engines", {{"scene", kText}, {"engine", kText}, {"speed_rpm", "rpm"},
                                                   {"section", kText}, {"peak_to_peak", "rad"}, {"exact", "rad"},
                                                   {"difference", "-"}, {"cycles", "-"}, {"accuracy", "-"},
                                                   {"periodicity", "-"}});
  t["torsion_ratio"] = Table("torsion_ratio", {{"scene", kText}, {"piston_mass_factor", "-"}, {"ratio", "-"},
                                               {"order", "-"}, {"speed_rpm", "rpm"}, {"holzer", "rad"},
                                               {"exact", "rad"}, {"worst_difference", "-"}});
  t["torsion_cost"] = Table("torsion_cost", {{"scene", kText}, {"route", kText}, {"speed_rpm", "rpm"},
                                             {"seconds", "s"}});
  return t;
}

// One speed point of a scene: Holzer and the exact steady state, every section, the orders of the section that twists
// most, and the cost of each route.
TableSet calcSpeedTables(const Mechanism& scene, double rpm, analytic::ThrowLoadOrders& load_orders) {
  TableSet tables = makeEmptyTables();
  const Mechanism m = withSpeed(scene, rpm);
  analytic::HolzerOptions holzer_options;
  holzer_options.convergence = kHolzerConvergence;
  auto start = std::chrono::steady_clock::now();
  const analytic::HolzerResponse holzer = analytic::calcHolzerResponse(m, holzer_options, load_orders);
  const double holzer_seconds = seconds(start);
  analytic::SteadyStateOptions exact_options;
  exact_options.tolerance = kExactTolerance;
  exact_options.samples = kExactSamples;
  start = std::chrono::steady_clock::now();
  const analytic::ExactSteadyState exact = analytic::calcExactSteadyState(m, holzer, exact_options);
  const double exact_seconds = seconds(start);
  const int n = static_cast<int>(exact.peak_to_peak.size());
  int most = 0, worst = 0;
  auto differenceAt = [&](int i) { return exact.peak_to_peak[i] / holzer.peak_to_peak[i] - 1.0; };
  for (int i = 0; i < n; ++i) {
    if (exact.peak_to_peak[i] > exact.peak_to_peak[most]) most = i;
    if (std::fabs(differenceAt(i)) > std::fabs(differenceAt(worst))) worst = i;
    tables["torsion_sections"].rows.push_back({m.name, num(rpm), std::to_string(i), nameSection(m, i, n),
                                               num(holzer.peak_to_peak[i]), num(holzer.peak_to_peak_order24[i]),
                                               num(exact.peak_to_peak[i]), num(differenceAt(i))});
  }
  tables["torsion"].rows.push_back({m.name, num(rpm), num(holzer.peak_to_peak[most]),
                                    num(holzer.peak_to_peak_order24[most]), num(exact.peak_to_peak[most]),
                                    num(differenceAt(most)), num(differenceAt(worst)), nameSection(m, most, n),
                                    nameSection(m, worst, n), num(exact.error_bound)});
  // Order p of the cycle's harmonics h: p = h x step (crank_train.h's PeriodicSignal), up to order 24.
  const double step = getOrderStep(m);
  const auto& hc = holzer.twists[most].coefficients;
  const auto& ec = exact.twists[most].coefficients;
  for (size_t h = 1; h * step <= kTextbookOrder + 1e-9; ++h)
    tables["torsion_orders"].rows.push_back({m.name, num(rpm), num(h * step), num(h < hc.size() ? std::abs(hc[h]) : 0.0),
                                             num(h < ec.size() ? std::abs(ec[h]) : 0.0)});
  tables["torsion_cost"].rows.push_back({m.name, "holzer", num(rpm), num(holzer_seconds)});
  tables["torsion_cost"].rows.push_back({m.name, getClosedFormEngine().name, num(rpm), num(exact_seconds)});
  return tables;
}

// J_min and J_max of throw j over a turn [kg m^2], J_t included (extremum.h: sampled, refined by Brent).
std::pair<double, double> findThrowInertiaRange(const Mechanism& m, int j) {
  auto J = [&](double psi) { return analytic::calcThrowReducedInertia(m, j, psi); };
  const double top = findMaxAbsOverTurn(J, 720).value;
  const double below = findMaxAbsOverTurn([&](double psi) { return top - J(psi); }, 720).value;
  const double jt = m.crankshaft->throw_inertia;
  return {jt + top - below, jt + top};
}

// The scene's inertias and modes: J_eq and its shortcuts per throw, and the frequencies at J_eq, J_min and J_max.
TableSet calcModeTables(const Mechanism& m) {
  TableSet tables = makeEmptyTables();
  const analytic::TorsionModes modes = analytic::calcTorsionModes(m);
  std::vector<double> low = modes.inertias, high = modes.inertias;
  const bool front = m.crankshaft->front_inertia > 0.0;
  const int throws = static_cast<int>(findThrows(m).size());
  for (int j = 0; j < throws; ++j) {
    const analytic::ThrowInertia inertia = analytic::calcThrowInertia(m, j);
    const auto [jmin, jmax] = findThrowInertiaRange(m, j);
    low[static_cast<size_t>(j + (front ? 1 : 0))] = jmin;
    high[static_cast<size_t>(j + (front ? 1 : 0))] = jmax;
    tables["torsion_inertia"].rows.push_back(
        {m.name, std::to_string(j), num(inertia.exact), num(jmin), num(jmax), num(inertia.half_reciprocating),
         num(inertia.half_reciprocating / inertia.exact - 1.0), num(inertia.second_order),
         num(inertia.second_order / inertia.exact - 1.0)});
  }
  // The lightest throws give the highest frequencies.
  const analytic::TorsionModes at_min = analytic::calcChainModes(low, modes.stiffness);
  const analytic::TorsionModes at_max = analytic::calcChainModes(high, modes.stiffness);
  for (int i = 0; i < modes.frequencies.size(); ++i)
    tables["torsion_modes"].rows.push_back({m.name, std::to_string(i + 1), num(modes.frequencies(i) / (2 * M_PI)),
                                            num(at_max.frequencies(i) / (2 * M_PI)),
                                            num(at_min.frequencies(i) / (2 * M_PI)),
                                            num(m.engine.cylinders * getOrderStep(m))});
  return tables;
}

// The analytic steady state at the first scene's own speed, which every engine's train is held against: computed once
// for the engines' tasks, by the first that needs it (each asks after its own run, so the others rarely wait).
using SharedSteadyState = SharedResult<analytic::ExactSteadyState>;
analytic::ExactSteadyState calcTrainReference(const Mechanism& m) {
  analytic::SteadyStateOptions exact_options;
  exact_options.tolerance = kExactTolerance;
  exact_options.samples = kExactSamples;
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
  const double run_seconds = seconds(start);
  const analytic::ExactSteadyState& exact = analytic_state.get();
  const int n = static_cast<int>(run.twists.size());
  for (int i = 0; i < n; ++i) {
    const double p2p = analytic::findSignalExtremes(analytic::calcSignalFromSamples(run.twists[i])).peakToPeak();
    tables["torsion_engines"].rows.push_back({m.name, engine.name, num(m.speed_rpm), nameSection(m, i, n), num(p2p),
                                              num(exact.peak_to_peak[i]),
                                              num((p2p - exact.peak_to_peak[i]) / exact.twist_scale),
                                              std::to_string(run.cycles), num(options.accuracy),
                                              num(options.periodicity)});
  }
  tables["torsion_cost"].rows.push_back({m.name, engine.name, num(m.speed_rpm), num(run_seconds)});
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
  analytic::HolzerOptions holzer_options;
  holzer_options.convergence = kHolzerConvergence;
  const analytic::HolzerResponse holzer = analytic::calcHolzerResponse(m, holzer_options);
  std::vector<std::string> row = {scene.name, num(factor), num(calcReciprocatingRatio(m)), num(order), num(rpm)};
  const size_t most_holzer = static_cast<size_t>(
      std::max_element(holzer.peak_to_peak.begin(), holzer.peak_to_peak.end()) - holzer.peak_to_peak.begin());
  row.push_back(num(holzer.peak_to_peak[most_holzer]));
  try {
    analytic::SteadyStateOptions exact_options;
    exact_options.tolerance = kExactTolerance;
    exact_options.samples = kExactSamples;
    const analytic::ExactSteadyState exact = analytic::calcExactSteadyState(m, holzer, exact_options);
    size_t worst = 0;
    for (size_t i = 0; i < exact.peak_to_peak.size(); ++i)
      if (std::fabs(exact.peak_to_peak[i] / holzer.peak_to_peak[i] - 1.0) >
          std::fabs(exact.peak_to_peak[worst] / holzer.peak_to_peak[worst] - 1.0))
        worst = i;
    row.push_back(num(exact.peak_to_peak[most_holzer]));
    row.push_back(num(exact.peak_to_peak[worst] / holzer.peak_to_peak[worst] - 1.0));
  } catch (const std::runtime_error&) {
    row.emplace_back();  // no periodic steady state (Newton did not converge): the constant-inertia model broke
    row.emplace_back();
  }
  tables["torsion_ratio"].rows.push_back(row);
  return tables;
}

std::vector<double> listRatioFactors(bool quick) {
  return quick ? std::vector<double>{1.0} : std::vector<double>{0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0};
}

// ---- derive: the resonances of the sweep ----

struct SweepPoint {
  double rpm = 0.0, holzer = 0.0, exact = 0.0;
};

// Local maxima of one route's curve (interior grid points 1 % above both neighbours), each placed by the parabola through
// the three points; its order the one whose amplitude rises most there (above the mean of its neighbours') among the
// orders within 25 % of a natural frequency, its mode the nearest (mode and critical speed empty when no such order
// rises: the order that rises most, no resonance).
void addResonances(Table& out, const std::string& scene, const std::string& route, const std::vector<SweepPoint>& sweep,
                   const std::map<double, std::map<double, double>>& amplitudes, const std::vector<double>& modes_hz) {
  const bool exact = route != "holzer";
  auto value = [&](size_t i) { return exact ? sweep[i].exact : sweep[i].holzer; };
  for (size_t i = 1; i + 1 < sweep.size(); ++i) {
    // A resonance stands out: at least 1 % above both neighbours (the example scenes' stand 7 % to 86 % above them on
    // this grid; what is below are ripples of the sum's shoulders, 0.04 % on the example four).
    if (!(value(i) > 1.01 * value(i - 1) && value(i) > 1.01 * value(i + 1))) continue;
    // The vertex of the parabola through (x_{i-1}, y_{i-1}), (x_i, y_i), (x_{i+1}, y_{i+1}).
    const double x0 = sweep[i - 1].rpm, x1 = sweep[i].rpm, x2 = sweep[i + 1].rpm;
    const double y0 = value(i - 1), y1 = value(i), y2 = value(i + 1);
    const double rpm = x1 - 0.5 * ((x1 - x0) * (x1 - x0) * (y1 - y2) - (x1 - x2) * (x1 - x2) * (y1 - y0)) /
                                ((x1 - x0) * (y1 - y2) - (x1 - x2) * (y1 - y0));
    const auto at = amplitudes.find(sweep[i].rpm), before = amplitudes.find(sweep[i - 1].rpm),
               after = amplitudes.find(sweep[i + 1].rpm);
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
    out.rows.push_back({scene, route, num(order), resonant ? std::to_string(mode + 1) : "", num(rpm), num(hz),
                        resonant ? num(modes_hz[mode] * 60.0 / order) : "", num(y1)});
  }
}

void deriveTorsion(TableSet& tables) {
  if (!tables.count("torsion") || !tables.count("torsion_orders") || !tables.count("torsion_modes")) return;
  Table resonances("torsion_resonances", {{"scene", kText}, {"route", kText}, {"order", "-"}, {"mode", "-"},
                                          {"speed_rpm", "rpm"}, {"frequency_hz", "Hz"}, {"critical_rpm", "rpm"},
                                          {"twist", "rad"}});
  const Table &t = tables.at("torsion"), &o = tables.at("torsion_orders"), &md = tables.at("torsion_modes");
  const size_t ts = columnOf(t, "scene"), tr = columnOf(t, "speed_rpm"), th = columnOf(t, "holzer"),
               te = columnOf(t, "exact");
  std::map<std::string, std::vector<SweepPoint>> sweeps;  // rows are sorted: by scene, then speed
  for (const auto& row : t.rows) sweeps[row[ts]].push_back({std::stod(row[tr]), std::stod(row[th]), std::stod(row[te])});
  const size_t os = columnOf(o, "scene"), orr = columnOf(o, "speed_rpm"), op = columnOf(o, "order"),
               oh = columnOf(o, "holzer"), oe = columnOf(o, "exact");
  std::map<std::string, std::map<double, std::map<double, double>>> holzer_orders, exact_orders;
  for (const auto& row : o.rows) {
    holzer_orders[row[os]][std::stod(row[orr])][std::stod(row[op])] = std::stod(row[oh]);
    exact_orders[row[os]][std::stod(row[orr])][std::stod(row[op])] = std::stod(row[oe]);
  }
  std::map<std::string, std::vector<double>> modes;
  const size_t ms = columnOf(md, "scene"), mh = columnOf(md, "holzer_hz");
  for (const auto& row : md.rows) modes[row[ms]].push_back(std::stod(row[mh]));
  for (const auto& [scene, sweep] : sweeps) {
    if (!modes.count(scene)) continue;
    addResonances(resonances, scene, "holzer", sweep, holzer_orders[scene], modes[scene]);
    addResonances(resonances, scene, "exact", sweep, exact_orders[scene], modes[scene]);
  }
  tables["torsion_resonances"] = resonances;
}

// ---- describe ----


void describeSweeps(const TableSet& tables, ReportPart& part) {
  const Table& t = tables.at("torsion");
  const size_t ts = columnOf(t, "scene"), tr = columnOf(t, "speed_rpm"), tw = columnOf(t, "worst_difference"),
               twn = columnOf(t, "worst_section"), th = columnOf(t, "holzer"), t24 = columnOf(t, "holzer_order24");
  std::map<std::string, std::vector<const std::vector<std::string>*>> by_scene;
  for (const auto& row : t.rows) by_scene[row[ts]].push_back(&row);
  for (const auto& [scene, rows] : by_scene) {
    int within = 0, beyond = 0;
    const std::vector<std::string>* worst = rows.front();
    double cut = 0.0;
    std::string cut_at;
    for (const auto* row : rows) {
      const double d = std::fabs(std::stod((*row)[tw]));
      within += d <= 0.01;
      beyond += d > 0.10;
      if (d > std::fabs(std::stod((*worst)[tw]))) worst = row;
      const double c = std::fabs(std::stod((*row)[t24]) / std::stod((*row)[th]) - 1.0);
      if (c > cut) {
        cut = c;
        cut_at = shortNumber(std::stod((*row)[tr]), 4);
      }
    }
    part.paragraphs.push_back(
        scene + ", " + std::to_string(rows.size()) + " speeds from " + shortNumber(std::stod(rows.front()->at(tr)), 4) +
        " to " + shortNumber(std::stod(rows.back()->at(tr)), 4) + " rpm: Holzer's peak-to-peak twist (every order summed) "
        "is within 1 % of the exact steady state's on every section at " + std::to_string(within) + " of them and off by "
        "more than 10 % on some section at " + std::to_string(beyond) + "; at worst " +
        formatPercent(std::stod((*worst)[tw])) + " (" + (*worst)[twn] + ", " + shortNumber(std::stod((*worst)[tr]), 4) +
        " rpm). The textbook's sum cut at order 24 differs from the converged sum by up to " + formatPercent(cut) +
        " (at " + cut_at + " rpm).");
  }
}

void describeResonances(const TableSet& tables, ReportPart& part) {
  const auto it = tables.find("torsion_resonances");
  if (it == tables.end()) return;
  const Table& r = it->second;
  const size_t rs = columnOf(r, "scene"), rr = columnOf(r, "route"), ro = columnOf(r, "order"),
               rm = columnOf(r, "mode"), rv = columnOf(r, "speed_rpm"), rc = columnOf(r, "critical_rpm");
  std::map<std::string, std::vector<const std::vector<std::string>*>> exact, holzer;
  for (const auto& row : r.rows) (row[rr] == "holzer" ? holzer : exact)[row[rs]].push_back(&row);
  auto join = [](std::string& list, const std::string& item) { list += (list.empty() ? "" : ", ") + item; };
  for (const auto& [scene, peaks] : exact) {
    std::string found, missed;
    for (const auto* peak : peaks) {
      const double rpm = std::stod((*peak)[rv]);
      std::string what = "order " + (*peak)[ro] + " at " + shortNumber(rpm, 4) + " rpm";
      if ((*peak)[rm].empty()) {
        what += " (no mode near its frequency)";
      } else {
        const double critical = std::stod((*peak)[rc]);
        what += " (mode " + (*peak)[rm] + "; Holzer's critical speed " + shortNumber(critical, 4) + " rpm, " +
                (rpm >= critical ? "+" : "") + formatPercent(rpm / critical - 1.0) + ")";
      }
      bool matched = false;
      for (const auto* h : holzer[scene])
        if ((*h)[ro] == (*peak)[ro] && std::fabs(std::stod((*h)[rv]) / rpm - 1.0) < 0.05) matched = true;
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
  const Table& md = tables.at("torsion_modes");
  const size_t ms = columnOf(md, "scene"), mm = columnOf(md, "mode"), mh = columnOf(md, "holzer_hz"),
               ml = columnOf(md, "min_hz"), mx = columnOf(md, "max_hz");
  for (const auto& row : md.rows) {
    if (row[mm] != "1") continue;
    const double h = std::stod(row[mh]), lo = std::stod(row[ml]), hi = std::stod(row[mx]);
    part.paragraphs.push_back(row[ms] + ": mode 1 is at " + shortNumber(h, 4) + " Hz with Holzer's J_eq; with every "
                              "throw at its lightest and at its heaviest over a turn it would be at " +
                              shortNumber(hi, 4) + " and " + shortNumber(lo, 4) + " Hz: a spread of " +
                              formatPercent((hi - lo) / h) + " that the constant inertia cannot show.");
  }
}

void describeRatio(const TableSet& tables, ReportPart& part) {
  const auto it = tables.find("torsion_ratio");
  if (it == tables.end() || it->second.rows.empty()) return;
  const Table& r = it->second;
  const size_t rs = columnOf(r, "scene"), rq = columnOf(r, "ratio"), ro = columnOf(r, "order"),
               rw = columnOf(r, "worst_difference");
  std::vector<std::pair<double, std::optional<double>>> points;
  for (const auto& row : r.rows)
    points.push_back({std::stod(row[rq]), row[rw].empty() ? std::nullopt : std::optional(std::stod(row[rw]))});
  std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  const std::string range = points.size() == 1 ? "is " + shortNumber(points.front().first, 3) + " times the rotating one"
                                                : "runs from " + shortNumber(points.front().first, 3) + " to " +
                                                      shortNumber(points.back().first, 3) + " times the rotating one";
  std::string sentence = r.rows.front()[rs] + ", its piston mass scaled so that the reciprocating inertia " + range +
                         ", at Holzer's critical speed of mode 1 and order " +
                         r.rows.front()[ro] + ": Holzer's worst section is off by ";
  std::string list;
  std::optional<double> breaks;
  for (const auto& [ratio, d] : points) {
    list += (list.empty() ? "" : ", ") + (d ? formatPercent(*d) : std::string("no periodic state")) + " at " +
            shortNumber(ratio, 3);
    if (!breaks && (!d || std::fabs(*d) > 0.10)) breaks = ratio;
  }
  sentence += list + ". ";
  sentence += breaks ? "The constant-inertia model is off by more than 10 % from a ratio of " + shortNumber(*breaks, 3) +
                           " on."
                     : "It stays within 10 % over the whole sweep.";
  part.paragraphs.push_back(sentence);
}

void describeEnginesAndCost(const TableSet& tables, ReportPart& part) {
  if (const auto it = tables.find("torsion_engines"); it != tables.end()) {
    const Table& e = it->second;
    const size_t ee = columnOf(e, "engine"), es = columnOf(e, "scene"), ed = columnOf(e, "difference"),
                 ea = columnOf(e, "accuracy"), ep = columnOf(e, "periodicity"), er = columnOf(e, "speed_rpm");
    std::map<std::string, double> worst;
    std::map<std::string, std::string> where;
    auto isGated = [](const std::string& engine) {
      for (const Engine& known : listEngines())
        if (known.name == engine) return known.crank_train_gated;
      return true;
    };
    for (const auto& row : e.rows) {
      worst[row[ee]] = std::max(worst[row[ee]], std::fabs(std::stod(row[ed])));
      const double accuracy = std::stod(row[ea]);
      // A soft route's accuracy is its fixed step as a fraction of a cycle.
      std::string how = "its default step";
      if (accuracy > 0.0)
        how = isGated(row[ee]) ? "accuracy " + shortNumber(accuracy, 1)
                               : "a fixed step of 1/" + shortNumber(1.0 / accuracy, 6) + " of a cycle";
      where[row[ee]] = row[es] + " at " + shortNumber(std::stod(row[er]), 4) + " rpm (" + how +
                       ", run until the cycle-to-cycle change is below " + shortNumber(std::stod(row[ep]), 1) +
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
  const auto it = tables.find("torsion_cost");
  if (it == tables.end()) return;
  const Table& c = it->second;
  const size_t cr = columnOf(c, "route"), cs = columnOf(c, "seconds");
  std::map<std::string, std::pair<double, int>> mean;
  for (const auto& row : c.rows) {
    mean[row[cr]].first += std::stod(row[cs]);
    ++mean[row[cr]].second;
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
  for (const char* name : {"torsion", "torsion_modes", "torsion_inertia"})
    if (!tables.count(name)) return part;
  if (tables.at("torsion").rows.empty()) return part;
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
      "rotating inertia at the major order's critical speed (bottom)";
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
  inertia.rows = formatRows(tables, "torsion_inertia",
                            {"scene", "throw", "exact_inertia", "min_inertia", "max_inertia", "half_reciprocating",
                             "half_reciprocating_error", "second_order", "second_order_error"},
                            {false, false, true, true, true, true, true, true, true});
  part.blocks.push_back(inertia);
  if (tables.count("torsion_resonances") && !tables.at("torsion_resonances").rows.empty()) {
    ReportBlock peaks;
    peaks.kind = ReportBlock::kTable;
    peaks.header = {"scene", "route", "order", "mode", "peak [rpm]", "frequency [Hz]", "Holzer critical [rpm]",
                    "twist [rad]"};
    peaks.rows = formatRows(tables, "torsion_resonances",
                            {"scene", "route", "order", "mode", "speed_rpm", "frequency_hz", "critical_rpm", "twist"},
                            {false, false, false, false, true, true, true, true});
    part.blocks.push_back(peaks);
  }
  return part;
}

// The notes' prefix of a route part 17 could not compute (calcOrNote).
constexpr const char* kRefusedNote = "Part 17 (torsion): ";

// A task whose route is refused for its scene (outside the small-twist domain at one of the sweep's speeds, past a
// work limit): its reason in the report's notes and no numbers (crankcheck torsion refuses the same with status 1).
// The part then leaves its figure and tables out (derive), rather than draw a sweep with holes; the other parts go
// on. A logic error still ends the campaign.
template <class Calc>
TableSet calcOrNote(const std::string& what, Calc calc) {
  try {
    return calc();
  } catch (const std::runtime_error& e) {
    return kNotesTable.tableSet({{kRefusedNote + what + " not computed: " + formatOneLine(e.what())}});
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
    const std::vector<const Mechanism*> scenes = listTrainScenes(context.scenes);
    for (size_t s = 0; s < scenes.size(); ++s) {
      const Mechanism& m = *scenes[s];
      out.push_back({"torsion modes " + m.name, false, [m] { return calcModeTables(m); }});
      // The throws' speed-free torque orders, computed once for the scene's speed points (torsion_forced.h).
      const auto load_orders = std::make_shared<analytic::ThrowLoadOrders>();
      for (double rpm : listSweepSpeeds(m, context.quick))
        out.push_back({"torsion " + m.name + " " + num(rpm) + " rpm", false,
                       [m, rpm, load_orders] {
                         return calcOrNote(m.name + " at " + num(rpm) + " rpm",
                                           [&] { return calcSpeedTables(m, rpm, *load_orders); });
                       },
                       task_cost::kShort});
      if (s > 0) continue;
      const auto analytic_state = std::make_shared<SharedSteadyState>([m] { return calcTrainReference(m); });
      for (const Engine& engine : listEngines())
        if (engine.simulate_crank_train && !engine.closed_form && (engine.crank_train_gated || !context.quick))
          out.push_back({"torsion " + m.name + " " + engine.name, false,
                         [m, &engine, quick = context.quick, analytic_state] {
                           return calcOrNote(m.name + " by " + engine.name,
                                             [&] { return calcEngineTables(m, engine, quick, *analytic_state); });
                         },
                         task_cost::kSimbodyRun});
    }
    if (!scenes.empty())
      for (double factor : listRatioFactors(context.quick))
        out.push_back({"torsion ratio " + num(factor), false,
                       [m = *scenes.front(), factor] {
                         return calcOrNote(m.name + " at the inertia ratio's factor " + num(factor),
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
    const std::vector<NoteRow>& notes = getRows(tables, kNotesTable);
    if (std::any_of(notes.begin(), notes.end(), [](const NoteRow& row) { return row.note.rfind(kRefusedNote, 0) == 0; })) {
      for (const std::string& name : this->tables()) tables.erase(name);
      addRows(tables, kNotesTable,
              {{"Part " + std::to_string(number()) + " (" + key() + ") is left out: the routes these notes name could "
                "not be computed, and a sweep with holes is not drawn. crankcheck torsion on each scene shows the rest."}});
      return;
    }
    deriveTorsion(tables);
  }
  ReportPart describe(const TableSet& tables) const override { return describeTorsionPart(tables, heading()); }
  std::vector<std::string> tables() const override {
    return {"torsion",         "torsion_sections", "torsion_orders", "torsion_modes", "torsion_inertia",
            "torsion_engines", "torsion_ratio",    "torsion_cost",   "torsion_resonances"};
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
