// The k-crank mechanism in Simbody. This is the only translation unit of the library that includes Simbody.
// It must never be compiled with NDEBUG (SIMBODY-NOTES.md); the top-level CMake sets flags without it and
// simbody_models/CMakeLists.txt checks. SimTK names stay qualified: a global `using namespace SimTK` breaks Eigen.
#include "crankcheck/simbody_models/k_crank_model.h"

#include <Simbody.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "crankcheck/scene/scene_file.h"
#include "block_newton.h"
#include "model_support.h"

#ifdef NDEBUG
#error "Simbody code must not be compiled with NDEBUG: Debian's Simbody was built without it (SIMBODY-NOTES.md)"
#endif

namespace crankcheck::simbody_models {

namespace {

// Refuses an evaluation with a non-finite value (a singular mass matrix); returns it otherwise. Without
// `with_static_pass` (evaluateMotion) U and Q are NaN by design and not checked.
const Evaluation& checkFinite(const Evaluation& ev, bool with_static_pass = true) {
  bool finite = (!with_static_pass || (std::isfinite(ev.U) && std::isfinite(ev.Q))) && std::isfinite(ev.drive_torque) &&
                std::isfinite(ev.bearing_force[0]) && std::isfinite(ev.bearing_force[1]);
  for (const CylinderEvaluation& c : ev.cylinders)
    finite = finite && std::isfinite(c.x_p) && std::isfinite(c.v_p) && std::isfinite(c.a_p) &&
             std::isfinite(c.crank_pin_force[0]) && std::isfinite(c.crank_pin_force[1]) &&
             std::isfinite(c.wrist_pin_force[0]) && std::isfinite(c.wrist_pin_force[1]) &&
             std::isfinite(c.wall_force);
  if (!finite)
    throw std::runtime_error("KCrankModel: Simbody returned non-finite results at phi = " + std::to_string(ev.phi) +
                             " rad (singular mass matrix?)");
  return ev;
}

}  // namespace

// The largest crank step [rad] over which an assembly starts from the last dynamic pass's Taylor step (assemble).
// Measured (k = 1 and 12, 4 turns at even steps): steps of 0.25 degrees took 2.8 (k = 1) to 3.8 (k = 12) Newton steps per
// assembly from the last angle's q, 1.0 from the Taylor start; 15 degrees 3.0 -> 2.0; 45 and 60 degrees 3.9 -> 3.0
// (k = 12); at 75 degrees and beyond it saves none.
constexpr double kTaylorStartLimit = 1.1;

class KCrankModel::Impl {
 public:
  Impl(const Mechanism& m, ModelOptions options);

  /// Assembles the positions at phi (crank prescribed, pistons and rods projected). On return the state is
  /// realized through Stage::Position.
  void assemble(double phi);
  /// Prescribes crank speed omega at the assembled positions, projects the velocities and realizes
  /// Stage::Acceleration.
  void solveMotion(double omega);
  /// The loops' acceleration errors (udoterr) of the last solveMotion, relative to r omega^2 + g at its omega.
  double calcLoopAccelerationResidual() const;
  double last_residual_omega_ = 0.0;
  /// Drive torque [N m] about +Z at the current (Acceleration-realized) state.
  double driveTorque() const;
  /// With `motion_only`, no static pass (U and Q NaN): EngineModel::evaluateMotion.
  Evaluation evaluateAt(double phi, Diagnostics* diagnostics, bool motion_only = false);
  void setSpeed(double omega) {
    if (!std::isfinite(omega)) throw std::invalid_argument("KCrankModel: crank speed omega must be finite");
    m_.machine.speed = omega;
    m_.speed_rpm = omega * (30.0 / M_PI);
  }
  double potentialEnergy(double phi);
  double kineticEnergy(double phi);
  double holdingTorque(double phi);
  double virtualPowerQ(double phi);

  const Mechanism& mechanism() const { return m_; }

  void startAssemblyFrom(const Impl& donor);

 private:
  BodyKinematics bodyKinematics(const SimTK::MobilizedBody& body) const;
  /// (dH_O/dt, dP/dt) of one body from Simbody's own accelerations and mass properties, at Acceleration stage.
  SimTK::SpatialVec momentumRate(const SimTK::MobilizedBody& body) const;
  /// Reads the motion and loads of `ev` (drive torque, reactions, kinematics, shaking) off the Acceleration-realized
  /// state; fills `reactions` (the mobilizer reactions) for the diagnostics.
  void readMotion(Evaluation& ev, SimTK::Vector_<SimTK::SpatialVec>& reactions) const;
  void setReferenceGuess();

