#include "crankcheck/analytic/shaking.h"

#include "crankcheck/analytic/kinematics.h"

namespace crankcheck::analytic {

Shaking calcShaking(const Mechanism& m, double phi) {
  const double r = m.crank.radius, w = m.engine.speed;
  const double m_o = m.piston.mass, m_k = m.rod.mass;
  const double I_G = m.rod.inertia_about_wrist_pin - m_k * m.rod.com_from_wrist_pin * m.rod.com_from_wrist_pin;
  const double throw_first_moment = m.crank.mass * m.crank.com_radius - m.crank.counterweight_mass * m.crank.counterweight_radius;
  double P_dot[2] = {0.0, 0.0}, H_dot[3] = {0.0, 0.0, 0.0};
  for (int j = 0; j < m.engine.cylinders; ++j) {
    const CylinderMotion c = calcCylinderMotion(m, j, phi);
    // m a of the piston, the rod and the throw (m_s at r_s, m_p at -r_p on the crank line: a = -omega^2 p), and
    // p x m a about O, all in cylinder j's frame (planar cross products are the same in every rotated frame).
    const double piston[2] = {m_o * c.a_A[0], m_o * c.a_A[1]};
    const double rod[2] = {m_k * c.a_G[0], m_k * c.a_G[1]};
    const double crank[2] = {-w * w * throw_first_moment / r * c.p_OB[0], -w * w * throw_first_moment / r * c.p_OB[1]};
    const double f_C[2] = {piston[0] + rod[0] + crank[0], piston[1] + rod[1] + crank[1]};
    const double moment_Z = (c.p_OA[0] * piston[1] - c.p_OA[1] * piston[0]) + (c.p_OG[0] * rod[1] - c.p_OG[1] * rod[0]) +
                            I_G * c.psi_ddot;  // the throw's p x m a is parallel: no Z part
    // To global X, Y: e = (cos gamma, sin gamma), n = (-sin gamma, cos gamma).
    const double f_X = f_C[0] * c.gamma.cos - f_C[1] * c.gamma.sin;
    const double f_Y = f_C[0] * c.gamma.sin + f_C[1] * c.gamma.cos;
    P_dot[0] += f_X;
    P_dot[1] += f_Y;
    H_dot[0] += -c.z * f_Y;
    H_dot[1] += c.z * f_X;
    H_dot[2] += moment_Z;
  }
  Shaking s;
  s.force = {-P_dot[0], -P_dot[1]};
  s.moment = {-H_dot[0], -H_dot[1], -H_dot[2]};
  return s;
}

}  // namespace crankcheck::analytic
