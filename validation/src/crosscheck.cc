#include "crankcheck/validation/crosscheck.h"

#include <cstdio>
#include <map>
#include <memory>
#include <utility>

#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/validation/variants.h"
#include "crankcheck/validation/worst_by_quantity.h"

namespace crankcheck::validation {

const Schema<CrossCheckRow> kCrossCheckTable{
    "crosscheck",
    {textField("family", &CrossCheckRow::family), textField("engine", &CrossCheckRow::engine),
     textField("case", &CrossCheckRow::case_name), numberField("lambda", "-", &CrossCheckRow::lambda),
     textField("quantity", &CrossCheckRow::quantity), numberField("worst_rel_error", "-", &CrossCheckRow::worst_rel_error),
     numberField("where_phi_deg", "deg", &CrossCheckRow::where_phi_deg),
     numberField("where_speed_rpm", "rpm", &CrossCheckRow::where_speed_rpm),
     numberField("tolerance_rel", "-", &CrossCheckRow::tolerance_rel), textField("pass", &CrossCheckRow::pass)}};

// Every model is asked what it would be asked alone, in the same order (Simbody then assembles once per angle, not once
// per gamma).
std::vector<CrossCheckRow> crossCheckCases(const std::string& family, const std::vector<Mechanism>& variants,
                         const std::vector<double>& angles_deg, bool measure_soft) {
  struct Case {
    std::vector<WorstByQuantity> worst;  // per engine of `others`
    std::vector<Mechanism> at_speed;  // the case at the scene's speed and at rest
    std::vector<Scales> scales;
    std::unique_ptr<EngineModel> closed_form;
    std::vector<std::pair<const Engine*, std::unique_ptr<EngineModel>>> others;
  };
  std::vector<Case> cases(variants.size());
  for (size_t v = 0; v < variants.size(); ++v) {
    const Mechanism& m = variants[v];
    Case& c = cases[v];
    // Every engine's model built once for the case and evaluated at both speeds (speed is a state:
    // EngineModel::setSpeed), the speeds inner, so that the second speed finds each model assembled at the same angle.
    for (double rpm : m.speed_rpm > 0.0 ? std::vector<double>{m.speed_rpm, 0.0} : std::vector<double>{0.0})
      c.at_speed.push_back(withSpeed(m, rpm));
    for (const Mechanism& case_m : c.at_speed) c.scales.push_back(calcScales(case_m));
    // The closed forms against every other registered engine, exact or soft (engines.h), with its second route to Q
    // where it offers one (Engine::second_q_route), at rest.
    c.closed_form = getClosedFormEngine().build(c.at_speed.front());
    for (const Engine& engine : listEngines())
      if (!engine.closed_form && (engine.gated || measure_soft)) c.others.emplace_back(&engine, engine.build(c.at_speed.front()));
    c.worst.resize(c.others.size());
  }
  for (double phi_deg : angles_deg) {
    const double phi = radiansFromDegrees(phi_deg);
    for (size_t v = 0; v < cases.size(); ++v) {
      Case& c = cases[v];
      if (v > 0)
        for (size_t e = 0; e < c.others.size(); ++e) c.others[e].second->startAssemblyFrom(*cases.front().others[e].second);
      for (size_t s = 0; s < c.at_speed.size(); ++s) {
        const Mechanism& case_m = c.at_speed[s];
        const double rpm = case_m.speed_rpm;
        c.closed_form->setSpeed(case_m.machine.speed);
        const Evaluation a = c.closed_form->evaluate(phi);
        for (size_t e = 0; e < c.others.size(); ++e) {
          auto& [engine, other] = c.others[e];
          other->setSpeed(case_m.machine.speed);
          const std::vector<Comparison> comparisons = compareEvaluations(case_m, c.scales[s], a, other->evaluate(phi));
          for (size_t i = 0; i < comparisons.size(); ++i)
            c.worst[e].note(i, comparisons[i], phi_deg, rpm);
          if (rpm == 0.0 && !engine->second_q_route.empty()) {
            const Comparison second{"Q (" + engine->second_q_route + ")", -1, a.Q, other->calcSecondRouteQ(phi),
                                    c.scales[s].energy, c.scales[s].conditioning};
            c.worst[e].note(comparisons.size(), second, phi_deg, rpm);
          }
        }
      }
    }
  }
  std::vector<CrossCheckRow> rows;
  for (size_t v = 0; v < variants.size(); ++v) {
    const Mechanism& m = variants[v];
    char case_name[160];
    std::snprintf(case_name, sizeof case_name, "%s lambda=%.4g", m.name.c_str(), calcCrankRatio(m));
    // In (engine, quantity) order, as before the slots.
    std::map<std::pair<std::string, std::string>, const WorstComparison*> ordered;
    for (size_t e = 0; e < cases[v].others.size(); ++e)
      for (const auto& [quantity, w] : cases[v].worst[e].slots()) ordered[{cases[v].others[e].first->name, quantity}] = &w;
    for (const auto& [key, w] : ordered)
      rows.push_back({family, key.first, case_name, calcCrankRatio(m), key.second, w->rel_error, w->phi_deg, w->rpm,
                      w->tolerance_rel, findEngine(key.first).gated ? (w->pass ? "pass" : "FAIL") : "reported"});
  }
  return rows;
}

}  // namespace crankcheck::validation
