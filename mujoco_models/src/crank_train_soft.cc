// The elastic crank train as MuJoCo's users build it (crank_train.h, simulateCrankTrainSoft): one MJCF
// (calcTrainMjcf, mjcf_writer.h), soft loops, stepped by mj_step (RK4) and run to periodic.
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numeric>
#include <string>
#include <vector>

#include "crankcheck/mujoco_models/crank_train.h"
#include "crankcheck/mujoco_models/k_crank_mujoco_model.h"
#include "crankcheck/solver/periodic_run.h"
#include "crankcheck/scene/scene_file.h"
#include "crank_train_run.h"
#include "mjcf_writer.h"
#include "model_support.h"

namespace crankcheck::mujoco_models {

namespace {

/// MuJoCo's soft train stepped by mj_step (RK4) at a whole number of steps per cycle: the soft route's CycleRun.
class SoftTrainRun final : public CycleRun {
 public:
  SoftTrainRun(const Mechanism& m, Variant variant, int steps_per_cycle);
  ~SoftTrainRun() override;
  void startCycle(double, double) override;
  std::vector<double> readCycleState() const override;
  bool moveTo(const std::vector<double>& cycle_state) override;
  void stepTo(double target) override;
  void readState(std::vector<double>& x, std::vector<double>& x_s) const override;
  long long countSteps() const override { return steps_; }
  /// The gas forces at the current state (MuJoCo's control callback, at every stage of RK4).
  void applyGas(const mjModel* model, mjData* d) const;
  const mjModel* model() const { return model_.get(); }

