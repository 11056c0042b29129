// No Simbody header here: the model is behind KCrankModel's pimpl. Compiled in the Simbody target all the same (never
// with NDEBUG: simbody_models/CMakeLists.txt).
#include "crankcheck/simbody_models/engine.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "crankcheck/simbody_models/crank_train.h"
#include "crankcheck/simbody_models/free_run.h"
#include "crankcheck/simbody_models/grid_sweep.h"
#include "crankcheck/simbody_models/k_crank_gravity_model.h"
#include "crankcheck/simbody_models/k_crank_model.h"

namespace crankcheck::simbody_models {
namespace {

// The full model (k_crank_model.h); its holding torque is the cheap route to Q, its virtual power the second route.
class Model final : public EngineModel {
 public:
  explicit Model(const Mechanism& m, ModelOptions options = {}) : model_(m, options) {}
  Evaluation evaluate(double phi) override { return model_.evaluate(phi); }
  Evaluation evaluateMotion(double phi) override { return model_.evaluateMotion(phi); }
  void setSpeed(double omega) override { model_.setSpeed(omega); }
  void startAssemblyFrom(const EngineModel& donor) override {
    if (const auto* same = dynamic_cast<const Model*>(&donor)) model_.startAssemblyFrom(same->model_);
  }
  double calcQ(double phi) override { return model_.calcHoldingTorque(phi); }
  double calcSecondRouteQ(double phi) override { return model_.calcVirtualPowerQ(phi); }

 private:
  KCrankModel model_;
};

// The reduced model of gravity alone (k_crank_gravity_model.h): U and Q at rest, the rest NaN.
class GravityModel final : public EngineModel {
 public:
  explicit GravityModel(const Mechanism& m) : model_(m), cylinders_(m.machine.cylinders) {}
  Evaluation evaluate(double phi) override {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    Evaluation e;
    e.engine = "simbody";
    e.phi = phi;
    e.U = model_.calcPotentialEnergy(phi);
    e.Q = model_.calcHoldingTorque(phi);
    e.drive_torque = nan;
    e.bearing_force = e.shaking_force = {nan, nan};
    e.shaking_moment = {nan, nan, nan};
    CylinderEvaluation c;
    c.x_p = c.v_p = c.a_p = c.wall_force = c.gas_force = c.rod_angle = c.rod_omega = c.rod_alpha = nan;
    c.crank_pin_force = c.wrist_pin_force = {nan, nan};
    e.cylinders.assign(static_cast<size_t>(cylinders_), c);
    return e;
  }
  // U and Q do not depend on the speed: the reduced model has none.
  void setSpeed(double omega) override {
    if (!std::isfinite(omega)) throw std::invalid_argument("KCrankGravityModel: crank speed omega must be finite");
  }
  double calcQ(double phi) override { return model_.calcHoldingTorque(phi); }
  double calcSecondRouteQ(double phi) override { return model_.calcVirtualPowerQ(phi); }

 private:
  KCrankGravityModel model_;
  int cylinders_;
};

}  // namespace

std::vector<Engine> describeEngines() {
  Engine e;
  e.name = "simbody";
  e.library = "Simbody " + getSimbodyVersion();
  e.method = "Simbody's multibody dynamics: prescribed crank motion, loop constraints closed to rounding on its own "
             "constraint errors, its own reactions";
  e.gated = true;
  e.build = [](const Mechanism& m) -> std::unique_ptr<EngineModel> { return std::make_unique<Model>(m); };
  for (IntegratorKind kind : {IntegratorKind::kRungeKuttaMerson, IntegratorKind::kCPodes, IntegratorKind::kSemiExplicitEuler2})
    e.integrators.push_back(toString(kind));
  e.integrator_orders = {4, 5, 1};  // RungeKuttaMerson 4th order; CPodes' BDF up to 5th; SemiExplicitEuler2 first order
  e.simulates_loads = true;
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
    options.gas = settings.gas;
    options.load_torque = settings.load_torque;
    return simulateFreeRun(m, omega0, options);
  };
  // Simbody's further routes (engine.h): the second route to Q, the reduced gravity model, the model at a constraint
  // accuracy, the grid superposition.
  e.second_q_route = "virtual power";
  e.build_gravity = [](const Mechanism& m) -> std::unique_ptr<EngineModel> { return std::make_unique<GravityModel>(m); };
  // At a constraint accuracy: Simbody's own projections at that tolerance (the loops' Newton would close them to
  // rounding whatever the tolerance).
  e.build_at_accuracy = [](const Mechanism& m, double accuracy) -> std::unique_ptr<EngineModel> {
    ModelOptions options;
    options.projection_tolerance = accuracy;
    options.simbody_projections = true;
    return std::make_unique<Model>(m, options);
  };
  e.calc_q_on_grid = [](const Mechanism& m, double phi0, double step, size_t n) {
    return calcHoldingTorqueOnGrid(m, phi0, step, n);
  };
  e.simulate_crank_train = [](const Mechanism& m, const CrankTrainRunOptions& options) {
    return simulateCrankTrainSteadyState(m, options);
  };
  e.crank_train_method = "the throws as bodies on their own pins, rods and pistons closed on them, run from the rigid "
                         "motion (RungeKuttaMerson) until periodic: accuracy 1e-10, cycle-to-cycle change 1e-6 of the "
                         "twist by default (crank_train.h)";
  e.crank_train_gated = true;
  return {e};
}

}  // namespace crankcheck::simbody_models
