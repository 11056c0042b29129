#include "crankcheck/analytic/reactions.h"

#include <Eigen/Core>
#include <cmath>

#include "crankcheck/analytic/balance_shafts.h"
#include "crankcheck/analytic/exact_trig.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/analytic/shaking.h"

namespace crankcheck::analytic {
namespace {

using Eigen::Vector2d;

// The Z component of a x b for planar vectors (in the cylinder frame (e, n), right-handed like (X, Y), so the same
// as in global coordinates).
double cross(const Vector2d& a, const Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// The reactions are computed with Eigen vectors; the results are stored as the plain Vec2 (std::array) of
// scene/evaluation.h, the type every engine fills: Simbody's translation units include it, and SimTK's catch-all
// operators clash with Eigen's (simbody_models/README.md, "Traps met").
Vec2 toVec2(const Vector2d& v) { return {v.x(), v.y()}; }

}  // namespace

Reactions calcReactions(const Mechanism& m, double phi, RodInertiaForm rod) {
  return calcReactions(m, phi, calcCylinderMotions(m, phi), rod);
}

Reactions calcReactions(const Mechanism& m, double phi, const std::vector<CylinderMotion>& motions, RodInertiaForm rod) {
  return calcReactionsAtState(m, phi, m.machine.speed, 0.0, motions, rod);
}

Reactions calcReactionsAtState(const Mechanism& m, double phi, double omega, double alpha,
                               const std::vector<CylinderMotion>& motions, RodInertiaForm rod) {
  const double r = m.crank.radius, w = omega, g = m.machine.gravity;
  const double m_o = m.piston.mass, m_k = m.rod.mass;
  // The rod's inertia about the wrist pin A: the two point masses give m_k3 l^2 = m_k z_k l; Delta_I makes up the rest.
  const double I_o = rod == RodInertiaForm::kTwoMassWithoutDeltaI ? m_k * m.rod.com_from_wrist_pin * m.rod.length
                                                                   : m.rod.inertia_about_wrist_pin;
  const double m_s = m.crank.mass, m_p = m.crank.counterweight_mass;

  Reactions out;
  for (int j = 0; j < m.machine.cylinders; ++j) {
    const CylinderMotion& c = motions[static_cast<size_t>(j)];
    // R_WC: cylinder frame (e_j, n_j) to global (X, Y); gravity (0, -g) in cylinder j's frame.
    const SinCos gamma = c.gamma;
    Eigen::Matrix2d R_WC;
    R_WC << gamma.cos, -gamma.sin, gamma.sin, gamma.cos;
    const Vector2d g_C{-g * gamma.sin, -g * gamma.cos};

    const Vector2d& p_OA = c.p_OA;
    const Vector2d& p_OB = c.p_OB;
    const Vector2d p_AB = p_OB - p_OA, p_AG = c.p_OG - p_OA;
    const Vector2d& a_A = c.a_A;

    // Piston along e gives F_A.e (the gas pushes it toward the crank with F_gas); rod moments about A give F_A.n.
    const double F_gas = calcGasForce(m, j, phi);
    Vector2d F_A;
    F_A.x() = m_o * (a_A.x() - g_C.x()) + F_gas;
    const Vector2d rod_net = m_k * (c.a_G - g_C);  // F_B - F_A
    const double moment = I_o * c.psi_ddot + cross(p_AG, m_k * a_A) - cross(p_AG, m_k * g_C) - cross(p_AB, rod_net);
    // moment = (B - A) x F_A = p_AB.e F_A.n - p_AB.n F_A.e
    F_A.y() = (moment + p_AB.y() * F_A.x()) / p_AB.x();
    const Vector2d F_B = rod_net + F_A;
    const double N_w = -F_A.y() - m_o * g_C.y();

    const Vector2d p_OS = (m.crank.com_radius / r) * p_OB;
    const Vector2d p_OC = (-m.crank.counterweight_radius / r) * p_OB;
    Vector2d a_S = (-w * w) * p_OS, a_C = (-w * w) * p_OC;  // the throw's masses on the crank line
    if (alpha != 0.0) {
      a_S += alpha * Vector2d{-p_OS.y(), p_OS.x()};
      a_C += alpha * Vector2d{-p_OC.y(), p_OC.x()};
    }
    const Vector2d F_O = m_s * (a_S - g_C) + m_p * (a_C - g_C) + F_B;
    double tau = cross(p_OB, F_B) - cross(p_OS, m_s * g_C) - cross(p_OC, m_p * g_C);
    if (alpha != 0.0)  // the rate of the throw's angular momentum about O
      tau += (m_s * m.crank.com_radius * m.crank.com_radius +
              m_p * m.crank.counterweight_radius * m.crank.counterweight_radius) * alpha;

    out.cylinders.push_back({toVec2(R_WC * F_B), toVec2(R_WC * F_A), N_w});
    const Vector2d F_O_W = R_WC * F_O;
    out.bearing_force[0] += F_O_W.x();
    out.bearing_force[1] += F_O_W.y();
    out.drive_torque += tau;
  }
  // The balance shafts: the gear gives each the torque it needs (its gravity torque at constant speed; plus its inertia
  // at an accelerating crank), times the ratio at the crank; no force on the main bearing (balance_shafts.h).
  out.drive_torque += calcBalanceShaftLoads(m, phi, omega, alpha).drive_torque;
  if (alpha != 0.0) out.drive_torque += m.flywheel_inertia.value_or(0.0) * alpha;  // the flywheel (I_w, motion.h's J)
  return out;
}

Evaluation calcEvaluation(const Mechanism& m, double phi) {
  return calcEvaluationAtState(m, phi, m.machine.speed, 0.0);
}

Evaluation calcEvaluationAtState(const Mechanism& m, double phi, double omega, double alpha) {
  Evaluation ev;
  ev.engine = "analytic";
  ev.phi = phi;
  ev.U = calcPotentialEnergy(m, phi);
  ev.Q = calcGravityTorque(m, phi);
  // Every cylinder's motion once: the reactions, the shaking and the kinematics below all read it.
  const std::vector<CylinderMotion> motions = calcCylinderMotions(m, phi, omega, alpha);
  const Reactions reactions = calcReactionsAtState(m, phi, omega, alpha, motions);
  ev.drive_torque = reactions.drive_torque;
  ev.bearing_force = reactions.bearing_force;
  const Shaking shaking = calcShaking(m, motions, phi, omega, alpha);
  ev.shaking_force = shaking.force;
  ev.shaking_moment = shaking.moment;
  for (size_t j = 0; j < motions.size(); ++j) {
    const CylinderMotion& motion = motions[j];
    CylinderEvaluation c;
    c.x_p = motion.piston.x_p;
    c.v_p = motion.piston.v_p;
    c.a_p = motion.piston.a_p;
    c.crank_pin_force = reactions.cylinders[j].crank_pin_force;
    c.wrist_pin_force = reactions.cylinders[j].wrist_pin_force;
    c.wall_force = reactions.cylinders[j].wall_force;
    c.gas_force = calcGasForce(m, static_cast<int>(j), phi);
    c.rod_angle = motion.rod.beta;
    c.rod_omega = motion.rod.beta_dot;
    c.rod_alpha = motion.rod.beta_ddot;
    ev.cylinders.push_back(c);
  }
  return ev;
}

}  // namespace crankcheck::analytic
