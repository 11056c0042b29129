// The elastic crank train in MuJoCo (crank_train.h). The exact route: MuJoCo's throws (KCrankMujocoModel, kExact)
// give each throw's inertia and torque; the train's equations are integrated here by Boost.Odeint.
#include "crankcheck/mujoco_models/crank_train.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <boost/numeric/odeint.hpp>

#include "crankcheck/mujoco_models/k_crank_mujoco_model.h"
#include "crankcheck/scene/scene_file.h"
#include "crank_train_run.h"

namespace crankcheck::mujoco_models {
namespace {

namespace odeint = boost::numeric::odeint;
using State = std::vector<double>;  // (x_0 .. x_{n-1}, dx_0/ds .. dx_{n-1}/ds), s = omega t

constexpr int kProbes = 64;  // states per cycle at which the first cycle's scale is read

/// The train's bodies and sections (CONVENTIONS "Torsion"), front first; MuJoCo's model of each throw.
struct Train {
  std::vector<KCrankMujocoModel> throws;  // throw j at throw_body[j]
  std::vector<int> throw_of_body;         // -1: the front mass
  std::vector<double> stiffness;          // K_s [N m/rad] of section i (body i to body i + 1, the last to W)
  std::vector<double> damping;            // C_s [N m s/rad]
  double front_inertia = 0.0;             // J_F [kg m^2]
  double throw_inertia = 0.0;             // J_t [kg m^2]
  double throw_damping = 0.0;             // c_t [N m s/rad]
  double omega = 0.0;                     // [rad/s]
  int bodies() const { return static_cast<int>(throw_of_body.size()); }

  /// dy/ds at s [rad] (the cycle's own s, from 0): x'' = (torques on the body) / (its inertia omega^2).
  void calcRates(const State& y, State& dy, double s) {
    const int n = bodies();
    const double w = omega, w2 = w * w;
    for (int b = 0; b < n; ++b) {
      dy[static_cast<size_t>(b)] = y[static_cast<size_t>(n + b)];
      dy[static_cast<size_t>(n + b)] = 0.0;
    }
    // Section i: K_i (x_b - x_a) + C_i omega (x_b' - x_a') on a = i, the opposite on b = i + 1 (x_W = x_W' = 0).
    double* torque = dy.data() + n;
    for (int i = 0; i < n; ++i) {
      const bool flywheel = i + 1 == n;
      const double twist = (flywheel ? 0.0 : y[static_cast<size_t>(i + 1)]) - y[static_cast<size_t>(i)];
      const double rate = (flywheel ? 0.0 : y[static_cast<size_t>(n + i + 1)]) - y[static_cast<size_t>(n + i)];
      const double t = stiffness[static_cast<size_t>(i)] * twist + damping[static_cast<size_t>(i)] * w * rate;
      torque[i] += t;
      if (!flywheel) torque[i + 1] -= t;
    }
    for (int b = 0; b < n; ++b) {
      const int j = throw_of_body[static_cast<size_t>(b)];
      if (j < 0) {
        torque[b] /= front_inertia * w2;
        continue;
      }
      const double x_s = y[static_cast<size_t>(n + b)];
      const CrankTorqueLine line =
          throws[static_cast<size_t>(j)].calcCrankTorqueLine(s + y[static_cast<size_t>(b)], w * (1.0 + x_s));
      torque[b] = (torque[b] - throw_damping * w * x_s - line.rest) / ((throw_inertia + line.inertia) * w2);
    }
  }
};

/// Odeint's system: a handle on the train (steppers copy their system).
struct TrainSystem {
  Train* train;
  void operator()(const State& y, State& dy, double s) const { train->calcRates(y, dy, s); }
};

/// Dormand-Prince 5(4) with step control, stepping exactly onto each target s (no interpolation): the exact route's
/// CycleRun. Error per step below `accuracy` relative and accuracy x scale [rad] absolute, scale the largest deviation
/// of the cycle before (the first cycle's: `first_scale`).
class Integration final : public CycleRun {
 public:
  Integration(Train& train, double cycle, double first_scale, long long max_steps)
      : system_{&train}, max_steps_(max_steps), cycle_(cycle), scale_(first_scale), ds_(cycle / 512),
        y_(static_cast<size_t>(2 * train.bodies()), 0.0) {}  // the rigid motion at t = 0

