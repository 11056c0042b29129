#include "crankcheck/mujoco_models/engine.h"

#include "crankcheck/mujoco_models/k_crank_mujoco_model.h"

namespace crankcheck::mujoco_models {
namespace {

class Model final : public EngineModel {
 public:
  Model(const Mechanism& m, Variant variant) : model_(m, variant) {}
  Evaluation evaluate(double phi) override { return model_.evaluate(phi); }

 private:
  KCrankMujocoModel model_;
};

Engine describe(Variant variant, bool gated, std::string method) {
  Engine e;
  e.name = toString(variant);
  e.library = "MuJoCo " + getMujocoVersion();
  e.method = std::move(method);
  e.gated = gated;
  e.build = [variant](const Mechanism& m) -> std::unique_ptr<EngineModel> { return std::make_unique<Model>(m, variant); };
  return e;
}

}  // namespace

std::vector<Engine> describeEngines() {
  return {describe(Variant::kExact, true,
                   "MuJoCo's kinematics, Jacobians and recursive Newton-Euler; loop closed by Newton to rounding, "
                   "loop forces as exact (hard) multipliers"),
          describe(Variant::kSoftDefault, false,
                   "MuJoCo's own soft constraint solver (mj_forward) at its default solref/solimp"),
          describe(Variant::kSoftStiff, false,
                   "MuJoCo's own soft constraint solver at its stiffest settings (solimp 0.9999, solref 2 time steps)")};
}

}  // namespace crankcheck::mujoco_models
