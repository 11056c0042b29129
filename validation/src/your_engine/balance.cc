// The scene sections' topic "Balance": the shaking force and moment of the scene's own layout (banks, throws, axial
// positions, pin offsets, balance shafts) at its own speed: their largest magnitudes over a turn and their harmonics
// by order, with the scene's balance shafts and, where it has shafts, without them; the closed form's harmonics
// (analytic/shaking.h, exact zeros by the layout's symmetry as balance.h decides them) beside every engine's DFT of its
// own evaluated shaking (listEngines(): the closed forms, the exact references and the soft ways).
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "crankcheck/analytic/shaking.h"
#include "crankcheck/validation/balance.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/extremum.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/scales.h"
#include "../part_math.h"
#include "../shaking_spectrum.h"
#include "topic.h"

namespace crankcheck::validation::your_engine {
namespace {

constexpr int kOrder = 8;             // the harmonics computed, 1..8
constexpr double kShownFloor = 1e-6;  // [-] an order whose every amplitude is below this of its scale is not shown
                                      // (the describe's sentence names it)
const std::string kClosedForm = "closed form";
const std::string kDft = "DFT";

// your_engine_balance: per scene, variant (its balance shafts as given, or none: `shafts` counts them) and engine, the
// largest shaking force magnitude |F_s| and moment magnitude over a turn (the couple |(M_X, M_Y)| where the scene
// places its cylinders along the shaft, else the rocking torque |M_Z|), from that engine's evaluations, found
// independently of the grid (extremum.h), with the scales they are judged against.
struct BalanceMaxRow {
  std::string scene;
  int shafts = 0;              ///< the balance shafts of this variant: the scene's number, or 0 (cleared)
  std::string engine;          ///< the engine's registry name
  int gated = 1;               ///< 1: an exact engine; 0: a soft way (measured, never gated)
  std::string moment;          ///< "couple X, Y" | "rocking Z": which moment max_moment is
  double max_force = 0.0;      ///< [N] max over phi of |F_s|
  double phi_force = 0.0;      ///< [deg] where
  double max_moment = 0.0;     ///< [N m] max over phi of |M|
  double phi_moment = 0.0;     ///< [deg] where
  double force_scale = 0.0;    ///< [N] calcScales(scene as given).force
  double moment_scale = 0.0;   ///< [N m] calcScales(scene as given).moment
  int force_resolved = 1;      ///< 0: max_force is at rounding level, a bound (part_math.h resolvedToOnePercent)
  int moment_resolved = 1;     ///< 0: likewise max_moment
};
const Schema<BalanceMaxRow> kBalanceMaxTable{
    "your_engine_balance",
    {textField("scene", &BalanceMaxRow::scene), countField("shafts", &BalanceMaxRow::shafts),
     textField("engine", &BalanceMaxRow::engine), countField("gated", &BalanceMaxRow::gated),
     textField("moment", &BalanceMaxRow::moment), numberField("max_force", "N", &BalanceMaxRow::max_force),
     numberField("phi_force", "deg", &BalanceMaxRow::phi_force),
     numberField("max_moment", "N m", &BalanceMaxRow::max_moment),
     numberField("phi_moment", "deg", &BalanceMaxRow::phi_moment),
     numberField("force_scale", "N", &BalanceMaxRow::force_scale),
     numberField("moment_scale", "N m", &BalanceMaxRow::moment_scale),
     countField("force_resolved", &BalanceMaxRow::force_resolved),
     countField("moment_resolved", &BalanceMaxRow::moment_resolved)}};

// your_engine_balance_harmonics: per scene, variant, order n = 1..8 and source, the amplitude of harmonic n of the
// shaking force (the largest |F_n(phi)|: the semi-major axis of its ellipse) and of the moment (the couple's likewise,
// or hypot(cos, sin) of M_Z). Source "closed form": analytic/shaking.h's harmonics (engine "analytic"), 0 where the
// layout's symmetry makes them vanish exactly (exact_zero); source "DFT": each engine's DFT of its own shaking over a
// turn, with its difference from the closed form's harmonic (the amplitude of the difference) relative to the scale.
struct BalanceHarmonicRow {
  std::string scene;
  int shafts = 0;
  int n = 1;
  std::string source;              ///< "closed form" | "DFT"
  std::string engine;
  int gated = 1;
  double force_amplitude = 0.0;    ///< [N]
  double moment_amplitude = 0.0;   ///< [N m]
  int force_exact_zero = 0;        ///< 1: the closed form's force harmonic vanishes exactly (the layout's symmetry)
  int moment_exact_zero = 0;       ///< 1: likewise the moment's
  double force_difference = 0.0;   ///< [-] |F_n(engine) - F_n(closed form)| amplitude / force scale; 0 for the closed form
  double moment_difference = 0.0;  ///< [-] likewise / moment scale
};
const Schema<BalanceHarmonicRow> kBalanceHarmonicsTable{
    "your_engine_balance_harmonics",
    {textField("scene", &BalanceHarmonicRow::scene), countField("shafts", &BalanceHarmonicRow::shafts),
     countField("n", &BalanceHarmonicRow::n), textField("source", &BalanceHarmonicRow::source),
     textField("engine", &BalanceHarmonicRow::engine), countField("gated", &BalanceHarmonicRow::gated),
     numberField("force_amplitude", "N", &BalanceHarmonicRow::force_amplitude),
     numberField("moment_amplitude", "N m", &BalanceHarmonicRow::moment_amplitude),
     countField("force_exact_zero", &BalanceHarmonicRow::force_exact_zero),
     countField("moment_exact_zero", &BalanceHarmonicRow::moment_exact_zero),
     numberField("force_difference", "-", &BalanceHarmonicRow::force_difference),
     numberField("moment_difference", "-", &BalanceHarmonicRow::moment_difference)}};

// The couple (M_X, M_Y) of harmonic h as a planar harmonic of its own, so that its amplitude is the largest
// |M_XY,n(phi)| over the turn, as the force's is (ShakingHarmonic::calcForceAmplitude).
double calcCoupleAmplitude(const analytic::ShakingHarmonic& h) {
  analytic::ShakingHarmonic couple;
  couple.force_cos = {h.moment_cos[0], h.moment_cos[1]};
  couple.force_sin = {h.moment_sin[0], h.moment_sin[1]};
  return couple.calcForceAmplitude();
}
double calcMomentAmplitude(const analytic::ShakingHarmonic& h, bool couple) {
  return couple ? calcCoupleAmplitude(h) : h.calcMomentAmplitude(2);
}
analytic::ShakingHarmonic minus(analytic::ShakingHarmonic a, const analytic::ShakingHarmonic& b) {
  for (int k = 0; k < 2; ++k) a.force_cos[k] -= b.force_cos[k], a.force_sin[k] -= b.force_sin[k];
  for (int k = 0; k < 3; ++k) a.moment_cos[k] -= b.moment_cos[k], a.moment_sin[k] -= b.moment_sin[k];
  return a;
}

// The closed form's harmonic with every part the layout makes vanish exactly set to 0 (they are rounding otherwise):
// the sums over the phases (withExactZeros, balance.h) and the orders or directions a centric cylinder cannot carry
// (analytic::HarmonicSymmetry).
analytic::ShakingHarmonic withAllExactZeros(const analytic::ShakingHarmonic& closed, const analytic::HarmonicSymmetry& s) {
  analytic::ShakingHarmonic h = withExactZeros(closed, s);
  if (s.force_order_absent) {
    h.force_cos = h.force_sin = Vec2{0.0, 0.0};
    for (int k = 0; k < 2; ++k) h.moment_cos[k] = h.moment_sin[k] = 0.0;
  }
  if (s.moment_x_direction_absent) h.moment_cos[0] = h.moment_sin[0] = 0.0;
  if (s.moment_y_direction_absent) h.moment_cos[1] = h.moment_sin[1] = 0.0;
  if (s.moment_z_order_absent) h.moment_cos[2] = h.moment_sin[2] = 0.0;
  return h;
}
bool forceVanishes(const analytic::HarmonicSymmetry& s) { return (s.decided && s.force_cancels) || s.force_order_absent; }
bool momentVanishes(const analytic::HarmonicSymmetry& s, bool couple) {
  if (!couple) return (s.decided && s.moment_z_cancels) || s.moment_z_order_absent;
  return (s.decided && s.moment_xy_cancels) || s.force_order_absent ||
         (s.moment_x_direction_absent && s.moment_y_direction_absent);
}

// The DFT's samples per turn: harmonic N - n folds onto n; the shaking's harmonics fall geometrically with the order
// (as the radical's series, lambda^n at most), so at 48 what folds onto orders up to 8 is below lambda^40 of the
// primary. The full campaign's 96 halves the sampling step of the maxima's grid; both refine them (extremum.h).
int dftSamplesPerTurn(bool quick) { return quick ? 48 : 96; }

// Every row of one variant of the scene (`m`, its shafts as given or cleared), judged against `sc` (the scene as
// given).
void addVariantRows(const Mechanism& m, const std::string& scene, const Scales& sc, bool quick,
                    std::vector<BalanceMaxRow>& maxima, std::vector<BalanceHarmonicRow>& harmonics) {
  const bool couple = hasAxialPositions(m);
  const int shafts = static_cast<int>(m.balance_shafts.size());
  const int samples = dftSamplesPerTurn(quick);
  const double tolerance = getAngleTolerance(quick);
  std::vector<analytic::ShakingHarmonic> closed = analytic::calcShakingHarmonics(m, kOrder);
  for (int n = 1; n <= kOrder; ++n) {
    const analytic::HarmonicSymmetry s = analytic::findHarmonicSymmetry(m, n);
    closed[n - 1] = withAllExactZeros(closed[n - 1], s);
    const analytic::ShakingHarmonic& h = closed[n - 1];
    harmonics.push_back({scene, shafts, n, kClosedForm, getClosedFormEngine().name, 1, h.calcForceAmplitude(),
                         calcMomentAmplitude(h, couple), forceVanishes(s) ? 1 : 0, momentVanishes(s, couple) ? 1 : 0,
                         0.0, 0.0});
  }
  for (const Engine& engine : listEngines()) {
    std::unique_ptr<EngineModel> model = engine.build(m);
    const ShakingTurn turn = sampleShakingTurn(*model, samples);
    const std::vector<analytic::ShakingHarmonic> spectrum = calcShakingSpectrum(turn, kOrder);
    for (int n = 1; n <= kOrder; ++n) {
      const analytic::ShakingHarmonic& h = spectrum[n - 1];
      const analytic::ShakingHarmonic d = minus(h, closed[n - 1]);
      harmonics.push_back({scene, shafts, n, kDft, engine.name, engine.gated ? 1 : 0, h.calcForceAmplitude(),
                           calcMomentAmplitude(h, couple), 0, 0, d.calcForceAmplitude() / sc.force,
                           calcMomentAmplitude(d, couple) / sc.moment});
    }
    // The maxima over the turn from the same samples, refined by Brent's method.
    std::vector<double> force(samples), moment(samples);
    for (int i = 0; i < samples; ++i) {
      force[i] = std::hypot(turn.force[i][0], turn.force[i][1]);
      moment[i] = couple ? std::hypot(turn.moment[i][0], turn.moment[i][1]) : std::fabs(turn.moment[i][2]);
    }
    const TurnMaximum max_force = findMaxAbsOverTurn(
        [&](double phi) {
          const Vec2 f = model->evaluateMotion(phi).shaking_force;
          return std::hypot(f[0], f[1]);
        },
        force, 4, tolerance);
    const TurnMaximum max_moment = findMaxAbsOverTurn(
        [&](double phi) {
          const std::array<double, 3> q = model->evaluateMotion(phi).shaking_moment;
          return couple ? std::hypot(q[0], q[1]) : std::fabs(q[2]);
        },
        moment, 4, tolerance);
    maxima.push_back({scene, shafts, engine.name, engine.gated ? 1 : 0, couple ? "couple X, Y" : "rocking Z",
                      max_force.value, degreesFromRadians(max_force.phi), max_moment.value,
                      degreesFromRadians(max_moment.phi), sc.force, sc.moment,
                      resolvedToOnePercent(max_force.value / sc.force) ? 1 : 0,
                      resolvedToOnePercent(max_moment.value / sc.moment) ? 1 : 0});
  }
}

TableSet calcBalanceTables(const Mechanism& m, bool quick) {
  const Scales sc = calcScales(m);
  std::vector<BalanceMaxRow> maxima;
  std::vector<BalanceHarmonicRow> harmonics;
  addVariantRows(m, m.name, sc, quick, maxima, harmonics);
  if (!m.balance_shafts.empty()) {
    Mechanism without = m;
    without.balance_shafts.clear();
    addVariantRows(without, m.name, sc, quick, maxima, harmonics);
  }
  TableSet out = kBalanceMaxTable.tableSet(std::move(maxima));
  out.merge(kBalanceHarmonicsTable.tableSet(std::move(harmonics)));
  return out;
}

// "2.3e-16 (mujoco)": the largest difference and its engine; "-" without one.
std::string formatLargest(double value, const std::string& engine) {
  return engine.empty() ? "-" : shortNumber(value, 2) + " (" + engine + ")";
}

class BalanceTopic final : public SceneTopic {
 public:
  std::string title() const override { return "Balance"; }
  std::vector<Task> tasks(const Mechanism& scene, bool quick) const override {
    return {{"your_engine balance " + scene.name, false, [scene, quick] { return calcBalanceTables(scene, quick); },
             task_cost::kShort}};
  }
  std::vector<ReportBlock> describe(const TableSet& tables, const std::string& scene) const override;
  std::vector<const TableSchema*> schemas() const override { return {&kBalanceMaxTable, &kBalanceHarmonicsTable}; }
  std::vector<ReportedMaximum> maxima() const override {
    const std::vector<std::string> key = {"scene", "shafts", "engine"};
    return {{kBalanceMaxTable.name(), key, {"max_force"}, "force_resolved", "0"},
            {kBalanceMaxTable.name(), key, {"max_moment"}, "moment_resolved", "0"}};
  }
};

std::vector<ReportBlock> BalanceTopic::describe(const TableSet& tables, const std::string& scene) const {
  std::vector<ReportBlock> out;
  const std::optional<SceneFactsRow> facts = findSceneFacts(tables, scene);
  std::vector<BalanceMaxRow> maxima;
  for (const BalanceMaxRow& row : getRows(tables, kBalanceMaxTable))
    if (row.scene == scene) maxima.push_back(row);
  if (!facts || maxima.empty()) return out;
  if (!(facts->speed_rpm > 0.0)) {
    out.push_back({ReportBlock::kParagraph,
                   "No speed: the scene is at rest ([engine] speed_rpm = 0), so nothing shakes. Give it its running "
                   "speed (docs/SCENE-FORMAT.md, [engine] speed_rpm) to see its shaking force and moment."});
    return out;
  }
  const int shafts = facts->balance_shafts;
  const std::string& closed_engine = getClosedFormEngine().name;
  auto closedMax = [&](int variant_shafts) -> const BalanceMaxRow* {
    for (const BalanceMaxRow& row : maxima)
      if (row.shafts == variant_shafts && row.engine == closed_engine) return &row;
    return nullptr;
  };
  const BalanceMaxRow* with = closedMax(shafts);
  if (!with) return out;
  const bool couple = with->moment == "couple X, Y";
  const std::string moment_name = couple ? "shaking couple about X and Y" : "rocking torque about Z";
  auto value = [](double v, int resolved, const std::string& unit) {
    if (resolved) return shortNumber(v, 4) + " " + unit;
    return v == 0.0 ? "0 " + unit : "0 to rounding (" + shortNumber(v, 2) + " " + unit + ")";
  };
  std::string text = "At " + shortNumber(facts->speed_rpm, 4) + " rpm the largest shaking force over a turn is " +
                     value(with->max_force, with->force_resolved, "N") +
                     (with->force_resolved ? " (at " + shortNumber(with->phi_force, 4) + " deg)" : "") +
                     " and the largest " + moment_name + " " + value(with->max_moment, with->moment_resolved, "N m") +
                     (with->moment_resolved ? " (at " + shortNumber(with->phi_moment, 4) + " deg)" : "") +
                     ", by the closed forms (" + closed_engine + ")" + (shafts > 0 ? " with its balance shafts" : "") +
                     ".";
  if (shafts > 0) {
    if (const BalanceMaxRow* without = closedMax(0))
      text += " Without its " + std::to_string(shafts) + " balance shaft" + (shafts == 1 ? "" : "s") + " they are " +
              value(without->max_force, without->force_resolved, "N") + " and " +
              value(without->max_moment, without->moment_resolved, "N m") + ".";
  } else {
    text += " It has no [[balance_shaft]]; `crankcheck balance SCENE --design N` prints the shafts that cancel order N "
            "of its shaking force (docs/SCENE-FORMAT.md, [[balance_shaft]]).";
  }
  text += couple ? " The cylinders sit along the shaft, so the moment is the couple about X and Y (about O)."
                 : " The scene places every cylinder in one plane (no axial positions), so the moment is the rocking "
                   "torque about Z; give them axial positions ([engine] cylinder_spacing or [[cylinder]] axial_position, "
                   "docs/SCENE-FORMAT.md) to see the couple about X and Y.";
  out.push_back({ReportBlock::kParagraph, text});

  // The harmonics: the closed form's per variant, and the engines' largest differences per order.
  struct Order {
    double force[2] = {0.0, 0.0}, moment[2] = {0.0, 0.0};  // [0]: as given, [1]: without shafts
    int force_zero[2] = {0, 0}, moment_zero[2] = {0, 0};
    double exact = -1.0, soft = -1.0;  // the largest difference relative to the scale, over force and moment
    std::string exact_engine, soft_engine;
  };
  std::map<int, Order> orders;
  for (const BalanceHarmonicRow& row : getRows(tables, kBalanceHarmonicsTable)) {
    if (row.scene != scene) continue;
    const int v = row.shafts == shafts ? 0 : 1;
    Order& o = orders[row.n];
    if (row.source == kClosedForm) {
      o.force[v] = row.force_amplitude, o.moment[v] = row.moment_amplitude;
      o.force_zero[v] = row.force_exact_zero, o.moment_zero[v] = row.moment_exact_zero;
      continue;
    }
    const double d = std::max(row.force_difference, row.moment_difference);
    double& worst = row.gated ? o.exact : o.soft;
    if (d > worst) {
      worst = d;
      (row.gated ? o.exact_engine : o.soft_engine) = row.engine;
    }
  }
  if (orders.empty()) return out;
  const double force_scale = with->force_scale, moment_scale = with->moment_scale;
  int last = 2;  // the largest order that matters: some amplitude at or above kShownFloor of its scale
  for (const auto& [n, o] : orders)
    for (int v = 0; v < 2; ++v)
      if (o.force[v] >= kShownFloor * force_scale || o.moment[v] >= kShownFloor * moment_scale) last = std::max(last, n);
  last = std::min(last, orders.rbegin()->first);
  const std::string moment_column = couple ? "couple X, Y [N m]" : "rocking Z [N m]";
  std::vector<std::string> header = {"order", "force [N]", moment_column};
  if (shafts > 0) header.insert(header.end(), {"force without shafts [N]", moment_column + " without shafts"});
  bool soft = false;
  for (const auto& [n, o] : orders) soft = soft || !o.soft_engine.empty();
  header.push_back("exact engines' largest difference [-]");
  if (soft) header.push_back("soft ways' largest difference [-]");
  ReportBlock table{ReportBlock::kTable, "", header, {}};
  auto amplitude = [](double a, int exact_zero) { return exact_zero ? std::string("0 (exact)") : shortNumber(a, 4); };
  for (const auto& [n, o] : orders) {
    if (n > last) break;
    std::vector<std::string> row = {std::to_string(n), amplitude(o.force[0], o.force_zero[0]),
                                    amplitude(o.moment[0], o.moment_zero[0])};
    if (shafts > 0)
      row.insert(row.end(), {amplitude(o.force[1], o.force_zero[1]), amplitude(o.moment[1], o.moment_zero[1])});
    row.push_back(formatLargest(o.exact, o.exact_engine));
    if (soft) row.push_back(formatLargest(o.soft, o.soft_engine));
    table.rows.push_back(std::move(row));
  }
  std::string after =
      "Amplitudes: the largest value of each order over the turn, by the closed form from the exact Fourier "
      "coefficients; \"0 (exact)\" where the layout's symmetry makes the order vanish exactly (decided in integers). "
      "The engines' columns: the largest difference of an engine's DFT of its own shaking over a turn from the closed "
      "form's harmonic, relative to the force scale (" + shortNumber(force_scale, 3) + " N) or the moment scale (" +
      shortNumber(moment_scale, 3) + " N m), over force and moment" + (shafts > 0 ? ", with and without shafts." : ".");
  const int computed = orders.rbegin()->first;
  if (last < computed)
    after += " Orders " + std::to_string(last + 1) + " to " + std::to_string(computed) + " are below 1e-6 of those scales or vanish exactly (data/your_engine_balance_harmonics.csv).";
  out.push_back(std::move(table));
  out.push_back({ReportBlock::kParagraph, after});
  return out;
}

}  // namespace

namespace topics {
const SceneTopic& balance() {
  static const BalanceTopic topic;
  return topic;
}
}  // namespace topics

}  // namespace crankcheck::validation::your_engine
