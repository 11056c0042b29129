// The analytic engine at a state (phi, omega, alpha) of an accelerating crank (calcEvaluationAtState) against
// independent routes, on every example scene (offset pins, V and boxer banks, the inline four with gas and balance
// shafts, the marine six): the constant-speed engine at alpha = 0; Lagrange's equation with the reduced inertia J
// (motion.h) for the drive torque; central differences in time along phi(t) = phi0 + omega t + alpha t^2 / 2 for the
// accelerations; and the momentum balance of all moving parts (external forces and moments against the shaking).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "../support/cases.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/analytic/motion.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/scene/scene_file.h"

namespace crankcheck::analytic {
namespace {

using testing::kEps;

Mechanism loadScene(const std::string& file) {
  return loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / file);
}

// The states: crank angles over the whole working cycle, off the pressure table's corners and the dead centres; speeds
// forward, backward and 0; accelerations of either sign, up to a few times omega_0^2 (a start or a stall), and 0.
struct State {
  double phi, omega, alpha;
};
std::vector<State> makeStates(const Mechanism& m) {
  const double w0 = m.machine.speed;
  std::vector<State> states;
  for (int i = 0; i < 29; ++i) {
    const double phi = 4.0 * M_PI * i / 29 + 0.0123;
    for (double omega : {w0, -0.7 * w0, 0.0, 2.5 * w0})
      for (double alpha : {0.0, 0.4 * w0 * w0, -3.0 * w0 * w0, 1e-3 * w0 * w0}) states.push_back({phi, omega, alpha});
  }
  return states;
}

// The same mechanism at another constant speed (what the constant-speed engine reads as omega).
Mechanism atSpeed(const Mechanism& m, double omega) {
  Mechanism out = m;
  out.machine.speed = omega;
  return out;
}

// Every acceleration at a state is x'' omega^2 + x' alpha (each part's per-radian derivatives times omega^2 or alpha),
// bounded by the constant-speed form at the speed sqrt(omega^2 + |alpha|): the scales of validation/scales.h there.
Mechanism atEffectiveSpeed(const Mechanism& m, double omega, double alpha) {
  return atSpeed(m, std::sqrt(omega * omega + std::fabs(alpha)));
}

void expectSameVec(const Vec2& a, const Vec2& b, const std::string& what) {
  EXPECT_EQ(a[0], b[0]) << what;
  EXPECT_EQ(a[1], b[1]) << what;
}

void expectSameEvaluation(const Evaluation& a, const Evaluation& b, const std::string& where) {
  EXPECT_EQ(a.U, b.U) << where;
  EXPECT_EQ(a.Q, b.Q) << where;
  EXPECT_EQ(a.drive_torque, b.drive_torque) << where;
  expectSameVec(a.bearing_force, b.bearing_force, where + " bearing");
  expectSameVec(a.shaking_force, b.shaking_force, where + " shaking");
  for (int k = 0; k < 3; ++k) EXPECT_EQ(a.shaking_moment[k], b.shaking_moment[k]) << where << " moment " << k;
  ASSERT_EQ(a.cylinders.size(), b.cylinders.size());
  for (size_t j = 0; j < a.cylinders.size(); ++j) {
    const CylinderEvaluation &x = a.cylinders[j], &y = b.cylinders[j];
    const std::string c = where + " cylinder " + std::to_string(j);
    EXPECT_EQ(x.x_p, y.x_p) << c;
    EXPECT_EQ(x.v_p, y.v_p) << c;
    EXPECT_EQ(x.a_p, y.a_p) << c;
    expectSameVec(x.crank_pin_force, y.crank_pin_force, c + " crank pin");
    expectSameVec(x.wrist_pin_force, y.wrist_pin_force, c + " wrist pin");
    EXPECT_EQ(x.wall_force, y.wall_force) << c;
    EXPECT_EQ(x.gas_force, y.gas_force) << c;
    EXPECT_EQ(x.rod_angle, y.rod_angle) << c;
    EXPECT_EQ(x.rod_omega, y.rod_omega) << c;
    EXPECT_EQ(x.rod_alpha, y.rod_alpha) << c;
  }
}

class AcceleratingCrankTest : public ::testing::TestWithParam<std::string> {};

// alpha = 0: the constant-speed engine, bit for bit: at the scene's omega (calcEvaluation is this state; the check
// keeps it so), and at other speeds against calcEvaluation of the scene with that speed (the state's light copy of
// r, l, omega must compute what the whole scene does, operation for operation).
TEST_P(AcceleratingCrankTest, AtZeroAlphaIsTheConstantSpeedEngineBitForBit) {
  const Mechanism m = loadScene(GetParam());
  const double w0 = m.machine.speed;
  for (int i = 0; i < 73; ++i) {
    const double phi = 4.0 * M_PI * i / 73 + 0.0071;
    expectSameEvaluation(calcEvaluationAtState(m, phi, w0, 0.0), calcEvaluation(m, phi),
                         "scene speed phi " + std::to_string(phi));
    for (double omega : {0.0, -0.7 * w0, 2.5 * w0})
      expectSameEvaluation(calcEvaluationAtState(m, phi, omega, 0.0), calcEvaluation(atSpeed(m, omega), phi),
                           "omega " + std::to_string(omega) + " phi " + std::to_string(phi));
  }
}

// Lagrange's equation (motion.h): the torque the drive applies at (phi, omega, alpha) is J alpha + (1/2) J' omega^2 + Q
// minus the gas's torque (which drives the shaft), J with the flywheel and the shafts. The reactions find it by
// Newton-Euler of every body: an independent route. Tolerance: 64 eps of the torque scale at the effective speed
// sqrt(omega^2 + |alpha|) (calcTorqueScale: every m a r term and the gas; the multiple and the 1 / (1 - lambda^2) of
// the constant-speed check in motion_test.cc, which these are the same roundings of, plus one add per throw), and of
// J |alpha| (the flywheel's I_w alpha, added once on each side). Seen: at most 2 eps of that scale.
TEST_P(AcceleratingCrankTest, DriveTorqueIsLagrangesEquation) {
  const Mechanism m = loadScene(GetParam());
  const double lambda = validation::calcLoopRatio(m);
  double worst = 0.0;
  for (const State& s : makeStates(m)) {
    const ReducedInertia inertia = calcReducedInertia(m, s.phi);
    const double lagrange = inertia.J * s.alpha + 0.5 * inertia.dJ * s.omega * s.omega + calcGravityTorque(m, s.phi) -
                            calcGasTorque(m, s.phi);
    const double scale =
        testing::calcTorqueScale(atEffectiveSpeed(m, s.omega, s.alpha)) + inertia.J * std::fabs(s.alpha);
    const double drive = calcEvaluationAtState(m, s.phi, s.omega, s.alpha).drive_torque;
    EXPECT_TRUE(testing::isClose(drive, lagrange, 64 * kEps * scale / ((1 - lambda) * (1 + lambda))))
        << s.phi << " " << s.omega << " " << s.alpha;
    worst = std::max(worst, std::fabs(drive - lagrange) / (kEps * scale));
  }
  RecordProperty("worst_in_eps_of_scale", std::to_string(worst));
}

// a_p and rod_alpha against central differences in time along phi(t) = phi0 + omega t + alpha t^2 / 2 (omega(t) =
// omega + alpha t): x_p's second difference, rod_omega's first. With S^2 = omega_max^2 + |alpha| (omega_max = |omega| +
// |alpha| h) and Faa di Bruno (phi''' = 0), |d^4 x_p / dt^4| <= 3 D S^4 and |d^4 beta / dt^4| <= 3 D_b S^4, D and D_b
// the largest derivative per radian (orders 1 to 4): x_p = r cos + l sqrt(1 - s^2) has |x^(k)| <= r (1 +
// k^2 lambda / 4 + ...) (the radical's harmonic 2 is -(lambda r / 4) cos 2 theta), bounded here by D = r (1 + 8 lambda
// (1 - lambda^2)^(-7/2)); beta' = lambda cos / cos(beta) and its derivatives by D_b = 4 lambda (1 - lambda^2)^(-7/2),
// lambda the loop ratio (r + max |delta|) / l. The truncation is then h^2 |d^4 x_p / dt^4| / 12 <= h^2 D S^4 / 4
// (second difference of x_p) and h^2 |d^4 beta / dt^4| / 6 <= h^2 D_b S^4 / 2 (first difference of rod_omega).
// Rounding: each x_p within 2 eps of l + r + max |delta| and, from its rounded angle
// (|phi| < 4 pi + 1), eps (|phi| + 1) D; the second difference's weights sum to 4, over h^2. Each rod_omega within
// (4 + |phi| + 1) eps D_b S, the first difference's weights sum to 1 / h. Step h = 1e-3 / S: the truncation dominates.
// Seen: at most 0.36 of the bound for a_p, 0.21 for rod_alpha; a wrong alpha term would be off by about r |alpha|.
TEST_P(AcceleratingCrankTest, AccelerationsAreTimeDerivativesAlongTheTrajectory) {
  const Mechanism m = loadScene(GetParam());
  const double r = m.crank.radius, l = m.rod.length, lambda = validation::calcLoopRatio(m);
  const double stiff = (1 - lambda) * (1 + lambda);
  const double D = r * (1 + 8 * lambda * std::pow(stiff, -3.5)), D_b = 4 * lambda * std::pow(stiff, -3.5);
  const double reach = l + lambda * l;  // the largest |x_p|, |delta|: l + r + max |delta|
  double worst_a = 0.0, worst_rod = 0.0;
  for (const State& s : makeStates(m)) {
    if (s.omega == 0.0 && s.alpha == 0.0) continue;  // at rest: nothing moves
    const double S0 = std::sqrt(s.omega * s.omega + std::fabs(s.alpha)), h = 1e-3 / S0;
    const double w_max = std::fabs(s.omega) + std::fabs(s.alpha) * h, S = std::sqrt(w_max * w_max + std::fabs(s.alpha));
    auto at = [&](double t) {
      return calcEvaluationAtState(m, s.phi + s.omega * t + 0.5 * s.alpha * t * t, s.omega + s.alpha * t, s.alpha);
    };
    const Evaluation minus = at(-h), mid = at(0.0), plus = at(h);
    const double angle = std::fabs(s.phi) + 1.0;
    const double tol_a = h * h * D * std::pow(S, 4) / 4 + 4 * kEps * (2 * reach + angle * D) / (h * h);
    const double tol_rod = h * h * D_b * std::pow(S, 4) / 2 + (4 + angle) * kEps * D_b * S / h;
    for (size_t j = 0; j < mid.cylinders.size(); ++j) {
      const double a_fd = (plus.cylinders[j].x_p - 2 * mid.cylinders[j].x_p + minus.cylinders[j].x_p) / (h * h);
      const double rod_fd = (plus.cylinders[j].rod_omega - minus.cylinders[j].rod_omega) / (2 * h);
      EXPECT_TRUE(testing::isClose(mid.cylinders[j].a_p, a_fd, tol_a))
          << j << " " << s.phi << " " << s.omega << " " << s.alpha;
      EXPECT_TRUE(testing::isClose(mid.cylinders[j].rod_alpha, rod_fd, tol_rod))
          << j << " " << s.phi << " " << s.omega << " " << s.alpha;
      worst_a = std::max(worst_a, std::fabs(mid.cylinders[j].a_p - a_fd) / tol_a);
      worst_rod = std::max(worst_rod, std::fabs(mid.cylinders[j].rod_alpha - rod_fd) / tol_rod);
    }
  }
  RecordProperty("worst_a_p_of_tolerance", std::to_string(worst_a));
  RecordProperty("worst_rod_alpha_of_tolerance", std::to_string(worst_rod));
}

// The momentum balance of all moving parts (pistons, rods, crank throws and flywheel; the balance shafts removed, their
// own bearings carry them): the external forces (the main bearing, the walls, the gas, gravity) are dP/dt = -F_s, and
// their moments about O with the drive torque are dH_O/dt = -M_s,Z. The reactions and the shaking are computed by
// different sums (per-body Newton-Euler against m a and p x m a). Tolerance: 64 eps of the force scale (moment: of the
// force scale times l + r + max |delta|, and of the flywheel's I_w |alpha|) at the effective speed sqrt(omega^2 +
// |alpha|) (calcForceScale: every m a and the gas; k cylinders of about ten roundings each). Seen: at most
// 0.017 of it (about 1 eps of the scale).
TEST_P(AcceleratingCrankTest, ExternalForcesAreTheMomentumRate) {
  Mechanism m = loadScene(GetParam());
  m.balance_shafts.clear();
  const double g = m.machine.gravity, r = m.crank.radius, l = m.rod.length, lambda = validation::calcLoopRatio(m);
  const double mu = m.rod.com_from_wrist_pin / l;
  const double I_w = m.flywheel_inertia.value_or(0.0);
  double worst_f = 0.0, worst_m = 0.0;
  for (const State& s : makeStates(m)) {
    const Evaluation ev = calcEvaluationAtState(m, s.phi, s.omega, s.alpha);
    double F[2] = {ev.bearing_force[0], ev.bearing_force[1]};
    double M = ev.drive_torque;  // about +Z, at O; the bearing force acts at O
    for (int j = 0; j < m.machine.cylinders; ++j) {
      const CylinderEvaluation& c = ev.cylinders[static_cast<size_t>(j)];
      const double gamma = getBankAngle(m, j), delta = getPinOffset(m, j);
      const double e[2] = {std::cos(gamma), std::sin(gamma)}, n[2] = {-std::sin(gamma), std::cos(gamma)};
      // At the wrist pin A = x_p e + delta n: the wall N_w n and the gas -F_gas e on the piston.
      const double A[2] = {c.x_p * e[0] + delta * n[0], c.x_p * e[1] + delta * n[1]};
      const double f_A[2] = {c.wall_force * n[0] - c.gas_force * e[0], c.wall_force * n[1] - c.gas_force * e[1]};
      F[0] += f_A[0];
      F[1] += f_A[1];
      M += A[0] * f_A[1] - A[1] * f_A[0];
      // Gravity (0, -g m) on the piston at A, the rod at G = A + mu (B - A), the throw's masses at r_s and -r_p along
      // the crank line to B (at theta = phi + alpha_j from e).
      const double theta = s.phi + m.machine.crank_angles[static_cast<size_t>(j)];
      const double Bc[2] = {r * std::cos(theta), r * std::sin(theta)};
      const double B[2] = {Bc[0] * e[0] + Bc[1] * n[0], Bc[0] * e[1] + Bc[1] * n[1]};
      const double G_x = A[0] + mu * (B[0] - A[0]);
      const double throw_moment =
          m.crank.mass * m.crank.com_radius - m.crank.counterweight_mass * m.crank.counterweight_radius;
      F[1] -= g * (m.piston.mass + m.rod.mass + m.crank.mass + m.crank.counterweight_mass);
      M -= g * (m.piston.mass * A[0] + m.rod.mass * G_x + throw_moment / r * B[0]);
    }
    const Mechanism eff = atEffectiveSpeed(m, s.omega, s.alpha);
    const double tol_f = 64 * kEps * testing::calcForceScale(eff);
    const double tol_m = 64 * kEps * (testing::calcForceScale(eff) * (l + lambda * l) + I_w * std::fabs(s.alpha));
    EXPECT_TRUE(testing::isClose(F[0], -ev.shaking_force[0], tol_f)) << s.phi << " " << s.omega << " " << s.alpha;
    EXPECT_TRUE(testing::isClose(F[1], -ev.shaking_force[1], tol_f)) << s.phi << " " << s.omega << " " << s.alpha;
    EXPECT_TRUE(testing::isClose(M, -ev.shaking_moment[2], tol_m)) << s.phi << " " << s.omega << " " << s.alpha;
    worst_f = std::max(
        {worst_f, std::fabs(F[0] + ev.shaking_force[0]) / tol_f, std::fabs(F[1] + ev.shaking_force[1]) / tol_f});
    worst_m = std::max(worst_m, std::fabs(M + ev.shaking_moment[2]) / tol_m);
  }
  RecordProperty("worst_force_of_tolerance", std::to_string(worst_f));
  RecordProperty("worst_moment_of_tolerance", std::to_string(worst_m));
}

// The balance shafts' share of the shaking at a state (the scene's shaking minus that of the same scene without its
// shafts) is -sum m a and -sum p x m a of their point masses at p = (x + rho cos psi, y + rho sin psi, z), psi =
// ratio phi(t) + phase, with a from the second central difference in time of p along phi(t) = phi0 + omega t +
// alpha t^2 / 2. With S^2 = ratio^2 (omega_max^2 + |alpha|), |d^4 p / dt^4| <= 3 rho S^4 (Faa di Bruno, as above), so
// the truncation is h^2 rho S^4 / 4 per mass, and the rounding 4 eps (|p| + (|psi| + 1) rho) / h^2 (p's and its
// angle's); h = 1e-3 / S. Tolerance: the sum over the shafts of m times that (times |p| + rho for the moments), and
// the rounding of the subtraction, 2 eps of the scene's shaking.
TEST(AcceleratingCrankShaftsTest, ShaftsShakingIsMinusTheirMassTimesAcceleration) {
  const Mechanism m = loadScene("inline4_pin_offset.toml");
  ASSERT_FALSE(m.balance_shafts.empty());
  Mechanism without = m;
  without.balance_shafts.clear();
  for (const State& s : makeStates(m)) {
    if (s.omega == 0.0 && s.alpha == 0.0) continue;
    double ratio_max = 0.0;
    for (const BalanceShaftParams& b : m.balance_shafts) ratio_max = std::max(ratio_max, std::fabs(b.ratio));
    const double S0 = ratio_max * std::sqrt(s.omega * s.omega + std::fabs(s.alpha)), h = 1e-3 / S0;
    const double w_max = std::fabs(s.omega) + std::fabs(s.alpha) * h;
    const double S = ratio_max * std::sqrt(w_max * w_max + std::fabs(s.alpha));
    double F[2] = {0.0, 0.0}, M[3] = {0.0, 0.0, 0.0}, tol_f = 0.0, tol_m = 0.0;
    for (const BalanceShaftParams& b : m.balance_shafts) {
      auto position = [&](double t) {
        const double psi = b.ratio * (s.phi + s.omega * t + 0.5 * s.alpha * t * t) + b.phase;
        return std::array<double, 2>{b.position[0] + b.radius * std::cos(psi),
                                     b.position[1] + b.radius * std::sin(psi)};
      };
      const auto minus = position(-h), mid = position(0.0), plus = position(h);
      const double a[2] = {(plus[0] - 2 * mid[0] + minus[0]) / (h * h), (plus[1] - 2 * mid[1] + minus[1]) / (h * h)};
      const double z = b.position[2];
      F[0] -= b.mass * a[0];
      F[1] -= b.mass * a[1];
      // -p x m a, p = (X, Y, z), a = (a_X, a_Y, 0)
      M[0] -= b.mass * (-z * a[1]);
      M[1] -= b.mass * (z * a[0]);
      M[2] -= b.mass * (mid[0] * a[1] - mid[1] * a[0]);
      const double reach = std::hypot(b.position[0], b.position[1], z) + b.radius;
      const double psi_max = std::fabs(b.ratio * s.phi) + std::fabs(b.phase) + 1.0;
      const double each =
          b.mass * (h * h * b.radius * std::pow(S, 4) / 4 + 4 * kEps * (reach + psi_max * b.radius) / (h * h));
      tol_f += each;
      tol_m += each * reach;
    }
    const Evaluation with_shafts = calcEvaluationAtState(m, s.phi, s.omega, s.alpha);
    const Evaluation cylinders = calcEvaluationAtState(without, s.phi, s.omega, s.alpha);
    for (int k = 0; k < 2; ++k)
      EXPECT_TRUE(testing::isClose(with_shafts.shaking_force[k] - cylinders.shaking_force[k], F[k],
                                   tol_f + 2 * kEps * std::fabs(with_shafts.shaking_force[k])))
          << k << " " << s.phi << " " << s.omega << " " << s.alpha;
    for (int k = 0; k < 3; ++k)
      EXPECT_TRUE(testing::isClose(with_shafts.shaking_moment[k] - cylinders.shaking_moment[k], M[k],
                                   tol_m + 2 * kEps * std::fabs(with_shafts.shaking_moment[k])))
          << k << " " << s.phi << " " << s.omega << " " << s.alpha;
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, AcceleratingCrankTest,
                         ::testing::Values("single_cylinder.toml", "inline4_four_stroke.toml",
                                           "inline4_pin_offset.toml", "v8_cross_plane.toml", "boxer4_four_stroke.toml",
                                           "inline3_lying_two_stroke.toml", "compressor2_explicit_angles.toml",
                                           "inline6_two_stroke_marine.toml"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param.substr(0, info.param.find('.'));
                         });

}  // namespace
}  // namespace crankcheck::analytic
