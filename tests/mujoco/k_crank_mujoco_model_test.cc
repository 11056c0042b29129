// The MuJoCo engine on its own (no analytic library, no Simbody): what it refuses, how well it closes the loop, its
// speeds, accelerations and Q against finite differences of its own positions and energies, a mirror symmetry, and
// MuJoCo's soft solver measured against MuJoCo's exact multipliers (the findings of the report's engines part, asserted).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "crankcheck/mujoco_models/k_crank_mujoco_model.h"
#include "crankcheck/scene/mechanism.h"
#include "../support/test_numbers.h"

namespace crankcheck {
namespace {

using mujoco_models::KCrankMujocoModel;
using mujoco_models::Variant;

using testing::kEps;

// A standing single cylinder of car size at lambda (crank 50 mm).
Mechanism single(double lambda, double rpm, double gamma_deg = 90.0) {
  Mechanism m;
  m.name = "single";
  m.machine.cylinders = 1;
  m.machine.crank_angles = {0.0};
  m.machine.cylinder_angle = radiansFromDegrees(gamma_deg);
  m.machine.speed = rpm * M_PI / 30.0;
  m.speed_rpm = rpm;
  m.crank = {0.05, 1.7, 0.02, 1.3, 0.04};
  m.rod.length = 0.05 / lambda;
  m.rod.mass = 0.61;
  m.rod.com_from_wrist_pin = 0.3 * m.rod.length;
  m.rod.inertia_about_wrist_pin = 0.61 * (std::pow(0.3 * m.rod.length, 2) + std::pow(0.27 * m.rod.length, 2));
  m.piston.mass = 0.43;
  return m;
}

// The absolute potential MuJoCo subtracts to form U = V(phi) - V(0): every mass at up to l + r from O [J].
double absolutePotential(const Mechanism& m) {
  return m.machine.gravity * (m.piston.mass + m.rod.mass + m.crank.mass + m.crank.counterweight_mass) *
         (m.rod.length + m.crank.radius);
}

void expectRefusal(const Mechanism& m, const std::string& key) {
  try {
    KCrankMujocoModel model(m);
    FAIL() << "built a model MuJoCo cannot build; expected a refusal naming " << key;
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind(key + ":", 0), 0u) << e.what();
  }
}

TEST(MujocoModel, RefusesWhatMujocoCannotBuildNamingTheKey) {
  Mechanism m = single(0.3, 3000.0);
  m.piston.mass = 0.0;
  expectRefusal(m, "piston.mass");
  m = single(0.3, 3000.0);
  m.rod.inertia_about_wrist_pin = m.rod.mass * m.rod.com_from_wrist_pin * m.rod.com_from_wrist_pin;  // a point-mass rod
  expectRefusal(m, "rod.inertia_about_wrist_pin");
  m = single(0.3, 3000.0);
  m.crank.mass = m.crank.counterweight_mass = 0.0;
  expectRefusal(m, "crank.mass");
}

TEST(MujocoModel, MjcfIsWrittenInMemoryWithOneConnectPerCylinder) {
  Mechanism m = single(0.3, 0.0);
  const std::string xml = mujoco_models::calcMjcf(m);
  EXPECT_NE(xml.find("<connect name=\"loop0\" body1=\"rod0\" body2=\"crank\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("constraint=\"disable\""), std::string::npos) << "the exact way never calls MuJoCo's solver";
  EXPECT_NE(mujoco_models::calcMjcf(m, Variant::kSoftStiff).find("solimp=\"0.9999 0.9999"), std::string::npos);
}

// Newton on MuJoCo's own kinematics closes every loop to 4 eps (l + r) (its stopping rule), even at lambda = 0.999
// where the rod is almost perpendicular to the cylinder at phi = 90 degrees.
TEST(MujocoModel, LoopClosesToRounding) {
  for (double lambda : {1e-6, 0.3, 0.999}) {
    const Mechanism m = single(lambda, 3000.0);
    KCrankMujocoModel model(m);
    for (double deg = -180.0; deg <= 180.0; deg += 7.5) {
      model.evaluate(radiansFromDegrees(deg));
      EXPECT_LE(model.getLoopClosureError(), 4.0 * kEps * (m.rod.length + m.crank.radius)) << lambda << " " << deg;
    }
  }
}

// v_p and a_p against central differences of MuJoCo's own x_p and v_p over the crank angle, Q against the central
// difference of its U. Step h = 1e-4 rad. Truncation: h^2 / 6 max |f'''|; at lambda = 0.3 the third derivatives of x_p
// and v_p / omega over theta are below 3 r and 6 r (r (1 + 4 lambda / (1 - lambda^2)^(5/2)) and the next order), of U
// below 3 E_abs; rounding: 4 eps of the absolute size over h.
TEST(MujocoModel, RatesAgreeWithFiniteDifferencesOfItsOwnPositions) {
  const Mechanism m = single(0.3, 3000.0, 37.0);
  KCrankMujocoModel model(m);
  const double h = 1e-4, w = m.machine.speed, r = m.crank.radius, size = m.rod.length + r;
  const double V = absolutePotential(m);
  for (double deg = 0.0; deg < 360.0; deg += 30.0) {
    const double phi = radiansFromDegrees(deg);
    const Evaluation e = model.evaluate(phi), plus = model.evaluate(phi + h), minus = model.evaluate(phi - h);
    const double x_rate = (plus.cylinders[0].x_p - minus.cylinders[0].x_p) / (2 * h);
    EXPECT_NEAR(e.cylinders[0].v_p, w * x_rate, w * (h * h / 6 * 3 * r + 4 * kEps * size / h)) << deg;
    const double v_rate = (plus.cylinders[0].v_p - minus.cylinders[0].v_p) / (2 * h);
    EXPECT_NEAR(e.cylinders[0].a_p, w * v_rate, w * w * (h * h / 6 * 6 * r) + w * 4 * kEps * (w * size) / h) << deg;
    const double u_rate = (model.calcPotentialEnergy(phi + h) - model.calcPotentialEnergy(phi - h)) / (2 * h);
    EXPECT_NEAR(e.Q, u_rate, h * h / 6 * 3 * V + 4 * kEps * V / h) << deg;
  }
}

// A closure started from MuJoCo's own last motion carried on to the next angle (its Taylor step, within 1 rad) against
// one started from the last angle's q (the motion at rest is none: the static walk) and one from the crude guess (the
// angle before 3 rad away): the same evaluation to rounding, 16 eps of each quantity's scale (three converged closures
// to 4 eps (l + r) each; the velocities and accelerations solved from the same closed positions), times the loop's
// conditioning: near lambda = 1 the rod swings almost across the cylinder (cos beta down to sqrt(1 - lambda^2)), a
// closure's rounding moves the piston by 1 / cos beta of it and the loads by up to 1 / cos^3 beta (the plain warm start
// differs from the crude one by 250 eps of the force scale at lambda = 0.999, 90 degrees; the bound there is 1.1e4 x
// 16 eps). Steps of 1e-6 to 57 degrees (a refinement's last, the offset sweep's, the cross-check's, the gate's), a long
// and a short rod, four cylinders at a bank angle.
TEST(MujocoModel, ClosureStartedFromItsLastMotionGivesTheSameEvaluation) {
  for (double lambda : {0.05, 0.3, 0.999}) {
    Mechanism m = single(lambda, 3000.0, 37.0);
    m.machine.cylinders = 4;
    m.machine.crank_angles = {0.0, M_PI, M_PI, 0.0};
    const double w = m.machine.speed, r = m.crank.radius, L = m.rod.length + r;
    const double mass = 4 * (m.piston.mass + m.rod.mass + m.crank.mass + m.crank.counterweight_mass);
    const double F = mass * (m.machine.gravity + r * w * w * (1 + lambda)), T = F * r, v = r * w * (1 + lambda);
    const double closure = 1.0 / std::sqrt(1.0 - lambda * lambda), c = 16 * kEps * std::pow(closure, 3);
    KCrankMujocoModel taylor(m), cold(m);
    for (double deg : {0.0, 17.0, 90.0, 133.0, 222.5, 300.0})
      for (double step_deg : {1e-6, 1.0, 15.0, 57.0}) {
        SCOPED_TRACE("lambda " + std::to_string(lambda) + ", " + std::to_string(deg) + " degrees after a step of " +
                     std::to_string(step_deg));
        const double phi = radiansFromDegrees(deg);
        taylor.evaluate(phi - radiansFromDegrees(step_deg));
        const Evaluation a = taylor.evaluate(phi);
        cold.evaluate(phi + 3.0);
        const Evaluation b = cold.evaluate(phi);
        EXPECT_NEAR(a.drive_torque, b.drive_torque, c * T);
        EXPECT_NEAR(a.Q, b.Q, c * T);
        for (int i = 0; i < 2; ++i) EXPECT_NEAR(a.bearing_force[i], b.bearing_force[i], c * F);
        for (size_t j = 0; j < a.cylinders.size(); ++j) {
          const CylinderEvaluation &x = a.cylinders[j], &y = b.cylinders[j];
          EXPECT_NEAR(x.x_p, y.x_p, 16 * kEps * closure * L);
          EXPECT_NEAR(x.v_p, y.v_p, c * v);
          EXPECT_NEAR(x.a_p, y.a_p, c * v * w);
          EXPECT_NEAR(x.wall_force, y.wall_force, c * F);
          for (int i = 0; i < 2; ++i) EXPECT_NEAR(x.crank_pin_force[i], y.crank_pin_force[i], c * F);
        }
      }
  }
}

// A standing engine mirrored about its axis: phi -> -phi leaves x_p and the wall force's size, and turns Q and the
// rod angle into their negatives (exactly in the mechanics; to a few eps of their scales in MuJoCo).
TEST(MujocoModel, StandingEngineIsMirrorSymmetric) {
  const Mechanism m = single(0.3, 0.0);
  KCrankMujocoModel model(m);
  const double E = m.machine.gravity * (m.piston.mass + m.rod.mass + m.crank.mass + m.crank.counterweight_mass) * m.crank.radius;
  for (double deg : {17.0, 45.0, 90.0, 133.0}) {
    const Evaluation a = model.evaluate(radiansFromDegrees(deg)), b = model.evaluate(radiansFromDegrees(-deg));
    EXPECT_NEAR(a.cylinders[0].x_p, b.cylinders[0].x_p, 8 * kEps * (m.rod.length + m.crank.radius));
    EXPECT_NEAR(a.cylinders[0].rod_angle, -b.cylinders[0].rod_angle, 8 * kEps);
    EXPECT_NEAR(a.Q, -b.Q, 16 * kEps * absolutePotential(m)) << "E = " << E;
  }
}

// MuJoCo's soft solver against MuJoCo's exact multipliers (same model, same state). At rest its error is the
// constraint's softness: a few percent of Q's size at the default impedance (0.9), a thousand times less at the
// stiffest (0.9999). At speed the stiff setting does not help: one forward step leaves out the loop's velocity-product
// term, so the drive torque is off by the same several percent whatever solref/solimp. Findings, asserted.
TEST(MujocoModel, SoftSolverErrorsAreFindings) {
  const Mechanism rest = single(0.3, 0.0), moving = single(0.3, 3000.0);
  KCrankMujocoModel exact_rest(rest), soft_rest(rest, Variant::kSoftDefault), stiff_rest(rest, Variant::kSoftStiff);
  KCrankMujocoModel exact(moving), soft(moving, Variant::kSoftDefault), stiff(moving, Variant::kSoftStiff);
  double q_peak = 0.0, soft_q = 0.0, stiff_q = 0.0, torque_peak = 0.0, soft_torque = 0.0, stiff_torque = 0.0;
  for (double deg = 0.0; deg < 360.0; deg += 15.0) {
    const double phi = radiansFromDegrees(deg);
    const double q = exact_rest.evaluate(phi).Q;
    q_peak = std::max(q_peak, std::fabs(q));
    soft_q = std::max(soft_q, std::fabs(soft_rest.evaluate(phi).Q - q));
    stiff_q = std::max(stiff_q, std::fabs(stiff_rest.evaluate(phi).Q - q));
    const double t = exact.evaluate(phi).drive_torque;
    torque_peak = std::max(torque_peak, std::fabs(t));
    soft_torque = std::max(soft_torque, std::fabs(soft.evaluate(phi).drive_torque - t));
    stiff_torque = std::max(stiff_torque, std::fabs(stiff.evaluate(phi).drive_torque - t));
  }
  EXPECT_GT(soft_q, 1e-2 * q_peak);
  EXPECT_LT(stiff_q, 1e-2 * soft_q);
  EXPECT_GT(soft_torque, 1e-2 * torque_peak);
  EXPECT_GT(stiff_torque, 0.5 * soft_torque);
}

}  // namespace
}  // namespace crankcheck
