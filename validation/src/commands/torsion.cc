#include "crankcheck/validation/commands/torsion.h"

#include <algorithm>
#include <cmath>

#include "crankcheck/analytic/crank_train.h"
#include "crankcheck/analytic/torsion_domain.h"
#include "crankcheck/validation/variants.h"

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

TorsionResult calcTorsion(const Mechanism& scene, const std::vector<double>& rpms, const std::vector<const Engine*>& engines,
                          const std::function<void(size_t)>& on_speed) {
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

  analytic::ThrowLoadOrders load_orders;  // the throws' speed-free torque orders, computed once for every speed
  for (size_t s = 0; s < rpms.size(); ++s) {
    if (on_speed) on_speed(s);
    const Mechanism m = withSpeed(scene, rpms[s]);
    TorsionSpeed r;
    r.rpm = rpms[s];
    try {
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
