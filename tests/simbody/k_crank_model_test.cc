// Unit tests of the Simbody k-crank model against things it did not produce and that need no analytic library:
// the three routes to Q = dU/dphi, dead centres, hand-computed energies, each body's Newton-Euler balance from
// Simbody's own accelerations, the energy balance, the static limit, the frictionless wall.
//
// Tolerances (CONVENTIONS.md): a multiple of machine epsilon times a physical scale of the case, or, for finite
// differences, the truncation bound plus the roundoff bound, each written next to its test.
//   torque scale (gravity)  T_g = m_total g r
//   force scale             F   = m_total (g + r omega^2 (1 + lambda))   (bound on |m a| + |m g| of every body)
//   torque scale (dynamic)  T   = F r
//   energy scale            E   = m_total (g (l + 2 r) + (r omega (1 + lambda))^2)
//                                 (bound on |V| with heights up to l + r + r_p <= l + 2r, and on 2 KE)
// Set CRANKCHECK_PRINT_RATIOS=1 to print the worst error / scale ratio seen by each check.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "crankcheck/scene/mechanism.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/simbody_models/k_crank_gravity_model.h"
#include "crankcheck/simbody_models/k_crank_model.h"
#include "../support/test_numbers.h"

namespace crankcheck::simbody_models {
namespace {

using testing::kEps;
constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------------------------------------------------------
// Worst error / scale ratios, printed at exit when CRANKCHECK_PRINT_RATIOS is set (for the report).
std::map<std::string, double>& worstRatios() {
  static std::map<std::string, double> ratios;
  return ratios;
}
void record(const std::string& check, double error, double scale) {
  double& worst = worstRatios()[check];
  worst = std::max(worst, std::abs(error) / scale);
}
class RatioPrinter : public ::testing::Environment {
 public:
  void TearDown() override {
    if (std::getenv("CRANKCHECK_PRINT_RATIOS") == nullptr) return;
    for (const auto& [check, ratio] : worstRatios())
      std::printf("worst |error| / scale  %-40s %.3g  (= %.3g eps)\n", check.c_str(), ratio, ratio / kEps);
  }
};
[[maybe_unused]] const auto* const kRatioPrinter = ::testing::AddGlobalTestEnvironment(new RatioPrinter);

// Checks |actual - expected| <= tolerance and records the ratio to `scale` under `check`.
#define EXPECT_WITHIN(check, actual, expected, tolerance, scale)                                            \
  do {                                                                                                       \
    const double actual_ = (actual);                                                                         \
    const double expected_ = (expected);                                                                     \
    record(check, actual_ - expected_, scale);                                                               \
    EXPECT_LE(std::abs(actual_ - expected_), (tolerance))                                                    \
        << check << ": actual " << actual_ << ", expected " << expected_ << ", error/scale "                 \
        << std::abs(actual_ - expected_) / (scale);                                                          \
  } while (0)

// ---------------------------------------------------------------------------------------------------------------
// Planar vector helpers.
Vec2 operator+(Vec2 a, Vec2 b) { return {a[0] + b[0], a[1] + b[1]}; }
Vec2 operator-(Vec2 a, Vec2 b) { return {a[0] - b[0], a[1] - b[1]}; }
Vec2 operator*(double s, Vec2 a) { return {s * a[0], s * a[1]}; }
double cross(Vec2 a, Vec2 b) { return a[0] * b[1] - a[1] * b[0]; }
double dot(Vec2 a, Vec2 b) { return a[0] * b[0] + a[1] * b[1]; }

// ---------------------------------------------------------------------------------------------------------------
// Test mechanisms: non-unit masses, rod centre of mass off the middle (z_k = 0.121 m != l/2 = 0.085 m), a rod
// inertia that is not the two-mass one, counterweight and crank mass at different radii.
struct Case {
  int k = 1;
  Cycle cycle = Cycle::kFourStroke;
  double gamma_deg = 90.0;
  double omega = 0.0;
};
std::string caseName(const Case& c);
void PrintTo(const Case& c, std::ostream* os) { *os << caseName(c); }  // stable, readable ctest names

Mechanism makeMechanism(const Case& c) {
  Mechanism m;
  m.name = "test";
  m.machine.cylinders = c.k;
  m.machine.cycle = c.cycle;
  m.machine.acting = Acting::kSingle;
  m.machine.crank_angles = calcPhaseAngles(c.k, c.cycle, Acting::kSingle);
  m.machine.cylinder_angle = radiansFromDegrees(c.gamma_deg);
  m.machine.speed = c.omega;
  m.machine.gravity = 9.80665;
  m.crank.radius = 0.05;
  m.crank.mass = 1.3;
  m.crank.com_radius = 0.021;
  m.crank.counterweight_mass = 0.9;
  m.crank.counterweight_radius = 0.037;
  m.rod.length = 0.17;  // lambda = 0.294
  m.rod.mass = 0.83;
  m.rod.com_from_wrist_pin = 0.121;
  m.rod.inertia_about_wrist_pin = 0.83 * 0.121 * 0.121 + 0.0019;
  m.piston.mass = 0.47;
  return m;
}

std::string caseName(const Case& c) {
  std::string gamma = std::to_string(static_cast<int>(std::lround(c.gamma_deg)));
  if (gamma[0] == '-') gamma = "m" + gamma.substr(1);
  return "k" + std::to_string(c.k) + (c.cycle == Cycle::kTwoStroke ? "_two" : "_four") + "_gamma" + gamma + "_w" +
         std::to_string(static_cast<int>(std::lround(c.omega)));
}

struct Scales {
  double m_total, r, l, lambda, omega, g;
  double torque_gravity;  // T_g
  double force;           // F
  double torque;          // T
  double energy;          // E
};

Scales scalesOf(const Mechanism& m) {
  Scales s{};
  s.m_total = m.machine.cylinders *
              (m.piston.mass + m.rod.mass + m.crank.mass + m.crank.counterweight_mass);
  s.r = m.crank.radius;
  s.l = m.rod.length;
  s.lambda = s.r / s.l;
  s.omega = m.machine.speed;
  s.g = m.machine.gravity;
  s.torque_gravity = s.m_total * s.g * s.r;
  s.force = s.m_total * (s.g + s.r * s.omega * s.omega * (1.0 + s.lambda));
  s.torque = s.force * s.r;
  const double v = s.r * s.omega * (1.0 + s.lambda);
  s.energy = s.m_total * (s.g * (s.l + 2.0 * s.r) + v * v);
  return s;
}

// Crank angles: both dead centres of cylinder 0 and generic angles in every quadrant, beyond 2 pi and negative.
const std::vector<double> kAngles = {0.0, kPi, 0.3, 1.234, 2.9, 4.4, 5.8, 7.5, -2.2};

std::vector<Case> allCases() {
  std::vector<Case> cases;
  for (int k : {1, 2, 3, 4, 6, 12})
    for (double gamma : {0.0, 90.0, -90.0, 180.0, 37.0})
      for (double omega : {0.0, 600.0})
        cases.push_back({k, (k % 2 == 0) ? Cycle::kFourStroke : Cycle::kTwoStroke, gamma, omega});
  return cases;
}

class KCrankModelTest : public ::testing::TestWithParam<Case> {
 protected:
  KCrankModelTest() : mechanism_(makeMechanism(GetParam())), scales_(scalesOf(mechanism_)), model_(mechanism_) {}
  // Two converged assemblies of the same angle (another start, another history): the same evaluation to roundoff, 16 eps
  // of each quantity's scale (two Newton solutions differ at roundoff; seen <= 2 eps).
  void expectSameToRoundoff(const std::string& what, const Evaluation& got, const Evaluation& expected) const {
    const double F = scales_.force, L = scales_.l + scales_.r;
    EXPECT_WITHIN(what + ": drive torque", got.drive_torque, expected.drive_torque, 16 * kEps * scales_.torque,
                  scales_.torque);
    EXPECT_WITHIN(what + ": Q", got.Q, expected.Q, 16 * kEps * scales_.torque_gravity, scales_.torque_gravity);
    EXPECT_WITHIN(what + ": U", got.U, expected.U, 16 * kEps * scales_.energy, scales_.energy);
    for (int i = 0; i < 2; ++i)
      EXPECT_WITHIN(what + ": bearing", got.bearing_force[i], expected.bearing_force[i], 16 * kEps * F, F);
    for (std::size_t j = 0; j < expected.cylinders.size(); ++j) {
      EXPECT_WITHIN(what + ": x_p", got.cylinders[j].x_p, expected.cylinders[j].x_p, 16 * kEps * L, L);
      EXPECT_WITHIN(what + ": wall", got.cylinders[j].wall_force, expected.cylinders[j].wall_force, 16 * kEps * F, F);
      EXPECT_WITHIN(what + ": crank pin", got.cylinders[j].crank_pin_force[0], expected.cylinders[j].crank_pin_force[0],
                    16 * kEps * F, F);
    }
  }
  Mechanism mechanism_;
  Scales scales_;
  KCrankModel model_;
};

// ---------------------------------------------------------------------------------------------------------------
// Q route 1 (static holding torque from the prescribed-motion force) against route 2 (virtual power of Simbody's
// gravity forces at unit crank speed). Both are linear algebra at the same assembled configuration, so they agree
// to roundoff: each is a sum over O(k) bodies of terms bounded by T_g, after solves whose condition number is
// O(1/(1 - lambda)) ~ 1.4. Allowed: 32 eps T_g (up to k + 1 = 13 bodies' terms of a few flops each, times the
// condition number; seen: 2 eps T_g).
TEST_P(KCrankModelTest, HoldingTorqueEqualsVirtualPower) {
  const double tolerance = 32 * kEps * scales_.torque_gravity;
  for (double phi : kAngles) {
    SCOPED_TRACE("phi = " + std::to_string(phi));
    const double holding = model_.calcHoldingTorque(phi);
    const double virtual_power = model_.calcVirtualPowerQ(phi);
    EXPECT_WITHIN("Q holding vs virtual power", holding, virtual_power, tolerance, scales_.torque_gravity);
    // evaluate() reports route 1.
    EXPECT_WITHIN("Q evaluate vs holding", model_.evaluate(phi).Q, holding, tolerance, scales_.torque_gravity);
  }
}

// Route 2 read off an evaluation at the scene's speed (the velocities there, per unit omega: the model keeps gravity's
// power of its dynamic pass) against route 2 solved afresh at unit crank speed by a model that evaluated nothing.
// The velocity solve is linear in omega, so the two differ by the roundoff of the scaling and of two projections:
// the same 32 eps T_g as above (seen: below 1 eps T_g).
TEST_P(KCrankModelTest, VirtualPowerAfterAnEvaluationEqualsAFreshOne) {
  const double tolerance = 32 * kEps * scales_.torque_gravity;
  for (double phi : kAngles) {
    SCOPED_TRACE("phi = " + std::to_string(phi));
    KCrankModel fresh(model_.mechanism());
    const double unit_speed = fresh.calcVirtualPowerQ(phi);
    model_.evaluate(phi);
    EXPECT_WITHIN("Q virtual power after evaluate vs fresh", model_.calcVirtualPowerQ(phi), unit_speed, tolerance,
                  scales_.torque_gravity);
  }
}

// evaluateMotion skips the static pass and nothing else: against evaluate() of a second model taken through the same
// angles (so that both assemble from the same warm starts), every field but U and Q is the same number, bit for bit
// (the dynamic pass starts from the same positions and zero velocities), and U and Q are NaN.
TEST_P(KCrankModelTest, MotionOnlyEvaluationIsTheEvaluationWithoutUAndQ) {
  KCrankModel full(mechanism_);
  for (double phi : kAngles) {
    SCOPED_TRACE("phi = " + std::to_string(phi));
    const Evaluation a = full.evaluate(phi), b = model_.evaluateMotion(phi);
    EXPECT_TRUE(std::isnan(b.U));
    EXPECT_TRUE(std::isnan(b.Q));
    EXPECT_EQ(b.drive_torque, a.drive_torque);
    EXPECT_EQ(b.bearing_force, a.bearing_force);
    EXPECT_EQ(b.shaking_force, a.shaking_force);
    EXPECT_EQ(b.shaking_moment, a.shaking_moment);
    ASSERT_EQ(b.cylinders.size(), a.cylinders.size());
    for (size_t j = 0; j < a.cylinders.size(); ++j) {
      const CylinderEvaluation &x = a.cylinders[j], &y = b.cylinders[j];
      EXPECT_EQ(y.x_p, x.x_p);
      EXPECT_EQ(y.v_p, x.v_p);
      EXPECT_EQ(y.a_p, x.a_p);
      EXPECT_EQ(y.crank_pin_force, x.crank_pin_force);
      EXPECT_EQ(y.wrist_pin_force, x.wrist_pin_force);
      EXPECT_EQ(y.wall_force, x.wall_force);
      EXPECT_EQ(y.gas_force, x.gas_force);
      EXPECT_EQ(y.rod_angle, x.rod_angle);
      EXPECT_EQ(y.rod_omega, x.rod_omega);
      EXPECT_EQ(y.rod_alpha, x.rod_alpha);
    }
  }
}

// Q route 3: central difference of U = V - V(0). Error = truncation h^2/6 |Q'''| + roundoff.
//  - Truncation: Q is periodic; its harmonic n has amplitude <~ T_g lambda^(n-1), so
//    |Q'''| <= T_g sum n^3 lambda^(n-1) ~ 10 T_g for lambda = 0.3 (an overestimate: ~0.2 T_g is typical).
//  - Roundoff: U(phi +- h) each carry a few eps |V| <= 4 eps E_g (E_g = m_total g (l + 2r)), plus the assembly
//    residual (~1e-17 m after the final Newton step, below eps l), so the difference quotient carries
//    8 eps E_g / (2h).
// h = 2e-5 rad balances the two (h^3 ~ eps (l + 2r) / r): total <~ 1e-9 T_g.
TEST_P(KCrankModelTest, CentralDifferenceOfPotentialEnergyEqualsHoldingTorque) {
  const double h = 2e-5;
  const double energy_gravity = scales_.m_total * scales_.g * (scales_.l + 2 * scales_.r);
  const double tolerance = 10.0 * h * h / 6.0 * scales_.torque_gravity + 8 * kEps * energy_gravity / (2 * h);
  for (double phi : kAngles) {
    SCOPED_TRACE("phi = " + std::to_string(phi));
    EXPECT_WITHIN("Q central difference vs holding", model_.calcQByCentralDifference(phi, h),
                  model_.calcHoldingTorque(phi), tolerance, scales_.torque_gravity);
  }
}

// U(0) = 0 by definition, and U is 2 pi periodic. Allowed: 16 eps E (a handful of roundoff-level terms of size
// up to |V| <= E in each V and in V(0)).
TEST_P(KCrankModelTest, PotentialEnergyIsZeroAtZeroAndPeriodic) {
  const double tolerance = 16 * kEps * scales_.energy;
  EXPECT_WITHIN("U(0)", model_.calcPotentialEnergy(0.0), 0.0, tolerance, scales_.energy);
  for (double phi : kAngles) {
    SCOPED_TRACE("phi = " + std::to_string(phi));
    EXPECT_WITHIN("U periodic", model_.calcPotentialEnergy(phi + 2 * kPi), model_.calcPotentialEnergy(phi),
                  tolerance, scales_.energy);
  }
}

// Piston j is at outer dead centre (x_p = r + l, v_p = 0) when theta_j = phi + alpha_j = 0 and at inner dead
// centre (x_p = l - r) at theta_j = pi. Position: Simbody's residual is below eps l after the final Newton step;
// allowed 16 eps (l + r). Velocity: phi = -alpha_j is itself rounded (|alpha_j| <= 4 pi, error ~ 2 eps), and
// v_p = -r omega sin(theta) (1 + ...) moves by r omega (1 + lambda) per radian: allowed 64 eps r omega.
TEST_P(KCrankModelTest, DeadCentres) {
  const double r = scales_.r;
  const double l = scales_.l;
  const double x_tolerance = 16 * kEps * (l + r);
  const double v_scale = std::max(r * scales_.omega, kEps);  // omega = 0: v_p must be exactly 0 anyway
  const double v_tolerance = 64 * kEps * v_scale;
  for (int j = 0; j < mechanism_.machine.cylinders; ++j) {
    SCOPED_TRACE("cylinder " + std::to_string(j));
    const double alpha = mechanism_.machine.crank_angles[j];
    const Evaluation outer = model_.evaluate(-alpha);
    EXPECT_WITHIN("x_p outer dead centre", outer.cylinders[j].x_p, r + l, x_tolerance, l + r);
    EXPECT_WITHIN("v_p outer dead centre", outer.cylinders[j].v_p, 0.0, v_tolerance, v_scale);
    const Evaluation inner = model_.evaluate(kPi - alpha);
    EXPECT_WITHIN("x_p inner dead centre", inner.cylinders[j].x_p, l - r, x_tolerance, l + r);
    EXPECT_WITHIN("v_p inner dead centre", inner.cylinders[j].v_p, 0.0, v_tolerance, v_scale);
  }
}

// Newton-Euler for every body with Simbody's own accelerations and the reactions the model reports:
//   piston j:   F_wrist_j + N_w,j n + m_o g = m_o a_A
//   rod j:      F_crank_j - F_wrist_j + m_k g = m_k a_G,      (B - G) x F_crank_j + (A - G) x (-F_wrist_j) = I_G alpha
//   crankshaft: F_bearing - sum F_crank_j + m_c g = m_c a_Gc,   drive + sum B_j x (-F_crank_j) + G_c x m_c g = 0
// (g = (0, -g); crankshaft moments about O, where the bearing acts; its angular acceleration is 0). A wrong
// frame, point or sign of any reaction breaks one of these by O(F). The reactions come from Simbody's
// articulated-body recursion and constraint multipliers, consistent with the accelerations to roundoff: each
// balance sums a few terms bounded by F (the crankshaft k + 2 terms) after solves of condition O(1/(1 - lambda)).
// Allowed: 16 (k + 2) eps F for forces and 16 (k + 2) eps F r for moments (arms are <= r, l; l/r ~ 3.4 absorbed
// in the 16). Seen: at most 1 eps F, resp. 1 eps F r.
TEST_P(KCrankModelTest, NewtonEulerBalanceOfEveryBody) {
  const int k = mechanism_.machine.cylinders;
  const double F = scales_.force;
  const double T = scales_.torque;
  const double force_tolerance = 16 * (k + 2) * kEps * F;
  const double moment_tolerance = 16 * (k + 2) * kEps * T;
  const double gamma = mechanism_.machine.cylinder_angle;
  const Vec2 n{-std::sin(gamma), std::cos(gamma)};
  const Vec2 gravity{0.0, -scales_.g};
  for (double phi : kAngles) {
    SCOPED_TRACE("phi = " + std::to_string(phi));
    const Diagnostics d = model_.calcDiagnostics(phi);
    const Evaluation& ev = d.evaluation;
    ASSERT_EQ(static_cast<int>(ev.cylinders.size()), k);
    ASSERT_EQ(static_cast<int>(d.cylinders.size()), k);
    // The masses Simbody carries are the scene's.
    EXPECT_DOUBLE_EQ(d.crankshaft.mass, k * (mechanism_.crank.mass + mechanism_.crank.counterweight_mass));
    Vec2 crank_net = ev.bearing_force + d.crankshaft.mass * gravity;
    double crank_moment = ev.drive_torque + cross(d.crankshaft.com, d.crankshaft.mass * gravity);
    for (int j = 0; j < k; ++j) {
      SCOPED_TRACE("cylinder " + std::to_string(j));
      const CylinderEvaluation& c = ev.cylinders[j];
      const CylinderDiagnostics& cd = d.cylinders[j];
      EXPECT_DOUBLE_EQ(cd.piston.mass, mechanism_.piston.mass);
      EXPECT_DOUBLE_EQ(cd.rod.mass, mechanism_.rod.mass);
      // Piston.
      const Vec2 piston_net = c.wrist_pin_force + c.wall_force * n + cd.piston.mass * gravity;
      const Vec2 piston_ma = cd.piston.mass * cd.piston.com_acceleration;
      for (int i = 0; i < 2; ++i)
        EXPECT_WITHIN("Newton piston", piston_net[i], piston_ma[i], force_tolerance, F);
      // Rod: forces and moment about its centre of mass G.
      const Vec2 rod_net = c.crank_pin_force - c.wrist_pin_force + cd.rod.mass * gravity;
      const Vec2 rod_ma = cd.rod.mass * cd.rod.com_acceleration;
      for (int i = 0; i < 2; ++i) EXPECT_WITHIN("Newton rod", rod_net[i], rod_ma[i], force_tolerance, F);
      const Vec2 G = cd.rod.com;
      const double rod_moment =
          cross(cd.crank_pin - G, c.crank_pin_force) + cross(cd.wrist_pin - G, -1.0 * c.wrist_pin_force);
      EXPECT_WITHIN("Euler rod about G", rod_moment, cd.rod.inertia_about_com * cd.rod.angular_acceleration,
                    moment_tolerance, T);
      crank_net = crank_net - c.crank_pin_force;
      crank_moment += cross(cd.crank_pin, -1.0 * c.crank_pin_force);
    }
    const Vec2 crank_ma = d.crankshaft.mass * d.crankshaft.com_acceleration;
    for (int i = 0; i < 2; ++i) EXPECT_WITHIN("Newton crankshaft", crank_net[i], crank_ma[i], force_tolerance, F);
    EXPECT_WITHIN("crankshaft angular acceleration", d.crankshaft.angular_acceleration, 0.0, 0.0, 1.0);
    EXPECT_WITHIN("Euler crankshaft about O", crank_moment, 0.0, moment_tolerance, T);
  }
}

// The geometry Simbody assembled: the rod's big end sits on the crank pin, the crank pin is at radius r and angle
// gamma + theta_j, the wrist pin is on the cylinder axis at x_p, and the rod is l long. Allowed 16 eps (l + r).
TEST_P(KCrankModelTest, AssembledGeometry) {
  const double r = scales_.r;
  const double l = scales_.l;
  const double tolerance = 16 * kEps * (l + r);
  const double gamma = mechanism_.machine.cylinder_angle;
  const Vec2 e{std::cos(gamma), std::sin(gamma)};
  for (double phi : kAngles) {
    SCOPED_TRACE("phi = " + std::to_string(phi));
    const Diagnostics d = model_.calcDiagnostics(phi);
    EXPECT_LE(d.position_constraint_error, tolerance);
    for (int j = 0; j < mechanism_.machine.cylinders; ++j) {
      const CylinderDiagnostics& cd = d.cylinders[j];
      const double angle = gamma + phi + mechanism_.machine.crank_angles[j];
      for (int i = 0; i < 2; ++i) {
        EXPECT_WITHIN("big end on crank pin", cd.rod_big_end[i], cd.crank_pin[i], tolerance, l + r);
        EXPECT_WITHIN("wrist pin on axis", cd.wrist_pin[i], d.evaluation.cylinders[j].x_p * e[i], tolerance, l + r);
      }
      EXPECT_WITHIN("crank pin x", cd.crank_pin[0], r * std::cos(angle), tolerance, l + r);
      EXPECT_WITHIN("crank pin y", cd.crank_pin[1], r * std::sin(angle), tolerance, l + r);
      const Vec2 rod = cd.crank_pin - cd.wrist_pin;
      EXPECT_WITHIN("rod length", std::sqrt(dot(rod, rod)), l, tolerance, l + r);
      EXPECT_GT(d.evaluation.cylinders[j].x_p, l - r - tolerance);  // the physical assembly branch
    }
  }
}

// Energy balance at constant omega: drive_torque omega = d(KE + PE)/dt = omega d(KE + U)/dphi, with Simbody's KE
// and PE and d/dphi by central difference. Error of the difference quotient: truncation h^2/6 |E'''| with
// |E'''| <= 10 T (harmonic argument as for Q, now on T = F r which bounds dKE/dphi and dU/dphi) plus roundoff
// 8 eps E / (2h) (KE and V each carry a few eps of E). h = 2e-5 rad as for Q. Compared in torque units.
TEST_P(KCrankModelTest, EnergyBalance) {
  const double h = 2e-5;
  const double tolerance = 10.0 * h * h / 6.0 * scales_.torque + 8 * kEps * scales_.energy / (2 * h);
  for (double phi : kAngles) {
    SCOPED_TRACE("phi = " + std::to_string(phi));
    const double up = model_.calcKineticEnergy(phi + h) + model_.calcPotentialEnergy(phi + h);
    const double down = model_.calcKineticEnergy(phi - h) + model_.calcPotentialEnergy(phi - h);
    const double dE_dphi = (up - down) / (2 * h);
    EXPECT_WITHIN("drive torque vs dE/dphi", model_.evaluate(phi).drive_torque, dE_dphi, tolerance,
                  scales_.torque);
  }
}

// At omega = 0 everything is at rest (KE = 0, v_p = a_p = 0) and the drive torque is the holding torque Q,
// computed by a separate velocity/acceleration pass. Every case is run with its omega set to 0. Allowed: 16 eps
// T_g against Q (same formula, same configuration; only the order of realizations differs; seen: exact), 32 eps
// T_g against the virtual-power route (as HoldingTorqueEqualsVirtualPower), exact zeros for the rest state.
TEST_P(KCrankModelTest, StaticLimitDriveTorqueIsQ) {
  Mechanism still = mechanism_;
  still.machine.speed = 0.0;
  KCrankModel model(still);
  for (double phi : kAngles) {
    SCOPED_TRACE("phi = " + std::to_string(phi));
    const Evaluation ev = model.evaluate(phi);
    EXPECT_WITHIN("omega = 0: drive torque vs Q", ev.drive_torque, ev.Q, 16 * kEps * scales_.torque_gravity,
                  scales_.torque_gravity);
    EXPECT_WITHIN("omega = 0: drive torque vs virtual power Q", ev.drive_torque, model.calcVirtualPowerQ(phi),
                  32 * kEps * scales_.torque_gravity, scales_.torque_gravity);
    EXPECT_EQ(model.calcKineticEnergy(phi), 0.0);
    for (const CylinderEvaluation& c : ev.cylinders) {
      EXPECT_EQ(c.v_p, 0.0);  // prescribed crank u = 0 and a consistent zero start: projectU has nothing to do
      // a_p comes out of Simbody's constrained acceleration solve (M udot = f - G^T lambda) as a difference of
      // gravity-sized terms: zero to 64 eps g (seen: 7 eps g).
      EXPECT_WITHIN("omega = 0: a_p", c.a_p, 0.0, 64 * kEps * scales_.g, scales_.g);
    }
  }
}

// The frictionless wall only pushes along n: the slider's reaction on the piston has no e-component and its n
// component is the reported wall force; the piston (a particle with the rod pinned at its centre) gets no
// moment from it. Allowed: 16 eps F (one reaction, a few terms bounded by F; seen 0.3 eps F) and 16 eps F r.
TEST_P(KCrankModelTest, WallForceIsNormalToTheCylinder) {
  const double F = scales_.force;
  const double gamma = mechanism_.machine.cylinder_angle;
  const Vec2 e{std::cos(gamma), std::sin(gamma)};
  const Vec2 n{-std::sin(gamma), std::cos(gamma)};
  for (double phi : kAngles) {
    SCOPED_TRACE("phi = " + std::to_string(phi));
    const Diagnostics d = model_.calcDiagnostics(phi);
    for (int j = 0; j < mechanism_.machine.cylinders; ++j) {
      const CylinderDiagnostics& cd = d.cylinders[j];
      EXPECT_WITHIN("wall force e-component", dot(cd.slider_reaction, e), 0.0, 16 * kEps * F, F);
      EXPECT_WITHIN("wall force n-component", dot(cd.slider_reaction, n), d.evaluation.cylinders[j].wall_force,
                    16 * kEps * F, F);
      EXPECT_WITHIN("slider moment on piston", cd.slider_reaction_moment, 0.0, 16 * kEps * scales_.torque,
                    scales_.torque);
    }
  }
}

// The result must not depend on where the previous assembly was (warm start vs cold start from far away): the same
// evaluation to roundoff (expectSameToRoundoff).
TEST_P(KCrankModelTest, ResultIndependentOfHistory) {
  const double phi = 1.234;
  model_.evaluate(phi + 0.01);
  const Evaluation warm = model_.evaluate(phi);
  model_.evaluate(phi + 3.0);
  const Evaluation cold = model_.evaluate(phi);
  expectSameToRoundoff("history", warm, cold);
}

// An assembly started from the last dynamic pass's motion carried on to the new angle (the Taylor start, up to 1.1 rad)
// against one started from the crude guess (the angle before 3 rad away): the same evaluation to the history's roundoff,
// at the steps the campaign takes (a refinement's last ones, about 1e-6 degrees; the offset sweep's 1 degree, the
// cross-check's 15, the gate's up to 61).
TEST_P(KCrankModelTest, AssemblyStartedFromTheLastMotionGivesTheSameEvaluation) {
  for (double phi : kAngles)
    for (double step_deg : {1e-6, 1.0, 15.0, 61.0}) {
      SCOPED_TRACE(std::to_string(phi) + " rad after a step of " + std::to_string(step_deg) + " degrees");
      model_.evaluate(phi - radiansFromDegrees(step_deg));
      const Evaluation taylor = model_.evaluate(phi);
      model_.evaluate(phi + 3.0);
      expectSameToRoundoff("taylor", taylor, model_.evaluate(phi));
    }
}

// An assembly started from another bank angle's model (startAssemblyFrom: the campaign's sweep over gamma assembles once
// per angle) against this model's own warm starts from the angle before, at every test angle: the same evaluation to
// the history's roundoff (as ResultIndependentOfHistory: 16 eps of each quantity's scale), since the donor's joint
// coordinates solve this model's loops to roundoff and the assembly still converges to its own tolerance.
TEST_P(KCrankModelTest, AssemblyStartedFromAnotherBankAngleGivesTheSameEvaluation) {
  Case donor_case = GetParam();
  donor_case.gamma_deg += 53.0;
  KCrankModel donor(makeMechanism(donor_case)), seeded(mechanism_);
  for (double phi : kAngles) {
    SCOPED_TRACE(phi);
    donor.evaluate(phi);
    seeded.startAssemblyFrom(donor);
    const Evaluation got = seeded.evaluate(phi), own = model_.evaluate(phi);
    expectSameToRoundoff("seeded", got, own);
  }
}

// A donor of another geometry (a longer rod) is ignored: the model walks the angles exactly as it would alone, bit
// for bit.
TEST_P(KCrankModelTest, AssemblyStartIgnoresAnotherGeometry) {
  Mechanism other = mechanism_;
  other.rod.length *= 1.1;
  KCrankModel donor(other), seeded(mechanism_);
  for (double phi : kAngles) {
    donor.evaluate(phi);
    seeded.startAssemblyFrom(donor);
    const Evaluation got = seeded.evaluate(phi), own = model_.evaluate(phi);
    EXPECT_EQ(got.drive_torque, own.drive_torque) << phi;
    EXPECT_EQ(got.Q, own.Q) << phi;
    for (std::size_t j = 0; j < own.cylinders.size(); ++j) EXPECT_EQ(got.cylinders[j].x_p, own.cylinders[j].x_p) << phi;
  }
}

// The loops closed by Newton's method on Simbody's own constraint errors (the default) against Simbody's projections
// (ModelOptions::simbody_projections) along the same walk of angles, with steps of 1e-6, 1, 15 and 61 degrees (those the
// campaign takes) and the crude start between walks: the same evaluation to roundoff, 16 eps of each quantity's scale
// (two converged solutions of the same loops), the velocities' scale r omega (1 + lambda). The velocities also within
// what Simbody's projection leaves (it stops at an RMS error of 0.1 of its tolerance, 1e-13 m/s for a machine up to 1 m:
// up to sqrt(m) times that on one of its m equations; seen 4 eps of the scale on the pin-offset four).
void expectLoopsNewtonIsSimbodysProjection(const Mechanism& m) {
  const Scales s = scalesOf(m);
  ModelOptions simbody_options;
  simbody_options.simbody_projections = true;
  KCrankModel newton(m), simbody(m, simbody_options);
  const double F = s.force, L = s.l + s.r, v = s.r * std::abs(s.omega) * (1.0 + s.lambda);
  const double equations = 2.0 * m.machine.cylinders + static_cast<double>(m.balance_shafts.size());
  const double v_tolerance =
      16 * kEps * v + 0.1 * simbody_options.projection_tolerance * std::max(1.0, L) * std::sqrt(equations);
  for (double phi : kAngles)
    for (double step_deg : {1e-6, 1.0, 15.0, 61.0}) {
      SCOPED_TRACE(std::to_string(phi) + " rad after a step of " + std::to_string(step_deg) + " degrees");
      for (double at : {phi + 3.0, phi - radiansFromDegrees(step_deg)}) {
        newton.evaluate(at);
        simbody.evaluate(at);
      }
      const Evaluation got = newton.evaluate(phi), expected = simbody.evaluate(phi);
      EXPECT_WITHIN("drive torque", got.drive_torque, expected.drive_torque, 16 * kEps * s.torque, s.torque);
      EXPECT_WITHIN("Q", got.Q, expected.Q, 16 * kEps * s.torque_gravity, s.torque_gravity);
      EXPECT_WITHIN("U", got.U, expected.U, 16 * kEps * s.energy, s.energy);
      for (int i = 0; i < 2; ++i) {
        EXPECT_WITHIN("bearing", got.bearing_force[i], expected.bearing_force[i], 16 * kEps * F, F);
        EXPECT_WITHIN("shaking force", got.shaking_force[i], expected.shaking_force[i], 16 * kEps * F, F);
      }
      for (std::size_t j = 0; j < expected.cylinders.size(); ++j) {
        const CylinderEvaluation &a = got.cylinders[j], &b = expected.cylinders[j];
        EXPECT_WITHIN("x_p", a.x_p, b.x_p, 16 * kEps * L, L);
        if (v > 0.0) {
          EXPECT_WITHIN("v_p", a.v_p, b.v_p, v_tolerance, v);
          EXPECT_WITHIN("rod_omega", a.rod_omega * s.l, b.rod_omega * s.l, v_tolerance, v);
        } else {  // at rest both solve u = 0
          EXPECT_EQ(a.v_p, 0.0);
          EXPECT_EQ(b.v_p, 0.0);
        }
        EXPECT_WITHIN("wall", a.wall_force, b.wall_force, 16 * kEps * F, F);
        for (int i = 0; i < 2; ++i) {
          EXPECT_WITHIN("crank pin", a.crank_pin_force[i], b.crank_pin_force[i], 16 * kEps * F, F);
          EXPECT_WITHIN("wrist pin", a.wrist_pin_force[i], b.wrist_pin_force[i], 16 * kEps * F, F);
        }
      }
    }
}

TEST_P(KCrankModelTest, LoopsNewtonGivesSimbodysProjection) { expectLoopsNewtonIsSimbodysProjection(mechanism_); }

// The reduced gravity model (KCrankGravityModel: one rod constraint per cylinder, closed by the same Newton near a known
// solution) against itself with Simbody's projections, along the same walk: U and Q to 16 eps of their scales.
TEST_P(KCrankModelTest, ReducedModelNewtonGivesSimbodysProjection) {
  ModelOptions simbody_options;
  simbody_options.simbody_projections = true;
  KCrankGravityModel newton(mechanism_), simbody(mechanism_, simbody_options);
  for (double phi : kAngles)
    for (double step_deg : {1e-6, 1.0, 15.0, 57.0}) {
      SCOPED_TRACE(std::to_string(phi) + " rad after a step of " + std::to_string(step_deg) + " degrees");
      for (double at : {phi + 3.0, phi - radiansFromDegrees(step_deg)}) {
        newton.calcHoldingTorque(at);
        simbody.calcHoldingTorque(at);
      }
      EXPECT_WITHIN("Q", newton.calcHoldingTorque(phi), simbody.calcHoldingTorque(phi),
                    16 * kEps * scales_.torque_gravity, scales_.torque_gravity);
      EXPECT_WITHIN("U", newton.calcPotentialEnergy(phi), simbody.calcPotentialEnergy(phi), 16 * kEps * scales_.energy,
                    scales_.energy);
    }
}

INSTANTIATE_TEST_SUITE_P(Cases, KCrankModelTest, ::testing::ValuesIn(allCases()),
                         [](const ::testing::TestParamInfo<Case>& info) { return caseName(info.param); });

// ---------------------------------------------------------------------------------------------------------------
// Single cylinder, hand-checked: between the two dead centres (rod along the axis in both) the piston and the rod
// both drop by 2r along e, the crank mass moves from r_s e to -r_s e and the counterweight from -r_p e to r_p e:
//   U(pi) = -2 g sin(gamma) (r m_o + r m_k + r_s m_s - r_p m_p).
// Allowed 16 eps E (two assembled potentials of size <= E).
TEST(KCrankModelHandChecks, PotentialEnergyBetweenDeadCentres) {
  for (double gamma_deg : {0.0, 90.0, -90.0, 180.0, 37.0}) {
    SCOPED_TRACE("gamma = " + std::to_string(gamma_deg));
    const Mechanism m = makeMechanism({1, Cycle::kFourStroke, gamma_deg, 0.0});
    const Scales s = scalesOf(m);
    KCrankModel model(m);
    const double expected = -2.0 * m.machine.gravity * std::sin(m.machine.cylinder_angle) *
                            (m.crank.radius * (m.piston.mass + m.rod.mass) + m.crank.com_radius * m.crank.mass -
                             m.crank.counterweight_radius * m.crank.counterweight_mass);
    EXPECT_WITHIN("U(pi) single cylinder", model.calcPotentialEnergy(kPi), expected, 16 * kEps * s.energy, s.energy);
    const Evaluation ev = model.evaluate(kPi);
    EXPECT_EQ(ev.engine, "simbody");
    EXPECT_EQ(ev.phi, kPi);
  }
}

// A standing single cylinder at outer dead centre, omega = 0: everything hangs on the crank vertically. The
// piston's weight goes through the rod; the bearing carries the whole weight. Allowed 16 eps F (seen 0.2 eps F).
TEST(KCrankModelHandChecks, StandingStaticDeadCentreCarriesTheWeight) {
  const Mechanism m = makeMechanism({1, Cycle::kFourStroke, 90.0, 0.0});
  const Scales s = scalesOf(m);
  KCrankModel model(m);
  const Evaluation ev = model.evaluate(0.0);
  const double g = m.machine.gravity;
  const double tolerance = 16 * kEps * s.force;
  const CylinderEvaluation& c = ev.cylinders[0];
  EXPECT_WITHIN("wrist pin carries the piston", c.wrist_pin_force[1], m.piston.mass * g, tolerance, s.force);
  EXPECT_WITHIN("wrist pin x", c.wrist_pin_force[0], 0.0, tolerance, s.force);
  EXPECT_WITHIN("crank pin carries piston and rod", c.crank_pin_force[1], (m.piston.mass + m.rod.mass) * g,
                tolerance, s.force);
  EXPECT_WITHIN("bearing carries everything", ev.bearing_force[1], s.m_total * g, tolerance, s.force);
  EXPECT_WITHIN("wall", c.wall_force, 0.0, tolerance, s.force);
  EXPECT_WITHIN("Q at dead centre", ev.Q, 0.0, 16 * kEps * s.torque_gravity, s.torque_gravity);
}

// A standing single cylinder at outer dead centre spinning at omega: the piston's acceleration is
// -r omega^2 (1 + lambda) along e (a kinematic fact at theta = 0 that needs only the triangle O-A-B: Simbody
// must reproduce it to roundoff). Allowed 16 eps r omega^2 (seen 3 eps).
TEST(KCrankModelHandChecks, PistonAccelerationAtOuterDeadCentre) {
  for (double gamma_deg : {90.0, 37.0}) {
    const Mechanism m = makeMechanism({1, Cycle::kFourStroke, gamma_deg, 600.0});
    KCrankModel model(m);
    const double r = m.crank.radius;
    const double w = m.machine.speed;
    const double lambda = r / m.rod.length;
    const Evaluation ev = model.evaluate(0.0);
    EXPECT_WITHIN("a_p at outer dead centre", ev.cylinders[0].a_p, -r * w * w * (1 + lambda),
                  16 * kEps * r * w * w, r * w * w);
    const Evaluation inner = model.evaluate(kPi);
    EXPECT_WITHIN("a_p at inner dead centre", inner.cylinders[0].a_p, r * w * w * (1 - lambda),
                  16 * kEps * r * w * w, r * w * w);
  }
}

// ---------------------------------------------------------------------------------------------------------------
// The example scenes (realistic scales, including a 3 m, 40 t marine engine): Q routes and the crankshaft's
// Euler balance about O, with the same tolerance arguments as above.
class SceneFileTest : public ::testing::TestWithParam<std::string> {};

TEST_P(SceneFileTest, QRoutesAndCrankshaftBalance) {
  const Mechanism m = loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / (GetParam() + ".toml"));
  const Scales s = scalesOf(m);
  KCrankModel model(m);
  const int k = m.machine.cylinders;
  const double h = 2e-5;
  const double energy_gravity = s.m_total * s.g * (s.l + 2 * s.r);
  for (double phi : kAngles) {
    SCOPED_TRACE("phi = " + std::to_string(phi));
    const double holding = model.calcHoldingTorque(phi);
    EXPECT_WITHIN("scene: Q holding vs virtual power", holding, model.calcVirtualPowerQ(phi),
                  32 * kEps * s.torque_gravity, s.torque_gravity);
    EXPECT_WITHIN("scene: Q central difference vs holding", model.calcQByCentralDifference(phi, h), holding,
                  10.0 * h * h / 6.0 * s.torque_gravity + 8 * kEps * energy_gravity / (2 * h), s.torque_gravity);
    const Diagnostics d = model.calcDiagnostics(phi);
    const Vec2 gravity{0.0, -s.g};
    double moment = d.evaluation.drive_torque + cross(d.crankshaft.com, d.crankshaft.mass * gravity);
    for (int j = 0; j < k; ++j)
      moment += cross(d.cylinders[j].crank_pin, -1.0 * d.evaluation.cylinders[j].crank_pin_force);
    EXPECT_WITHIN("scene: Euler crankshaft about O", moment, 0.0, 16 * (k + 2) * kEps * s.torque, s.torque);
  }
}

// The loops' Newton on the example scenes (a balance shaft's gearing, pin offsets, two banks, gas, a 3 m marine engine).
class LoopsSceneTest : public ::testing::TestWithParam<std::string> {};

TEST_P(LoopsSceneTest, LoopsNewtonGivesSimbodysProjection) {
  expectLoopsNewtonIsSimbodysProjection(
      loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / (GetParam() + ".toml")));
}

