// No Simbody header here: the model is behind KCrankModel's pimpl. Compiled in the Simbody target all the same (never
// with NDEBUG: simbody_models/CMakeLists.txt).
#include "crankcheck/simbody_models/engine.h"

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
  return {e};
}

}  // namespace crankcheck::simbody_models
