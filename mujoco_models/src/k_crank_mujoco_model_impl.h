#pragma once
// KCrankMujocoModel's implementation (k_crank_mujoco_model.cc), shared with the free run (free_run.cc), which starts
// from its exactly closed state. Private to the library.

#include <mujoco/mujoco.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "crankcheck/mujoco_models/k_crank_mujoco_model.h"
#include "crankcheck/scene/evaluation.h"
#include "crankcheck/scene/mechanism.h"
#include "model_support.h"

namespace crankcheck::mujoco_models {

class KCrankMujocoModel::Impl {
 public:
  Impl(const Mechanism& m, Variant variant);

  Evaluation evaluate(double phi);
  void setSpeed(double omega) {
    if (!std::isfinite(omega)) throw std::invalid_argument("KCrankMujocoModel: crank speed omega must be finite");
    m_.machine.speed = omega;
    m_.speed_rpm = omega * (30.0 / M_PI);
  }
  double potentialEnergy(double phi);
  double holdingTorque(double phi);
  CrankTorqueLine crankTorqueLine(double phi, double phi_dot);
  double closureError() const { return closure_error_; }
  /// The exactly closed state at crank angle phi and crank speed omega: MuJoCo's qpos and qvel.
  void calcClosedState(double phi, double omega, std::vector<double>& qpos, std::vector<double>& qvel) {
    close(phi);
    solveVelocities(omega);
    qpos.assign(data_->qpos, data_->qpos + model_->nq);
    qvel.assign(data_->qvel, data_->qvel + model_->nv);
  }
  int crankJoint() const { return crank_q_; }
  const Mechanism& mechanism() const { return m_; }
  Variant variant() const { return variant_; }

 private:
  struct Cylinder {
    int slide_q = 0, slide_v = 0, wrist_q = 0, wrist_v = 0;
    int piston_body = 0, rod_body = 0, crank_pin_site = 0, big_end_site = 0, equality = 0;
    double n[3] = {0, 0, 0};  // e_j turned +90 degrees
    // The loop's Jacobian columns at the closed configuration (rows X, Y): the big end's with respect to the slide
    // and the wrist hinge, the crank pin's with respect to the crank hinge.
    double jb_s[2] = {0, 0}, jb_h[2] = {0, 0}, jc[2] = {0, 0};
  };
  /// Closes every loop at crank angle phi by Newton's method on the big end's gap (MuJoCo's kinematics and site
  /// Jacobians); leaves the kinematics and the Jacobian columns of the closed configuration.
  void close(double phi);
  /// Every joint's velocity [rad/s, m/s] at crank speed omega with the loops closed (J v = 0: the dependent speeds
  /// from the Jacobian columns of the last closure) into qvel (nv values).
  void calcLoopVelocities(double omega, double* qvel) const;
  /// Dependent speeds for crank speed omega (calcLoopVelocities), then MuJoCo's velocity-dependent quantities
  /// (mj_comVel).
  void solveVelocities(double omega);
  /// Dependent accelerations at zero crank acceleration: J qacc = -(Jdot v), Jdot v from MuJoCo's site
  /// accelerations at qacc = 0.
  void solveAccelerations();
  /// Exact multipliers at the current q, v, qacc: J_dep^T f_j = (M qacc + bias - applied)_dep, then the crank
  /// torque. `gas` adds the gas forces as applied forces. Returns tau; f_j in forces_.
  double solveExactForces(double phi, bool gas);
  /// MuJoCo's soft solver: the crank torque that gives the crank zero acceleration, and the solver's qacc (into
  /// data_->qacc) and loop forces (into forces_). State q, v copied from data_.
  double solveSoftForces(double phi, bool gas);
  /// Joint reactions from the loop forces forces_ and data_->qacc, by mj_rnePostConstraint.
  void fillReactions(Evaluation& e);
  /// -dP/dt, -dH_O/dt with gravity off from data_->qacc (MuJoCo's body accelerations).
  void fillShaking(Evaluation& e);
  double potential() {
    mj_energyPos(model_.get(), data_.get());
    return data_->energy[0];
  }
  void checkFinite(const Evaluation& e, double phi) const;

  Mechanism m_;
  Variant variant_;
  ModelPtr model_;  // constraint solver off: closure, exact multipliers, reactions
  DataPtr data_;
  ModelPtr soft_model_;  // soft variants: MuJoCo's own constraint solver
  DataPtr soft_data_;
  int crank_q_ = 0, crank_v_ = 0, crank_body_ = 0;
  std::vector<Cylinder> cylinders_;
  struct Shaft {
    int q = 0, v = 0, body = 0;
    double ratio = 0.0, phase = 0.0;
  };
  std::vector<Shaft> shafts_;
  std::vector<std::array<double, 2>> forces_;  // f_j: the crank on rod j at its crank pin (crank_pin_force)
  std::vector<double> jacobian_;               // 3 x nv scratch
  std::vector<double> rne_;                    // nv scratch
  std::vector<double> unit_, mass_times_unit_; // nv scratch: u at unit crank speed, M u
  double rotor_inertia_ = 0.0;                 // [kg m^2] the rotors' part of u^T M u (crankTorqueLine)
  double reference_potential_ = 0.0;           // V(0)
  double closure_error_ = 0.0;
  double closure_tolerance_ = 0.0;
  bool closed_ = false;
  double closed_phi_ = 0.0;
  // The motion of the last exact kinematics at crank speed != 0, per unit crank angle: each cylinder's slide and hinge
  // rates dq/dphi = qvel / omega and dq^2/dphi^2 = qacc / omega^2 (constant crank speed) at `phi`. The next closure
  // near it starts from q + dq h + dq^2 h^2 / 2 (close).
  struct AngleMotion {
    bool valid = false;
    double phi = 0.0;
    std::vector<std::array<double, 4>> rates;  // per cylinder: slide dq, slide dq^2, hinge dq, hinge dq^2
  };
  AngleMotion motion_;
  /// Keeps the motion of the kinematics just solved (solveVelocities and solveAccelerations at omega != 0).
  void keepMotion(double omega);
};

}  // namespace crankcheck::mujoco_models
