// Topic `gravity` of the scene sections: the paper's question, does gravity matter for this engine, answered on the
// scene exactly as given in every engine: max |Q| over a turn (Q = dU/dphi, gravity's torque on the crank) against the
// inertia torque at the scene's speed (the drive torque with gas and gravity off).
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/extremum.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/scales.h"
#include "../part_math.h"
#include "gravity_model.h"
#include "topic.h"

namespace crankcheck::validation::your_engine {

std::unique_ptr<EngineModel> buildSceneGravityModel(const Engine& engine, const Mechanism& m) {
  try {
    return buildGravityModel(engine, m);
  } catch (const std::invalid_argument&) {
    return engine.build(withLoads(m, false, false, true));
  }
}

namespace {

// Below this share of the inertia torque gravity is negligible (the paper's question, answered at 1 %).
constexpr double kNegligibleShare = 0.01;

// The closed form's samples of a turn (1 degree, 4 with quick: the maxima refined all the same); a soft way's (5
// degrees, 10 with quick).
int turnSamples(bool quick) { return quick ? 90 : 360; }
int softSamples(bool quick) { return quick ? 36 : 72; }

// max |f| over a turn: the closed form's (closed null) from its samples, the best four refined; another engine's
// refined within one sampling step either side of the closed form's maximum (the gate holds an exact engine to the
// closed forms, so its maximum is there), a soft way's also from its own samples, the best two refined: the larger.
TurnMaximum maxOverTurn(const std::function<double(double)>& f, bool quick, const TurnMaximum* closed, bool gated) {
  const double tolerance = getAngleTolerance(quick);
  if (!closed) return findMaxAbsOverTurn(f, turnSamples(quick), 4, tolerance);
  const double step = 2.0 * M_PI / turnSamples(quick);
  TurnMaximum best = refineMaxAbs(f, closed->phi - step, closed->phi + step, tolerance);
  best.phi = std::fmod(best.phi + 2.0 * M_PI, 2.0 * M_PI);
  if (!gated) {
    const TurnMaximum own = findMaxAbsOverTurn(f, softSamples(quick), 2, tolerance);
    if (own.value > best.value) best = own;
  }
  return best;
}

TableSet calcGravityTables(const Mechanism& m, bool quick) {
  std::vector<GravityRow> rows;
  const Mechanism inertia_only = withLoads(m, false, true, false);
  const bool moving = m.machine.speed != 0.0;
  TurnMaximum closed_q, closed_inertia;
  // The closed forms first (their maxima locate the others').
  std::vector<const Engine*> engines = {&getClosedFormEngine()};
  for (const Engine& e : listEngines())
    if (!e.closed_form) engines.push_back(&e);
  for (const Engine* engine : engines) {
    const bool first = engine->closed_form;
    std::unique_ptr<EngineModel> gravity = buildSceneGravityModel(*engine, m);
    const TurnMaximum q = maxOverTurn([&](double phi) { return gravity->calcQ(phi); }, quick, first ? nullptr : &closed_q,
                                     engine->gated);
    TurnMaximum inertia;
    if (moving) {
      std::unique_ptr<EngineModel> model = engine->build(inertia_only);
      inertia = maxOverTurn([&](double phi) { return model->evaluateMotion(phi).drive_torque; }, quick,
                            first ? nullptr : &closed_inertia, engine->gated);
    }
    if (first) {
      closed_q = q;
      closed_inertia = inertia;
    }
    // At speed 0 there is no inertia torque: the ratio is not defined (NaN in the table, said so in the report).
    // max |Q| at rounding level (a layout whose gravity torques cancel, such as a lying inline three) is a bound.
    const Scales scales = calcScales(m);
    rows.push_back({m.name, engine->name, q.value, degreesFromRadians(q.phi), inertia.value,
                    moving ? q.value / inertia.value : std::numeric_limits<double>::quiet_NaN(), engine->gated ? 1 : 0,
                    resolvedToOnePercent(q.value / scales.energy, scales.conditioning) ? 1 : 0});
  }
  // With gas, the torque gravity competes with is the working torque: the closed forms' max |drive torque| over the
  // working cycle (phi in [0, cycle): sampled as x = phi / n over a turn, n = 2 for a four-stroke cycle).
  if (m.gas && moving) {
    const std::unique_ptr<EngineModel> full = getClosedFormEngine().build(m);
    const double n = m.gas->cycle / (2.0 * M_PI);
    rows.front().max_abs_working_torque =
        findMaxAbsOverTurn([&](double x) { return full->evaluateMotion(n * x).drive_torque; },
                           static_cast<int>(std::lround(n * turnSamples(quick))), 4, getAngleTolerance(quick) / n)
            .value;
  }
  return kGravityTable.tableSet(std::move(rows));
}

class GravityTopic final : public SceneTopic {
 public:
  std::string title() const override { return "Gravity"; }
  std::vector<Task> tasks(const Mechanism& scene, bool quick) const override {
    return {{"your_engine gravity " + scene.name, false, [scene, quick] { return calcGravityTables(scene, quick); },
             task_cost::kShort}};
  }
  std::vector<ReportBlock> describe(const TableSet& tables, const std::string& scene) const override {
    std::vector<ReportBlock> out;
    std::vector<GravityRow> rows;
    for (const GravityRow& r : getRows(tables, kGravityTable))
      if (r.scene == scene) rows.push_back(r);
    const std::string closed_name = getClosedFormEngine().name;
    const auto closed = std::find_if(rows.begin(), rows.end(), [&](const GravityRow& r) { return r.engine == closed_name; });
    if (closed == rows.end()) return out;
    const std::optional<SceneFactsRow> facts = findSceneFacts(tables, scene);
    std::string text = "max |Q| = " + shortNumber(closed->max_abs_Q, 4) + " N m at " +
                       shortNumber(closed->phi_deg_at_max, 4) + " deg";
    if (!closed->resolved) {
      const bool all_exact = std::all_of(rows.begin(), rows.end(), [](const GravityRow& r) { return !r.gated || !r.resolved; });
      out.push_back({ReportBlock::kParagraph,
                     "Gravity's torque cancels over the turn for this layout: max |Q| is at rounding level (" +
                         shortNumber(closed->max_abs_Q, 2) + " N m, a bound) in the closed forms" +
                         (all_exact ? " and every exact engine" : " (an exact engine finds more: see data/your_engine_gravity.csv)") +
                         ", so gravity puts no torque on the crankshaft of this engine at any speed."});
      return out;
    }
    if (std::isnan(closed->ratio) || closed->max_abs_inertia_torque == 0.0) {
      text += "; at 0 rpm there is no inertia torque, so gravity's share of it is not defined: at rest gravity's torque "
              "is the whole drive torque without gas. Give the scene a speed ([engine] speed_rpm, docs/SCENE-FORMAT.md) "
              "to weigh gravity against the inertia torque.";
    } else {
      const std::string rpm = facts ? shortNumber(facts->speed_rpm, 4) + " rpm" : "the scene's speed";
      text += ", " + formatPercent(closed->ratio) + " of the inertia torque (max |drive torque| with gas and gravity "
              "off, " + shortNumber(closed->max_abs_inertia_torque, 4) + " N m) at " + rpm;
      if (const std::optional<double> working = closed->max_abs_working_torque) {
        // With gas the crank works against the working torque: the verdict is against it (the paper's question,
        // asked without gas, is answered against the inertia torque beside it).
        const double share = closed->max_abs_Q / std::max(*working, 1e-300);
        text += " and " + formatPercent(share) + " of the working torque (max |drive torque| over the cycle with its " +
                "[gas], " + shortNumber(*working, 4) + " N m): against the working torque, gravity " +
                (share < kNegligibleShare ? "is negligible (below 1 %)" : "matters") + " for this engine" +
                ((share < kNegligibleShare) != (closed->ratio < kNegligibleShare)
                     ? std::string(" (against the inertia torque alone, as the paper asks without gas, it ") +
                           (closed->ratio < kNegligibleShare ? "would not matter)" : "would matter)")
                     : std::string()) +
                ".";
      } else {
        text += ": gravity " + std::string(closed->ratio < kNegligibleShare ? "is negligible (below 1 %)" : "matters") +
                " for this engine.";
      }
    }
    // The engines' agreement: the largest relative difference of max |Q| from the closed forms', exact and soft apart.
    double exact = 0.0, soft = 0.0;
    bool any_soft = false;
    for (const GravityRow& r : rows) {
      if (r.engine == closed_name) continue;
      const double d = std::fabs(r.max_abs_Q - closed->max_abs_Q) / std::max(closed->max_abs_Q, 1e-300);
      if (r.gated) exact = std::max(exact, d);
      else {
        soft = std::max(soft, d);
        any_soft = true;
      }
    }
    text += " The exact engines' max |Q| agree with the closed forms' within " + shortNumber(exact, 2) + " relative" +
            (any_soft ? "; the soft ways (not gated) within " + shortNumber(soft, 2) : std::string()) + ".";
    out.push_back({ReportBlock::kParagraph, text});
    return out;
  }
  std::vector<const TableSchema*> schemas() const override { return {&kGravityTable}; }
  std::vector<ReportedMaximum> maxima() const override {
    // max |Q| where it is resolved (column resolved 0: the cylinders cancel gravity, a bound at rounding level).
    return {{kGravityTable.name(), {"scene", "engine"}, {"max_abs_inertia_torque"}, "", ""},
            {kGravityTable.name(), {"scene", "engine"}, {"max_abs_Q"}, "resolved", "0"}};
  }
};

}  // namespace

namespace topics {
const SceneTopic& gravity() {
  static const GravityTopic topic;
  return topic;
}
}  // namespace topics

}  // namespace crankcheck::validation::your_engine
