#pragma once
/// @file
/// The k-crank mechanism of docs/CONVENTIONS.md (any layout) built as a Simbody multibody system: the second,
/// independent engine of crankcheck. The positions and velocities satisfy Simbody's own constraint errors (closed by
/// Newton's method on them loop by loop near a known solution, by Simbody's projections elsewhere: ModelOptions), and
/// Simbody computes the accelerations and reactions itself; no closed-form kinematics is used anywhere in this library,
/// and it never includes the analytic library.
///
/// Simbody stays behind a pimpl: this header pulls in no Simbody header, so translation units that only use the
/// model compile fast and never see SimTK names (see SIMBODY-NOTES.md: Simbody headers must not be compiled with
/// NDEBUG, and SimTK's operators clash with Eigen).
///
/// The model (one degree of freedom, no redundant constraint equations):
///  - crankshaft: MobilizedBody::Pin from Ground about +Z at O, a 3D body carrying every throw's point masses (m_s
///    at r_s on the crank line, m_p at r_p opposite, in the plane z_j of the throw's cylinder) and nothing else (no nominal inertia is needed: its motion is
///    prescribed). Its angle is prescribed by a position-level Motion: q = phi, qdot = omega, qdotdot = 0
///    (constant crank speed).
///  - piston j: MobilizedBody::Slider from Ground along e_j (its own bank gamma_j, in the plane z = z_j), a
///    particle of mass m_o at the wrist pin A_j.
///  - rod j: MobilizedBody::Pin on piston j at A_j; mass m_k, centre of mass on the rod axis at z_k from A_j,
///    inertia I_o about A_j (Z axis).
///  - loop closure j: Constraint::PointOnLine, the rod's big-end point on the Z-parallel line through the crank
///    pin B_j of the crankshaft (2 equations).
///  - gravity: Force::Gravity, (0, -g).
/// Shaking force and moment: -dP/dt and -dH_O/dt summed over the bodies from Simbody's own body accelerations,
/// angular velocities and mass properties (m a_C, p_C x m a_C + I_C w_dot + w x I_C w).

#include <memory>
#include <string>
#include <vector>

#include "crankcheck/scene/evaluation.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::simbody_models {

/// Numerical options of the Simbody model.
struct ModelOptions {
  /// Required RMS accuracy of the position and velocity projections (System::projectQ/projectU) [m, m/s] for a
  /// mechanism up to 1 m; multiplied by l + r above that (roundoff of a long rod is eps l). Simbody's default (1e-4) leaves
  /// 0.2 N of reaction error; 1e-12..1e-13 is tight, 1e-14 hits roundoff and Simbody throws.
  double projection_tolerance = 1e-12;
  /// How the loops are closed. false (the default): Newton's method on Simbody's own constraint errors, loop by loop
  /// (each loop's closure involves its piston and rod alone: a 2 x 2 Jacobian per loop, by finite differences of
  /// Simbody's errors, all loops at once), to 2 eps (l + r) of closure and 2 eps r |omega| of velocity error;
  /// System::projectQ and projectU where it does not converge or lands off the physical branch. true: Simbody's
  /// projections at every angle, the reference the default is tested against (System::projectQ forms the whole m x m
  /// constraint matrix, O(k^2) for k cylinders).
  bool simbody_projections = false;
};

/// One rigid body of the Simbody model at one crank angle, planar part only, as Simbody sees it.
struct BodyKinematics {
  double mass = 0.0;                  ///< [kg] as built into the Simbody body
  double inertia_about_com = 0.0;     ///< [kg m^2] about the Z axis through the centre of mass, as built
  Vec2 com{};                         ///< [m] centre of mass, global
  Vec2 com_acceleration{};            ///< [m/s^2] from Simbody's body accelerations
  double angular_acceleration = 0.0;  ///< [rad/s^2] about +Z, from Simbody
};

/// Per-cylinder details that the Evaluation does not carry; for checks of the reported reactions.
struct CylinderDiagnostics {
  BodyKinematics piston;
  BodyKinematics rod;
  Vec2 wrist_pin{};          ///< [m] A_j: origin of the piston body (Simbody station location)
  Vec2 crank_pin{};          ///< [m] B_j: the crank pin station on the crankshaft body
  Vec2 rod_big_end{};        ///< [m] the rod's big-end station (equals crank_pin to the projection tolerance)
  Vec2 slider_reaction{};    ///< [N] force on piston j from the frame through its slider, global (wall_force n
                             ///<     plus an e-component that must be zero: nothing acts along the slider)
  double slider_reaction_moment = 0.0;  ///< [N m] Z moment of that reaction about A_j (zero for a particle)
};

/// Everything evaluate() reports plus Simbody's own kinematics and energies at the same state.
struct Diagnostics {
  Evaluation evaluation;
  double omega = 0.0;                       ///< [rad/s] the crank speed used
  double kinetic_energy = 0.0;              ///< [J] Simbody's KE of the whole mechanism
  double potential_energy = 0.0;            ///< [J] Simbody's V (zero height at O), not V - V(0)
  BodyKinematics crankshaft;
  std::vector<CylinderDiagnostics> cylinders;
  double position_constraint_error = 0.0;   ///< [m] max |constraint error| after projectQ
  double velocity_constraint_error = 0.0;   ///< [m/s] max |constraint error| after projectU
};

