#include "crankcheck/scene/stepped_run.h"

#include <cmath>
#include <stdexcept>

namespace crankcheck {

StartState calcStartState(const Mechanism& m, const Evaluation& exact) {
  const int k = m.machine.cylinders;
  if (static_cast<int>(exact.cylinders.size()) != k)
    throw std::invalid_argument("calcStartState: the evaluation has " + std::to_string(exact.cylinders.size()) +
                                " cylinders, the mechanism " + std::to_string(k));
  const double r = m.crank.radius, omega = m.machine.speed;
  StartState s;
  s.phi = exact.phi;
  s.omega = omega;
  for (int j = 0; j < k; ++j) {
    const CylinderEvaluation& c = exact.cylinders[j];
    CylinderStartState cyl;
    const double gamma = getBankAngle(m, j), delta = getPinOffset(m, j);
    cyl.e = {std::cos(gamma), std::sin(gamma)};
    cyl.n = {-cyl.e[1], cyl.e[0]};
    const double crank_angle = exact.phi + getThrowAngle(m, j);
    cyl.p_WB_W = {r * std::cos(crank_angle), r * std::sin(crank_angle)};
    cyl.x_p = c.x_p;
    cyl.v_p = c.v_p;
    cyl.p_WA_W = {c.x_p * cyl.e[0] + delta * cyl.n[0], c.x_p * cyl.e[1] + delta * cyl.n[1]};
    const Vec2 v_A = {c.v_p * cyl.e[0], c.v_p * cyl.e[1]};
    // The rod from A to B is l (-cos beta e + sin beta n) (CONVENTIONS); its body turns about +Z at -beta_dot.
    const Vec2 u = {-std::cos(c.rod_angle) * cyl.e[0] + std::sin(c.rod_angle) * cyl.n[0],
                    -std::cos(c.rod_angle) * cyl.e[1] + std::sin(c.rod_angle) * cyl.n[1]};
    const double z = m.rod.com_from_wrist_pin;
    cyl.rod.p_WBcm_W = {cyl.p_WA_W[0] + z * u[0], cyl.p_WA_W[1] + z * u[1]};
    cyl.rod.angle = std::atan2(u[1], u[0]);
    cyl.rod.omega = -c.rod_omega;
    cyl.rod.v_WBcm_W = {v_A[0] - cyl.rod.omega * z * u[1], v_A[1] + cyl.rod.omega * z * u[0]};
    cyl.piston.p_WBcm_W = cyl.p_WA_W;
    cyl.piston.v_WBcm_W = v_A;
    s.cylinders.push_back(cyl);
  }
  return s;
}

}  // namespace crankcheck
