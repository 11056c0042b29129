#include "crankcheck/analytic/engine.h"

#include <cmath>
#include <stdexcept>

#include "crankcheck/analytic/reactions.h"
#include "crankcheck/analytic/torsion_steady.h"

namespace crankcheck::analytic {
namespace {

class Model final : public EngineModel {
 public:
  explicit Model(const Mechanism& m) : m_(m) {}
  Evaluation evaluate(double phi) override {
    if (!std::isfinite(phi)) throw std::invalid_argument("analytic: crank angle phi must be finite");
    return calcEvaluation(m_, phi);
  }
  void setSpeed(double omega) override {
    if (!std::isfinite(omega)) throw std::invalid_argument("analytic: crank speed omega must be finite");
    m_.machine.speed = omega;
    m_.speed_rpm = omega * (30.0 / M_PI);
  }

 private:
  Mechanism m_;
};

}  // namespace

std::vector<Engine> describeEngines() {
  Engine e;
  e.name = "analytic";
  e.library = "crankcheck's closed forms";
  e.method = "closed-form kinematics (Norton 13.3), energy and Newton-Euler reactions of the exact mechanism";
  e.gated = true;
  e.closed_form = true;  // the closed forms under test: every other engine is compared with this one
  e.build = [](const Mechanism& m) -> std::unique_ptr<EngineModel> { return std::make_unique<Model>(m); };
  e.simulate_crank_train = [](const Mechanism& m, const CrankTrainRunOptions& options) {
    SteadyStateOptions steady;
    if (options.accuracy != 0.0) steady.tolerance = options.accuracy;
    const ExactSteadyState exact = calcExactSteadyState(m, steady);
    CrankTrainRun run;
    for (const PeriodicSignal& twist : exact.twists) {
      std::vector<double> samples(static_cast<size_t>(options.samples));
      for (int k = 0; k < options.samples; ++k) samples[static_cast<size_t>(k)] = twist.evaluate(2 * M_PI * k / options.samples);
      run.twists.push_back(std::move(samples));
    }
    run.cycle_change = exact.residual;
    run.steps = exact.steps;
    return run;
  };
  e.crank_train_method = "shooting on the one-cycle map, Newton on the variational equations, Dormand-Prince 5(4) at "
                         "a relative accuracy of 1e-11 by default (torsion_steady.h)";
  e.crank_train_gated = true;
  return {e};
}

}  // namespace crankcheck::analytic