INSTANTIATE_TEST_SUITE_P(Scenes, LoopsSceneTest,
                         ::testing::Values("single_cylinder", "inline3_lying_two_stroke", "inline4_four_stroke",
                                           "inline4_pin_offset", "v8_cross_plane", "inline6_two_stroke_marine",
                                           "compressor2_explicit_angles"),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

// evaluateMotion on the example scenes (with gas, two banks, pin offsets: the parts that call it run them: the offset
// sweep, the pin loads, the balance): the same numbers as evaluate() of a model taken through the same angles, bit for
// bit, U and Q NaN.
class MotionOnlySceneTest : public ::testing::TestWithParam<std::string> {};

TEST_P(MotionOnlySceneTest, MotionOnlyEvaluationIsTheEvaluationWithoutUAndQ) {
  const Mechanism m = loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / (GetParam() + ".toml"));
  KCrankModel full(m), motion(m);
  for (double phi : kAngles) {
    SCOPED_TRACE("phi = " + std::to_string(phi));
    const Evaluation a = full.evaluate(phi), b = motion.evaluateMotion(phi);
    EXPECT_TRUE(std::isnan(b.U) && std::isnan(b.Q));
    EXPECT_EQ(b.drive_torque, a.drive_torque);
    EXPECT_EQ(b.bearing_force, a.bearing_force);
    EXPECT_EQ(b.shaking_force, a.shaking_force);
    EXPECT_EQ(b.shaking_moment, a.shaking_moment);
    for (size_t j = 0; j < a.cylinders.size(); ++j) {
      EXPECT_EQ(b.cylinders[j].x_p, a.cylinders[j].x_p);
      EXPECT_EQ(b.cylinders[j].a_p, a.cylinders[j].a_p);
      EXPECT_EQ(b.cylinders[j].crank_pin_force, a.cylinders[j].crank_pin_force);
      EXPECT_EQ(b.cylinders[j].wrist_pin_force, a.cylinders[j].wrist_pin_force);
      EXPECT_EQ(b.cylinders[j].wall_force, a.cylinders[j].wall_force);
      EXPECT_EQ(b.cylinders[j].gas_force, a.cylinders[j].gas_force);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, MotionOnlySceneTest,
                         ::testing::Values("single_cylinder", "inline4_four_stroke", "inline4_pin_offset",
                                           "v8_cross_plane", "inline6_two_stroke_marine"),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

INSTANTIATE_TEST_SUITE_P(Scenes, SceneFileTest,
                         ::testing::Values("single_cylinder", "inline3_lying_two_stroke", "inline4_four_stroke",
                                           "inline6_two_stroke_marine", "compressor2_explicit_angles"),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

// ---------------------------------------------------------------------------------------------------------------
TEST(KCrankModelErrors, RejectsInvalidInput) {
  Mechanism m = makeMechanism({2, Cycle::kFourStroke, 90.0, 0.0});
  {
    Mechanism bad = m;
    bad.machine.crank_angles.pop_back();
    EXPECT_THROW(KCrankModel{bad}, std::invalid_argument);
  }
  {
    Mechanism bad = m;
    bad.crank.radius = bad.rod.length;  // lambda = 1
    EXPECT_THROW(KCrankModel{bad}, std::invalid_argument);
  }
  {
    Mechanism bad = m;
    bad.rod.mass = 0.0;
    bad.rod.inertia_about_wrist_pin = 0.0;
    EXPECT_THROW(KCrankModel{bad}, std::invalid_argument);
  }
  EXPECT_THROW(KCrankModel(m, ModelOptions{0.0}), std::invalid_argument);
  KCrankModel model(m);
  EXPECT_THROW(model.evaluate(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  EXPECT_THROW(model.calcQByCentralDifference(0.1, 0.0), std::invalid_argument);
  EXPECT_NO_THROW(model.evaluate(0.1));  // still usable after the errors
}

// A massless piston or crankshaft is allowed (the crank's motion is prescribed; the piston is not terminal).
TEST(KCrankModelErrors, MasslessPistonAndCrankshaftWork) {
  Mechanism m = makeMechanism({3, Cycle::kTwoStroke, 37.0, 600.0});
  m.piston.mass = 0.0;
  m.crank.mass = 0.0;
  m.crank.counterweight_mass = 0.0;
  KCrankModel model(m);
  const Scales s = scalesOf(m);
  EXPECT_WITHIN("massless: Q routes", model.calcHoldingTorque(0.7), model.calcVirtualPowerQ(0.7),
                32 * kEps * s.torque_gravity, s.torque_gravity);
}

}  // namespace
}  // namespace crankcheck::simbody_models

namespace crankcheck::simbody_models {
namespace {

// Balance shafts as heavy as a marine engine's (m r^2 of a few thousand kg m^2): a point mass's central inertia is zero,
// and computing it as its inertia about the shaft's axis minus m r^2 left -1.8e-12 on the diagonal, which Simbody
// refuses (`validate scenes/inline6_two_stroke_marine.toml` failed in the balance-shaft part). Built, the shafts add
// exactly their centrifugal forces to the shaking force: sum m (n omega)^2 r at the angle n phi + phase.
TEST(KCrankModelHandChecks, HeavyBalanceShaftsAddTheirCentrifugalForces) {
  Mechanism without = loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / "inline6_two_stroke_marine.toml");
  Mechanism with = without;
  // The pair `crankcheck balance --design 1` gives a single cylinder of these parts.
  for (const double ratio : {1.0, -1.0}) {
    BalanceShaftParams s;
    s.ratio = ratio;
    s.mass = ratio > 0 ? std::nextafter(16800.0, 1e9) : 9200.0;  // as the design computes it: 16800.000000000004
    s.radius = 1.2;
    s.phase = -std::numbers::pi / 2;
    s.position = {1.2 * ratio, -2.4, 0.0};
    with.balance_shafts.push_back(s);
  }
  KCrankModel model_with(with), model_without(without);
  const double w = with.machine.speed;
  double F = std::abs(model_without.evaluate(0.0).shaking_force[0]);  // the scale: the largest force in the check
  for (const BalanceShaftParams& s : with.balance_shafts) F += s.mass * s.ratio * s.ratio * w * w * s.radius;
  for (const double phi : {0.0, 0.7, 2.1, 4.4}) {
    const Evaluation a = model_with.evaluate(phi), b = model_without.evaluate(phi);
    std::array<double, 2> expected{0.0, 0.0};
    for (const BalanceShaftParams& s : with.balance_shafts) {
      const double angle = s.ratio * phi + s.phase, f = s.mass * s.ratio * s.ratio * w * w * s.radius;
      expected[0] += f * std::cos(angle);
      expected[1] += f * std::sin(angle);
    }
    // 64 eps (the gate's multiple): the difference of two shaking forces, each a sum of every body's momentum rate
    // (measured: 20 eps of F at most).
    for (int i = 0; i < 2; ++i)
      EXPECT_WITHIN("shafts' centrifugal force", a.shaking_force[i] - b.shaking_force[i], expected[i], 64 * kEps * F, F);
  }
}

}  // namespace
}  // namespace crankcheck::simbody_models