  // The static pass of the last evaluation (U, Q, the position error) at the angle the state is assembled at: an
  // evaluation at the same angle (the cross-check's second speed) reuses the assembly and it. Any assembly clears it.
  struct StaticPass {
    bool valid = false;
    double phi = 0.0, U = 0.0, Q = 0.0, position_error = 0.0;
    // Without gas the static pass is the dynamic pass at rest: its whole evaluation, read off the same solved state.
    bool at_rest_valid = false;
    Evaluation at_rest;
  };
  StaticPass static_pass_;

  // Gravity's power per unit crank speed at the assembled angle, from the last dynamic pass at omega != 0 (velocities are
  // linear in omega): the second route to Q (virtualPowerQ) reads it instead of solving the velocities again.
  struct UnitPower {
    bool valid = false;
    double phi = 0.0, power = 0.0;
  };
  UnitPower unit_power_;

  // The velocities of a dynamic pass (every u: joint rates, each cylinder's own, and the crank's omega): this model's last
  // one, and one taken from a donor (startAssemblyFrom) that starts the velocity projection at the same angle and speed.
  // The last one also keeps qdot and qdotdot (the motion at constant crank speed), from which the next assembly near it
  // starts (assemble: the Taylor step of the motion to the next angle).
  struct MotionStart {
    bool valid = false;
    double phi = 0.0, omega = 0.0;
    SimTK::Vector u, qdot, qdotdot;
  };
  MotionStart last_motion_, seeded_motion_;

  Mechanism m_;
  ModelOptions options_;
  int k_ = 0;
  std::vector<SimTK::Vec3> e_;  // cylinder j's axis, global
  std::vector<SimTK::Vec3> n_;  // e_j turned +90 degrees about Z

  std::shared_ptr<CrankDrive> drive_ = std::make_shared<CrankDrive>();
  SimTK::MultibodySystem system_;
  SimTK::SimbodyMatterSubsystem matter_{system_};
  SimTK::GeneralForceSubsystem forces_{system_};
  SimTK::Force::Gravity gravity_;
  SimTK::MobilizedBody::Pin crank_;
  std::vector<SimTK::MobilizedBody::Slider> pistons_;
  std::vector<SimTK::MobilizedBody::Pin> rods_;
  std::vector<SimTK::MobilizedBody::Pin> shafts_;  // balance shafts (coupled to the crank)
  // The loops closed by Newton's method on Simbody's own errors near a known solution (block_newton.h): loop j's block
  // is piston j's slide and rod j's pin, shaft i's its pin.
  std::unique_ptr<BlockNewton> newton_;
  std::vector<SimTK::Vec3> crank_pins_in_crank_;  // B_j in the crankshaft body frame
  SimTK::Vec3 rod_big_end_in_rod_;                // B in the rod body frame
  SimTK::State state_;

