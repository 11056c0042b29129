#include "crankcheck/validation/stepped_errors.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <numbers>
#include <stdexcept>

#include "crankcheck/scene/quantities.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/scales.h"

namespace crankcheck::validation {

long calcStepsPerTurn(const Mechanism& m, double dt) {
  if (!(std::isfinite(dt) && dt > 0.0)) throw std::invalid_argument("the step dt must be a positive number of seconds");
  if (!(std::fabs(m.machine.speed) > 0.0))
    throw std::invalid_argument("[engine].speed_rpm must be != 0: a stepped engine is driven at the scene's speed");
  return static_cast<long>(std::ceil(2.0 * std::numbers::pi / (std::fabs(m.machine.speed) * dt)));
}

void checkStepAngle(const Mechanism& m, double dt) {
  calcStepsPerTurn(m, dt);  // a step <= 0, a scene without speed
  const double angle = std::fabs(m.machine.speed) * dt;
  if (angle <= kMaxStepAngle) return;
  char line[240];
  std::snprintf(line, sizeof line,
                "a step of %.6g s turns the crank by %.4g deg at %.6g rpm, more than a quarter turn: a turn is not "
                "sampled (steps up to %.4g s are measured)",
                dt, degreesFromRadians(angle), m.speed_rpm, kMaxStepAngle / std::fabs(m.machine.speed));
  throw std::invalid_argument(line);
}

std::vector<SteppedError> calcSteppedErrors(const Mechanism& m, const Trajectory& run, size_t first) {
  const size_t n = run.time.size();
  if (run.phi.size() != n || run.values.size() != n || run.loop_error.size() != n)
    throw std::invalid_argument("calcSteppedErrors: the run's time, phi, values and loop_error must have as many samples");
  if (first < 1) throw std::invalid_argument("calcSteppedErrors: the first step's start is the caller's; measure from 1");
  if (first >= n) throw std::invalid_argument("calcSteppedErrors: the run has no sample to measure");
  const Scales scales = calcScales(m);
  const std::unique_ptr<EngineModel> exact = getClosedFormEngine().build(m);
  std::vector<const Quantity*> quantities;
  std::vector<SteppedError> errors;
  for (const QuantityInstant& r : run.reported) {
    const Quantity& q = getQuantity(r.quantity);
    if (!isQuantityDefined(q, m)) throw std::invalid_argument(std::string("the run reports ") + q.name + ", which this scene does not define");
    quantities.push_back(&q);
    errors.push_back({q.name, 0.0, 0.0, r.step_fraction});
  }
  SteppedError loop{kLoopErrorName, 0.0, 0.0, 1.0};
  bool has_loop = false;
  auto note = [](SteppedError& e, double rel, double phi) {
    if (!(rel <= e.worst_rel_error)) {  // NaN too: a NaN the engine reports is its worst
      e.worst_rel_error = rel;
      double deg = std::fmod(degreesFromRadians(phi), 360.0);
      e.where_phi_deg = deg < 0.0 ? deg + 360.0 : deg;
    }
  };
  const int k = m.machine.cylinders;
  for (size_t i = first; i < n; ++i) {
    const double phi_start = run.phi[i - 1], phi_end = run.phi[i];
    std::map<double, Evaluation> at;  // the exact evaluation at each instant of this step
    for (size_t r = 0; r < quantities.size(); ++r) {
      const Quantity& q = *quantities[r];
      const double phi = phi_start + run.reported[r].step_fraction * (phi_end - phi_start);
      auto it = at.find(phi);
      if (it == at.end()) it = at.emplace(phi, exact->evaluate(phi)).first;
      const double scale = getQuantityScale(scales, q.scale, m);
      for (int c = q.per_cylinder ? 0 : -1; c < (q.per_cylinder ? k : 0); ++c) {
        const double* want = readQuantity(q, it->second, c);
        const double* got = readQuantity(q, run.values[i], c);
        for (int component = 0; component < q.components; ++component)
          if (isComponentDefined(q, component, m)) note(errors[r], std::fabs(got[component] - want[component]) / scale, phi);
      }
    }
    if (!std::isnan(run.loop_error[i])) {
      has_loop = true;
      note(loop, run.loop_error[i] / scales.position, phi_end);
    }
  }
  if (has_loop) errors.push_back(loop);
  return errors;
}

SteppedMeasure measureSteppedRun(const Engine& engine, const Mechanism& m, const std::string& settings, double dt) {
  if (std::find(engine.settings.begin(), engine.settings.end(), settings) == engine.settings.end()) {
    std::string names;
    for (const std::string& s : engine.settings) names += (names.empty() ? "" : ", ") + s;
    throw std::invalid_argument(engine.name + " has no settings \"" + settings + "\"; its settings are " + names);
  }
  checkStepAngle(m, dt);
  const long turn = calcStepsPerTurn(m, dt);
  ConstantSpeedRunOptions options;
  options.dt = dt;
  options.settings = settings;
  const long settle = std::max(kSettlingSteps, turn);
  options.steps = settle + turn;
  options.start = calcStartState(m, getClosedFormEngine().build(m)->evaluate(0.0));
  const Trajectory run = engine.step_at_speed(m, options);
  if (static_cast<long>(run.time.size()) != options.steps)
    throw std::runtime_error(engine.name + " returned " + std::to_string(run.time.size()) + " steps of " +
                             std::to_string(options.steps));
  SteppedMeasure measure;
  measure.errors = calcSteppedErrors(m, run, static_cast<size_t>(settle));
  measure.seconds_per_step = run.seconds_per_step;
  measure.settling_steps = settle;
  measure.measured_steps = turn;
  return measure;
}

double calcObservedStepOrder(double e1, double dt1, double e2, double dt2) {
  if (!(e1 > 0.0 && e2 > 0.0) || dt1 == dt2) return std::nan("");
  return std::log(e1 / e2) / std::log(dt1 / dt2);
}

}  // namespace crankcheck::validation
