#include "crankcheck/validation/commands/torsion.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>

#include "crankcheck/analytic/crank_train.h"
#include "crankcheck/analytic/torsion_domain.h"
#include "crankcheck/scene/scene_writer.h"
#include "crankcheck/validation/timing.h"
#include "crankcheck/validation/variants.h"
#include "crankcheck/validation/work_limit.h"

namespace crankcheck::validation {

CrankTrainRunOptions makeTrainOptions(const Engine& engine) {
  CrankTrainRunOptions options;
  if (engine.crank_train_gated) {
    options.accuracy = 1e-11;
    options.periodicity = 1e-7;
    options.samples = 8192;
  }
  return options;
}

namespace {

// An engine's train at `m`, capped at `steps` steps: the seconds it took, and whether it finished within them.
std::pair<double, bool> timeTrainRun(const Engine& engine, const Mechanism& m, long long steps) {
  CrankTrainRunOptions options = makeTrainOptions(engine);
  options.max_steps = steps;
  const auto begin = std::chrono::steady_clock::now();
  try {
    engine.simulate_crank_train(m, options);
    return {secondsSince(begin), true};
  } catch (const std::runtime_error&) {  // the cap (or the engine's own refusal, which the sweep then names)
    return {secondsSince(begin), false};
  }
}

}  // namespace

TorsionWorkEstimate estimateTorsionWork(const Mechanism& scene, const std::vector<double>& rpms,
                                        const std::vector<const Engine*>& engines,
                                        std::map<size_t, analytic::HolzerResponse>* holzer) {
  TorsionWorkEstimate estimate;
  if (rpms.empty()) return estimate;
  // The speeds probed: every one of a short sweep, else kProbedSpeeds spread evenly, the first and the last among them.
  std::vector<size_t> probed;
  for (size_t j = 0; j < std::min(rpms.size(), kProbedSpeeds); ++j)
    probed.push_back(rpms.size() <= kProbedSpeeds ? j : (j * (rpms.size() - 1) + (kProbedSpeeds - 1) / 2) / (kProbedSpeeds - 1));
  analytic::ThrowLoadOrders load_orders;
  double dearest = 0.0, steps_per_cycle = 0.0, dearest_evaluations = 0.0, probed_seconds = 0.0, probed_steps = 0.0;
  size_t dearest_speed = 0, stiffest_speed = 0;
  for (size_t i : probed) {
    const Mechanism m = withSpeed(scene, rpms[i]);
    const auto begin = std::chrono::steady_clock::now();
    analytic::HolzerResponse response;
    analytic::SteadyStateWork work;
    double holzer_seconds = 0.0;
    try {
      response = analytic::calcHolzerResponse(m, {}, load_orders);
      holzer_seconds = secondsSince(begin);
      analytic::checkHolzerTwist(response, rpms[i]);  // a speed outside the small-twist domain: refused before any work
      work = analytic::estimateExactSteadyStateWork(m, response);
    } catch (const std::invalid_argument&) {
      throw;
    } catch (const std::runtime_error& e) {
      throw TorsionSpeedError(rpms[i], e.what());
    }
    if (holzer) holzer->emplace(i, std::move(response));
    probed_seconds += holzer_seconds + work.seconds;
    if (holzer_seconds + work.seconds >= dearest)
      dearest = holzer_seconds + work.seconds, dearest_speed = i, dearest_evaluations = work.evaluations;
    probed_steps += work.steps_per_cycle;
    if (work.steps_per_cycle >= steps_per_cycle) steps_per_cycle = work.steps_per_cycle, stiffest_speed = i;
  }
  const double count = static_cast<double>(rpms.size());
  // The probed speeds' mean for every speed: they are spread evenly over the sweep.
  const double mean = probed_seconds / static_cast<double>(probed.size());
  estimate.seconds = mean * count;
  char text[400];
  if (rpms.size() == 1)
    std::snprintf(text, sizeof text, "the analytic steady state %s (%.2g evaluations of the train's equations)",
                  formatDuration(dearest).c_str(), dearest_evaluations);
  else
    std::snprintf(text, sizeof text, "%zu speeds at the mean of %zu probed: the analytic steady state %s a speed, "
                  "the dearest %s at %s rpm (%.2g evaluations of the train's equations)", rpms.size(), probed.size(),
                  formatDuration(mean).c_str(), formatDuration(dearest).c_str(),
                  formatShortest(rpms[dearest_speed]).c_str(), dearest_evaluations);
  estimate.how = text;
  // The advice names the dearest part: the speeds' count, an engine, or the train itself (its fastest rate, a heavy
  // damping or a stiff shaft, sets the explicit steps of every route).
  double dearest_part = estimate.seconds;
  estimate.smaller = rpms.size() > 1 ? "fewer --speeds" : "a lighter [crankshaft] damping or stiffness (the train's "
                                                          "fastest rate sets the integrators' steps)";
  // Each engine's train at the speed of the most steps a cycle: a run capped at kEngineProbeSteps, against one capped
  // at a single step (its build), gives its cost of a step; a run that finishes within the cap is its own cost. Its
  // steps a speed: the probed speeds' mean steps a cycle over kEngineCycles.
  const Mechanism m = withSpeed(scene, rpms[stiffest_speed]);
  for (const Engine* engine : engines) {
    // Longer probes while they stay short (50 ms), as the stepped runs' estimate: a run's first steps cost more than
    // its steady ones (64 of Simbody's read twice its cost of a step).
    const auto [one, done_one] = timeTrainRun(*engine, m, 1);
    double more = one, step = 0.0;
    bool done = done_one;
    for (long long n = kEngineProbeSteps; !done; n *= 4) {
      std::tie(more, done) = timeTrainRun(*engine, m, 1 + n);
      step = std::max(more - one, 0.0) / static_cast<double>(n);
      if (more - one > 0.05 || n >= 64 * kEngineProbeSteps) break;
    }
    const double samples = static_cast<double>(makeTrainOptions(*engine).samples);
    const double mean_steps = probed_steps / static_cast<double>(probed.size());
    const double steps = (kEngineCycles - 1.0) * mean_steps + std::max(mean_steps, samples);
    const double per_speed = done ? more : one + steps * step;
    estimate.seconds += per_speed * count;
    if (per_speed * count > dearest_part)
      dearest_part = per_speed * count, estimate.smaller = "without --engine " + engine->name;
    const char* each = rpms.size() > 1 ? " a speed" : "";
    if (done)
      std::snprintf(text, sizeof text, "; %s %s%s (run)", engine->name.c_str(), formatDuration(per_speed).c_str(), each);
    else
      std::snprintf(text, sizeof text, "; %s %s%s (%.2g steps at the measured %s a step)", engine->name.c_str(),
                    formatDuration(per_speed).c_str(), each, steps, formatDuration(step).c_str());
    estimate.how += text;
  }
  if (rpms.size() > 1 && estimate.smaller.rfind("without", 0) == 0) estimate.smaller += " or fewer --speeds";
  return estimate;
}

TorsionResult calcTorsion(const Mechanism& scene, const std::vector<double>& rpms, const std::vector<const Engine*>& engines,
                          double work_limit_seconds, const std::function<void(size_t)>& on_speed) {
  if (!scene.crankshaft)
    throw std::invalid_argument("[crankshaft]: missing table (the elastic crank train: throw_inertia, stiffness, ...; "
                                "docs/SCENE-FORMAT.md)");
  if (rpms.empty()) throw std::invalid_argument("torsion: no speed given");
  analytic::checkTorsionDomain(scene);  // the speed-free domain: a shaft the mean torque twists beyond a crankshaft's
  TorsionResult result;
  try {
    result.modes = analytic::calcTorsionModes(scene);
    for (int j = 0; j < static_cast<int>(findThrows(scene).size()); ++j)
      result.inertias.push_back(analytic::calcThrowInertia(scene, j));
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("[crankshaft]: ") + e.what());
  } catch (const std::runtime_error& e) {
    throw UncomputableError(e.what());
  }
  // Critical speeds of every order n <= 24 of every mode, in the range asked (one speed: half to twice it).
  const double order_step = scene.machine.cycle == Cycle::kFourStroke ? 0.5 : 1.0;
  result.range_lo = rpms.size() > 1 ? rpms.front() : 0.5 * rpms.front();
  result.range_hi = rpms.size() > 1 ? rpms.back() : 2.0 * rpms.front();
  for (int i = 0; i < result.modes.frequencies.size(); ++i)
    for (double n = order_step; n <= kTextbookOrder + 1e-9; n += order_step) {
      const double rpm = result.modes.frequencies(i) / n * 30.0 / M_PI;
      if (rpm >= result.range_lo && rpm <= result.range_hi) result.critical.push_back({i + 1, n, rpm});
    }
  std::sort(result.critical.begin(), result.critical.end(),
            [](const CriticalSpeed& a, const CriticalSpeed& b) { return a.rpm < b.rpm; });

