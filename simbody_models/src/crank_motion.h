#pragma once
// Internal to simbody_models: the prescribed crank motion shared by the full and the reduced model.
// Include only from Simbody translation units (never compiled with NDEBUG).

#include <Simbody.h>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <utility>

#include "crankcheck/scene/evaluation.h"

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

}  // namespace
}  // namespace crankcheck::simbody_models
