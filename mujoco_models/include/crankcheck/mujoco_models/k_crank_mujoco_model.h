#pragma once
/// @file
/// The k-crank mechanism of docs/CONVENTIONS.md (any layout, axial positions, gas, gravity) built as a MuJoCo
/// model: crankcheck's third engine. MuJoCo computes the kinematics, the bias forces (recursive Newton-Euler) and
/// the joint reactions itself; this library never includes the analytic library nor Simbody. No MuJoCo header here:
/// MuJoCo stays in src/.
///
/// The model (MJCF written in memory, calcMjcf, and loaded through MuJoCo's virtual file system):
///  - crank: a body on a hinge about +Z at O carrying every throw's point masses (m_s at r_s on the crank line, m_p
///    at r_p opposite, in the plane z_j of the throw's cylinder) as one inertial (mass, centre of mass, full inertia
///    tensor), plus the flywheel I_w about Z (isotropic: only I_zz, I_xz, I_yz act) when the scene has one, and a crank-pin
///    site per cylinder at r (cos beta_j, sin beta_j, z_j).
///  - piston j: a body on a slide along e_j, its origin at z_j on the crank axis moved by the pin offset delta_j along
///    n_j, so the slide's coordinate is x_p;
///    a particle m_o (with a nominal isotropic inertia, which never acts: the piston does not turn).
///  - rod j: a body on a hinge about +Z at the wrist pin, child of piston j; at hinge angle 0 it points along -e_j:
///    centre of mass at -z_k e_j, inertia about it I_o - m_k z_k^2 about Z, big-end site at -l e_j. The rod angle of
///    CONVENTIONS.md is minus the hinge angle.
///  - the loop: a `connect` equality between the rod's big end and the crank pin (anchors set on both bodies).
///  - gravity (0, -g, 0) in MuJoCo's options; gas as a generalized force -p_j A on piston j's slide.
///
/// Two ways to evaluate (Variant):
///  - kExact ("mujoco"): the constraint solver is off. The loop is closed by Newton's method on the big end's gap
///    with MuJoCo's own forward kinematics and site Jacobians (mj_kinematics, mj_jacSite), the crank at phi; the
///    dependent speeds and accelerations from the same Jacobians and MuJoCo's site accelerations at zero qacc
///    (the Jdot v term); then mj_rne gives M qacc + bias, and the crank torque and the loop forces are the exact
///    multipliers of J^T f + tau e_crank = M qacc + bias - applied (hard constraints, 2 x 2 per cylinder). The loop
///    forces go back in as body forces and mj_rnePostConstraint gives every joint's reaction (cfrc_int).
///  - kSoftDefault ("mujoco-soft") and kSoftStiff ("mujoco-soft-stiff"): MuJoCo's own soft constraint solver
///    (mj_forward) with its default solref/solimp, or with the stiffest impedance it accepts (solimp 0.9999 0.9999)
///    and solref at twice the time step (the smallest its safety rule keeps). The state (q, v) is the exact one
///    (so x_p, v_p, U and the rod angle and speed are exact); the crank torque is the one for which MuJoCo's solver
///    gives the crank zero acceleration (its response is linear in the torque: two solves, then a third with it),
///    and the accelerations and loop forces are the solver's. Its error is a finding, not a failure.

#include <memory>
#include <string>
#include <vector>

#include "crankcheck/scene/evaluation.h"
#include "crankcheck/solver/free_run.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::mujoco_models {

enum class Variant {
  kExact,        ///< "mujoco": hard multipliers, loop closed by Newton to rounding
  kSoftDefault,  ///< "mujoco-soft": MuJoCo's constraint solver, default solref/solimp
  kSoftStiff,    ///< "mujoco-soft-stiff": MuJoCo's constraint solver, the stiffest solimp/solref it accepts
};
std::string toString(Variant variant);  ///< the engine name: "mujoco", "mujoco-soft", "mujoco-soft-stiff"

/// The MJCF text of the model (for the curious and for tests); soft variants carry their solref/solimp defaults.
/// @throws std::invalid_argument as KCrankMujocoModel.
std::string calcMjcf(const Mechanism& m, Variant variant = Variant::kExact);

