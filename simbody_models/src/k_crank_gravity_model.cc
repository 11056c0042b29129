// The reduced Simbody model for U and Q (k_crank_gravity_model.h). Never compiled with NDEBUG.
#include "crankcheck/simbody_models/k_crank_gravity_model.h"

#include <Simbody.h>

#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "block_newton.h"
#include "model_support.h"
#include "crankcheck/scene/scene_file.h"

#ifdef NDEBUG
#error "Simbody code must not be compiled with NDEBUG: Debian's Simbody was built without it (SIMBODY-NOTES.md)"
#endif

namespace crankcheck::simbody_models {

class KCrankGravityModel::Impl {
 public:
  Impl(const Mechanism& m, ModelOptions options) : m_(m) {
    checkModelInputs(m_, options, "KCrankGravityModel");
    if (!isSingleBank(m_))
      throw std::invalid_argument("KCrankGravityModel: the reduced model is built for one bank of cylinders (one gamma)");
    if (!m_.balance_shafts.empty())
      throw std::invalid_argument("KCrankGravityModel: the reduced model has no balance shafts; use KCrankModel");
    const double r = m_.crank.radius, l = m_.rod.length, z = m_.rod.com_from_wrist_pin;
    const double wrist_mass = m_.piston.mass + m_.rod.mass * (l - z) / l;   // rod mass whose first moment...
    const double crank_pin_mass = m_.rod.mass * z / l;                      // ...about A equals the rod's
    if (!(wrist_mass > 0.0))
      throw std::invalid_argument("KCrankGravityModel: the piston with its share of the rod has no mass; use KCrankModel");
    tolerance_ = options.projection_tolerance * std::max(1.0, l + r);  // as KCrankModel: relative above 1 m
    simbody_projections_ = options.simbody_projections;
    const double gamma = m_.machine.cylinder_angle;

    gravity_ = SimTK::Force::Gravity(forces_, matter_, SimTK::UnitVec3(0, -1, 0), m_.machine.gravity);
    SimTK::Real crank_mass = 0.0;
    SimTK::Vec3 first_moment(0);
    SimTK::Inertia crank_inertia(0);
    std::vector<SimTK::Vec3>& pins = pins_;
    for (double alpha : m_.machine.crank_angles) {
      const SimTK::Vec3 u(std::cos(alpha), std::sin(alpha), 0.0);
      pins.push_back(r * u);
      const SimTK::Vec3 p_s = m_.crank.com_radius * u, p_p = -m_.crank.counterweight_radius * u, p_b = r * u;
      crank_mass += m_.crank.mass + m_.crank.counterweight_mass + crank_pin_mass;
      first_moment += m_.crank.mass * p_s + m_.crank.counterweight_mass * p_p + crank_pin_mass * p_b;
      crank_inertia += SimTK::Inertia(p_s, m_.crank.mass) + SimTK::Inertia(p_p, m_.crank.counterweight_mass) +
                       SimTK::Inertia(p_b, crank_pin_mass);
    }
    const SimTK::Rotation cylinder_rotation(gamma, SimTK::ZAxis);
    crank_ = SimTK::MobilizedBody::Pin(
        matter_.Ground(), SimTK::Transform(cylinder_rotation, SimTK::Vec3(0)),
        SimTK::Body::Rigid(SimTK::MassProperties(crank_mass, crank_mass > 0 ? first_moment / crank_mass : SimTK::Vec3(0),
                                                 crank_inertia)),
        SimTK::Transform());
    SimTK::Motion::Custom(crank_, new CrankMotion(drive_));
    const SimTK::Body::Rigid piston_body(SimTK::MassProperties(wrist_mass, SimTK::Vec3(0), SimTK::Inertia(0)));
    for (size_t j = 0; j < pins.size(); ++j) {
      // the wrist pin on x_p e + delta_j n (the pin offset)
      const double delta_j = getPinOffset(m_, static_cast<int>(j));
      pistons_.emplace_back(matter_.Ground(),
                            SimTK::Transform(cylinder_rotation, SimTK::Vec3(-delta_j * std::sin(gamma), delta_j * std::cos(gamma), 0.0)),
                            piston_body, SimTK::Transform());
      rods_.emplace_back(crank_, pins[j], pistons_.back(), SimTK::Vec3(0), l);  // |B_j - A_j| = l: 1 equation
    }
    system_.realizeTopology();
    state_ = system_.getDefaultState();
    system_.realize(state_, SimTK::Stage::Instance);
    // Near a known solution the rods are closed by Newton's method on Simbody's own errors (block_newton.h): rod j's
    // one equation involves piston j's slide alone (the crank is prescribed).
    std::vector<BlockNewton::Block> blocks;
    for (size_t j = 0; j < pistons_.size(); ++j)
      blocks.push_back({{pistons_[j].getFirstQIndex(state_)}, {pistons_[j].getFirstUIndex(state_)},
                        {BlockNewton::kStep * (l + r)}, rods_[j]});
    newton_ = std::make_unique<BlockNewton>(std::move(blocks), state_);
    assemble(0.0);
    system_.realize(state_, SimTK::Stage::Dynamics);
    reference_potential_ = system_.calcPotentialEnergy(state_);
  }

