#pragma once
// Internal to simbody_models: what the models share (the mechanism's bodies, built once for the full model and the
// free run; the prescribed crank motion; the position projection; gravity's power).
// Include only from Simbody translation units (never compiled with NDEBUG).

#include <Simbody.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "crankcheck/scene/evaluation.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/simbody_models/k_crank_model.h"

namespace crankcheck::simbody_models {
namespace {

/// What the crank mobilizer is told to do: angle phi [rad] and constant speed omega [rad/s].
struct CrankDrive {
  double phi = 0.0;
  double omega = 0.0;
  bool gas = true;  ///< whether GasForce applies the scene's gas force (off for the static holding torque Q)
};

/// Position-level prescribed motion of the crank: q = phi, qdot = omega, qdotdot = 0. The values live in a
/// CrankDrive owned by the model; whoever changes them must invalidate the state's cache (phi: Stage::Time, where
/// Simbody evaluates the prescribed q; omega: Stage::Position, where it evaluates the prescribed qdot).
class CrankMotion : public SimTK::Motion::Custom::Implementation {
 public:
  explicit CrankMotion(std::shared_ptr<const CrankDrive> drive) : drive_(std::move(drive)) {}
  Implementation* clone() const override { return new CrankMotion(*this); }
  SimTK::Motion::Level getLevel(const SimTK::State&) const override { return SimTK::Motion::Position; }
  void calcPrescribedPosition(const SimTK::State&, int nq, SimTK::Real* q) const override {
    if (nq != 1) throw std::logic_error("CrankMotion: the crank pin has one q");
    q[0] = drive_->phi;
  }
  void calcPrescribedPositionDot(const SimTK::State&, int nq, SimTK::Real* qdot) const override {
    if (nq != 1) throw std::logic_error("CrankMotion: the crank pin has one q");
    qdot[0] = drive_->omega;
  }
  void calcPrescribedPositionDotDot(const SimTK::State&, int nq, SimTK::Real* qdotdot) const override {
    if (nq != 1) throw std::logic_error("CrankMotion: the crank pin has one q");
    qdotdot[0] = 0.0;
  }

 private:
  std::shared_ptr<const CrankDrive> drive_;
};

Vec2 toVec2(const SimTK::Vec3& v) { return {v[0], v[1]}; }

/// The gas force on every piston (scene/gas.h, an input every engine applies alike): -p A e_j at the wrist pin, with p
/// taken at the crank angle the crank mobilizer has in the state (q = phi). A station force on the piston body, so
/// the slider's reaction stays the wall's; the equal force on the cylinder head stays in the frame.
class GasForce : public SimTK::Force::Custom::Implementation {
 public:
  GasForce(const Mechanism& m, std::shared_ptr<const CrankDrive> drive, const SimTK::SimbodyMatterSubsystem& matter,
           const SimTK::MobilizedBody::Pin& crank, const std::vector<SimTK::MobilizedBody::Slider>& pistons)
      : m_(m), drive_(std::move(drive)), matter_(matter), crank_(crank), pistons_(pistons) {}
  void calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& body_forces,
                 SimTK::Vector_<SimTK::Vec3>&, SimTK::Vector&) const override {
    if (!drive_->gas) return;
    const double phi = crank_.getQ(state);
    for (size_t j = 0; j < pistons_.size(); ++j) {
      const double gamma_j = getBankAngle(m_, static_cast<int>(j));
      const SimTK::Vec3 e_j(std::cos(gamma_j), std::sin(gamma_j), 0.0);
      matter_.addInStationForce(state, pistons_[j].getMobilizedBodyIndex(), SimTK::Vec3(0),
                                -calcGasForce(m_, static_cast<int>(j), phi) * e_j, body_forces);
    }
  }
  SimTK::Real calcPotentialEnergy(const SimTK::State&) const override { return 0.0; }  // not conservative