/// The crank torque [N m] that moves the mechanism at crank angle phi, speed phi_dot and acceleration phi_ddot
/// against its gas and gravity is affine in phi_ddot: inertia phi_ddot + rest (KCrankMujocoModel::calcCrankTorqueLine).
struct CrankTorqueLine {
  /// J(phi) [kg m^2]: the reduced inertia about the crank axis of the crankshaft's point masses, the rods, the pistons
  /// (and the balance shafts' point masses), without the crankshaft's rotor (the flywheel I_w, or calcMjcf's nominal one)
  double inertia = 0.0;
  /// [N m] the torque at phi_ddot = 0: (1/2) J'(phi) phi_dot^2 + Q(phi) - T_gas(phi) (velocity terms, gravity, gas)
  double rest = 0.0;
};

/// The k-crank mechanism in MuJoCo. Loads one model in the constructor and reuses it for every crank angle: within
/// 1 rad of the previous closure the next starts from it, carried on to the new angle by the last motion solved at
/// speed (q + dq/dphi h + d2q/dphi2 h^2 / 2) when there is one. Not thread-safe: one object per thread.
class KCrankMujocoModel {
 public:
  /// @throws std::invalid_argument if m is not a valid mechanism, or MuJoCo cannot build it: MuJoCo refuses a body
  ///         on a joint lighter than 1e-15 kg or with an inertia below 1e-15 kg m^2, so the piston needs m_o > 0, the
  ///         rod m_k > 0 and I_o - m_k z_k^2 > 0, the crankshaft some mass (m_s or m_p > 0). The message names the
  ///         scene key.
  /// @throws std::runtime_error if MuJoCo fails to compile the MJCF or the loop does not close at phi = 0.
  explicit KCrankMujocoModel(const Mechanism& m, Variant variant = Variant::kExact);
  ~KCrankMujocoModel();
  KCrankMujocoModel(const KCrankMujocoModel&) = delete;
  KCrankMujocoModel& operator=(const KCrankMujocoModel&) = delete;
  KCrankMujocoModel(KCrankMujocoModel&&) noexcept;
  KCrankMujocoModel& operator=(KCrankMujocoModel&&) noexcept;

  /// Everything at crank angle phi [rad] and the scene's omega [rad/s], engine = toString(variant): U [J], Q [N m]
  /// (static holding torque, gravity only), drive_torque [N m], bearing_force [N], shaking_force [N],
  /// shaking_moment [N m], and per cylinder x_p, v_p, a_p, crank_pin_force, wrist_pin_force, wall_force, gas_force,
  /// rod_angle, rod_omega, rod_alpha. Signs and frames: CONVENTIONS.md.
  /// @throws std::invalid_argument if phi is not finite.
  /// @throws std::runtime_error if the loop does not close at phi (Newton fails) or MuJoCo returns non-finite values.
  Evaluation evaluate(double phi);

  /// Sets the crank speed omega [rad/s] of every later evaluation (the mechanism's engine.speed): the MJCF does not
  /// depend on it. @throws std::invalid_argument if omega is not finite.
  void setSpeed(double omega);

  /// U = V(phi) - V(0) [J] only (MuJoCo's mj_energyPos at the closed loop). @throws as evaluate().
  double calcPotentialEnergy(double phi);

  /// Q [N m] only: the static torque holding the crank at phi against gravity. @throws as evaluate().
  double calcHoldingTorque(double phi);

  /// The crank torque as a line in the crank acceleration at crank angle phi [rad] and crank speed phi_dot [rad/s]
  /// (kExact only; the scene's omega is not used): the loops closed at phi (Newton, as evaluate), u = MuJoCo's joint
  /// velocities at unit crank speed (the loops' null space), inertia = u^T M u from MuJoCo's composite-rigid-body mass
  /// matrix (mj_crb) minus the crankshaft body's own rotor (its body_inertia about Z, and each balance shaft's ratio^2
  /// times its nominal one); rest = the exact multipliers' crank torque (as evaluate's drive torque) at phi_dot and
  /// zero crank acceleration, gas at phi. For the elastic crank train (crank_train.h): one throw's J_j and torque.
  /// @throws std::invalid_argument for a soft variant or a non-finite phi or phi_dot.
  /// @throws std::runtime_error as evaluate().
  CrankTorqueLine calcCrankTorqueLine(double phi, double phi_dot);

  /// Largest |gap| [m] between a rod's big end and its crank pin at the last closure (exact: rounding).
  double getLoopClosureError() const;

  const Mechanism& mechanism() const;
  Variant variant() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
  friend FreeRunResult simulateFreeRun(const Mechanism&, double, Variant, const FreeRunSettings&);  // free_run.h
};

/// The version of the MuJoCo library linked in, e.g. "2.2.2" (for reports).
std::string getMujocoVersion();

}  // namespace crankcheck::mujoco_models
