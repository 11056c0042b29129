#include "crankcheck/validation/commands/stepped.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/stepped_errors.h"

namespace crankcheck::validation {

const Schema<SteppedErrorRow> kSteppedErrorsTable{
    "stepped_errors",
    {textField("scene", &SteppedErrorRow::scene), textField("engine", &SteppedErrorRow::engine),
     textField("settings", &SteppedErrorRow::settings), numberField("dt", "s", &SteppedErrorRow::dt),
     textField("quantity", &SteppedErrorRow::quantity),
     numberField("worst_rel_error", "-", &SteppedErrorRow::worst_rel_error),
     numberField("where_phi_deg", "deg", &SteppedErrorRow::where_phi_deg),
     numberField("step_fraction", "-", &SteppedErrorRow::step_fraction)}};

const Schema<SteppedCostRow> kSteppedCostTable{
    "stepped_cost",
    {textField("scene", &SteppedCostRow::scene), textField("engine", &SteppedCostRow::engine),
     textField("settings", &SteppedCostRow::settings), numberField("dt", "s", &SteppedCostRow::dt),
     numberField("ns_per_step", "ns", &SteppedCostRow::ns_per_step)}};

const Schema<SteppedOrderRow> kSteppedOrdersTable{
    "stepped_orders",
    {textField("scene", &SteppedOrderRow::scene), textField("engine", &SteppedOrderRow::engine),
     textField("settings", &SteppedOrderRow::settings), textField("quantity", &SteppedOrderRow::quantity),
     numberField("dt_coarse", "s", &SteppedOrderRow::dt_coarse), numberField("dt_fine", "s", &SteppedOrderRow::dt_fine),
     numberField("order", "-", &SteppedOrderRow::order)}};

const Schema<SteppedRefusalRow> kSteppedRefusalsTable{
    "stepped_refusals",
    {textField("scene", &SteppedRefusalRow::scene), textField("engine", &SteppedRefusalRow::engine),
     textField("settings", &SteppedRefusalRow::settings), numberField("dt", "s", &SteppedRefusalRow::dt),
     textField("reason", &SteppedRefusalRow::reason)}};

std::vector<double> getDefaultSteppedSteps() { return {1.0 / 240.0, 1e-3, 1e-4, 1e-5}; }

namespace {

// The settings of `engine` the sweep runs: `asked` where it has them, else all of its own.
std::vector<std::string> chooseSettings(const SteppedEngine& engine, const std::vector<std::string>& asked) {
  if (asked.empty()) return engine.settings;
  std::vector<std::string> chosen;
  for (const std::string& s : asked)
    if (std::find(engine.settings.begin(), engine.settings.end(), s) != engine.settings.end()) chosen.push_back(s);
  return chosen;
}

}  // namespace

double countSteppedSteps(const Mechanism& m, const std::vector<const SteppedEngine*>& engines,
                         const std::vector<std::string>& settings, const std::vector<double>& steps) {
  double total = 0.0;
  for (double dt : steps) {
    const long turn = calcStepsPerTurn(m, dt);
    for (const SteppedEngine* engine : engines)
      total += static_cast<double>(chooseSettings(*engine, settings).size()) * static_cast<double>(std::max(kSettlingSteps, turn) + turn);
  }
  return total;
}

SteppedSweep calcSteppedSweep(const Mechanism& m, const std::string& scene, const std::vector<const SteppedEngine*>& engines,
                              const std::vector<std::string>& settings, std::vector<double> steps) {
  for (double dt : steps) calcStepsPerTurn(m, dt);  // a scene without speed, a step <= 0: before any work
  std::sort(steps.begin(), steps.end(), std::greater<double>());
  SteppedSweep sweep;
  for (const SteppedEngine* engine : engines) {
    for (const std::string& s : chooseSettings(*engine, settings)) {
      // A scene the engine cannot build is refused by a one-step run at the smallest step (the steps an engine
      // refuses, too long for its solver, are the large ones): one refusal row for the scene, not one per step.
      try {
        ConstantSpeedRunOptions one;
        one.dt = steps.back();
        one.steps = 1;
        one.settings = s;
        one.start = calcStartState(m, getClosedFormEngine().build(m)->evaluate(0.0));
        engine->run(m, one);
      } catch (const std::exception& e) {
        sweep.refusals.push_back({scene, engine->name, "", 0.0, e.what()});
        break;  // the same scene for every settings of this engine
      }
      std::vector<std::pair<double, SteppedMeasure>> measured;
      for (double dt : steps) {
        try {
          measured.emplace_back(dt, measureSteppedRun(*engine, m, s, dt));
        } catch (const std::exception& e) {
          sweep.refusals.push_back({scene, engine->name, s, dt, e.what()});
        }
      }
      for (const auto& [dt, measure] : measured) {
        for (const SteppedError& e : measure.errors)
          sweep.errors.push_back({scene, engine->name, s, dt, e.quantity, e.worst_rel_error, e.where_phi_deg, e.step_fraction});
        sweep.costs.push_back({scene, engine->name, s, dt, measure.seconds_per_step * 1e9});
      }
      for (size_t i = 1; i < measured.size(); ++i)
        for (size_t q = 0; q < measured[i].second.errors.size() && q < measured[i - 1].second.errors.size(); ++q) {
          const SteppedError& coarse = measured[i - 1].second.errors[q];
          const SteppedError& fine = measured[i].second.errors[q];
          sweep.orders.push_back({scene, engine->name, s, coarse.quantity, measured[i - 1].first, measured[i].first,
                                  calcObservedStepOrder(coarse.worst_rel_error, measured[i - 1].first,
                                                        fine.worst_rel_error, measured[i].first)});
        }
    }
  }
  return sweep;
}

}  // namespace crankcheck::validation
