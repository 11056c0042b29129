#pragma once
/// @file
/// The smallest Simbody model that still computes U and Q = dU/dphi by Simbody's own dynamics, for scenes and sweeps
/// that ask for nothing else. No Simbody header here (pimpl), like k_crank_model.h.
///
/// The model: the crankshaft on a Pin (prescribed angle, as in KCrankModel) carrying each throw's crank and
/// counterweight masses; each piston a particle on a Slider; each rod reduced to two point masses that have the rod's
/// mass and first moment about the wrist pin (m_k (l - z_k)/l on the piston, m_k z_k / l on the crank pin: exact for
/// gravity, not for inertia), and the rod itself to a distance constraint (Constraint::Rod): one constraint equation
/// per cylinder instead of two, and no rod bodies. At rest the holding torque needs no inertia, so U and Q are exact;
/// kinematics, reactions and drive torque at speed need the full KCrankModel. The gate checks this model against the
/// full one.

#include <memory>

#include "crankcheck/scene/mechanism.h"
#include "crankcheck/simbody_models/k_crank_model.h"

namespace crankcheck::simbody_models {

class KCrankGravityModel {  // one per thread; one System reused across angles, warm-started
 public:
  /// @throws std::invalid_argument for an invalid mechanism, cylinders not in one bank, a tolerance not > 0, or a
  ///         piston with no mass
  ///         (m_o + m_k (l - z_k)/l = 0 makes the slider's mass matrix singular); std::runtime_error if Simbody fails.
  explicit KCrankGravityModel(const Mechanism& m, ModelOptions options = {});
  ~KCrankGravityModel();
  KCrankGravityModel(const KCrankGravityModel&) = delete;
  KCrankGravityModel& operator=(const KCrankGravityModel&) = delete;
  KCrankGravityModel(KCrankGravityModel&&) noexcept;
  KCrankGravityModel& operator=(KCrankGravityModel&&) noexcept;

  double calcPotentialEnergy(double phi);  ///< U = V(phi) - V(0) [J]
  double calcHoldingTorque(double phi);    ///< Q [N m]: static torque holding the crank at phi
  double calcVirtualPowerQ(double phi);    ///< Q [N m]: minus gravity's power at unit crank speed

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace crankcheck::simbody_models