 private:
  Mechanism m_;
  std::shared_ptr<const CrankDrive> drive_;
  const SimTK::SimbodyMatterSubsystem& matter_;
  SimTK::MobilizedBody::Pin crank_;
  std::vector<SimTK::MobilizedBody::Slider> pistons_;
};

/// The mobilized bodies of the mechanism (k_crank_model.h describes them) and the stations of its loop closures.
struct MechanismBodies {
  SimTK::MobilizedBody::Pin crank;
  std::vector<SimTK::MobilizedBody::Slider> pistons;
  std::vector<SimTK::MobilizedBody::Pin> rods;
  std::vector<SimTK::Vec3> crank_pins_in_crank;  // B_j in the crankshaft body frame
  SimTK::Vec3 rod_big_end_in_rod;                // B in the rod body frame
  std::vector<SimTK::MobilizedBody::Pin> shafts; // the balance shafts, geared to the crank by coupler constraints
  std::vector<SimTK::Constraint::PointOnLine> loops;           // loop j's closure (2 equations: piston j, rod j)
  std::vector<SimTK::Constraint::CoordinateCoupler> couplers;  // shaft i's gearing (1 equation: shaft i)
};

/// Builds the crankshaft (a 3D body: throw j's point masses and crank pin in the plane z_j of its cylinder, plus
/// `shaft_inertia` about O, e.g. the flywheel), one piston per cylinder on a slider along its own bank e_j in the
/// plane z_j, one rod per piston on a pin at the wrist pin, and the loop closures (Constraint::PointOnLine). The
/// crankshaft's mobilizer frame is turned by gamma_0 (cylinder 0's bank), so its pin angle q is phi; cylinder j's
/// crank pin sits at beta_j - gamma_0 in the body (alpha_j for an inline engine). Every layout, one construction.
MechanismBodies buildMechanismBodies(SimTK::SimbodyMatterSubsystem& matter, const Mechanism& m,
                                     const SimTK::Inertia& shaft_inertia = SimTK::Inertia(0)) {
  MechanismBodies b;
  const int k = m.machine.cylinders;
  const double r = m.crank.radius, l = m.rod.length, gamma = m.machine.cylinder_angle;
  SimTK::Real crank_mass = 0.0;
  SimTK::Vec3 first_moment(0);
  SimTK::Inertia crank_inertia = shaft_inertia;  // about the body origin O
  for (int j = 0; j < k; ++j) {
    const double pin_angle = (getBankAngle(m, j) - gamma) + m.machine.crank_angles[j];
    const SimTK::Vec3 u(std::cos(pin_angle), std::sin(pin_angle), 0.0), z(0.0, 0.0, getAxialPosition(m, j));
    b.crank_pins_in_crank.push_back(r * u + z);
    const SimTK::Vec3 p_s = m.crank.com_radius * u + z;
    const SimTK::Vec3 p_p = -m.crank.counterweight_radius * u + z;
    crank_mass += m.crank.mass + m.crank.counterweight_mass;
    first_moment += m.crank.mass * p_s + m.crank.counterweight_mass * p_p;
    crank_inertia += SimTK::Inertia(p_s, m.crank.mass) + SimTK::Inertia(p_p, m.crank.counterweight_mass);
  }
  // A prescribed crank needs no nominal inertia: Simbody never divides by it (a crankshaft without mass works).
  const SimTK::Body::Rigid crank_body(SimTK::MassProperties(
      crank_mass, crank_mass > 0.0 ? first_moment / crank_mass : SimTK::Vec3(0), crank_inertia));
  b.crank = SimTK::MobilizedBody::Pin(matter.Ground(), SimTK::Transform(SimTK::Rotation(gamma, SimTK::ZAxis), SimTK::Vec3(0)),
                                      crank_body, SimTK::Transform());

  // Rod body frame = its mobilizer frame M, origin at the wrist pin A. At rod pin angle 0 the rod points along -x
  // of the piston frame (from A toward O): big end at (-l, 0, 0), centre of mass at (-z_k, 0, 0); central inertia
  // about Z (and about the in-plane axis normal to the rod), zero about the rod axis.
  b.rod_big_end_in_rod = SimTK::Vec3(-l, 0, 0);
  const double z_k = m.rod.com_from_wrist_pin, m_k = m.rod.mass;
  const double rod_central = std::max(0.0, m.rod.inertia_about_wrist_pin - m_k * z_k * z_k);
  const SimTK::Vec3 rod_com(-z_k, 0, 0);
  const SimTK::Body::Rigid rod_body(
      SimTK::MassProperties(m_k, rod_com, SimTK::Inertia(0.0, rod_central, rod_central) + SimTK::Inertia(rod_com, m_k)));
  const SimTK::Body::Rigid piston_body(SimTK::MassProperties(m.piston.mass, SimTK::Vec3(0), SimTK::Inertia(0)));
  for (int j = 0; j < k; ++j) {
    // Piston: slider along the x axis of F = Ground turned by gamma_j and moved to z_j and by the pin offset delta_j
    // along n_j, so the wrist pin is at x_p e_j + delta_j n_j with q = x_p.
    const double gamma_j = getBankAngle(m, j), delta_j = getPinOffset(m, j);
    const SimTK::Transform X_GF(SimTK::Rotation(gamma_j, SimTK::ZAxis),
                                SimTK::Vec3(-delta_j * std::sin(gamma_j), delta_j * std::cos(gamma_j), getAxialPosition(m, j)));
    b.pistons.emplace_back(matter.Ground(), X_GF, piston_body, SimTK::Transform());
    b.rods.emplace_back(b.pistons.back(), SimTK::Transform(), rod_body, SimTK::Transform());
    // Loop closure: the rod's big end on the line through B_j parallel to Z (2 equations, planar).
    b.loops.emplace_back(b.crank, SimTK::UnitVec3(SimTK::ZAxis), b.crank_pins_in_crank[j], b.rods.back(),
                         b.rod_big_end_in_rod);
  }
  // Balance shafts: a body on a pin about Z through (x, y, z) from Ground, its eccentric point mass at (rho, 0, 0) of
  // the pin's frame (at angle q from +X), geared to the crank by a coordinate coupler q_shaft - ratio q_crank - phase =
  // 0 (the crank's q is phi): a constraint, never a prescribed function of time. The body's origin is the point mass
  // itself (the pin's frame M at (-rho, 0, 0) of the body), so its central inertia is exactly zero: given about the axis
  // as m rho^2, Simbody's m rho^2 - m rho^2 came out at -1 ulp for some masses and was refused (a marine engine's
  // designed shafts).
  for (const BalanceShaftParams& s : m.balance_shafts) {
    const SimTK::Body::Rigid shaft_body(SimTK::MassProperties(s.mass, SimTK::Vec3(0), SimTK::Inertia(0)));
    b.shafts.emplace_back(matter.Ground(), SimTK::Transform(SimTK::Vec3(s.position[0], s.position[1], s.position[2])),
                          shaft_body, SimTK::Transform(SimTK::Vec3(-s.radius, 0.0, 0.0)));
    SimTK::Vector coefficients(3);
    coefficients[0] = -s.ratio;  // q_crank
    coefficients[1] = 1.0;       // q_shaft
    coefficients[2] = -s.phase;
    SimTK::Array_<SimTK::MobilizedBodyIndex> bodies{b.crank.getMobilizedBodyIndex(), b.shafts.back().getMobilizedBodyIndex()};
    SimTK::Array_<SimTK::MobilizerQIndex> coordinates{SimTK::MobilizerQIndex(0), SimTK::MobilizerQIndex(0)};
    b.couplers.emplace_back(matter, new SimTK::Function::Linear(coefficients), bodies, coordinates);
  }
  return b;
}

/// Angle difference reduced to (-pi, pi].
double wrappedDifference(double a, double b) {
  return std::remainder(a - b, 2.0 * SimTK::Pi);
}

/// The checks every model makes of its inputs. @throws std::invalid_argument naming `who` and the rule.
inline void checkModelInputs(const Mechanism& m, const ModelOptions& options, const std::string& who) {
  try {
    validateMechanism(m, m.name.empty() ? std::string("mechanism") : m.name);
  } catch (const SceneError& error) {
    throw std::invalid_argument(who + ": invalid mechanism: " + error.what());
  }
  if (!(std::isfinite(options.projection_tolerance) && options.projection_tolerance > 0.0))
    throw std::invalid_argument(who + ": projection_tolerance must be finite and > 0");
}

/// max |v_i|
inline double calcMaxAbs(const SimTK::Vector& v) {
  double result = 0.0;
  for (int i = 0; i < v.size(); ++i) result = std::max(result, std::abs(v[i]));
  return result;
}

/// projectQ to `tolerance`, then, if the largest constraint error is still above `polish_threshold` (projectQ stops
/// as soon as the RMS error is below 0.1 tolerance, up to 1e-13 m), one forced Newton step, which lands on roundoff.
/// @throws what projectQ throws.
inline void projectPositions(const SimTK::MultibodySystem& system, SimTK::State& state, double tolerance,
                             double polish_threshold) {
  system.projectQ(state, tolerance);
  if (calcMaxAbs(state.getQErr()) <= polish_threshold) return;
  SimTK::Vector no_error_estimate;
  SimTK::ProjectOptions polish(tolerance);
  polish.setOption(SimTK::ProjectOptions::ForceProjection);
  SimTK::ProjectResults results;
  system.projectQ(state, no_error_estimate, polish, results);
}

/// Gravity's power on every body at the state's velocities (realized through Stage::Velocity). At unit crank speed
/// it is -dV/dphi = -Q.
inline double calcGravityPower(const SimTK::SimbodyMatterSubsystem& matter, const SimTK::Force::Gravity& gravity,
                               const SimTK::State& state) {
  const SimTK::Vector_<SimTK::SpatialVec>& forces = gravity.getBodyForces(state);  // moment about, force at the origin
  double power = 0.0;
  for (SimTK::MobilizedBodyIndex b(1); b < matter.getNumBodies(); ++b) {
    const SimTK::SpatialVec& velocity = matter.getMobilizedBody(b).getBodyVelocity(state);  // w, v of the origin
    power += SimTK::dot(forces[b][0], velocity[0]) + SimTK::dot(forces[b][1], velocity[1]);
  }
  return power;
}

}  // namespace
}  // namespace crankcheck::simbody_models
