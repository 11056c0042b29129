#include "crankcheck/solver/stepped_run.h"

#include <algorithm>
#include <cmath>
#include <limits>
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

namespace {
[[noreturn]] void refuse(const std::string& library, const std::string& key, const std::string& why) {
  throw std::invalid_argument(library + " cannot build this scene: " + key + " " + why);
}
}  // namespace

LumpedCrank calcLumpedCrank(const Mechanism& m, const std::string& library) {
  LumpedCrank c;
  double first_x = 0.0, first_y = 0.0;
  for (int j = 0; j < m.machine.cylinders; ++j) {
    const double beta = getThrowAngle(m, j);
    const double first = m.crank.mass * m.crank.com_radius - m.crank.counterweight_mass * m.crank.counterweight_radius;
    c.mass += m.crank.mass + m.crank.counterweight_mass;
    first_x += first * std::cos(beta);
    first_y += first * std::sin(beta);
    c.inertia_about_o += m.crank.mass * m.crank.com_radius * m.crank.com_radius +
                         m.crank.counterweight_mass * m.crank.counterweight_radius * m.crank.counterweight_radius;
  }
  if (!(c.mass > 0.0)) refuse(library, "[crank].mass", "and counterweight_mass are 0 (a body needs a mass)");
  c.p_OBcm = {first_x / c.mass, first_y / c.mass};
  c.inertia_about_cm = c.inertia_about_o - c.mass * (c.p_OBcm[0] * c.p_OBcm[0] + c.p_OBcm[1] * c.p_OBcm[1]);
  if (!(c.inertia_about_cm > 0.0))
    refuse(library, "[crank].com_radius", "and counterweight_radius leave the crank no inertia about its centre of mass");
  return c;
}

Evaluation makeUnreportedEvaluation(const std::string& engine, int cylinders) {
  Evaluation ev;
  ev.engine = engine;
  ev.phi = std::numeric_limits<double>::quiet_NaN();
  ev.cylinders.resize(static_cast<size_t>(cylinders));
  for (const Quantity& q : getQuantityCatalogue())
    for (int c = q.per_cylinder ? 0 : -1; c < (q.per_cylinder ? cylinders : 0); ++c) {
      double* v = accessQuantity(q, ev, c);
      std::fill(v, v + q.components, std::numeric_limits<double>::quiet_NaN());
    }
  return ev;
}

double calcRodCentroidalInertia(const Mechanism& m) {
  return m.rod.inertia_about_wrist_pin - m.rod.mass * m.rod.com_from_wrist_pin * m.rod.com_from_wrist_pin;
}

void checkSteppedScene(const Mechanism& m, const std::string& library) {
  if (!m.balance_shafts.empty()) refuse(library, "[[balance_shaft]]", "has no geared coupling in this " + library + " model");
  if (!(m.rod.mass > 0.0)) refuse(library, "[rod].mass", "must be > 0 (a body needs a mass)");
  if (!(m.piston.mass > 0.0)) refuse(library, "[piston].mass", "must be > 0 (a body needs a mass)");
  if (!(calcRodCentroidalInertia(m) > 0.0))
    refuse(library, "[rod].inertia_about_wrist_pin", "must exceed m_k z_k^2 (the rod's inertia about its centre of mass must be > 0)");
}

}  // namespace crankcheck
