// No Simbody header here: the model is behind KCrankModel's pimpl. Compiled in the Simbody target all the same (never
// with NDEBUG: simbody_models/CMakeLists.txt).
#include "crankcheck/simbody_models/engine.h"

#include <stdexcept>

#include "crankcheck/simbody_models/free_run.h"
#include "crankcheck/simbody_models/k_crank_model.h"

namespace crankcheck::simbody_models {
namespace {

class Model final : public EngineModel {
 public:
  explicit Model(const Mechanism& m) : model_(m) {}
  Evaluation evaluate(double phi) override { return model_.evaluate(phi); }

 private:
  KCrankModel model_;
};

}  // namespace

std::vector<Engine> describeEngines() {
  Engine e;
  e.name = "simbody";
  e.library = "Simbody " + getSimbodyVersion();
  e.method = "Simbody's multibody dynamics: prescribed crank motion, projected loop constraints, its own reactions";
  e.gated = true;
  e.build = [](const Mechanism& m) -> std::unique_ptr<EngineModel> { return std::make_unique<Model>(m); };
  for (IntegratorKind kind : {IntegratorKind::kRungeKuttaMerson, IntegratorKind::kCPodes, IntegratorKind::kSemiExplicitEuler2})
    e.integrators.push_back(toString(kind));
  e.accuracy_meaning = "the integrator's relative accuracy (Integrator::setAccuracy), default 1e-10";
  e.default_accuracy = 1e-10;
  e.simulate = [](const Mechanism& m, double omega0, const FreeRunSettings& settings) {
    FreeRunOptions options;
    options.integrator = settings.integrator == "CPodes"               ? IntegratorKind::kCPodes
                         : settings.integrator == "SemiExplicitEuler2" ? IntegratorKind::kSemiExplicitEuler2
                         : settings.integrator == "RungeKuttaMerson" || settings.integrator.empty()
                             ? IntegratorKind::kRungeKuttaMerson
                             : throw std::invalid_argument("Simbody has no integrator \"" + settings.integrator + "\"");
    options.accuracy = settings.accuracy;
    options.revolutions = settings.revolutions;
    options.gravity = settings.gravity;
    return simulateFreeRun(m, omega0, options);
  };
  return {e};
}

}  // namespace crankcheck::simbody_models