  // The work, estimated before it: refused past the limit (status 2), nothing run.
  std::map<size_t, analytic::HolzerResponse> probed;  // Holzer's responses of the speeds probed, not computed twice
  const TorsionWorkEstimate estimate = estimateTorsionWork(scene, rpms, engines, &probed);
  checkWorkLimit(rpms.size() == 1 ? "torsion at " + formatShortest(rpms.front()) + " rpm"
                                   : "torsion at " + std::to_string(rpms.size()) + " speeds",
                 estimate.seconds, estimate.how, estimate.smaller, work_limit_seconds);

  analytic::ThrowLoadOrders load_orders;  // the throws' speed-free torque orders, computed once for every speed
  for (size_t s = 0; s < rpms.size(); ++s) {
    if (on_speed) on_speed(s);
    const Mechanism m = withSpeed(scene, rpms[s]);
    TorsionSpeed r;
    r.rpm = rpms[s];
    try {
      const auto it = probed.find(s);
      if (it != probed.end())
        r.holzer = std::move(it->second);
      else
        r.holzer = analytic::calcHolzerResponse(m, {}, load_orders);
      r.exact = analytic::calcExactSteadyState(m, r.holzer);
      for (const Engine* e : engines) {
        const CrankTrainRun run = e->simulate_crank_train(m, makeTrainOptions(*e));
        r.trains.emplace_back();
        for (const std::vector<double>& twist : run.twists)
          r.trains.back().push_back(analytic::findSignalExtremes(analytic::calcSignalFromSamples(twist)).peakToPeak());
        r.train_cycles.push_back(run.cycles);
      }
    } catch (const std::invalid_argument&) {
      throw;
    } catch (const std::runtime_error& e) {
      throw TorsionSpeedError(rpms[s], e.what());
    }
    result.speeds.push_back(std::move(r));
  }
  return result;
}

}  // namespace crankcheck::validation