 private:
  Mechanism m_;
  ModelPtr model_;
  DataPtr data_;
  double omega_ = 0.0, cycle_ = 0.0;
  int steps_per_cycle_ = 0, step_in_cycle_ = 0;
  long long steps_ = 0;
  int flywheel_q_ = 0, flywheel_v_ = 0;
  std::vector<int> body_q_, body_v_;  // the bodies' relative hinges, front first
  struct Gas {
    int cylinder = 0, slide_v = 0, body = 0;  // body: the throw's index along the shaft
  };
  std::vector<Gas> gas_;
};

thread_local const SoftTrainRun* active_train = nullptr;
void applyTrainGas(const mjModel* model, mjData* d) {
  if (active_train && active_train->model() == model) active_train->applyGas(model, d);
}

SoftTrainRun::SoftTrainRun(const Mechanism& m, Variant variant, int steps_per_cycle)
    : m_(m), steps_per_cycle_(steps_per_cycle) {
  const CrankshaftParams& c = *m.crankshaft;
  omega_ = m.machine.speed;
  cycle_ = m.machine.cycle == Cycle::kFourStroke ? 4.0 * M_PI : 2.0 * M_PI;
  const std::vector<std::vector<int>> throws = findThrows(m);
  const int front = c.front_inertia > 0.0 ? 1 : 0;
  // W: 1e9 x the train's own inertias, so that within a step its speed moves by 1e-9 of what a throw's does; it is
  // put back on omega t after every step (the bench's drive).
  const double flywheel_inertia = 1e9 * (c.front_inertia + c.throw_inertia * static_cast<double>(throws.size()));
  model_.reset(loadModel(calcTrainMjcf(m, variant, flywheel_inertia)));
  setCrankPinAnchors(model_.get(), m);
  model_->opt.integrator = mjINT_RK4;
  model_->opt.timestep = cycle_ / omega_ / steps_per_cycle_;
  if (variant == Variant::kSoftStiff)  // the refsafe floor at this step: a time constant of two steps
    for (int e = 0; e < model_->neq; ++e) model_->eq_solref[2 * e] = 2.0 * model_->opt.timestep;
  data_.reset(mj_makeData(model_.get()));
  const mjModel* mm = model_.get();
  auto joint = [&](const std::string& name) { return mj_name2id(mm, mjOBJ_JOINT, name.c_str()); };
  flywheel_q_ = mm->jnt_qposadr[joint("flywheel")];
  flywheel_v_ = mm->jnt_dofadr[joint("flywheel")];
  std::vector<std::string> bodies;
  if (front) bodies.push_back("front");
  for (size_t j = 0; j < throws.size(); ++j) bodies.push_back("throw" + std::to_string(j));
  for (const std::string& b : bodies) {
    body_q_.push_back(mm->jnt_qposadr[joint(b)]);
    body_v_.push_back(mm->jnt_dofadr[joint(b)]);
  }
  // The rigid motion at t = 0: every body at 0 turning at omega (relative hinges at rest), each throw's pistons and
  // rods closed exactly on it (its exact model: slide = x_p, wrist hinge = -rod angle).
  mjData* d = data_.get();
  mju_zero(d->qpos, mm->nq);
  mju_zero(d->qvel, mm->nv);
  d->qvel[flywheel_v_] = omega_;
  for (size_t j = 0; j < throws.size(); ++j) {
    KCrankMujocoModel exact(selectThrow(m, static_cast<int>(j)));
    const Evaluation e = exact.evaluate(0.0);
    for (size_t k = 0; k < throws[j].size(); ++k) {
      const std::string C = std::to_string(throws[j][k]);
      const CylinderEvaluation& cylinder = e.cylinders[k];
      d->qpos[mm->jnt_qposadr[joint("slide" + C)]] = cylinder.x_p;
      d->qvel[mm->jnt_dofadr[joint("slide" + C)]] = cylinder.v_p;
      d->qpos[mm->jnt_qposadr[joint("wrist" + C)]] = -cylinder.rod_angle;
      d->qvel[mm->jnt_dofadr[joint("wrist" + C)]] = -cylinder.rod_omega;
      if (m.gas) gas_.push_back({throws[j][k], mm->jnt_dofadr[joint("slide" + C)], static_cast<int>(j) + front});
    }
  }
  static std::once_flag once;
  std::call_once(once, [] { mjcb_control = applyTrainGas; });
  active_train = this;
}

SoftTrainRun::~SoftTrainRun() {
  if (active_train == this) active_train = nullptr;
}

void SoftTrainRun::applyGas(const mjModel*, mjData* d) const {
  for (const Gas& g : gas_) {
    double psi = d->qpos[flywheel_q_];  // the throw's absolute angle: W's plus the hinges from W to it
    for (size_t b = static_cast<size_t>(g.body); b < body_q_.size(); ++b) psi += d->qpos[body_q_[b]];
    d->qfrc_applied[g.slide_v] = -calcGasForce(m_, g.cylinder, psi);
  }
}

void SoftTrainRun::startCycle(double, double) {
  // A new cycle: W back by one cycle (the same configuration: the gas repeats every cycle), time from 0.
  mjData* d = data_.get();
  step_in_cycle_ = 0;
  d->time = 0.0;
  d->qpos[flywheel_q_] = 0.0;
  d->qvel[flywheel_v_] = omega_;
}

void SoftTrainRun::stepTo(double target) {
  const mjModel* mm = model_.get();
  mjData* d = data_.get();
  const int last = static_cast<int>(std::lround(target / cycle_ * steps_per_cycle_));
  while (step_in_cycle_ < last) {
    mj_step(mm, d);
    checkRowsFit(d);
    ++step_in_cycle_;
    ++steps_;
    d->time = mm->opt.timestep * step_in_cycle_;
    d->qpos[flywheel_q_] = omega_ * d->time;  // the drive
    d->qvel[flywheel_v_] = omega_;
  }
}

// The soft chain's own state: every joint's position and speed but the flywheel's (driven: reset each cycle), the
// loops' give included (soft constraints hold no state of their own; MuJoCo's solver warm start only speeds it).
std::vector<double> SoftTrainRun::readCycleState() const {
  const mjModel* mm = model_.get();
  const mjData* d = data_.get();
  std::vector<double> y;
  for (int i = 0; i < mm->nq; ++i)
    if (i != flywheel_q_) y.push_back(d->qpos[i]);
  for (int i = 0; i < mm->nv; ++i)
    if (i != flywheel_v_) y.push_back(d->qvel[i]);
  return y;
}

bool SoftTrainRun::moveTo(const std::vector<double>& y) {
  const mjModel* mm = model_.get();
  mjData* d = data_.get();
  if (static_cast<int>(y.size()) != mm->nq + mm->nv - 2) return false;
  size_t k = 0;
  for (int i = 0; i < mm->nq; ++i)
    if (i != flywheel_q_) d->qpos[i] = y[k++];
  for (int i = 0; i < mm->nv; ++i)
    if (i != flywheel_v_) d->qvel[i] = y[k++];
  startCycle(0.0, 0.0);  // at a cycle's start: time 0, W at 0 turning at omega
  return true;
}

void SoftTrainRun::readState(std::vector<double>& x, std::vector<double>& x_s) const {
  // x_b = psi_b - omega t: the hinges from W to body b (W on omega t); dx/ds = their rates / omega.
  const mjData* d = data_.get();
  const size_t n = body_q_.size();
  x.assign(n, 0.0);
  x_s.assign(n, 0.0);
  double angle = d->qpos[flywheel_q_] - omega_ * d->time, rate = d->qvel[flywheel_v_] - omega_;
  for (size_t b = n; b-- > 0;) {
    angle += d->qpos[body_q_[b]];
    rate += d->qvel[body_v_[b]];
    x[b] = angle;
    x_s[b] = rate / omega_;
  }
}

}  // namespace

CrankTrainRun simulateCrankTrainSoft(const Mechanism& m, Variant variant, const CrankTrainRunOptions& asked) {
  if (variant == Variant::kExact)
    refuseCrankTrain("variant", "the soft route is MuJoCo's soft constraints' (mujoco-soft, mujoco-soft-stiff)");
  const CrankTrainRunOptions options = resolveCrankTrainOptions(m, asked, kSoftCrankTrainStep, kCrankTrainPeriodicity);
  if (!(options.accuracy <= 0.01))
    refuseCrankTrain("CrankTrainRunOptions", "the soft route's accuracy is its time step as a fraction of a cycle: "
                     "at most 0.01");
  const CrankshaftParams& c = *m.crankshaft;
  if (!(c.throw_inertia >= mjMINVAL))
    refuseCrankTrain("[crankshaft].throw_inertia", "MuJoCo's soft train needs J_t > 1e-15 kg m^2 (the throws' bodies "
                     "on hinges need an inertia)");
  if (c.front_inertia > 0.0 && !(c.front_inertia >= mjMINVAL))
    refuseCrankTrain("[crankshaft].front_inertia", "MuJoCo needs 0 or > 1e-15 kg m^2");
  // Whole steps per cycle, a multiple of the probes' (64) and the samples' spacing, at most `accuracy` of a cycle.
  const long long grain = std::lcm(64LL, static_cast<long long>(options.samples));
  const long long steps = std::max(1LL, static_cast<long long>(std::ceil(1.0 / options.accuracy / grain))) * grain;
  if (steps > (1LL << 24)) refuseCrankTrain("CrankTrainRunOptions", "the soft route's step is too small (over 2^24 a cycle)");
  SoftTrainRun run(m, variant, static_cast<int>(steps));
  const double cycle = m.machine.cycle == Cycle::kFourStroke ? 4.0 * M_PI : 2.0 * M_PI;
  // One stage (a fixed step), moved to the extrapolation of its cycle starts' whole states as the exact routes.
  return runToPeriodic(run, cycle, options, PeriodicPolicy{options.accuracy, kExtrapolationWindow}, "mujoco");
}

}  // namespace crankcheck::mujoco_models
