#include "crankcheck/mujoco_models/engine.h"

#include "crankcheck/mujoco_models/crank_train.h"
#include "crankcheck/mujoco_models/free_run.h"
#include "crankcheck/mujoco_models/k_crank_mujoco_model.h"

namespace crankcheck::mujoco_models {
namespace {

class Model final : public EngineModel {
 public:
  Model(const Mechanism& m, Variant variant) : model_(m, variant) {}
  Evaluation evaluate(double phi) override { return model_.evaluate(phi); }
  void setSpeed(double omega) override { model_.setSpeed(omega); }

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
  if (variant == Variant::kExact) {  // the elastic crank train: MuJoCo's throws in the train's equations (crank_train.h)
    e.simulate_crank_train = [](const Mechanism& m, const CrankTrainRunOptions& options) {
      return simulateCrankTrainSteadyState(m, options);
    };
    e.crank_train_method = "each throw's inertia and torque from MuJoCo's exact closed loops (mass matrix, inverse "
                           "dynamics), the train's equations by Dormand-Prince 5(4) from the rigid motion until "
                           "periodic; accuracy: error per step relative (and x the deviations absolute), default 1e-10; "
                           "periodicity default 1e-6 of the deviations";
    e.crank_train_gated = true;
  }
  if (variant != Variant::kExact) {  // the elastic crank train as MuJoCo's users build it: soft loops, RK4 (not gated)
    e.simulate_crank_train = [variant](const Mechanism& m, const CrankTrainRunOptions& options) {
      return simulateCrankTrainSoft(m, variant, options);
    };
    e.crank_train_method = "one MJCF: hinges with MuJoCo's joint stiffness and damping between neighbours, soft "
                           "connect loops, throw damping as tendons, the flywheel reset on omega t; mj_step RK4; "
                           "accuracy: the fixed step as a fraction of a cycle, default 1/4096; periodicity default 1e-6";
    e.crank_train_gated = false;
  }
  if (variant != Variant::kExact) {  // MuJoCo's integrators step its soft constraints
    e.integrators = {"RK4", "Euler", "implicit"};
    e.accuracy_meaning = "the fixed time step as a fraction of one revolution at the release speed, default 1e-3";
    e.default_accuracy = 1e-3;
    e.simulate = [variant](const Mechanism& m, double omega0, const FreeRunSettings& settings) {
      return simulateFreeRun(m, omega0, variant, settings);
    };
  }
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
