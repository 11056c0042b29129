#include "crankcheck/validation/commands/stepped.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <stdexcept>

#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/stepped_errors.h"
#include "crankcheck/validation/work_limit.h"

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
std::vector<std::string> chooseSettings(const Engine& engine, const std::vector<std::string>& asked) {
  if (asked.empty()) return engine.settings;
  std::vector<std::string> chosen;
  for (const std::string& s : asked)
    if (std::find(engine.settings.begin(), engine.settings.end(), s) != engine.settings.end()) chosen.push_back(s);
  return chosen;
}

}  // namespace

std::vector<SteppedJob> listSteppedJobs(const Mechanism& m, const std::vector<const Engine*>& engines,
                                        const std::vector<std::string>& settings, const std::vector<double>& steps) {
  std::vector<SteppedJob> jobs;
  for (const Engine* engine : engines)
    for (const std::string& s : chooseSettings(*engine, settings))
      for (double dt : steps) {
        if (std::fabs(m.machine.speed) * dt > kMaxStepAngle) continue;  // refused before it runs (checkStepAngle)
        const long turn = calcStepsPerTurn(m, dt);
        jobs.push_back({engine, s, dt, static_cast<double>(std::max(kSettlingSteps, turn) + turn)});
      }
  return jobs;
}

SteppedWorkEstimate estimateSteppedWork(const Mechanism& m, const std::vector<SteppedJob>& jobs, double budget_seconds,
                                        const std::string& what, const std::string& smaller) {
  double total = 0.0;
  for (const SteppedJob& job : jobs) total += job.steps;
  if (total > kMaxSteppedSteps) {
    char line[160];
    std::snprintf(line, sizeof line, "%.3g steps at %.6g rpm, more than the %.3g a sweep may take", total,
                  m.speed_rpm, kMaxSteppedSteps);
    throw UsageError(what + ": " + line + "; nothing was run: " + smaller);
  }
  // Within the limit even at a ceiling on a step's cost (kStepCostCeiling, growing as k^3: a direct solve of the
  // loops' constraints), nothing needs measuring: the example scenes' default sweeps pass here without a probe.
  const double k = m.machine.cylinders;
  const double ceiling = total * kStepCostCeiling * std::max(1.0, std::pow(k / 4.0, 3.0));
  char how[200];
  if (ceiling <= budget_seconds) {
    std::snprintf(how, sizeof how, "%.3g steps at a ceiling of %s a step", total,
                  formatDuration(kStepCostCeiling * std::max(1.0, std::pow(k / 4.0, 3.0))).c_str());
    return {ceiling, how};
  }
  // The cost of a step of each engine and settings, measured at the smallest step its jobs take (the dearest: an
  // iterative solver's work does not fall with the step).
  std::map<std::pair<const Engine*, std::string>, double> smallest;
  for (const SteppedJob& job : jobs) {
    auto [it, inserted] = smallest.try_emplace({job.engine, job.settings}, job.dt);
    if (!inserted) it->second = std::min(it->second, job.dt);
  }
  const StartState start = calcStartState(m, getClosedFormEngine().build(m)->evaluate(0.0));
  std::map<std::pair<const Engine*, std::string>, double> cost;
  for (const auto& [key, dt] : smallest) {
    auto seconds = [&, engine = key.first, s = key.second](long n) {
      ConstantSpeedRunOptions probe;
      probe.dt = dt;
      probe.steps = n;
      probe.settings = s;
      probe.start = start;
      const auto begin = std::chrono::steady_clock::now();
      engine->step_at_speed(m, probe);
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    };
    try {
      // Longer probes while they stay short (50 ms): a run's first steps and its build cost more than its steady
      // steps, so that a short probe of a cheap engine overstates its step tenfold.
      const double one = seconds(1);
      for (long n = kProbeSteps;; n *= 4) {
        const double more = seconds(1 + n);
        cost[key] = std::max(more - one, 0.0) / static_cast<double>(n);
        if (more > 0.05 || n >= 64 * kProbeSteps) break;
      }
    } catch (const std::exception&) {
      // The engine cannot build the scene or take the step: the sweep names it; nothing of its runs is counted.
    }
  }
  double seconds = 0.0, dearest = 0.0;
  std::string dearest_name;
  for (const SteppedJob& job : jobs) {
    const auto it = cost.find({job.engine, job.settings});
    if (it == cost.end()) continue;
    seconds += job.steps * it->second;
    if (it->second > dearest) dearest = it->second, dearest_name = job.engine->name + " " + job.settings;
  }
  std::snprintf(how, sizeof how, "%.3g steps; the dearest step, %s's, measured at %s", total, dearest_name.c_str(),
                formatDuration(dearest).c_str());
  return {seconds, how};
}

void checkSteppedWork(const Mechanism& m, const std::vector<SteppedJob>& jobs, double limit_seconds,
                      const std::string& what, const std::string& smaller) {
  const SteppedWorkEstimate estimate = estimateSteppedWork(m, jobs, limit_seconds, what, smaller);
  checkWorkLimit(what, estimate.seconds, estimate.how, smaller, limit_seconds);
}

SteppedSweep calcSteppedSweep(const Mechanism& m, const std::string& scene, const std::vector<const Engine*>& engines,
                              const std::vector<std::string>& settings, std::vector<double> steps) {
  for (double dt : steps) calcStepsPerTurn(m, dt);  // a scene without speed, a step <= 0: before any work
  std::sort(steps.begin(), steps.end(), std::greater<double>());
  SteppedSweep sweep;
  // A step longer than a quarter turn is refused for every engine at once (one row, engine "all"): a turn of it is
  // not sampled, whatever the solver.
  std::vector<double> sampled;
  for (double dt : steps) {
    try {
      checkStepAngle(m, dt);
      sampled.push_back(dt);
    } catch (const std::invalid_argument& e) {
      sweep.refusals.push_back({scene, "all", "", dt, e.what()});
    }
  }
  steps = std::move(sampled);
  if (steps.empty()) return sweep;
  for (const Engine* engine : engines) {
    for (const std::string& s : chooseSettings(*engine, settings)) {
      // A scene the engine cannot build is refused by a one-step run at the smallest step (the steps an engine
      // refuses, too long for its solver, are the large ones): one refusal row for the scene, not one per step.
      try {
        ConstantSpeedRunOptions one;
        one.dt = steps.back();
        one.steps = 1;
        one.settings = s;
        one.start = calcStartState(m, getClosedFormEngine().build(m)->evaluate(0.0));
        engine->step_at_speed(m, one);
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
