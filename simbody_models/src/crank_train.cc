// The elastic crank train in Simbody (crank_train.h). Never compiled with NDEBUG.
#include "crankcheck/simbody_models/crank_train.h"

#include <Simbody.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "crankcheck/solver/periodic_run.h"
#include "crankcheck/scene/scene_file.h"
#include "model_support.h"

#ifdef NDEBUG
#error "Simbody code must not be compiled with NDEBUG: Debian's Simbody was built without it (SIMBODY-NOTES.md)"
#endif

namespace crankcheck::simbody_models {
namespace {

// The sections' springs and dampers and the throws' damping, as mobility forces on the pins (CONVENTIONS: K (psi_b -
// psi_a) + C (psi_b' - psi_a') on a, the opposite on b; -c_t (psi' - omega) on a throw). The last section's far end
// is the flywheel, at omega t.
class ShaftForces : public SimTK::Force::Custom::Implementation {
 public:
  ShaftForces(std::vector<SimTK::MobilizedBody::Pin> bodies, std::vector<bool> is_throw, const CrankshaftParams& c,
              std::vector<double> section_damping, double omega)
      : bodies_(std::move(bodies)), is_throw_(std::move(is_throw)), stiffness_(c.stiffness),
        damping_(std::move(section_damping)), throw_damping_(c.throw_damping), omega_(omega) {}
  void calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>&, SimTK::Vector_<SimTK::Vec3>&,
                 SimTK::Vector& mobility_forces) const override {
    const size_t n = bodies_.size();
    const double t = state.getTime();
    for (size_t i = 0; i < n; ++i) {
      const double psi_a = bodies_[i].getQ(state), rate_a = bodies_[i].getU(state);
      const bool flywheel = i + 1 == n;
      const double psi_b = flywheel ? omega_ * t : bodies_[i + 1].getQ(state);
      const double rate_b = flywheel ? omega_ : bodies_[i + 1].getU(state);
      const double torque = stiffness_[i] * (psi_b - psi_a) + damping_[i] * (rate_b - rate_a);
      bodies_[i].applyOneMobilityForce(state, SimTK::MobilizerUIndex(0), torque, mobility_forces);
      if (!flywheel) bodies_[i + 1].applyOneMobilityForce(state, SimTK::MobilizerUIndex(0), -torque, mobility_forces);
      if (is_throw_[i])
        bodies_[i].applyOneMobilityForce(state, SimTK::MobilizerUIndex(0), -throw_damping_ * (rate_a - omega_),
                                         mobility_forces);
    }
  }
  SimTK::Real calcPotentialEnergy(const SimTK::State& state) const override {
    double energy = 0.0;
    for (size_t i = 0; i < bodies_.size(); ++i) {
      const double psi_b = i + 1 == bodies_.size() ? omega_ * state.getTime() : bodies_[i + 1].getQ(state);
      const double twist = psi_b - bodies_[i].getQ(state);
      energy += 0.5 * stiffness_[i] * twist * twist;
    }
    return energy;
  }

