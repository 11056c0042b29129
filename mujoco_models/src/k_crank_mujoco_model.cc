// The k-crank mechanism in MuJoCo (Debian libmujoco-dev 2.2.2): KCrankMujocoModel (its Impl in
// k_crank_mujoco_model_impl.h). Never includes the analytic library or Simbody: MuJoCo computes the kinematics
// (mj_kinematics, mj_jacSite, mj_objectAcceleration), the bias forces (mj_rne) and the joint reactions
// (mj_rnePostConstraint). mujoco_models/README.md lists the traps this file avoids.
#include "crankcheck/mujoco_models/k_crank_mujoco_model.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "crankcheck/scene/scene_file.h"
#include "k_crank_mujoco_model_impl.h"
#include "mjcf_writer.h"
#include "model_support.h"

namespace crankcheck::mujoco_models {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr int kMaxNewtonIterations = 100;

/// Solves the 2 x 2 system [a b; c d] x = (p, q).
std::array<double, 2> solve2(double a, double b, double c, double d, double p, double q) {
  const double det = a * d - b * c;
  return {(p * d - b * q) / det, (a * q - c * p) / det};
}

std::array<double, 3> cross(const double* a, const double* b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

}  // namespace

std::string toString(Variant variant) {
  switch (variant) {
    case Variant::kExact: return "mujoco";
    case Variant::kSoftDefault: return "mujoco-soft";
    case Variant::kSoftStiff: return "mujoco-soft-stiff";
  }
  return "mujoco";
}

std::string getMujocoVersion() {
  const int v = mj_version();  // e.g. 222
  return std::to_string(v / 100) + "." + std::to_string(v / 10 % 10) + "." + std::to_string(v % 10);
}

KCrankMujocoModel::Impl::Impl(const Mechanism& m, Variant variant) : m_(m), variant_(variant) {
  model_.reset(loadModel(calcMjcf(m_, Variant::kExact)));
  data_.reset(mj_makeData(model_.get()));
  if (variant_ != Variant::kExact) {
    soft_model_.reset(loadModel(calcMjcf(m_, variant_)));
    soft_data_.reset(mj_makeData(soft_model_.get()));
    // Deterministic results: each solve starts cold, not from the previous call's accelerations.
    soft_model_->opt.disableflags |= mjDSBL_WARMSTART;
  }
  const mjModel* mm = model_.get();
  const int crank_joint = mj_name2id(mm, mjOBJ_JOINT, "crank");
  crank_q_ = mm->jnt_qposadr[crank_joint];
  crank_v_ = mm->jnt_dofadr[crank_joint];
  crank_body_ = mj_name2id(mm, mjOBJ_BODY, "crank");
  const int k = m_.machine.cylinders;
  cylinders_.resize(k);
  forces_.assign(k, {0.0, 0.0});
  for (int j = 0; j < k; ++j) {
    Cylinder& c = cylinders_[j];
    const std::string J = std::to_string(j);
    const int slide = mj_name2id(mm, mjOBJ_JOINT, ("slide" + J).c_str());
    const int wrist = mj_name2id(mm, mjOBJ_JOINT, ("wrist" + J).c_str());
    c.slide_q = mm->jnt_qposadr[slide];
    c.slide_v = mm->jnt_dofadr[slide];
    c.wrist_q = mm->jnt_qposadr[wrist];
    c.wrist_v = mm->jnt_dofadr[wrist];
    c.piston_body = mj_name2id(mm, mjOBJ_BODY, ("piston" + J).c_str());
    c.rod_body = mj_name2id(mm, mjOBJ_BODY, ("rod" + J).c_str());
    c.crank_pin_site = mj_name2id(mm, mjOBJ_SITE, ("crank_pin" + J).c_str());
    c.big_end_site = mj_name2id(mm, mjOBJ_SITE, ("big_end" + J).c_str());
    c.equality = mj_name2id(mm, mjOBJ_EQUALITY, ("loop" + J).c_str());
    const double gamma = getBankAngle(m_, j);
    c.n[0] = -std::sin(gamma);
    c.n[1] = std::cos(gamma);
  }
  if (soft_model_) setCrankPinAnchors(soft_model_.get(), m_);
  for (size_t i = 0; i < m_.balance_shafts.size(); ++i) {
    const int joint = mj_name2id(mm, mjOBJ_JOINT, ("shaft" + std::to_string(i)).c_str());
    shafts_.push_back({mm->jnt_qposadr[joint], mm->jnt_dofadr[joint], mj_name2id(mm, mjOBJ_BODY, ("shaft" + std::to_string(i)).c_str()),
                       m_.balance_shafts[i].ratio, m_.balance_shafts[i].phase});
  }
  jacobian_.resize(3 * static_cast<size_t>(mm->nv));
  rne_.resize(static_cast<size_t>(mm->nv));
  unit_.resize(static_cast<size_t>(mm->nv));
  mass_times_unit_.resize(static_cast<size_t>(mm->nv));
  // The isotropic rotor inertias calcMjcf gives the crankshaft (I_w or nominal) and the balance shafts (nominal):
  // their Z component, at unit crank speed the shaft turning at its ratio.
  rotor_inertia_ = mm->body_inertia[3 * crank_body_ + 2];
  for (const Shaft& s : shafts_) rotor_inertia_ += s.ratio * s.ratio * mm->body_inertia[3 * s.body + 2];
  closure_tolerance_ = 4.0 * kEps * (m_.rod.length + m_.crank.radius);
  close(0.0);
  reference_potential_ = potential();
}

void KCrankMujocoModel::Impl::close(double phi) {
  if (!std::isfinite(phi)) throw std::invalid_argument("KCrankMujocoModel: crank angle phi must be finite");
  const mjModel* mm = model_.get();
  mjData* d = data_.get();
  const double l = m_.rod.length;
  // Warm start from the previous closure when it is near; otherwise a crude guess that is no solution: the piston at
  // x = l, the rod along -e (its big end at O). Newton's first step from there puts the piston on the outer branch.
  const double step = std::remainder(phi - closed_phi_, 2.0 * M_PI);
  const bool warm = closed_ && std::fabs(step) <= 1.0;
  if (!warm) {
    for (Cylinder& c : cylinders_) {
      d->qpos[c.slide_q] = l;
      d->qpos[c.wrist_q] = 0.0;
    }
  } else if (motion_.valid && motion_.phi == closed_phi_) {
    // Near the last motion: MuJoCo's own motion carried on to phi (its second-order Taylor step), not the last angle's
    // q: Newton then needs about one step fewer. A hinge carried out of (-pi/2, pi/2) keeps the last angle's q.
    for (size_t j = 0; j < cylinders_.size(); ++j) {
      const Cylinder& c = cylinders_[j];
      const std::array<double, 4>& r = motion_.rates[j];
      const double hinge = d->qpos[c.wrist_q] + r[2] * step + 0.5 * r[3] * step * step;
      if (!(std::fabs(hinge) < M_PI_2)) continue;
      d->qpos[c.slide_q] += r[0] * step + 0.5 * r[1] * step * step;
      d->qpos[c.wrist_q] = hinge;
    }
  }
  d->qpos[crank_q_] = phi;
  for (const Shaft& s : shafts_) d->qpos[s.q] = s.ratio * phi + s.phase;  // the gear's (linear) constraint, solved
  const int nv = mm->nv;
  for (int iteration = 0;; ++iteration) {
    mj_kinematics(mm, d);
    mj_comPos(mm, d);
    double worst = 0.0;
    for (Cylinder& c : cylinders_) {
      const double* b = d->site_xpos + 3 * c.big_end_site;
      const double* p = d->site_xpos + 3 * c.crank_pin_site;
      worst = std::max({worst, std::fabs(b[0] - p[0]), std::fabs(b[1] - p[1])});
    }
    // Jacobian columns at this configuration (kept: at the closed configuration they are the loop's Jacobian).
    for (Cylinder& c : cylinders_) {
      mj_jacSite(mm, d, jacobian_.data(), nullptr, c.big_end_site);
      c.jb_s[0] = jacobian_[c.slide_v];
      c.jb_s[1] = jacobian_[nv + c.slide_v];
      c.jb_h[0] = jacobian_[c.wrist_v];
      c.jb_h[1] = jacobian_[nv + c.wrist_v];
      mj_jacSite(mm, d, jacobian_.data(), nullptr, c.crank_pin_site);
      c.jc[0] = jacobian_[crank_v_];
      c.jc[1] = jacobian_[nv + crank_v_];
    }
    if (worst <= closure_tolerance_) {
      closure_error_ = worst;
      break;
    }
    if (iteration == kMaxNewtonIterations) {
      closed_ = false;
      throw std::runtime_error("MuJoCo: the loop does not close at phi = " + num(phi) + " rad (gap " + num(worst) +
                               " m after " + std::to_string(kMaxNewtonIterations) + " Newton steps)");
    }
    for (Cylinder& c : cylinders_) {
      const double* b = d->site_xpos + 3 * c.big_end_site;
      const double* p = d->site_xpos + 3 * c.crank_pin_site;
      const auto step = solve2(c.jb_s[0], c.jb_h[0], c.jb_s[1], c.jb_h[1], p[0] - b[0], p[1] - b[1]);
      d->qpos[c.slide_q] += step[0];
      // The rod hinge stays within (-pi/2, pi/2): the physical branch (piston outside the crank pin). A step that
      // would leave it goes halfway to the limit instead.
      const double psi = d->qpos[c.wrist_q];
      double next = psi + step[1];
      if (!(std::fabs(next) < M_PI_2)) next = 0.5 * (psi + std::copysign(M_PI_2, step[1]));
      d->qpos[c.wrist_q] = next;
    }
  }
  closed_ = true;
  closed_phi_ = phi;
}

void KCrankMujocoModel::Impl::keepMotion(double omega) {
  if (omega == 0.0) return;
  const mjData* d = data_.get();
  motion_.valid = true;
  motion_.phi = closed_phi_;
  motion_.rates.resize(cylinders_.size());
  for (size_t j = 0; j < cylinders_.size(); ++j) {
    const Cylinder& c = cylinders_[j];
    motion_.rates[j] = {d->qvel[c.slide_v] / omega, d->qacc[c.slide_v] / (omega * omega), d->qvel[c.wrist_v] / omega,
                        d->qacc[c.wrist_v] / (omega * omega)};
  }
}

void KCrankMujocoModel::Impl::calcLoopVelocities(double omega, double* qvel) const {
  qvel[crank_v_] = omega;
  for (const Shaft& s : shafts_) qvel[s.v] = s.ratio * omega;
  for (const Cylinder& c : cylinders_) {
    // J_big_end,dep v_dep = J_crank_pin,crank omega
    const auto v = solve2(c.jb_s[0], c.jb_h[0], c.jb_s[1], c.jb_h[1], c.jc[0] * omega, c.jc[1] * omega);
    qvel[c.slide_v] = v[0];
    qvel[c.wrist_v] = v[1];
  }
}

void KCrankMujocoModel::Impl::solveVelocities(double omega) {
  calcLoopVelocities(omega, data_->qvel);
  mj_comVel(model_.get(), data_.get());
}

void KCrankMujocoModel::Impl::solveAccelerations() {
  const mjModel* mm = model_.get();
  mjData* d = data_.get();
  mju_zero(d->qacc, mm->nv);
  mju_zero(d->xfrc_applied, 6 * mm->nbody);
  mj_rnePostConstraint(mm, d);  // body accelerations at qacc = 0: velocity terms (and gravity's offset) only
  for (const Cylinder& c : cylinders_) {
    double ab[6], ac[6];
    mj_objectAcceleration(mm, d, mjOBJ_SITE, c.big_end_site, ab, 0);
    mj_objectAcceleration(mm, d, mjOBJ_SITE, c.crank_pin_site, ac, 0);
    // Jdot v = a_big_end - a_crank_pin at qacc = 0 (the gravity offset MuJoCo adds to every body cancels)
    const auto a = solve2(c.jb_s[0], c.jb_h[0], c.jb_s[1], c.jb_h[1], -(ab[3] - ac[3]), -(ab[4] - ac[4]));
    d->qacc[c.slide_v] = a[0];
    d->qacc[c.wrist_v] = a[1];
  }
  d->qacc[crank_v_] = 0.0;
  for (const Shaft& s : shafts_) d->qacc[s.v] = 0.0;
}

double KCrankMujocoModel::Impl::solveExactForces(double phi, bool gas) {
  const mjModel* mm = model_.get();
  mjData* d = data_.get();
  mj_rne(mm, d, 1, rne_.data());  // M qacc + bias (gravity, centrifugal, Coriolis)
  double tau = rne_[crank_v_];
  for (size_t j = 0; j < cylinders_.size(); ++j) {
    const Cylinder& c = cylinders_[j];
    const double applied_slide = gas ? -calcGasForce(m_, static_cast<int>(j), phi) : 0.0;  // -p A along e_j
    // J_dep^T f = (M qacc + bias - applied)_dep
    forces_[j] = solve2(c.jb_s[0], c.jb_s[1], c.jb_h[0], c.jb_h[1], rne_[c.slide_v] - applied_slide, rne_[c.wrist_v]);
    // crank row: M qacc + bias = tau - J_crank_pin^T f
    tau += c.jc[0] * forces_[j][0] + c.jc[1] * forces_[j][1];
  }
  // Each gear: the shaft's row, M qacc + bias = mu, and the crank's gets -ratio mu: tau = ... + ratio mu.
  for (const Shaft& s : shafts_) tau += s.ratio * rne_[s.v];
  return tau;
}

double KCrankMujocoModel::Impl::solveSoftForces(double phi, bool gas) {
  const mjModel* sm = soft_model_.get();
  mjData* s = soft_data_.get();
  const mjData* d = data_.get();
  mju_copy(s->qpos, d->qpos, sm->nq);
  mju_copy(s->qvel, d->qvel, sm->nv);
  mju_zero(s->qfrc_applied, sm->nv);
  for (size_t j = 0; j < cylinders_.size(); ++j)
    s->qfrc_applied[cylinders_[j].slide_v] = gas ? -calcGasForce(m_, static_cast<int>(j), phi) : 0.0;
  // The solver's crank acceleration is linear in the crank torque (equality constraints only: one quadratic
  // problem); two solves give the line, a third the state at the torque where it crosses zero. The torque is an
  // applied force: only the acceleration stage depends on it, so the second and third solves redo that stage alone
  // (mj_forwardSkip past mjSTAGE_VEL: the positions and velocities are the first solve's).
  bool first_solve = true;
  auto crankAcceleration = [&](double tau) {
    s->qfrc_applied[crank_v_] = tau;
    if (first_solve) mj_forward(sm, s);
    else mj_forwardSkip(sm, s, mjSTAGE_VEL, 1);
    first_solve = false;
    checkRowsFit(s);
    return s->qacc[crank_v_];
  };
  const double a0 = crankAcceleration(0.0);
  const double a1 = crankAcceleration(1.0);
  const double tau = -a0 / (a1 - a0);
  crankAcceleration(tau);
  mju_copy(data_->qacc, s->qacc, sm->nv);
  for (size_t j = 0; j < cylinders_.size(); ++j) forces_[j] = {0.0, 0.0};
  for (int i = 0; i < s->nefc; ++i) {
    if (s->efc_type[i] != mjCNSTR_EQUALITY) continue;
    for (size_t j = 0; j < cylinders_.size(); ++j) {
      // connect rows: X, Y, Z of (big end - crank pin); the force acts on body1, the rod
      if (s->efc_id[i] != cylinders_[j].equality) continue;
      forces_[j] = {s->efc_force[i], s->efc_force[i + 1]};
      i += 2;
      break;
    }
  }
  return tau;
}

void KCrankMujocoModel::Impl::fillReactions(Evaluation& e) {
  const mjModel* mm = model_.get();
  mjData* d = data_.get();
  mju_zero(d->xfrc_applied, 6 * mm->nbody);
  // The loop forces as body forces (force, torque about the body's centre of mass): f on the rod at its big end,
  // -f on the crankshaft at the crank pin. Gravity, gas and the crank torque are MuJoCo's own (gravity in cacc, gas
  // and torque as joint forces: they arrive in the joint reactions).
  for (size_t j = 0; j < cylinders_.size(); ++j) {
    const Cylinder& c = cylinders_[j];
    const double f[3] = {forces_[j][0], forces_[j][1], 0.0};
    const double minus_f[3] = {-f[0], -f[1], 0.0};
    const double* b = d->site_xpos + 3 * c.big_end_site;
    const double* p = d->site_xpos + 3 * c.crank_pin_site;
    const double* rod_com = d->xipos + 3 * c.rod_body;
    const double* crank_com = d->xipos + 3 * crank_body_;
    const double arm_b[3] = {b[0] - rod_com[0], b[1] - rod_com[1], b[2] - rod_com[2]};
    const double arm_p[3] = {p[0] - crank_com[0], p[1] - crank_com[1], p[2] - crank_com[2]};
    const auto torque_b = cross(arm_b, f);
    const auto torque_p = cross(arm_p, minus_f);
    double* rod = d->xfrc_applied + 6 * c.rod_body;
    double* crank = d->xfrc_applied + 6 * crank_body_;
    for (int i = 0; i < 3; ++i) {
      rod[i] += f[i];
      rod[3 + i] += torque_b[i];
      crank[i] += minus_f[i];
      crank[3 + i] += torque_p[i];
    }
  }
  mj_rnePostConstraint(mm, d);
  // cfrc_int[b] = (torque, force) on body b's subtree from its parent; the force part is independent of the point.
  const double* bearing = d->cfrc_int + 6 * crank_body_ + 3;
  e.bearing_force = {bearing[0], bearing[1]};
  for (size_t j = 0; j < cylinders_.size(); ++j) {
    const Cylinder& c = cylinders_[j];
    CylinderEvaluation& out = e.cylinders[j];
    out.crank_pin_force = forces_[j];
    const double* on_rod = d->cfrc_int + 6 * c.rod_body + 3;  // the piston on the rod through the wrist pin
    out.wrist_pin_force = {-on_rod[0], -on_rod[1]};
    const double* on_piston = d->cfrc_int + 6 * c.piston_body + 3;  // the frame on the piston through the slide
    out.wall_force = on_piston[0] * c.n[0] + on_piston[1] * c.n[1];
  }
  mju_zero(d->xfrc_applied, 6 * mm->nbody);
}

void KCrankMujocoModel::Impl::fillShaking(Evaluation& e) {
  mjModel* mm = model_.get();
  mjData* d = data_.get();
  const std::array<double, 3> gravity{mm->opt.gravity[0], mm->opt.gravity[1], mm->opt.gravity[2]};
  mju_zero(mm->opt.gravity, 3);
  mju_zero(d->xfrc_applied, 6 * mm->nbody);
  mj_rnePostConstraint(mm, d);
  for (int i = 0; i < 3; ++i) mm->opt.gravity[i] = gravity[i];
  // Each tree's root (the crankshaft, each piston) receives from the frame the rate of change of its tree's momentum
  // (no external loads now): cfrc_int at the tree's centre of mass c; about O, torque + c x force.
  double dP[3] = {0, 0, 0}, dH[3] = {0, 0, 0};
  std::vector<int> roots{crank_body_};
  for (const Cylinder& c : cylinders_) roots.push_back(c.piston_body);
  for (const Shaft& s : shafts_) roots.push_back(s.body);
  for (int b : roots) {
    const double* frc = d->cfrc_int + 6 * b;
    const double* c = d->subtree_com + 3 * mm->body_rootid[b];
    const auto arm = cross(c, frc + 3);
    for (int i = 0; i < 3; ++i) {
      dP[i] += frc[3 + i];
      dH[i] += frc[i] + arm[i];
    }
  }
  e.shaking_force = {-dP[0], -dP[1]};
  e.shaking_moment = {-dH[0], -dH[1], -dH[2]};
}

void KCrankMujocoModel::Impl::checkFinite(const Evaluation& e, double phi) const {
  bool ok = std::isfinite(e.U) && std::isfinite(e.Q) && std::isfinite(e.drive_torque) &&
            std::isfinite(e.bearing_force[0]) && std::isfinite(e.bearing_force[1]);
  for (const CylinderEvaluation& c : e.cylinders)
    ok = ok && std::isfinite(c.x_p) && std::isfinite(c.v_p) && std::isfinite(c.a_p) && std::isfinite(c.wall_force) &&
         std::isfinite(c.crank_pin_force[0]) && std::isfinite(c.wrist_pin_force[0]);
  if (!ok) throw std::runtime_error("MuJoCo returned non-finite values at phi = " + num(phi) + " rad");
}

double KCrankMujocoModel::Impl::potentialEnergy(double phi) {
  close(phi);
  return potential() - reference_potential_;
}

double KCrankMujocoModel::Impl::holdingTorque(double phi) {
  close(phi);
  solveVelocities(0.0);
  mju_zero(data_->qacc, model_->nv);
  return variant_ == Variant::kExact ? solveExactForces(phi, false) : solveSoftForces(phi, false);
}

CrankTorqueLine KCrankMujocoModel::Impl::crankTorqueLine(double phi, double phi_dot) {
  if (variant_ != Variant::kExact)
    throw std::invalid_argument("KCrankMujocoModel: the crank torque line is the exact variant's (hard multipliers)");
  if (!std::isfinite(phi_dot)) throw std::invalid_argument("KCrankMujocoModel: crank speed phi_dot must be finite");
  const mjModel* mm = model_.get();
  mjData* d = data_.get();
  close(phi);
  // J = u^T M u: the kinetic energy's form at unit crank speed (the loop forces do no work along u).
  calcLoopVelocities(1.0, unit_.data());
  mj_crb(mm, d);
  mj_mulM(mm, d, mass_times_unit_.data(), unit_.data());
  CrankTorqueLine line;
  line.inertia = mju_dot(unit_.data(), mass_times_unit_.data(), mm->nv) - rotor_inertia_;
  solveVelocities(phi_dot);
  solveAccelerations();
  keepMotion(phi_dot);
  line.rest = solveExactForces(phi, true);
  if (!(std::isfinite(line.inertia) && std::isfinite(line.rest)))
    throw std::runtime_error("MuJoCo returned non-finite values at phi = " + num(phi) + " rad");
  return line;
}

Evaluation KCrankMujocoModel::Impl::evaluate(double phi) {
  Evaluation e;
  e.engine = toString(variant_);
  e.phi = phi;
  e.cylinders.resize(cylinders_.size());
  const bool exact = variant_ == Variant::kExact;
  const double omega = m_.machine.speed;

  close(phi);
  e.U = potential() - reference_potential_;
  // Q: at rest, gravity alone (no gas)
  e.Q = holdingTorque(phi);

  // At speed: the exact kinematics, then forces by the variant's rule.
  solveVelocities(omega);
  solveAccelerations();
  keepMotion(omega);
  e.drive_torque = exact ? solveExactForces(phi, true) : solveSoftForces(phi, true);
  const mjData* d = data_.get();
  for (size_t j = 0; j < cylinders_.size(); ++j) {
    const Cylinder& c = cylinders_[j];
    CylinderEvaluation& out = e.cylinders[j];
    out.x_p = d->qpos[c.slide_q];
    out.v_p = d->qvel[c.slide_v];
    out.a_p = d->qacc[c.slide_v];
    out.gas_force = calcGasForce(m_, static_cast<int>(j), phi);
    // the hinge turns the rod from -e toward -n: the rod angle of CONVENTIONS.md is minus the hinge angle
    out.rod_angle = -d->qpos[c.wrist_q];
    out.rod_omega = -d->qvel[c.wrist_v];
    out.rod_alpha = -d->qacc[c.wrist_v];
  }
  fillReactions(e);

  // Shaking: gravity and gas off, the same motion.
  if (exact) {
    solveAccelerations();
  } else {
    mjModel* sm = soft_model_.get();
    const std::array<double, 3> gravity{sm->opt.gravity[0], sm->opt.gravity[1], sm->opt.gravity[2]};
    mju_zero(sm->opt.gravity, 3);
    solveSoftForces(phi, false);
    for (int i = 0; i < 3; ++i) sm->opt.gravity[i] = gravity[i];
  }
  fillShaking(e);
  checkFinite(e, phi);
  return e;
}

KCrankMujocoModel::KCrankMujocoModel(const Mechanism& m, Variant variant) : impl_(std::make_unique<Impl>(m, variant)) {}
KCrankMujocoModel::~KCrankMujocoModel() = default;
KCrankMujocoModel::KCrankMujocoModel(KCrankMujocoModel&&) noexcept = default;
KCrankMujocoModel& KCrankMujocoModel::operator=(KCrankMujocoModel&&) noexcept = default;

Evaluation KCrankMujocoModel::evaluate(double phi) { return impl_->evaluate(phi); }
void KCrankMujocoModel::setSpeed(double omega) { impl_->setSpeed(omega); }
double KCrankMujocoModel::calcPotentialEnergy(double phi) { return impl_->potentialEnergy(phi); }
double KCrankMujocoModel::calcHoldingTorque(double phi) { return impl_->holdingTorque(phi); }
CrankTorqueLine KCrankMujocoModel::calcCrankTorqueLine(double phi, double phi_dot) {
  return impl_->crankTorqueLine(phi, phi_dot);
}
double KCrankMujocoModel::getLoopClosureError() const { return impl_->closureError(); }
const Mechanism& KCrankMujocoModel::mechanism() const { return impl_->mechanism(); }
Variant KCrankMujocoModel::variant() const { return impl_->variant(); }

}  // namespace crankcheck::mujoco_models