  void startCycle(double accuracy, double scale) override {
    if (scale > 0.0) scale_ = scale;
    stepper_ = odeint::make_controlled(accuracy * scale_, accuracy, odeint::runge_kutta_dopri5<State>());
    s_ = 0.0;
  }
  void stepTo(double target) override {
    while (s_ < target) {
      if (steps_ > max_steps_) return;  // runToPeriodic refuses the run (CrankTrainRunOptions::max_steps)
      const double remaining = target - s_;
      double ds = std::min(ds_, remaining), tried = ds;
      for (int fails = 0;; ++fails) {
        tried = ds;
        if (stepper_.try_step(system_, y_, s_, ds) == odeint::success) break;  // else ds is cut
        if (fails == 1000 || !(ds > 1e-14 * cycle_))
          throw std::runtime_error("mujoco: the crank train's integration step collapsed at s = " + std::to_string(s_) +
                                   " rad of the cycle (a train that runs away)");
      }
      ++steps_;
      if (tried == remaining) s_ = target;    // landed: odeint's s_ + ds, to rounding
      if (tried < remaining || ds > ds_) ds_ = ds;  // the controller's next step (a landing's only if larger)
    }
  }
  void readState(std::vector<double>& x, std::vector<double>& x_s) const override {
    const size_t n = y_.size() / 2;
    x.assign(y_.begin(), y_.begin() + static_cast<long>(n));
    x_s.assign(y_.begin() + static_cast<long>(n), y_.end());
  }
  bool moveTo(const std::vector<double>& y) override {  // y = (x, x_s): the train's whole state
    y_ = y;
    s_ = 0.0;
    return true;
  }
  long long countSteps() const override { return steps_; }

 private:
  TrainSystem system_;
  long long max_steps_;
  odeint::result_of::make_controlled<odeint::runge_kutta_dopri5<State>>::type stepper_;
  double cycle_, scale_, ds_, s_ = 0.0;
  State y_;
  long long steps_ = 0;
};

}  // namespace

void refuseCrankTrain(const std::string& key, const std::string& rule) {
  throw std::invalid_argument(key + ": " + rule + " (MuJoCo's elastic crank train)");
}

CrankTrainRunOptions resolveCrankTrainOptions(const Mechanism& m, const CrankTrainRunOptions& asked, double accuracy,
                                              double periodicity) {
  if (!m.crankshaft) refuseCrankTrain("[crankshaft]", "missing table: the train's inertias, sections and damping");
  if (!(m.machine.speed > 0.0))
    refuseCrankTrain("[engine].speed_rpm",
                     "must be > 0: the flywheel end turns at the scene's speed (CONVENTIONS \"Torsion\")");
  try {
    validateMechanism(m, m.name.empty() ? std::string("mechanism") : m.name);
  } catch (const SceneError& error) {
    refuseCrankTrain("invalid mechanism", error.what());
  }
  const CrankTrainRunOptions defaults;
  CrankTrainRunOptions options = asked;
  if (options.accuracy == 0.0) options.accuracy = accuracy;
  if (options.periodicity == 0.0) options.periodicity = periodicity;
  if (options.samples == 0) options.samples = defaults.samples;
  if (options.max_cycles == 0) options.max_cycles = defaults.max_cycles;
  if (options.max_steps == 0) options.max_steps = kCrankTrainMaxSteps;
  if (!(std::isfinite(options.accuracy) && options.accuracy > 0.0 && std::isfinite(options.periodicity) &&
        options.periodicity > 0.0) ||
      options.samples < 16 || options.samples % 2 != 0 || options.max_cycles < 1 || options.max_steps < 1)
    refuseCrankTrain("CrankTrainRunOptions", "accuracy and periodicity must be finite and >= 0, samples even and >= "
                     "16, max_cycles and max_steps >= 0 (each 0: the default)");
  return options;
}

CrankTrainRun simulateCrankTrainSteadyState(const Mechanism& m, const CrankTrainRunOptions& asked) {
  const CrankTrainRunOptions options = resolveCrankTrainOptions(m, asked, kCrankTrainAccuracy, kCrankTrainPeriodicity);

  const CrankshaftParams& c = *m.crankshaft;
  Train train;
  train.omega = m.machine.speed;
  train.front_inertia = c.front_inertia;
  train.throw_inertia = c.throw_inertia;
  train.throw_damping = c.throw_damping;
  if (c.front_inertia > 0.0) train.throw_of_body.push_back(-1);
  const int throw_count = static_cast<int>(findThrows(m).size());
  for (int j = 0; j < throw_count; ++j) {
    train.throw_of_body.push_back(j);
    train.throws.emplace_back(selectThrow(m, j), Variant::kExact);
  }
  const int n = train.bodies();
  train.stiffness = c.stiffness;  // validateMechanism: one per section
  for (int i = 0; i < n; ++i) train.damping.push_back(getSectionDamping(c, i));

  const double omega = train.omega;
  const double cycle = m.machine.cycle == Cycle::kFourStroke ? 4.0 * M_PI : 2.0 * M_PI;
  // The first cycle's deviation scale: the rigid motion's largest throw torques, summed, over the softest section.
  double scale = 0.0;
  for (KCrankMujocoModel& model : train.throws) {
    double largest = 0.0;
    for (int k = 0; k < kProbes; ++k)
      largest = std::max(largest, std::fabs(model.calcCrankTorqueLine(cycle * k / kProbes, omega).rest));
    scale += largest;
  }
  scale /= *std::min_element(train.stiffness.begin(), train.stiffness.end());
  if (!(scale > 0.0)) scale = 1.0;  // no load at all: the deviations stay 0

  Integration integration(train, cycle, scale, options.max_steps);
  return runToPeriodic(integration, cycle, options, PeriodicPolicy{1000.0 * options.accuracy, kExtrapolationWindow},
                       "mujoco");
}

}  // namespace crankcheck::mujoco_models