 private:
  std::vector<SimTK::MobilizedBody::Pin> bodies_;
  std::vector<bool> is_throw_;
  std::vector<double> stiffness_, damping_;
  double throw_damping_, omega_;
};


// Puts the train in `state` (at its time t) with every pin at psi_i = x_i + omega t turning at omega (1 + x_s,i): the
// pins locked there, the pistons and rods assembled to them from what `state` holds, the pins unlocked. False when a
// piston lands inside the crank circle (the unphysical branch).
bool assembleTrain(const SimTK::MultibodySystem& system, const std::vector<SimTK::MobilizedBody::Pin>& shaft,
                   const std::vector<MechanismBodies>& throws, double omega, const std::vector<double>& x,
                   const std::vector<double>& x_s, double tolerance, SimTK::State& state) {
  const double t = state.getTime();
  for (size_t i = 0; i < shaft.size(); ++i) shaft[i].lockAt(state, x[i] + omega * t, SimTK::Motion::Position);
  system.realizeModel(state);
  system.projectQ(state, tolerance);
  for (size_t i = 0; i < shaft.size(); ++i) shaft[i].lockAt(state, omega * (1.0 + x_s[i]), SimTK::Motion::Velocity);
  system.realizeModel(state);
  system.projectU(state, tolerance);
  for (const auto& pin : shaft) pin.unlock(state);
  system.realizeModel(state);
  for (const MechanismBodies& b : throws)
    for (const auto& piston : b.pistons)
      if (!(piston.getQ(state) > 0.0)) return false;
  return true;
}

// Simbody's integration of the train (RungeKuttaMerson, every probe and sample an integrated state), cycle by cycle:
// crankcheck/solver/periodic_run.h's CycleRun. Time runs on (t = t0 + s / omega, t0 the cycle's start).
class TrainRun final : public CycleRun {
 public:
  TrainRun(SimTK::MultibodySystem& system, const std::vector<SimTK::MobilizedBody::Pin>& shaft,
           const std::vector<MechanismBodies>& throws, double omega, double constraint_tolerance,
           double assembly_tolerance, const SimTK::State& state)
      : system_(system), shaft_(shaft), throws_(throws), omega_(omega), assembly_tolerance_(assembly_tolerance),
        integrator_(system) {
    integrator_.setConstraintTolerance(constraint_tolerance);
    integrator_.setAllowInterpolation(false);  // every sample an integrated state
    state_ = state;
  }
  void startCycle(double accuracy, double) override {
    if (!started_ || accuracy != accuracy_) {
      steps_ += started_ ? integrator_.getNumStepsTaken() : 0;
      integrator_.setAccuracy(accuracy);
      integrator_.initialize(started_ ? integrator_.getState() : state_);
      accuracy_ = accuracy;
      started_ = true;
    }
    t0_ = integrator_.getTime();
  }
  void stepTo(double target) override {
    // At most the steps left of the work limit in this call (runToPeriodic refuses the run past it).
    integrator_.setInternalStepLimit(static_cast<int>(std::clamp(max_steps_ + 1 - countSteps(), 1LL, 1LL << 30)));
    const SimTK::Integrator::SuccessfulStepStatus status = integrator_.stepTo(t0_ + target / omega_);
    if (status == SimTK::Integrator::ReachedStepLimit) return;
    if (status == SimTK::Integrator::EndOfSimulation)
      throw std::runtime_error("simbody: the integrator ended the crank train's run at t = " +
                               std::to_string(integrator_.getTime()));
  }
  void readState(std::vector<double>& x, std::vector<double>& x_s) const override {
    const SimTK::State& s = started_ ? integrator_.getState() : state_;
    x.clear();
    x_s.clear();
    for (const SimTK::MobilizedBody::Pin& pin : shaft_) {
      x.push_back(pin.getQ(s) - omega_ * s.getTime());
      x_s.push_back((pin.getU(s) - omega_) / omega_);
    }
  }
  bool moveTo(const std::vector<double>& y) override {
    // y = (x, x_s): assembled as at t = 0 (assembleTrain); on the unphysical branch the run stays where it is.
    const size_t n = shaft_.size();
    SimTK::State s = integrator_.getState();
    if (!assembleTrain(system_, shaft_, throws_, omega_, std::vector<double>(y.begin(), y.begin() + static_cast<long>(n)),
                       std::vector<double>(y.begin() + static_cast<long>(n), y.end()), assembly_tolerance_, s))
      return false;
    steps_ += integrator_.getNumStepsTaken();
    integrator_.initialize(s);
    return true;
  }
  long long countSteps() const override { return steps_ + integrator_.getNumStepsTaken(); }
  void setMaxSteps(long long max_steps) { max_steps_ = max_steps; }

 private:
  SimTK::MultibodySystem& system_;
  const std::vector<SimTK::MobilizedBody::Pin>& shaft_;
  const std::vector<MechanismBodies>& throws_;
  double omega_, assembly_tolerance_;
  SimTK::RungeKuttaMersonIntegrator integrator_;
  long long max_steps_ = kCrankTrainMaxSteps;
  SimTK::State state_;  // the start, before the first cycle
  bool started_ = false;
  double accuracy_ = 0.0, t0_ = 0.0;
  long long steps_ = 0;
};

}  // namespace