/// The k-crank mechanism in Simbody. Builds one System in the constructor and reuses it for every crank angle
/// (the previous configuration is the warm start of the next assembly). Not thread-safe: one object per thread.
class KCrankModel {
 public:
  /// Builds the Simbody system for `m` (k = m.machine.cylinders, phases m.machine.crank_angles, gamma, omega, g)
  /// and assembles it at phi = 0 to get the reference potential V(0).
  /// @throws std::invalid_argument if m is not a valid mechanism (k < 1, crank angle count != k, non-positive
  ///         lengths, lambda >= 1, negative masses, I_o < m_k z_k^2, non-finite values, projection tolerance
  ///         not > 0), and if the rod has no mass or no inertia about the wrist pin (m_k = 0 or I_o = 0: Simbody's
  ///         mass matrix is then singular; a massless piston or crankshaft is fine).
  /// @throws std::runtime_error if Simbody fails to build or assemble the system.
  explicit KCrankModel(const Mechanism& m, ModelOptions options = {});
  ~KCrankModel();
  KCrankModel(const KCrankModel&) = delete;
  KCrankModel& operator=(const KCrankModel&) = delete;
  KCrankModel(KCrankModel&&) noexcept;
  KCrankModel& operator=(KCrankModel&&) noexcept;

  /// Everything at crank angle phi [rad] and the scene's omega [rad/s], engine = "simbody":
  /// U [J] (= V(phi) - V(0)), Q [N m] (static holding torque route, as calcHoldingTorque), drive_torque [N m],
  /// bearing_force [N], shaking_force [N], shaking_moment [N m], and per cylinder x_p [m], v_p [m/s], a_p [m/s^2], crank_pin_force [N],
  /// wrist_pin_force [N], wall_force [N]. Signs and frames: CONVENTIONS.md.
  /// @throws std::invalid_argument if phi is not finite.
  /// @throws std::runtime_error if Simbody cannot assemble the mechanism at phi or returns non-finite values.
  Evaluation evaluate(double phi);

  /// evaluate(phi) without its static pass (the solve at rest that gives Q, and U with it): U and Q are NaN, every other
  /// field the same numbers (the dynamic pass starts from the same assembled positions and zero velocities).
  /// @throws as evaluate().
  Evaluation evaluateMotion(double phi);

  /// Sets the crank speed omega [rad/s] of every later evaluation (the mechanism's engine.speed): the System does not
  /// depend on it. @throws std::invalid_argument if omega is not finite.
  void setSpeed(double omega);
  /// How well Simbody's constraint solve resolves this mechanism: the largest of the loops' acceleration errors
  /// (Simbody's udoterr at Stage::Acceleration) of the motion at phi [rad] and omega [rad/s], relative to the
  /// acceleration scale r omega^2 + g [-]. At most 2e4 eps where the bodies' masses are of a size (every gate case,
  /// at the speed where r omega^2 = g); it grows as the inverse of a body's mass where one is a tiny fraction of the
  /// others (the factorization then drops what it cannot resolve): there 2.0e-5 for a 1e-9 kg rod against a 0.32 kg
  /// piston, 6.2e-8 at 1e-6 kg, 5.8e-10 at 1e-4 kg. It has a floor that does not grow with omega: it weighs most at
  /// low speed. The speed set before is kept. @throws as evaluateMotion.
  double calcLoopAccelerationResidual(double phi, double omega);

  /// Starts this model's next assembly from `donor`'s configuration (its pistons' slider and rods' pin coordinates where
  /// it was last assembled) when both are of the same mechanism up to the bank angles (the same cylinder count, crank
  /// angles, pin offsets, crank radius, rod length and balance shafts): those coordinates are measured from each
  /// cylinder's own axis, so the donor's solution is this model's to roundoff and the assembly at the donor's angle has
  /// nothing left to iterate (a sweep over gamma assembles once per angle); the donor's last velocities at that angle
  /// (its dynamic pass) start the velocity projection of this model's at the same speed alike. Warm starts, as the
  /// previous angle's is: the projections still converge to this model's own tolerance. Nothing changes if the
  /// mechanisms differ otherwise or the donor has not been assembled.
  void startAssemblyFrom(const KCrankModel& donor);

  /// evaluate(phi) together with Simbody's own body kinematics and energies at the same state.
  /// @throws as evaluate().
  Diagnostics calcDiagnostics(double phi);

  /// U = V(phi) - V(0) [J], from MultibodySystem::calcPotentialEnergy. @throws as evaluate().
  double calcPotentialEnergy(double phi);

  /// Simbody's kinetic energy [J] of the whole mechanism at phi [rad] and the scene's omega.
  /// @throws as evaluate().
  double calcKineticEnergy(double phi);

  /// Q route 1 [N m]: the static torque about +Z that holds the crank still at phi against gravity (omega = 0),
  /// from the prescribed-motion force of the crank mobilizer. @throws as evaluate().
  double calcHoldingTorque(double phi);

  /// Q route 2 [N m]: -(sum over bodies of Simbody's gravity spatial force . body spatial velocity) at unit
  /// crank speed, i.e. dU/dphi by virtual power. @throws as evaluate().
  double calcVirtualPowerQ(double phi);

  /// Q route 3 [N m]: (U(phi + h) - U(phi - h)) / (2 h), h [rad] > 0.
  /// @throws std::invalid_argument if h is not finite and > 0; otherwise as evaluate().
  double calcQByCentralDifference(double phi, double h);

  /// The mechanism the model was built from.
  const Mechanism& mechanism() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

/// The version of the Simbody library linked in, "major.minor.build" (for reports).
std::string getSimbodyVersion();

}  // namespace crankcheck::simbody_models
