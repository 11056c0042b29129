// Scene topic `fitness` ("Formula fitness"): every textbook formula the report judges that applies to the scene, its
// largest error over the working cycle on the scene exactly as given (its lambda, speed, banks, pin offsets), relative
// to the quantity's scale, against the analytic engine's exact closed forms and against every reference engine
// (rows of kFitnessTable, topic.h). The formulas and their exact counterparts are the survey parts' own
// (error_vs_lambda, errata, rod_models, offset), here on the user's engine instead of a swept textbook one.
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "../part_math.h"
#include "crankcheck/analytic/exact_trig.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/scene/quantities.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/extremum.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/scales.h"
#include "topic.h"

namespace crankcheck::validation::your_engine {
namespace {

using analytic::Eq5Form;
using analytic::LambdaSource;
using analytic::RodInertiaForm;

// A formula that is not judged on a scene, and why (data/your_engine_fitness_scope.csv): describe() says so in one
// paragraph, from this table alone.
struct FitnessScopeRow {
  std::string scene;
  std::string formula;  ///< the formula (or group of formulas) left out
  std::string reason;   ///< why, and how to see it where the scene could have it
};
const Schema<FitnessScopeRow> kFitnessScopeTable{
    "your_engine_fitness_scope",
    {textField("scene", &FitnessScopeRow::scene), textField("formula", &FitnessScopeRow::formula),
     textField("reason", &FitnessScopeRow::reason)}};

// The formulas' names as the table prints them.
const char* const kNortonSeries = "Norton's two-term series (eq 13.3)";
const char* const kEq15 = "Stanczak eq (15) as printed (Lambda_2..Lambda_12)";
const char* const kEq5 = "Stanczak eq (5) as printed (U1, U2)";
const char* const kTwoMass = "two-mass rod without Delta_I";
const char* const kTwoMassDeltaI = "two-mass rod with Delta_I";
const char* const kCentric = "centric forms (delta = 0)";
std::string formatFourierFormula(int order) {
  return "Fourier series of Q to order " + std::to_string(order) + " (exact Lambda_n)";
}

// The orders of Q's series judged: those of the paper's eq (15), Lambda_2..Lambda_12 (Q holds n = 1 and even n only,
// so an odd order gives the series of the order below).
constexpr int kFourierOrders[] = {2, 4, 6, 8, 10, 12};

// The samples of one crank turn: every refined maximum (extremum.h) needs a sample on its hump; the errors judged here
// hold harmonics up to about 2 k (k <= 12 cylinders' sums), and 360 a turn keeps 15 samples per period of order 24,
// 90 a turn (the quick campaign) still 3.75.
int samplesPerTurn(bool quick) { return quick ? 90 : 360; }
// The reference engines' own grid, 5 degrees (10 in the quick campaign): each reference's maximum is the larger of its
// grid's and its value where the analytic engine's error is largest (the engines agree to rounding, so that is the
// reference's maximum to rounding); the grid guards against a reference that disagrees elsewhere.
int referenceSamplesPerTurn(bool quick) { return quick ? 36 : 72; }

// One formula judged on one quantity: its value, the exact closed form's and a reference engine's, per cylinder j
// (cylinders > 0) or of the whole mechanism (cylinders = 0, j = 0).
struct Judged {
  int order = 0;
  std::string formula, quantity, scale, scale_unit;
  double scale_value = 0.0;
  int cylinders = 0;
  std::function<double(double phi, int j)> formula_value;
  std::function<double(double phi, int j)> exact_value;
  std::function<double(const Evaluation&, int j)> engine_value;
  /// The analytic reference's error found another way (the series' remainder from the exact harmonics); empty: by
  /// formula_value - exact_value.
  std::function<TurnMaximum()> analytic_maximum;
  /// The rounding a maximum must exceed to be resolved (part_math.h resolvedToOnePercent): its absolute size [SI]. The
  /// analytic reference's error from analytic_maximum is exact to rounding however small: resolved unless zero.
  double rounding = 0.0;
};

struct Found {
  double value = 0.0;  ///< [SI] the largest |error|
  double phi = 0.0;    ///< [rad] where, in the working cycle
  int cylinder = 0;
};

// The working cycle as one turn u in [0, 2 pi): phi = turns u (two turns for a four-stroke engine, whose gas table
// repeats every 720 degrees).
int cycleTurns(const Mechanism& m) { return m.machine.cycle == Cycle::kFourStroke ? 2 : 1; }

// The best sampled humps refined over the working cycle (extremum.h): an error's humps can be of nearly one height
// (a four-stroke cycle repeats a 2 pi periodic error; a harmonic's humps are moved by the next one's few percent), so
// more than the 4 of the survey parts; each costs about 30 evaluations of the closed forms.
constexpr int kRefinements = 16;

// The analytic reference's largest error of `judged`: over every cylinder, each refined.
Found findAnalyticMaximum(const Mechanism& m, const Judged& judged, bool quick) {
  if (judged.analytic_maximum) {
    const TurnMaximum t = judged.analytic_maximum();
    return {t.value, t.phi, 0};
  }
  const int turns = cycleTurns(m);
  Found best{-1.0, 0.0, 0};
  for (int j = 0; j < std::max(1, judged.cylinders); ++j) {
    const TurnMaximum t = findMaxAbsOverTurn(
        [&](double u) {
          const double phi = turns * u;
          return judged.formula_value(phi, j) - judged.exact_value(phi, j);
        },
        samplesPerTurn(quick) * turns, kRefinements, getAngleTolerance(quick));
    if (t.value > best.value) best = {t.value, turns * t.phi, j};
  }
  return best;
}

// The rows of one scene: the judged formulas, each against the analytic engine and every reference engine.
TableSet calcFitnessTables(const Mechanism& m, bool quick) {
  const int k = m.machine.cylinders;
  const double r = m.crank.radius, w = m.machine.speed;
  const double E = calcEnergyScale(m);
  const Scales sc = calcScales(m);
  const double tolerance = getAngleTolerance(quick);
  std::vector<Judged> judged;
  std::vector<FitnessScopeRow> scope;
  auto leaveOut = [&](const std::string& formula, const std::string& reason) { scope.push_back({m.name, formula, reason}); };
  auto rounding = [](double scale, double conditioning) { return 100.0 * kAgreementMultiple * kEps * scale * conditioning; };

  // 1. Norton's two-term series against the exact kinematics of each cylinder (its own pin offset).
  auto kinematics = [&m](double phi, int j) {
    return analytic::calcPistonKinematics(m, analytic::calcThrowSinCos(phi, m.machine.crank_angles[j]), getPinOffset(m, j));
  };
  auto norton = [&m](double phi, int j) { return analytic::calcPistonKinematicsNorton(m, phi + m.machine.crank_angles[j]); };
  judged.push_back({0, kNortonSeries, nameOf(QuantityId::kPistonPosition), "r", "m", r, k,
                    [=](double phi, int j) { return norton(phi, j).x_p; },
                    [=](double phi, int j) { return kinematics(phi, j).x_p; },
                    [](const Evaluation& e, int j) { return e.cylinders[j].x_p; }, {}, rounding(r, 1.0)});
  if (w > 0.0) {
    judged.push_back({1, kNortonSeries, nameOf(QuantityId::kPistonVelocity), "r omega", "m/s", r * w, k,
                      [=](double phi, int j) { return norton(phi, j).v_p; },
                      [=](double phi, int j) { return kinematics(phi, j).v_p; },
                      [](const Evaluation& e, int j) { return e.cylinders[j].v_p; }, {}, rounding(r * w, 1.0)});
    judged.push_back({2, kNortonSeries, nameOf(QuantityId::kPistonAcceleration), "r omega^2", "m/s^2", r * w * w, k,
                      [=](double phi, int j) { return norton(phi, j).a_p; },
                      [=](double phi, int j) { return kinematics(phi, j).a_p; },
                      [](const Evaluation& e, int j) { return e.cylinders[j].a_p; }, {}, rounding(r * w * w, 1.0)});
  } else {
    leaveOut(std::string(kNortonSeries) + " for v_p and a_p", "the scene's speed is 0: v_p and a_p vanish ([engine].speed_rpm)");
  }

  // 2. Q's series and the paper's printed coefficients. Q's scale is its own maximum over a turn, or the energy scale
  // where Q vanishes by the layout's symmetry (then every error is rounding).
  if (E > 0.0) {
    const TurnMaximum max_Q = findMaxAbsOverTurn([&](double phi) { return analytic::calcGravityTorque(m, phi); },
                                                 samplesPerTurn(quick), 4, tolerance);
    const TurnMaximum max_U = findMaxAbsOverTurn([&](double phi) { return analytic::calcPotentialEnergy(m, phi); },
                                                 samplesPerTurn(quick), 4, tolerance);
    const double vanishing = kAgreementMultiple * kEps * E * sc.conditioning;
    const bool Q_vanishes = max_Q.value <= vanishing, U_vanishes = max_U.value <= vanishing;
    const std::string Q_scale = Q_vanishes ? "energy scale E" : "max |Q|", U_scale = U_vanishes ? "energy scale E" : "max |U|";
    const double Q_scale_value = Q_vanishes ? E : max_Q.value, U_scale_value = U_vanishes ? E : max_U.value;
    const std::string Q_name = nameOf(QuantityId::kQ), U_name = nameOf(QuantityId::kU);
    auto exact_Q = [&m](double phi, int) { return analytic::calcGravityTorque(m, phi); };
    auto engine_Q = [](const Evaluation& e, int) { return e.Q; };
    // The paper's series (eqs 14-16) hold for one bank of centric cylinders and no balance shafts.
    std::vector<std::string> why_not;
    if (!isSingleBank(m)) why_not.push_back("several banks");
    if (hasPinOffsets(m)) why_not.push_back("pin offsets");
    if (!m.balance_shafts.empty()) why_not.push_back("balance shafts");
    if (why_not.empty()) {
      const std::vector<analytic::TorqueHarmonic> exact = exactHarmonics(m);
      for (int order : kFourierOrders) {
        const std::vector<analytic::TorqueHarmonic> series = analytic::calcGravityTorqueHarmonics(m, order);
        const std::vector<analytic::TorqueHarmonic> above = harmonicsAbove(exact, order);
        // The remainder's terms are each their own size: exact to rounding however small, so resolved unless zero.
        judged.push_back({10 + order / 2 - 1, formatFourierFormula(order), Q_name, Q_scale, "N m", Q_scale_value, 0,
                          [series](double phi, int) { return analytic::evaluateTorqueHarmonics(series, phi); }, exact_Q,
                          engine_Q,
                          [above] {  // every hump of the remainder's first harmonic refined (part_math.h)
                            return findMaxAbsOfHarmonics(above);
                          },
                          rounding(E, sc.conditioning)});
      }
      const std::vector<analytic::TorqueHarmonic> printed = analytic::calcGravityTorqueHarmonics(m, 12, LambdaSource::kAsPrinted);
      judged.push_back({16, kEq15, Q_name, Q_scale, "N m", Q_scale_value, 0,
                        [printed](double phi, int) { return analytic::evaluateTorqueHarmonics(printed, phi); }, exact_Q,
                        engine_Q, {}, rounding(E, 1.0)});
    } else {
      std::string list;
      for (size_t i = 0; i < why_not.size(); ++i)
        list += (i == 0 ? "" : i + 1 == why_not.size() ? " and " : ", ") + why_not[i];
      leaveOut("Q's Fourier series (orders 2-12) and eq (15)",
               "the paper's series are for one bank of centric cylinders without balance shafts; this scene has " + list +
                   " (eq (5) is judged all the same: its U1 and U2 are one cylinder's masses split between its pins, "
                   "and U and Q their sum over the cylinders at each one's own angles, which holds for every layout; "
                   "what it gets wrong on any engine is the printed split)");
    }
    // Eq (5)'s coefficients are per cylinder: they apply to every layout.
    judged.push_back({17, kEq5, Q_name, Q_scale, "N m", Q_scale_value, 0,
                      [&m](double phi, int) { return analytic::calcGravityTorque(m, phi, Eq5Form::kAsPrinted); },
                      exact_Q, engine_Q, {}, rounding(E, 1.0)});
    judged.push_back({18, kEq5, U_name, U_scale, "J", U_scale_value, 0,
                      [&m](double phi, int) { return analytic::calcPotentialEnergy(m, phi, Eq5Form::kAsPrinted); },
                      [&m](double phi, int) { return analytic::calcPotentialEnergy(m, phi); },
                      [](const Evaluation& e, int) { return e.U; }, {}, rounding(E, 1.0)});
  } else {
    leaveOut("Q's series, eq (15) and eq (5)", "the scene's gravity is 0: U and Q vanish ([engine].gravity)");
  }

  // The drive torque's and the wall force's errors are judged against their own peaks over the working cycle (the
  // exact closed forms', refined): what an engineer reads "within 1 %" against. The cross-check's torque and force
  // scales (scales.h) bound every term of the sum, and on an engine with gas they are tens of times the peak. Where a
  // peak is 0 (nothing loads the engine), the cross-check's scale stands in: a scale is never zero.
  auto peakOverCycle = [&](const std::function<double(double, int)>& f, int cylinders, double fallback) {
    const int turns = cycleTurns(m);
    double peak = 0.0;
    for (int j = 0; j < std::max(1, cylinders); ++j)
      peak = std::max(peak, findMaxAbsOverTurn([&](double u) { return f(turns * u, j); }, samplesPerTurn(quick) * turns,
                                               kRefinements, tolerance).value);
    return peak > 0.0 ? peak : fallback;
  };
  const double torque_peak =
      sc.torque > 0.0 ? peakOverCycle([&m](double phi, int) { return analytic::calcReactions(m, phi).drive_torque; }, 0, sc.torque) : 0.0;
  const std::string torque_peak_name = "max |drive torque|";

  // 3. The two-mass rod, without and with Delta_I: the drive torque at the scene's speed, gas and gravity (the rod
  // model changes the inertia torque alone).
  if (sc.torque > 0.0) {
    const std::string name = nameOf(QuantityId::kDriveTorque);
    auto exact = [&m](double phi, int) { return analytic::calcReactions(m, phi).drive_torque; };
    auto engine = [](const Evaluation& e, int) { return e.drive_torque; };
    const double torque_rounding = rounding(sc.torque, sc.acceleration_conditioning);
    judged.push_back({20, kTwoMass, name, torque_peak_name, "N m", torque_peak, 0,
                      [&m](double phi, int) { return analytic::calcReactions(m, phi, RodInertiaForm::kTwoMassWithoutDeltaI).drive_torque; },
                      exact, engine, {}, torque_rounding});
    judged.push_back({21, kTwoMassDeltaI, name, torque_peak_name, "N m", torque_peak, 0,
                      [&m](double phi, int) { return analytic::calcReactions(m, phi, RodInertiaForm::kTwoMassWithDeltaI).drive_torque; },
                      exact, engine, {}, torque_rounding});
  }

  // 4. The centric forms (the same scene with delta = 0, at the same crank angle) against the offset engine.
  Mechanism centric = m;
  centric.machine.pin_offsets.clear();
  if (hasPinOffsets(m)) {
    double stroke = 0.0;  // the largest stroke of the cylinders
    for (int j = 0; j < k; ++j) stroke = std::max(stroke, analytic::calcDeadCentres(m, getPinOffset(m, j)).stroke);
    auto centricKinematics = [centric](double phi, int j) {
      return analytic::calcPistonKinematics(centric, analytic::calcThrowSinCos(phi, centric.machine.crank_angles[j]));
    };
    judged.push_back({30, kCentric, nameOf(QuantityId::kPistonPosition), "stroke", "m", stroke, k,
                      [=](double phi, int j) { return centricKinematics(phi, j).x_p; },
                      [=](double phi, int j) { return kinematics(phi, j).x_p; },
                      [](const Evaluation& e, int j) { return e.cylinders[j].x_p; }, {}, rounding(stroke, sc.closure)});
    if (w > 0.0)
      judged.push_back({31, kCentric, nameOf(QuantityId::kPistonAcceleration), "r omega^2", "m/s^2", r * w * w, k,
                        [=](double phi, int j) { return centricKinematics(phi, j).a_p; },
                        [=](double phi, int j) { return kinematics(phi, j).a_p; },
                        [](const Evaluation& e, int j) { return e.cylinders[j].a_p; }, {},
                        rounding(r * w * w, sc.acceleration_conditioning)});
    if (sc.force > 0.0)
      judged.push_back({32, kCentric, nameOf(QuantityId::kWallForce), "max |N_w|", "N",
                        peakOverCycle([&m](double phi, int j) { return analytic::calcReactions(m, phi).cylinders[j].wall_force; },
                                      k, sc.force),
                        k,
                        [centric](double phi, int j) { return analytic::calcReactions(centric, phi).cylinders[j].wall_force; },
                        [&m](double phi, int j) { return analytic::calcReactions(m, phi).cylinders[j].wall_force; },
                        [](const Evaluation& e, int j) { return e.cylinders[j].wall_force; }, {},
                        rounding(sc.force, sc.acceleration_conditioning)});
    if (sc.torque > 0.0)
      judged.push_back({33, kCentric, nameOf(QuantityId::kDriveTorque), torque_peak_name, "N m", torque_peak, 0,
                        [centric](double phi, int) { return analytic::calcReactions(centric, phi).drive_torque; },
                        [&m](double phi, int) { return analytic::calcReactions(m, phi).drive_torque; },
                        [](const Evaluation& e, int) { return e.drive_torque; }, {},
                        rounding(sc.torque, sc.acceleration_conditioning)});
  } else {
    leaveOut(kCentric, "no pin offsets: the centric forms are this scene's exact ones (add pin_offset, "
                       "docs/SCENE-FORMAT.md, \"Pin offset (desaxe)\", to see what they cost)");
  }

  // The analytic engine's exact closed forms, then every reference engine.
  std::vector<FitnessRow> rows;
  auto addRow = [&](const Judged& j, const std::string& reference, const Found& found, bool closed_form) {
    const bool resolved = closed_form && j.analytic_maximum ? found.value > 0.0 : found.value > j.rounding;
    double deg = std::remainder(degreesFromRadians(found.phi), 360.0 * cycleTurns(m));
    if (deg < 0.0) deg += 360.0 * cycleTurns(m);
    rows.push_back({m.name, j.order, j.formula, j.quantity, reference, found.value / j.scale_value, j.scale,
                    j.scale_value, j.scale_unit, deg, resolved ? 1 : 0});
  };
  std::vector<Found> analytic;
  for (const Judged& j : judged) {
    analytic.push_back(findAnalyticMaximum(m, j, quick));
    addRow(j, getClosedFormEngine().name, analytic.back(), true);
  }
  const int turns = cycleTurns(m), grid = referenceSamplesPerTurn(quick) * turns;
  for (const Engine* engine : listReferenceEngines()) {
    const std::unique_ptr<EngineModel> model = engine->build(m);
    std::map<double, Evaluation> evaluations;
    auto at = [&](double phi) -> const Evaluation& {
      const auto [it, added] = evaluations.try_emplace(phi);
      if (added) it->second = model->evaluate(phi);
      return it->second;
    };
    for (size_t i = 0; i < judged.size(); ++i) {
      const Judged& j = judged[i];
      auto error = [&](double phi, int c) { return std::fabs(j.formula_value(phi, c) - j.engine_value(at(phi), c)); };
      Found best{error(analytic[i].phi, analytic[i].cylinder), analytic[i].phi, analytic[i].cylinder};
      for (int s = 0; s < grid; ++s) {
        const double phi = 2.0 * M_PI * turns * s / grid;
        for (int c = 0; c < std::max(1, j.cylinders); ++c)
          if (const double e = error(phi, c); e > best.value) best = {e, phi, c};
      }
      addRow(j, engine->name, best, false);
    }
  }
  return {{kFitnessTable.name(), kFitnessTable.table(std::move(rows))},
          {kFitnessScopeTable.name(), kFitnessScopeTable.table(std::move(scope))}};
}

// "phi = 42.5 deg" where a row has its angle; "-" else.
std::string formatWhere(const FitnessRow& row) {
  return row.phi_deg_at_max ? shortNumber(*row.phi_deg_at_max, 4) + " deg" : std::string("-");
}

class FitnessTopic final : public SceneTopic {
 public:
  std::string title() const override { return "Formula fitness"; }
  std::vector<Task> tasks(const Mechanism& scene, bool quick) const override {
    return {{"your_engine fitness " + scene.name, false, [scene, quick] { return calcFitnessTables(scene, quick); },
             task_cost::kShort}};
  }
  std::vector<ReportBlock> describe(const TableSet& tables, const std::string& scene) const override {
    std::vector<ReportBlock> out;
    if (!tables.count(kFitnessTable.name())) return out;  // not run
    std::vector<FitnessRow> rows;
    for (const FitnessRow& row : getRows(tables, kFitnessTable))
      if (row.scene == scene) rows.push_back(row);
    std::stable_sort(rows.begin(), rows.end(), [](const FitnessRow& a, const FitnessRow& b) { return a.order < b.order; });
    // One line per formula and quantity: the analytic reference's row (or the first there is).
    const std::string closed_form = getClosedFormEngine().name;
    std::vector<const FitnessRow*> shown;
    std::map<int, std::vector<const FitnessRow*>> by_order;
    for (const FitnessRow& row : rows) by_order[row.order].push_back(&row);
    double spread = 0.0;
    std::string spread_where;
    std::set<std::string> references;
    for (const auto& [order, group] : by_order) {
      const FitnessRow* pick = group.front();
      for (const FitnessRow* row : group)
        if (row->reference == closed_form) pick = row;
      shown.push_back(pick);
      for (const FitnessRow* row : group) {
        if (row == pick) continue;
        references.insert(row->reference);
        const double d = std::fabs(row->max_error_rel - pick->max_error_rel);
        if (spread_where.empty() || d > spread) {
          spread = d;
          spread_where = pick->formula + ", " + pick->quantity;
        }
      }
    }
    if (!shown.empty()) {
      out.push_back({ReportBlock::kParagraph,
                     "Each formula's largest error over the working cycle on this engine as given, relative to the "
                     "scale named, against " + closed_form + "'s exact closed forms (Q's series: the orders of the "
                     "paper's eq (15), 2 to 12; data/your_engine_fitness.csv has every reference engine's row)."});
      ReportBlock table{ReportBlock::kTable, "", {"formula", "quantity", "max error", "scale", "verdict", "where"}};
      for (const FitnessRow* row : shown)
        // A bound (rounding) has no place of its own: its angle is left out.
        table.rows.push_back({row->formula, row->quantity, shortNumber(row->max_error_rel, row->resolved ? 3 : 2),
                              row->scale + " = " + shortNumber(row->scale_value, 4) + " " + row->scale_unit,
                              formatFitness(row->max_error_rel, row->resolved != 0),
                              row->resolved ? formatWhere(*row) : std::string("-")});
      out.push_back(std::move(table));
      if (!references.empty()) {
        std::string list;
        for (const std::string& name : references) list += (list.empty() ? "" : ", ") + name;
        out.push_back({ReportBlock::kParagraph,
                       "Against the reference engines (" + list + ") every error is the same to " +
                           shortNumber(std::max(spread, 1e-17), 2) + " of its scale at most (" + spread_where +
                           "): the engines agree to rounding."});
      }
    }
    std::vector<std::string> notes;
    for (const FitnessScopeRow& row : getRows(tables, kFitnessScopeTable))
      if (row.scene == scene) notes.push_back(row.formula + ": " + row.reason);
    if (!notes.empty()) {
      std::string text = "Not judged on this scene: ";
      for (size_t i = 0; i < notes.size(); ++i) text += (i == 0 ? "" : "; ") + notes[i];
      out.push_back({ReportBlock::kParagraph, text + "."});
    }
    return out;
  }
  std::vector<const TableSchema*> schemas() const override { return {&kFitnessTable, &kFitnessScopeTable}; }
  std::vector<ReportedMaximum> maxima() const override {
    return {{kFitnessTable.name(), {"scene", "order", "formula", "quantity", "reference"}, {"max_error_rel", "scale_value"},
             "resolved", "0"}};
  }
};

}  // namespace

namespace topics {
const SceneTopic& fitness() {
  static const FitnessTopic topic;
  return topic;
}
}  // namespace topics

}  // namespace crankcheck::validation::your_engine
