// No Simbody header here: the model is behind KCrankModel's pimpl. Compiled in the Simbody target all the same (never
// with NDEBUG: simbody_models/CMakeLists.txt).
#include "crankcheck/simbody_models/engine.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

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

  // The loops' acceleration residual at a generic angle (1 rad), at the speed where the crank pin's acceleration is
  // standard gravity's: the residual has a floor that does not grow with the speed, so that a scene is probed where
  // it weighs most against the scale, as the campaign's static evaluations (Q) and slow runs take it. Against
  // kResidualLimit. @throws std::invalid_argument with the measured residual and the masses past the limit.
  void checkResolves(const Mechanism& m) {
    const double omega = std::sqrt(9.80665 / m.crank.radius);
    const double residual = model_.calcLoopAccelerationResidual(1.0, omega);
    if (residual <= kResidualLimit) return;
    char line[720];
    std::snprintf(line, sizeof line,
                  "cannot hold its accuracy on this scene: its constraint solve leaves the loops' accelerations off by "
                  "%.2g of r omega^2 + g (more than %.0e eps), past what it resolves, as where one body's mass is a "
                  "tiny fraction of another's or a load dwarfs the masses it moves; here %s; the other engines take "
                  "the scene",
                  residual, kResidualLimit / std::numeric_limits<double>::epsilon(), describeSpreads(m, omega).c_str());
    throw std::invalid_argument(line);
  }

 private:
  /// The scene's two spreads that a constraint solve cannot resolve past (measured, not blamed): its lightest body
  /// against its heaviest (rods, pistons, the crank's point masses, the balance shafts' masses), and the gas's largest
  /// force against the piston's mass times the probe's acceleration scale r omega^2 + g.
  static std::string describeSpreads(const Mechanism& m, double omega) {
    struct Body {
      std::string name;
      double mass;
    };
    std::vector<Body> bodies{{"the rod", m.rod.mass}, {"the piston", m.piston.mass}};
    if (m.crank.mass > 0.0) bodies.push_back({"the crank's mass", m.crank.mass});
    if (m.crank.counterweight_mass > 0.0) bodies.push_back({"the counterweight", m.crank.counterweight_mass});
    for (std::size_t i = 0; i < m.balance_shafts.size(); ++i)
      bodies.push_back({"balance_shaft[" + std::to_string(i) + "]", m.balance_shafts[i].mass});
    const auto by_mass = [](const Body& a, const Body& b) { return a.mass < b.mass; };
    const Body& lightest = *std::min_element(bodies.begin(), bodies.end(), by_mass);
    const Body& heaviest = *std::max_element(bodies.begin(), bodies.end(), by_mass);
    char text[400];
    std::snprintf(text, sizeof text, "the lightest body, %s, %.3g kg against the heaviest, %s, %.3g kg (%.2g of it)",
                  lightest.name.c_str(), lightest.mass, heaviest.name.c_str(), heaviest.mass,
                  lightest.mass / heaviest.mass);
    std::string out = text;
    if (lightest.name == "the rod") {
      std::snprintf(text, sizeof text, ", the rod's I_o %.3g kg m^2", m.rod.inertia_about_wrist_pin);
      out += text;
    }
    if (m.gas) {
      double largest = 0.0;  // [N] over the working cycle, 1/4 degree apart
      for (int i = 0; i < 2880; ++i) largest = std::max(largest, std::abs(calcGasForce(m, 0, i * (4.0 * M_PI / 2880.0))));
      const double inertia = m.piston.mass * (m.crank.radius * omega * omega + std::abs(m.machine.gravity));
      std::snprintf(text, sizeof text, "; the gas's largest force %.3g N against the piston's mass times r omega^2 + g, "
                    "%.3g N (%.2g times it)", largest, inertia, largest / inertia);
      out += text;
    }
    return out;
  }

  // 1e5 eps (2.2e-11): the largest residual at the probe on every example scene is 9.7e-13, on every gate case 4.3e-12
  // (1.9e4 eps); the inline four's rod at 1e-4 kg against its 0.32 kg piston gives 5.8e-10, at 1e-6 kg 6.2e-8, at
  // 1e-9 kg 2.0e-5 (its values off by as much: a primary couple of 77.5 N m for 1240.7).
  static constexpr double kResidualLimit = 1e5 * std::numeric_limits<double>::epsilon();
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
  // The model, probed once: a scene whose masses Simbody's constraint solve cannot resolve to rounding is refused by
  // name before any value is given (issue 58: a 1e-9 kg rod gave a primary couple of 77.5 N m for 1240.7).
  e.build = [](const Mechanism& m) -> std::unique_ptr<EngineModel> {
    auto model = std::make_unique<Model>(m);
    model->checkResolves(m);
    return model;
  };
  for (IntegratorKind kind : {IntegratorKind::kRungeKuttaMerson, IntegratorKind::kCPodes, IntegratorKind::kSemiExplicitEuler2})
    e.integrators.push_back(toString(kind));
  e.integrator_orders = {4, 5, 1};  // RungeKuttaMerson 4th order; CPodes' BDF up to 5th; SemiExplicitEuler2 first order
  e.simulates_loads = true;
  e.accuracy_meaning = "the integrator's relative accuracy (Integrator::setAccuracy), default 1e-10";
  e.default_accuracy = 1e-10;
  e.simulate = [](const Mechanism& m, double omega0, const FreeRunSettings& settings) {
    Model(m).checkResolves(m);  // the same probe as build's: a free run on a scene it cannot resolve is refused too
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