CrankTrainRun simulateCrankTrainSteadyState(const Mechanism& m, const CrankTrainRunOptions& asked) {
  CrankTrainRunOptions options = asked;
  if (options.accuracy == 0.0) options.accuracy = kCrankTrainAccuracy;
  if (options.periodicity == 0.0) options.periodicity = kCrankTrainPeriodicity;
  if (options.max_steps == 0) options.max_steps = kCrankTrainMaxSteps;
  checkModelInputs(m, ModelOptions{}, "simulateCrankTrainSteadyState");
  if (!m.crankshaft) throw std::invalid_argument("simulateCrankTrainSteadyState: the scene has no [crankshaft] table");
  const double omega = m.machine.speed;
  if (!(omega > 0.0)) throw std::invalid_argument("simulateCrankTrainSteadyState: the train needs a speed > 0");
  if (!(m.rod.mass > 0.0 && m.rod.inertia_about_wrist_pin > 0.0))
    throw std::invalid_argument("simulateCrankTrainSteadyState: the Simbody model needs a rod with mass > 0 and "
                                "inertia about the wrist pin > 0");
  if (options.samples < 16 || options.samples % 2 != 0 || !(options.accuracy > 0.0) || !(options.periodicity > 0.0) ||
      options.max_steps < 1)
    throw std::invalid_argument("simulateCrankTrainSteadyState: bad options");
  const CrankshaftParams& c = *m.crankshaft;

  SimTK::MultibodySystem system;
  SimTK::SimbodyMatterSubsystem matter(system);
  SimTK::GeneralForceSubsystem forces(system);
  SimTK::Force::Gravity gravity(forces, matter, SimTK::UnitVec3(0, -1, 0), m.machine.gravity);
  // Bodies along the shaft, front first: q of each pin is its angle psi (the throws' frames turned by gamma, as
  // KCrankModel's crankshaft, whose q is phi; the front mass's too, so that all start at q = 0).
  std::vector<SimTK::MobilizedBody::Pin> shaft;
  std::vector<bool> is_throw;
  std::vector<MechanismBodies> throws;
  auto drive = std::make_shared<CrankDrive>();  // gas on; the pins are free (no Motion)
  const SimTK::Transform X_GF(SimTK::Rotation(m.machine.cylinder_angle, SimTK::ZAxis), SimTK::Vec3(0));
  if (c.front_inertia > 0.0) {
    // A disk of polar inertia J_F; its unit mass sits on the axis (no torque from gravity, none on the twist).
    const double J = c.front_inertia;
    shaft.emplace_back(matter.Ground(), X_GF,
                       SimTK::Body::Rigid(SimTK::MassProperties(1.0, SimTK::Vec3(0), SimTK::Inertia(0.5 * J, 0.5 * J, J))),
                       SimTK::Transform());
    is_throw.push_back(false);
  }
  const int throw_count = static_cast<int>(findThrows(m).size());
  for (int j = 0; j < throw_count; ++j) {
    const Mechanism tm = selectThrow(m, j);
    const double J_t = c.throw_inertia;
    throws.push_back(buildMechanismBodies(matter, tm, SimTK::Inertia(0.5 * J_t, 0.5 * J_t, J_t)));
    shaft.push_back(throws.back().crank);
    is_throw.push_back(true);
    if (tm.gas) SimTK::Force::Custom(forces, new GasForce(tm, drive, matter, throws.back().crank, throws.back().pistons));
  }
  const int n = static_cast<int>(shaft.size());
  if (static_cast<int>(c.stiffness.size()) != n)
    throw std::invalid_argument("simulateCrankTrainSteadyState: [crankshaft].stiffness needs one value per section (" +
                                std::to_string(n) + ")");
  std::vector<double> section_damping;
  for (int i = 0; i < n; ++i) section_damping.push_back(getSectionDamping(c, i));
  SimTK::Force::Custom(forces, new ShaftForces(shaft, is_throw, c, section_damping, omega));
  system.realizeTopology();
  SimTK::State state = system.getDefaultState();

  // The rigid motion at t = 0: every pin at 0 turning at omega, the pistons and rods assembled to it.
  const double l = m.rod.length, r = m.crank.radius;
  const double tolerance = 1e-12 * std::max(1.0, l + r);
  for (const MechanismBodies& b : throws)
    for (size_t j = 0; j < b.pistons.size(); ++j) {
      b.pistons[j].setQ(state, l);
      b.rods[j].setQ(state, 0.0);
    }
  const std::vector<double> rigid(shaft.size(), 0.0);  // x = 0, x_s = 0 at t = 0
  if (!assembleTrain(system, shaft, throws, omega, rigid, rigid, tolerance, state))
    throw std::runtime_error("simulateCrankTrainSteadyState: assembly landed on the unphysical branch");

  TrainRun run(system, shaft, throws, omega, std::min(options.accuracy, 1e-6), tolerance, state);
  run.setMaxSteps(options.max_steps);
  const double cycle = m.machine.cycle == Cycle::kFourStroke ? 4.0 * SimTK::Pi : 2.0 * SimTK::Pi;
  return runToPeriodic(run, cycle, options, PeriodicPolicy{1000.0 * options.accuracy, kExtrapolationWindow}, "simbody");
}

}  // namespace crankcheck::simbody_models