  double reference_potential_ = 0.0;  // V(0)
  double polish_threshold_ = 0.0;     // [m] constraint error below which no extra Newton step is taken
  double projection_tolerance_ = 0.0; // [m, m/s] options_.projection_tolerance times max(1 m, l + r)
  bool assembled_ = false;
  double assembled_phi_ = 0.0;
};

KCrankModel::Impl::Impl(const Mechanism& m, ModelOptions options) : m_(m), options_(options) {
  checkModelInputs(m_, options_, "KCrankModel");

  // Simbody's rod pin and the pistons' sliders are free mobilities whose accelerations come from the mass
  // matrix: a rod without mass or without inertia about its wrist pin makes it singular (the answers were NaN).
  if (!(m_.rod.mass > 0.0 && m_.rod.inertia_about_wrist_pin > 0.0))
    throw std::invalid_argument(
        "KCrankModel: the Simbody model needs a rod with mass > 0 and inertia about the wrist pin > 0 (a massless "
        "rod makes Simbody's mass matrix singular)");

  k_ = m_.machine.cylinders;
  for (int j = 0; j < k_; ++j) {
    const double gamma_j = getBankAngle(m_, j);
    e_.emplace_back(std::cos(gamma_j), std::sin(gamma_j), 0.0);
    n_.emplace_back(-std::sin(gamma_j), std::cos(gamma_j), 0.0);
  }
  const double r = m_.crank.radius;
  const double l = m_.rod.length;
  // 2 eps (l + r): the closure is left at the rounding of the mechanism's size. At 8 eps, a projection whose last Newton
  // step from a near start (the Taylor start of assemble) ends just below it leaves up to 7.6 eps (l + r): at lambda =
  // 1e-6 (l + r = 50 km) 1e-9 of r omega^2 in a_p. Simbody's worst comparison over the campaign's cross-checks at each
  // threshold: bench/README.md, "Simbody's closure threshold".
  polish_threshold_ = 2.0 * std::numeric_limits<double>::epsilon() * (l + r);
  // Simbody's projections measure constraint errors in absolute units (m, m/s). A very long mechanism (a 50 km
  // rod at lambda = 1e-6) cannot close its loop to 1e-12 m: roundoff alone is eps l = 1e-11 m. The tolerance is
  // therefore relative to the mechanism's size, and never tighter than the absolute value for machines below 1 m.
  projection_tolerance_ = options_.projection_tolerance * std::max(1.0, l + r);

  try {
    // Gravity (0, -g): Simbody's potential energy has zero height at the Ground origin O.
    gravity_ = SimTK::Force::Gravity(forces_, matter_, SimTK::UnitVec3(0, -1, 0), m_.machine.gravity);

    MechanismBodies bodies = buildMechanismBodies(matter_, m_);
    crank_ = bodies.crank;
    SimTK::Motion::Custom(crank_, new CrankMotion(drive_));
    pistons_ = std::move(bodies.pistons);
    rods_ = std::move(bodies.rods);
    shafts_ = std::move(bodies.shafts);
    crank_pins_in_crank_ = std::move(bodies.crank_pins_in_crank);
    rod_big_end_in_rod_ = bodies.rod_big_end_in_rod;
    if (m_.gas) SimTK::Force::Custom(forces_, new GasForce(m_, drive_, matter_, crank_, pistons_));

    system_.realizeTopology();
    state_ = system_.getDefaultState();
    system_.realizeModel(state_);
    const double slide_step = BlockNewton::kStep * (m_.rod.length + m_.crank.radius);
    std::vector<BlockNewton::Block> blocks;
    for (int j = 0; j < k_; ++j)
      blocks.push_back({{pistons_[j].getFirstQIndex(state_), rods_[j].getFirstQIndex(state_)},
                        {pistons_[j].getFirstUIndex(state_), rods_[j].getFirstUIndex(state_)},
                        {slide_step, BlockNewton::kStep},
                        bodies.loops[j]});
    for (size_t i = 0; i < shafts_.size(); ++i)
      blocks.push_back({{shafts_[i].getFirstQIndex(state_)}, {shafts_[i].getFirstUIndex(state_)}, {BlockNewton::kStep},
                        bodies.couplers[i]});
    system_.realize(state_, SimTK::Stage::Instance);
    newton_ = std::make_unique<BlockNewton>(std::move(blocks), state_);
  } catch (const std::invalid_argument&) {
    throw;
  } catch (const std::exception& error) {
    throw std::runtime_error(std::string("KCrankModel: Simbody failed to build the system: ") + error.what());
  }

  assemble(0.0);
  system_.realize(state_, SimTK::Stage::Dynamics);
  reference_potential_ = system_.calcPotentialEnergy(state_);
}

void KCrankModel::Impl::setReferenceGuess() {
  // A crude, angle-independent starting configuration for the projection (not a solution): every piston at
  // x = l along e, every rod pointing back at O. Newton's method from here lands on the physical branch
  // (piston outside the crank circle), which assemble() checks.
  for (int j = 0; j < k_; ++j) {
    pistons_[j].setQ(state_, m_.rod.length);
    rods_[j].setQ(state_, 0.0);
  }
}

void KCrankModel::Impl::startAssemblyFrom(const Impl& donor) {
  if (&donor == this || !donor.assembled_) return;
  const Mechanism& d = donor.m_;
  // The coordinates depend on the geometry in each cylinder's own frame alone (theta_j = phi + alpha_j, r, l, delta_j).
  const bool same = d.machine.cylinders == m_.machine.cylinders && d.machine.crank_angles == m_.machine.crank_angles &&
                    d.crank.radius == m_.crank.radius && d.rod.length == m_.rod.length &&
                    d.machine.pin_offsets == m_.machine.pin_offsets && shafts_.size() == donor.shafts_.size();
  if (!same) return;
  for (int j = 0; j < k_; ++j) {
    pistons_[j].setQ(state_, donor.pistons_[j].getQ(donor.state_));
    rods_[j].setQ(state_, donor.rods_[j].getQ(donor.state_));
  }
  for (size_t i = 0; i < shafts_.size(); ++i) shafts_[i].setQ(state_, donor.shafts_[i].getQ(donor.state_));
  // The next assembly starts here (warm) and clears what was kept of the last angle; the donor's last dynamic pass at
  // this angle starts the velocity projection at the same speed (solveMotion).
  assembled_ = true;
  assembled_phi_ = donor.assembled_phi_;
  static_pass_.valid = false;
  unit_power_.valid = false;
  seeded_motion_ = donor.last_motion_.valid && donor.last_motion_.phi == donor.assembled_phi_ ? donor.last_motion_
                                                                                               : MotionStart{};
}

void KCrankModel::Impl::assemble(double phi) {
  if (!std::isfinite(phi)) throw std::invalid_argument("KCrankModel: crank angle phi must be finite");
  static_pass_.valid = false;
  // The start: near the last dynamic pass, its motion carried on to phi (below); else the previous solution when it is
  // near; else the crude guess.
  const double step = wrappedDifference(phi, assembled_phi_);  // [rad]
  const bool taylor = assembled_ && std::abs(step) <= kTaylorStartLimit && last_motion_.valid && last_motion_.phi == assembled_phi_;
  const bool warm = taylor || (assembled_ && std::abs(step) <= 1.0);
  if (!warm) setReferenceGuess();
  if (taylor) {
    // Near the last dynamic pass: the start is Simbody's own motion carried on to phi, q + qdot t + qdotdot t^2 / 2 with
    // t = step / omega (the crank turns at constant omega), not the q of the last angle: the projection then needs
    // about one Newton step where it needed two or three.
    const double t = step / last_motion_.omega;
    state_.updQ() += t * last_motion_.qdot + (0.5 * t * t) * last_motion_.qdotdot;
  }
  unit_power_.valid = false;
  newton_->invalidate();
  drive_->phi = phi;
  // u's are irrelevant to positions but zero them so nothing stale survives a failed attempt.
  state_.updU() = 0;
  state_.invalidateAllCacheAtOrAbove(SimTK::Stage::Time);

  auto physical = [&]() {
    for (const auto& piston : pistons_)
      if (!(piston.getQ(state_) > 0.0)) return false;
    return true;
  };
  // Prescribes crank q = phi and closes the loops, to roundoff: by the loops' own Newton on Simbody's errors (from
  // either start: from the crude one its Jacobian is computed again after each slow step, a full Newton), else (where
  // that does not converge or lands off the physical branch) by Simbody's projection from the same start
  // (model_support.h).
  auto project = [&]() {
    if (!options_.simbody_projections) {
      const SimTK::Vector start = state_.getQ();
      system_.realize(state_, SimTK::Stage::Time);
      system_.prescribeQ(state_);
      // Closed to 2 eps (l + r); stalled at rounding, accepted where Simbody's projection stops (RMS 0.1 tol).
      if (newton_->closePositions(system_, state_, polish_threshold_, 0.1 * projection_tolerance_) && physical())
        return;
      state_.updQ() = start;
      newton_->invalidate();
      state_.invalidateAllCacheAtOrAbove(SimTK::Stage::Time);
    }
    projectPositions(system_, state_, projection_tolerance_, polish_threshold_);
  };
  try {
    project();
    if (!physical()) {
      if (!warm) throw std::runtime_error("assembly converged on the unphysical branch (piston inside the crank)");
      setReferenceGuess();
      state_.invalidateAllCacheAtOrAbove(SimTK::Stage::Time);
      project();
      if (!physical())
        throw std::runtime_error("assembly converged on the unphysical branch (piston inside the crank)");
    }
  } catch (const std::exception& error) {
    assembled_ = false;
    throw std::runtime_error("KCrankModel: Simbody could not assemble the mechanism at phi = " +
                             std::to_string(phi) + " rad: " + error.what());
  }
  assembled_ = true;
  assembled_phi_ = phi;
}

void KCrankModel::Impl::solveMotion(double omega) {
  drive_->omega = omega;
  if (omega != 0.0 && seeded_motion_.valid && seeded_motion_.phi == assembled_phi_ && seeded_motion_.omega == omega) {
    state_.updU() = seeded_motion_.u;  // a donor's solution (startAssemblyFrom): the projection has nothing to iterate
    seeded_motion_.valid = false;
  }
  // The prescribed qdot is evaluated at Stage::Position: invalidate it (the q's stay as assembled).
  state_.invalidateAllCacheAtOrAbove(SimTK::Stage::Position);
  // The velocities' errors are differences of terms of about r omega (the crank pin's, the slide's, the rod's swing
  // about its far end): solved to 2 eps r |omega|, their rounding, with the assembly's Jacobian when it was computed
  // within 1e-6 (l + r) of closure (its relative error then about 1e-6: three steps at most).
  auto solveVelocitiesByNewton = [&]() {
    system_.realize(state_, SimTK::Stage::Position);
    system_.prescribeU(state_);
    return newton_->solveVelocities(system_, state_,
                                    2.0 * std::numeric_limits<double>::epsilon() * m_.crank.radius * std::abs(omega),
                                    0.1 * projection_tolerance_, 1e-6 * (m_.rod.length + m_.crank.radius));
  };
  try {
    // Prescribes crank u = omega and solves the rest: by the loops' Newton, else by Simbody's projection.
    if (options_.simbody_projections) {
      system_.projectU(state_, projection_tolerance_);
    } else if (!solveVelocitiesByNewton()) {
      state_.updU() = 0;  // Simbody's projection from rest (the Newton's u may be anywhere)
      system_.projectU(state_, projection_tolerance_);
    }
    system_.realize(state_, SimTK::Stage::Acceleration);
  } catch (const std::exception& error) {
    throw std::runtime_error("KCrankModel: Simbody failed to solve the motion at phi = " +
                             std::to_string(drive_->phi) + " rad: " + error.what());
  }
  last_residual_omega_ = omega;
  if (omega != 0.0) {
    unit_power_ = {true, assembled_phi_, calcGravityPower(matter_, gravity_, state_) / omega};
    last_motion_.valid = true;  // fields assigned, so that u's storage is reused at every pass
    last_motion_.phi = assembled_phi_;
    last_motion_.omega = omega;
    last_motion_.u = state_.getU();
    last_motion_.qdot = state_.getQDot();
    last_motion_.qdotdot = state_.getQDotDot();
  }
}

double KCrankModel::Impl::calcLoopAccelerationResidual() const {
  const SimTK::Vector& error = state_.getUDotErr();
  double worst = 0.0;
  for (int i = 0; i < error.size(); ++i) worst = std::max(worst, std::abs(error[i]));
  const double omega = last_residual_omega_;
  return worst / (m_.crank.radius * omega * omega + std::abs(m_.machine.gravity));
}

double KCrankModel::Impl::driveTorque() const {
  // tau is the generalized force Simbody's equations carry on the left-hand side with the multipliers
  // (M udot + tau + ~G lambda = f), i.e. minus the torque the drive applies to the crank.
  return -crank_.getOneTau(state_, SimTK::MobilizerUIndex(0));
}


SimTK::SpatialVec KCrankModel::Impl::momentumRate(const SimTK::MobilizedBody& body) const {
  const SimTK::MassProperties& mp = body.getBodyMassProperties(state_);
  const SimTK::Rotation& R_GB = body.getBodyRotation(state_);
  const SimTK::Vec3 p_GC = body.findStationLocationInGround(state_, mp.getMassCenter());
  const SimTK::Vec3 a_GC = body.findStationAccelerationInGround(state_, mp.getMassCenter());
  const SimTK::Vec3& w = body.getBodyAngularVelocity(state_);
  const SimTK::Vec3& w_dot = body.getBodyAngularAcceleration(state_);
  // Central inertia re-expressed in Ground: I_G = R_GB I_B R_BG.
  const SimTK::Inertia I_C = mp.calcCentralInertia().reexpress(~R_GB);
  const SimTK::Vec3 force = mp.getMass() * a_GC;
  const SimTK::Vec3 moment = SimTK::cross(p_GC, force) + I_C * w_dot + SimTK::cross(w, I_C * w);
  return SimTK::SpatialVec(moment, force);
}

BodyKinematics KCrankModel::Impl::bodyKinematics(const SimTK::MobilizedBody& body) const {
  BodyKinematics b;
  const SimTK::MassProperties& mp = body.getBodyMassProperties(state_);
  b.mass = mp.getMass();
  const SimTK::Vec3 com_in_body = mp.getMassCenter();
  b.inertia_about_com = mp.calcCentralInertia().getMoments()[2];  // Z axis, body Z = global Z
  b.com = toVec2(body.findStationLocationInGround(state_, com_in_body));
  b.com_acceleration = toVec2(body.findStationAccelerationInGround(state_, com_in_body));
  b.angular_acceleration = body.getBodyAngularAcceleration(state_)[2];
  return b;
}

void KCrankModel::Impl::readMotion(Evaluation& ev, SimTK::Vector_<SimTK::SpatialVec>& reactions) const {
  ev.drive_torque = driveTorque();

  // Mobilizer reactions: force ON the child FROM its parent, at the child's M origin, in Ground.
  matter_.calcMobilizerReactionForces(state_, reactions);
  // Constraint forces as applied forces (negated multipliers), at each body's origin, in Ground.
  SimTK::Vector_<SimTK::SpatialVec> constraint_body_forces;
  SimTK::Vector constraint_mobility_forces;
  matter_.calcConstraintForcesFromMultipliers(state_, -matter_.getConstraintMultipliers(state_),
                                              constraint_body_forces, constraint_mobility_forces);

  // Crank mobilizer M origin is O: its reaction force is the bearing on the crankshaft.
  ev.bearing_force = toVec2(reactions[crank_.getMobilizedBodyIndex()][1]);
  ev.cylinders.resize(k_);
  for (int j = 0; j < k_; ++j) {
    const auto& piston = pistons_[j];
    const auto& rod = rods_[j];
    CylinderEvaluation& c = ev.cylinders[j];
    c.x_p = piston.getQ(state_);
    c.v_p = piston.getU(state_);
    c.a_p = piston.getUDot(state_);
    // The only constraint acting on rod j is its loop closure; it acts at the crank pin (a force, no moment
    // there), reported as a force at the rod origin A plus the moment (B - A) x F. The force is what we need.
    c.crank_pin_force = toVec2(constraint_body_forces[rod.getMobilizedBodyIndex()][1]);
    // Rod reaction is on the rod from the piston; the piston gets the opposite.
    const SimTK::Vec3 piston_on_rod = reactions[rod.getMobilizedBodyIndex()][1];
    c.wrist_pin_force = toVec2(-piston_on_rod);
    const SimTK::Vec3 frame_on_piston = reactions[piston.getMobilizedBodyIndex()][1];
    c.wall_force = SimTK::dot(frame_on_piston, n_[j]);
    c.gas_force = calcGasForce(m_, j, crank_.getQ(state_));  // the input, at Simbody's crank angle
    // The rod's pin angle q turns the rod from pointing at O (-e): B - A = l (-cos q, -sin q), so beta = -q, reduced
    // to (-pi, pi] (the pin's q may have gathered whole turns during assembly).
    c.rod_angle = wrappedDifference(-rod.getQ(state_), 0.0);
    c.rod_omega = -rod.getU(state_);
    c.rod_alpha = -rod.getUDot(state_);
  }

  // Shaking force and moment, -dP/dt and -dH_O/dt of every moving body, from Simbody's own body accelerations
  // (the accelerations are those of the prescribed constant-speed motion, with or without gravity).
  SimTK::SpatialVec rate(SimTK::Vec3(0), SimTK::Vec3(0));
  rate += momentumRate(crank_);
  for (int j = 0; j < k_; ++j) rate += momentumRate(pistons_[j]) + momentumRate(rods_[j]);
  for (const SimTK::MobilizedBody::Pin& shaft : shafts_) rate += momentumRate(shaft);
  ev.shaking_force = {-rate[1][0], -rate[1][1]};
  ev.shaking_moment = {-rate[0][0], -rate[0][1], -rate[0][2]};
}

Evaluation KCrankModel::Impl::evaluateAt(double phi, Diagnostics* diagnostics, bool motion_only) {
  Evaluation ev;
  ev.engine = "simbody";
  ev.phi = phi;
  const double omega = m_.machine.speed;
  if (motion_only && diagnostics == nullptr) {
    // The dynamic pass alone, from the assembled positions and zero velocities, as evaluate()'s after its static pass
    // (which leaves u = 0: at rest the velocities project to zero). The assembly as evaluate()'s: reused where its
    // static pass was made at this angle, else made.
    ev.U = ev.Q = std::numeric_limits<double>::quiet_NaN();
    if (!(static_pass_.valid && static_pass_.phi == phi)) assemble(phi);
    state_.updU() = 0;
    solveMotion(omega);
    SimTK::Vector_<SimTK::SpatialVec> reactions;
    readMotion(ev, reactions);
    return checkFinite(ev, false);
  }
  // Without a gas force the dynamic pass at rest solves the very problem of the static pass (omega = 0, gravity
  // alone): its evaluation is the static pass's, read off the same solved state, not solved a second time.
  const bool rest_is_static = omega == 0.0 && !m_.gas && diagnostics == nullptr;

  double position_error = 0.0;
  if (static_pass_.valid && static_pass_.phi == phi && diagnostics == nullptr) {
    // Assembled at this angle by the last evaluation, its static pass done: only the speed differs. The velocities
    // start from zero as after an assembly, so the dynamic pass below computes what it computes after one.
    if (rest_is_static && static_pass_.at_rest_valid) return static_pass_.at_rest;
    ev.U = static_pass_.U;
    ev.Q = static_pass_.Q;
    position_error = static_pass_.position_error;
    state_.updU() = 0;
  } else {
    assemble(phi);
    position_error = calcMaxAbs(state_.getQErr());

    // Static pass (omega = 0, gas off): the holding torque is Q, route 1.
    drive_->gas = false;
    try {
      solveMotion(0.0);
    } catch (...) {
      drive_->gas = true;
      throw;
    }
    drive_->gas = true;
    ev.U = system_.calcPotentialEnergy(state_) - reference_potential_;
    ev.Q = driveTorque();
    static_pass_ = {true, phi, ev.U, ev.Q, position_error, false, {}};
    if (!m_.gas && diagnostics == nullptr) {
      // The at-rest evaluation, kept for the same angle's evaluation at rest (the cross-check's second speed).
      SimTK::Vector_<SimTK::SpatialVec> reactions;
      static_pass_.at_rest = ev;
      readMotion(static_pass_.at_rest, reactions);
      static_pass_.at_rest_valid = true;
      if (rest_is_static) return checkFinite(static_pass_.at_rest);
    }
  }

  // Dynamic pass at the scene's omega (also at omega = 0 with gas, so the two passes stay independent computations).
  solveMotion(omega);
  SimTK::Vector_<SimTK::SpatialVec> reactions;
  readMotion(ev, reactions);
  checkFinite(ev);

  if (diagnostics != nullptr) {
    Diagnostics& d = *diagnostics;
    d.omega = omega;
    d.kinetic_energy = system_.calcKineticEnergy(state_);
    d.potential_energy = system_.calcPotentialEnergy(state_);
    d.crankshaft = bodyKinematics(crank_);
    d.position_constraint_error = position_error;
    d.velocity_constraint_error = calcMaxAbs(state_.getUErr());
    d.cylinders.resize(k_);
    for (int j = 0; j < k_; ++j) {
      CylinderDiagnostics& c = d.cylinders[j];
      c.piston = bodyKinematics(pistons_[j]);
      c.rod = bodyKinematics(rods_[j]);
      c.wrist_pin = toVec2(pistons_[j].getBodyOriginLocation(state_));
      c.crank_pin = toVec2(crank_.findStationLocationInGround(state_, crank_pins_in_crank_[j]));
      c.rod_big_end = toVec2(rods_[j].findStationLocationInGround(state_, rod_big_end_in_rod_));
      const SimTK::SpatialVec& slider = reactions[pistons_[j].getMobilizedBodyIndex()];
      c.slider_reaction = toVec2(slider[1]);
      c.slider_reaction_moment = slider[0][2];
    }
    d.evaluation = ev;
  }
  return ev;
}

double KCrankModel::Impl::potentialEnergy(double phi) {
  assemble(phi);
  system_.realize(state_, SimTK::Stage::Dynamics);
  return system_.calcPotentialEnergy(state_) - reference_potential_;
}

double KCrankModel::Impl::kineticEnergy(double phi) {
  assemble(phi);
  drive_->omega = m_.machine.speed;
  state_.invalidateAllCacheAtOrAbove(SimTK::Stage::Position);
  system_.projectU(state_, projection_tolerance_);
  system_.realize(state_, SimTK::Stage::Dynamics);
  return system_.calcKineticEnergy(state_);
}

double KCrankModel::Impl::holdingTorque(double phi) {
  assemble(phi);
  drive_->gas = false;  // Q is gravity's alone
  try {
    solveMotion(0.0);
  } catch (...) {
    drive_->gas = true;
    throw;
  }
  drive_->gas = true;
  return driveTorque();
}

double KCrankModel::Impl::virtualPowerQ(double phi) {
  // Power of gravity = -dV/dt = -Q dphi/dt: per unit crank speed, -Q.
  if (assembled_ && assembled_phi_ == phi && unit_power_.valid && unit_power_.phi == phi) return -unit_power_.power;
  assemble(phi);
  // Unit crank speed: every body's velocity is then its velocity per unit dphi/dt.
  drive_->omega = 1.0;
  state_.invalidateAllCacheAtOrAbove(SimTK::Stage::Position);
  system_.projectU(state_, projection_tolerance_);
  system_.realize(state_, SimTK::Stage::Velocity);
  const double power = calcGravityPower(matter_, gravity_, state_);
  // Power of gravity = -dV/dt = -Q dphi/dt with dphi/dt = 1.
  return -power;
}

KCrankModel::KCrankModel(const Mechanism& m, ModelOptions options)
    : impl_(std::make_unique<Impl>(m, options)) {}
KCrankModel::~KCrankModel() = default;
KCrankModel::KCrankModel(KCrankModel&&) noexcept = default;
KCrankModel& KCrankModel::operator=(KCrankModel&&) noexcept = default;

Evaluation KCrankModel::evaluate(double phi) { return impl_->evaluateAt(phi, nullptr); }
Evaluation KCrankModel::evaluateMotion(double phi) { return impl_->evaluateAt(phi, nullptr, true); }
void KCrankModel::startAssemblyFrom(const KCrankModel& donor) { impl_->startAssemblyFrom(*donor.impl_); }
void KCrankModel::setSpeed(double omega) { impl_->setSpeed(omega); }

double KCrankModel::calcLoopAccelerationResidual(double phi, double omega) {
  const double speed = impl_->mechanism().machine.speed;
  impl_->setSpeed(omega);
  try {
    impl_->evaluateAt(phi, nullptr, true);
  } catch (...) {
    impl_->setSpeed(speed);
    throw;
  }
  const double residual = impl_->calcLoopAccelerationResidual();
  impl_->setSpeed(speed);
  return residual;
}

Diagnostics KCrankModel::calcDiagnostics(double phi) {
  Diagnostics d;
  impl_->evaluateAt(phi, &d);
  return d;
}

double KCrankModel::calcPotentialEnergy(double phi) { return impl_->potentialEnergy(phi); }
double KCrankModel::calcKineticEnergy(double phi) { return impl_->kineticEnergy(phi); }
double KCrankModel::calcHoldingTorque(double phi) { return impl_->holdingTorque(phi); }
double KCrankModel::calcVirtualPowerQ(double phi) { return impl_->virtualPowerQ(phi); }

double KCrankModel::calcQByCentralDifference(double phi, double h) {
  if (!(std::isfinite(h) && h > 0.0))
    throw std::invalid_argument("KCrankModel::calcQByCentralDifference: step h must be finite and > 0");
  const double up = impl_->potentialEnergy(phi + h);
  const double down = impl_->potentialEnergy(phi - h);
  return (up - down) / (2.0 * h);
}

const Mechanism& KCrankModel::mechanism() const { return impl_->mechanism(); }

std::string getSimbodyVersion() {
  int major = 0, minor = 0, build = 0;
  SimTK_version_simbody(&major, &minor, &build);
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(build);
}

}  // namespace crankcheck::simbody_models
