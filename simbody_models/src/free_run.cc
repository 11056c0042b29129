// The free run in Simbody (free_run.h). Never compiled with NDEBUG.
#include "crankcheck/simbody_models/free_run.h"

#include <Simbody.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "crankcheck/scene/scene_file.h"
#include "model_support.h"

#ifdef NDEBUG
#error "Simbody code must not be compiled with NDEBUG: Debian's Simbody was built without it (SIMBODY-NOTES.md)"
#endif

namespace crankcheck::simbody_models {

std::string toString(IntegratorKind kind) {
  switch (kind) {
    case IntegratorKind::kRungeKuttaMerson: return "RungeKuttaMerson";
    case IntegratorKind::kCPodes: return "CPodes";
    case IntegratorKind::kSemiExplicitEuler2: return "SemiExplicitEuler2";
  }
  return "?";
}

namespace {

// x as printf's %g: 1e-10, for messages.
std::string shortText(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

// Cubic Hermite interpolation of q(t) between two samples with slopes u: the time at which q reaches `target`.
double hermiteCrossing(double t0, double q0, double u0, double t1, double q1, double u1, double target) {
  const double h = t1 - t0;
  double s = (target - q0) / (q1 - q0);  // linear guess in [0, 1]
  for (int it = 0; it < 20; ++it) {
    const double s2 = s * s, s3 = s2 * s;
    const double q = (2 * s3 - 3 * s2 + 1) * q0 + (s3 - 2 * s2 + s) * h * u0 + (-2 * s3 + 3 * s2) * q1 + (s3 - s2) * h * u1;
    const double dq = (6 * s2 - 6 * s) * q0 + (3 * s2 - 4 * s + 1) * h * u0 + (-6 * s2 + 6 * s) * q1 + (3 * s2 - 2 * s) * h * u1;
    const double step = (q - target) / dq;
    s -= step;
    if (std::fabs(step) < 1e-16) break;
  }
  return t0 + s * h;
}

// Extremes of u(t) on [t0, t1] from the cubic Hermite interpolant with the end slopes udot (what the dynamics
// gives at each step): the stationary points of the cubic, from its quadratic derivative, plus the ends.
void hermiteExtremes(double h, double u0, double a0, double u1, double a1, double& lo, double& hi) {
  // u(s) = h00 u0 + h10 h a0 + h01 u1 + h11 h a1, s in [0, 1]; u'(s) = A s^2 + B s + C.
  const double A = 6 * u0 + 3 * h * a0 - 6 * u1 + 3 * h * a1;
  const double B = -6 * u0 - 4 * h * a0 + 6 * u1 - 2 * h * a1;
  const double C = h * a0;
  auto value = [&](double s) {
    const double s2 = s * s, s3 = s2 * s;
    return (2 * s3 - 3 * s2 + 1) * u0 + (s3 - 2 * s2 + s) * h * a0 + (-2 * s3 + 3 * s2) * u1 + (s3 - s2) * h * a1;
  };
  auto consider = [&](double s) {
    if (s > 0.0 && s < 1.0) {
      const double v = value(s);
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  };
  lo = std::min({lo, u0, u1});
  hi = std::max({hi, u0, u1});
  if (std::fabs(A) < 1e-300) {
    if (B != 0.0) consider(-C / B);
    return;
  }
  const double disc = B * B - 4 * A * C;
  if (disc < 0.0) return;
  const double root = std::sqrt(disc);
  const double q = -0.5 * (B + (B >= 0 ? root : -root));  // stable quadratic roots
  consider(q / A);
  if (q != 0.0) consider(C / q);
}

}  // namespace

FreeRunResult simulateFreeRun(const Mechanism& m, double omega0, const FreeRunOptions& options) {
  try {
    validateMechanism(m, m.name.empty() ? std::string("mechanism") : m.name);
  } catch (const SceneError& error) {
    throw std::invalid_argument(std::string("the free run's mechanism is invalid: ") + error.what());
  }
  if (!(omega0 > 0.0)) throw std::invalid_argument("simulateFreeRun: the release speed must be > 0");
  if (!m.flywheel_inertia) throw std::invalid_argument("simulateFreeRun: the scene needs [flywheel].inertia");
  if (!(m.rod.mass > 0.0 && m.rod.inertia_about_wrist_pin > 0.0))
    throw std::invalid_argument("simulateFreeRun: the Simbody model needs a rod with mass and inertia");

  const double r = m.crank.radius, l = m.rod.length;
  SimTK::MultibodySystem system;
  SimTK::SimbodyMatterSubsystem matter(system);
  SimTK::GeneralForceSubsystem forces(system);
  SimTK::Force::Gravity gravity(forces, matter, SimTK::UnitVec3(0, -1, 0), options.gravity ? m.machine.gravity : 0.0);
  // The mechanism as KCrankModel builds it (every layout), the crankshaft also carrying the shaft and flywheel: a
  // disk of polar inertia I_w about Z.
  const double I_w = *m.flywheel_inertia;
  MechanismBodies bodies = buildMechanismBodies(matter, m, SimTK::Inertia(0.5 * I_w, 0.5 * I_w, I_w));
  SimTK::MobilizedBody::Pin& crank = bodies.crank;
  // The flywheel run: the gas on the pistons (at the crank's own angle q) and the load against the crank.
  auto drive = std::make_shared<CrankDrive>();
  drive->gas = options.gas && m.gas.has_value();
  if (drive->gas) SimTK::Force::Custom(forces, new GasForce(m, drive, matter, crank, bodies.pistons));
  if (options.load_torque != 0.0) SimTK::Force::MobilityConstantForce(forces, crank, 0, -options.load_torque);
  const std::vector<SimTK::MobilizedBody::Slider>& pistons = bodies.pistons;
  const std::vector<SimTK::MobilizedBody::Pin>& rods = bodies.rods;
  system.realizeTopology();
  SimTK::State state = system.getDefaultState();

  // Release: assemble at phi = 0 with the crank locked, then the velocities at omega0, then unlock.
  const double tolerance = 1e-12 * std::max(1.0, l + r);
  for (size_t j = 0; j < pistons.size(); ++j) {
    pistons[j].setQ(state, l);
    rods[j].setQ(state, 0.0);
  }
  crank.lockAt(state, 0.0, SimTK::Motion::Position);
  system.realizeModel(state);
  system.projectQ(state, tolerance);
  crank.lockAt(state, omega0, SimTK::Motion::Velocity);
  system.realizeModel(state);
  system.projectU(state, tolerance);
  crank.unlock(state);
  system.realize(state, SimTK::Stage::Acceleration);
  for (const auto& piston : pistons)
    if (!(piston.getQ(state) > 0.0)) throw std::runtime_error("simulateFreeRun: assembly landed on the unphysical branch");

  std::unique_ptr<SimTK::Integrator> integrator;
  switch (options.integrator) {
    case IntegratorKind::kRungeKuttaMerson: integrator = std::make_unique<SimTK::RungeKuttaMersonIntegrator>(system); break;
    case IntegratorKind::kCPodes: integrator = std::make_unique<SimTK::CPodesIntegrator>(system); break;
    case IntegratorKind::kSemiExplicitEuler2: integrator = std::make_unique<SimTK::SemiExplicitEuler2Integrator>(system); break;
  }
  integrator->setAccuracy(options.accuracy);
  integrator->setConstraintTolerance(std::min(options.accuracy, 1e-6));
  // Every internal step is recorded: the integrator alone chooses its steps (report times would cap them), and the
  // extremes and the revolution time come from Hermite cubics through the steps (slopes from the dynamics).
  const double two_pi = 2.0 * SimTK::Pi;
  const double target = two_pi * options.revolutions;
  const double t_limit = 20.0 * options.revolutions * two_pi / omega0;
  integrator->setReturnEveryInternalStep(true);
  integrator->setFinalTime(t_limit);
  integrator->initialize(state);

  FreeRunResult out;
  std::vector<double> accel;  // crank phi'' at each recorded step
  Trajectory& run = out.trajectory;
  auto record = [&](const SimTK::State& s) {
    // The integrator's first return is its initial state again: a sample at the time of the last is not recorded.
    if (!run.time.empty() && s.getTime() == run.time.back()) return;
    system.realize(s, SimTK::Stage::Acceleration);
    run.time.push_back(s.getTime());
    run.phi.push_back(crank.getQ(s));
    run.omega.push_back(crank.getU(s));
    accel.push_back(crank.getOneUDot(s, SimTK::MobilizerUIndex(0)));
    out.energy.push_back(system.calcEnergy(s));
  };
  record(integrator->getState());
  try {
    while (run.phi.back() < target) {
      if (!(run.omega.back() > 0.0))
        throw std::runtime_error("the crank stops or turns back before " + std::to_string(options.revolutions) + " revolutions");
      if (integrator->getNumStepsTaken() > static_cast<long long>(options.max_steps_per_revolution) * options.revolutions)
        throw std::runtime_error("took more than " + std::to_string(options.max_steps_per_revolution) +
                                 " steps per revolution at accuracy " + shortText(options.accuracy) +
                                 " without completing " + std::to_string(options.revolutions) +
                                 " revolutions: the scene's dynamics are too stiff for this run (masses or inertias "
                                 "many orders apart); refused rather than left running");
      const SimTK::Integrator::SuccessfulStepStatus status = integrator->stepTo(t_limit);
      if (status == SimTK::Integrator::EndOfSimulation || status == SimTK::Integrator::ReachedFinalTime)
        throw std::runtime_error("the crank does not complete " + std::to_string(options.revolutions) + " revolutions in time");
      record(integrator->getState());
    }
  } catch (const std::exception& e) {
    throw std::runtime_error("simulateFreeRun (" + toString(options.integrator) + "): " + e.what());
  }
  out.steps = integrator->getNumStepsTaken();

  // First revolution (the flywheel run: the first working cycle): its time at phi = period, its extremes over the steps
  // up to there.
  const double period = options.gas && m.gas ? m.gas->cycle : two_pi;
  if (period > target) throw std::invalid_argument("simulateFreeRun: the revolutions do not cover the working cycle");
  size_t i1 = 1;
  while (run.phi[i1] < period) ++i1;
  const double t_rev = hermiteCrossing(run.time[i1 - 1], run.phi[i1 - 1], run.omega[i1 - 1], run.time[i1], run.phi[i1],
                                       run.omega[i1], period);
  out.omega_mean = period / t_rev;
  double lo = run.omega[0], hi = run.omega[0];
  for (size_t i = 0; i < i1; ++i)
    hermiteExtremes(run.time[i + 1] - run.time[i], run.omega[i], accel[i], run.omega[i + 1], accel[i + 1], lo, hi);
  out.omega_min = lo;
  out.omega_max = hi;
  out.delta = (out.omega_max - out.omega_min) / out.omega_mean;
  double drift = 0.0;
  for (double e : out.energy) drift = std::max(drift, std::fabs(e - out.energy.front()));
  const double kinetic = 0.5 * I_w * omega0 * omega0;  // the scale of the run's energy
  if (drive->gas || options.load_torque != 0.0) {
    // Gas and load do work: the mechanical energy returns only after a whole cycle (the load is the gas's mean), at
    // the cycle's end, between the two steps around it
    const double s = (t_rev - run.time[i1 - 1]) / (run.time[i1] - run.time[i1 - 1]);
    drift = std::fabs((1.0 - s) * out.energy[i1 - 1] + s * out.energy[i1] - out.energy.front());
    out.energy_drift_per_revolution = drift / std::max(kinetic, std::fabs(out.energy.front())) / (period / two_pi);
  } else {
    out.energy_drift_per_revolution = drift / std::max(kinetic, std::fabs(out.energy.front())) / options.revolutions;
  }
  return out;
}

}  // namespace crankcheck::simbody_models
