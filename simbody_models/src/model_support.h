#pragma once
// Internal to simbody_models: what the full and the reduced model share (the prescribed crank motion, the
// position projection, gravity's power).
// Include only from Simbody translation units (never compiled with NDEBUG).

#include <Simbody.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "crankcheck/scene/evaluation.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/simbody_models/k_crank_model.h"

namespace crankcheck::simbody_models {
namespace {

/// What the crank mobilizer is told to do: angle phi [rad] and constant speed omega [rad/s].
struct CrankDrive {
  double phi = 0.0;
  double omega = 0.0;
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