  void assemble(double phi) {
    if (!std::isfinite(phi)) throw std::invalid_argument("KCrankGravityModel: crank angle phi must be finite");
    drive_->phi = phi;
    drive_->omega = 0.0;
    // Warm start from the previous solution when near; if that lands on the wrong branch (possible near the toggle
    // positions of lambda -> 1, where both roots of the loop closure are close), start again from x = l + r cos theta,
    // from which Newton's iteration on the convex closure equation can only reach the physical root.
    const bool warm = assembled_ && std::abs(std::remainder(phi - assembled_phi_, 2.0 * SimTK::Pi)) <= 1.0;
    if (!(warm && ((!simbody_projections_ && closeByNewton()) || project()) && physical())) {
      for (size_t j = 0; j < pistons_.size(); ++j)
        pistons_[j].setQ(state_, m_.rod.length + m_.crank.radius * std::cos(phi + m_.machine.crank_angles[j]));
      if (!((!simbody_projections_ && closeByNewton()) || (project() && physical()))) {
        assembled_ = false;
        throw std::runtime_error("KCrankGravityModel: Simbody could not assemble the physical branch at phi = " +
                                 std::to_string(phi) + (error_.empty() ? "" : ": " + error_));
      }
    }
    assembled_ = true;
    assembled_phi_ = phi;
  }

  // The rods closed by the blocks' Newton from the current start (to the polish threshold; stalled at rounding,
  // accepted where Simbody's projection stops) onto the physical branch; false (the start restored) otherwise.
  bool closeByNewton() {
    state_.updU() = 0;
    state_.invalidateAllCacheAtOrAbove(SimTK::Stage::Time);
    const SimTK::Vector start = state_.getQ();
    system_.realize(state_, SimTK::Stage::Time);
    system_.prescribeQ(state_);
    if (newton_->closePositions(system_, state_, polishThreshold(), 0.1 * tolerance_) && physical()) return true;
    state_.updQ() = start;
    return false;
  }
  double polishThreshold() const {
    return 8.0 * std::numeric_limits<double>::epsilon() * (m_.rod.length + m_.crank.radius);
  }

  // Projects the positions; false (with error_ set) if Simbody could not.
  bool project() {
    state_.updU() = 0;
    state_.invalidateAllCacheAtOrAbove(SimTK::Stage::Time);
    try {
      projectPositions(system_, state_, tolerance_, polishThreshold());
    } catch (const std::exception& e) {
      error_ = e.what();
      return false;
    }
    return true;
  }

  // The physical branch: each wrist pin lies beyond its crank pin along the cylinder axis (x_p - r cos theta > 0).
  bool physical() {
    system_.realize(state_, SimTK::Stage::Position);
    const double gamma = m_.machine.cylinder_angle;
    const SimTK::Vec3 e(std::cos(gamma), std::sin(gamma), 0.0);
    for (size_t j = 0; j < pistons_.size(); ++j) {
      const double crank_pin_along_e = SimTK::dot(crank_.findStationLocationInGround(state_, pins_[j]), e);
      if (!(pistons_[j].getQ(state_) - crank_pin_along_e > 0.0)) return false;
    }
    return true;
  }

  double potentialEnergy(double phi) {
    assemble(phi);
    system_.realize(state_, SimTK::Stage::Dynamics);
    return system_.calcPotentialEnergy(state_) - reference_potential_;
  }

  double holdingTorque(double phi) {
    assemble(phi);  // leaves every u = 0 and the crank's prescribed speed 0: the velocity constraints hold exactly
    system_.realize(state_, SimTK::Stage::Acceleration);
    return -crank_.getOneTau(state_, SimTK::MobilizerUIndex(0));  // tau is minus the drive's torque
  }

  double virtualPowerQ(double phi) {
    assemble(phi);
    drive_->omega = 1.0;
    state_.invalidateAllCacheAtOrAbove(SimTK::Stage::Position);
    system_.projectU(state_, tolerance_);
    system_.realize(state_, SimTK::Stage::Velocity);
    const double power = calcGravityPower(matter_, gravity_, state_);
    drive_->omega = 0.0;
    return -power;
  }

 private:
  Mechanism m_;
  double tolerance_ = 0.0;
  bool simbody_projections_ = false;  // ModelOptions::simbody_projections
  std::shared_ptr<CrankDrive> drive_ = std::make_shared<CrankDrive>();
  SimTK::MultibodySystem system_;
  SimTK::SimbodyMatterSubsystem matter_{system_};
  SimTK::GeneralForceSubsystem forces_{system_};
  SimTK::Force::Gravity gravity_;
  SimTK::MobilizedBody::Pin crank_;
  std::vector<SimTK::MobilizedBody::Slider> pistons_;
  std::vector<SimTK::Constraint::Rod> rods_;
  std::unique_ptr<BlockNewton> newton_;
  std::vector<SimTK::Vec3> pins_;  // B_j in the crankshaft frame
  std::string error_;              // Simbody's message of the last failed projection
  SimTK::State state_;
  double reference_potential_ = 0.0;
  bool assembled_ = false;
  double assembled_phi_ = 0.0;
};

KCrankGravityModel::KCrankGravityModel(const Mechanism& m, ModelOptions options)
    : impl_(std::make_unique<Impl>(m, options)) {}
KCrankGravityModel::~KCrankGravityModel() = default;
KCrankGravityModel::KCrankGravityModel(KCrankGravityModel&&) noexcept = default;
KCrankGravityModel& KCrankGravityModel::operator=(KCrankGravityModel&&) noexcept = default;
double KCrankGravityModel::calcPotentialEnergy(double phi) { return impl_->potentialEnergy(phi); }
double KCrankGravityModel::calcHoldingTorque(double phi) { return impl_->holdingTorque(phi); }
double KCrankGravityModel::calcVirtualPowerQ(double phi) { return impl_->virtualPowerQ(phi); }

}  // namespace crankcheck::simbody_models
