// Holzer's model of the crank train (analytic/torsion.h) against what the code did not produce: J_eq against an
// independent Gauss-Legendre quadrature of J(theta) and against closed forms; natural frequencies against the closed
// forms of one and two bodies; Holzer's table (the torque propagated along the chain) at each computed frequency; the
// modes' J-orthogonality.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include <Eigen/Dense>

#include "crankcheck/analytic/motion.h"
#include "crankcheck/analytic/torsion.h"
#include "crankcheck/scene/scene_file.h"
#include "../support/crankshaft_scene.h"
#include "../support/test_numbers.h"

namespace crankcheck::analytic {
namespace {

using testing::kEps;

Mechanism loadWithCrankshaft(const std::string& scene, const std::string& crankshaft_table) {
  return testing::loadSceneWithCrankshaft(std::filesystem::path(CRANKCHECK_SCENES_DIR) / scene, crankshaft_table);
}

// The mean over a turn of f by composite Gauss-Legendre: `panels` panels of `order` nodes, the nodes and weights by
// Golub-Welsch (the eigenvalues of the Jacobi matrix of the Legendre polynomials and the squares of the eigenvectors'
// first components): a rule independent of the trapezoidal sums of the code.
template <typename F>
double meanByGaussLegendre(F f, int order, int panels) {
  Eigen::MatrixXd jacobi = Eigen::MatrixXd::Zero(order, order);
  for (int k = 1; k < order; ++k) jacobi(k, k - 1) = jacobi(k - 1, k) = k / std::sqrt(4.0 * k * k - 1.0);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(jacobi);
  const Eigen::VectorXd nodes = solver.eigenvalues();
  const Eigen::VectorXd weights = 2.0 * solver.eigenvectors().row(0).transpose().array().square();
  const double h = 2.0 * M_PI / panels;
  double sum = 0.0;
  for (int p = 0; p < panels; ++p)
    for (int i = 0; i < order; ++i) sum += weights(i) * f(h * (p + 0.5 * (1.0 + nodes(i))));
  return sum * 0.5 * h / (2.0 * M_PI) * (2.0 / weights.sum());  // weights.sum() = 2 up to rounding: divided out
}

// J_eq of a single throw: the exact mean against Gauss-Legendre on J(theta) of motion.h called directly (the
// mechanism alone, without its flywheel), at the example's lambda = 0.297 and at lambda = 0.9 (slower convergence).
// Tolerance 32 eps x J_eq: both sides are sums of about 10^3 positive terms with compensated or pairwise-free
// rounding of a few eps each (the quadrature's nodes and weights from an eigensolver carry about 4 n eps relative);
// 32 covers both with room, and a wrong mean (a missing cylinder, a wrong J_t) is off by percent.
TEST(TorsionThrowInertia, ExactMeanAgreesWithGaussLegendre) {
  for (double rod_length : {0.145, 0.043 / 0.9}) {
    Mechanism m = loadWithCrankshaft("single_cylinder.toml", "throw_inertia = 2.0e-3\nstiffness = [5.0e5]\n");
    m.rod.length = rod_length;
    m.rod.com_from_wrist_pin = 0.7 * rod_length;
    m.rod.inertia_about_wrist_pin = 1.2 * m.rod.mass * m.rod.com_from_wrist_pin * m.rod.com_from_wrist_pin;
    SCOPED_TRACE("lambda = " + std::to_string(calcCrankRatio(m)));
    Mechanism alone = m;
    alone.flywheel_inertia.reset();
    const double reference =
        2.0e-3 + meanByGaussLegendre([&](double theta) { return calcReducedInertia(alone, theta).J; }, 20, 64);
    const ThrowInertia J = calcThrowInertia(m, 0);
    EXPECT_NEAR(J.exact, reference, 32 * kEps * reference);
    EXPECT_GE(J.samples, 32);
    EXPECT_EQ(calcThrowReducedInertia(m, 0, 0.7), calcReducedInertia(alone, 0.7).J);  // the same J(theta)
  }
}

// The rod's whole mass at the crank pin (z_k = l, I_o = m_k l^2: I_G = 0) and no piston: every part turns on a circle,
// J is constant, and J_eq = J_t + m_s r_s^2 + m_p r_p^2 + m_k r^2 exactly; the two-mass shortcuts are then exact too.
// Tolerance 4 eps x J_eq: a handful of roundings of positive terms.
TEST(TorsionThrowInertia, RodMassAtTheCrankPinGivesTheClosedForm) {
  Mechanism m = loadWithCrankshaft("single_cylinder.toml", "throw_inertia = 2.0e-3\nstiffness = [5.0e5]\n");
  m.piston.mass = 0.0;
  m.rod.com_from_wrist_pin = m.rod.length;
  m.rod.inertia_about_wrist_pin = m.rod.mass * m.rod.length * m.rod.length;
  const double r = m.crank.radius;
  const double closed = 2.0e-3 + m.crank.mass * m.crank.com_radius * m.crank.com_radius +
                        m.crank.counterweight_mass * m.crank.counterweight_radius * m.crank.counterweight_radius +
                        m.rod.mass * r * r;
  const ThrowInertia J = calcThrowInertia(m, 0);
  EXPECT_NEAR(J.exact, closed, 4 * kEps * closed);
  EXPECT_NEAR(J.half_reciprocating, closed, 4 * kEps * closed);
  EXPECT_NEAR(J.second_order, closed, 4 * kEps * closed);
}

// The piston alone (massless rod and crank): J = m_o x'^2 with x' = -r sin(theta) (1 + lambda cos(theta) /
// sqrt(1 - lambda^2 sin^2 theta)), whose mean expands as r^2 (1/2 + lambda^2/8 + lambda^4/16 + c6 lambda^6 + ...), all
// terms positive, c6 = 5/128 (the lambda^4 term: 2 (lambda s c)(lambda^3 s^3 c / 2) averages lambda^4 mean(s^4 c^2)
// = lambda^4 / 16). So the exact mean lies in [series to lambda^4, + 0.05 lambda^6] for lambda <= 0.3 (the tail beyond
// lambda^6 adds under 0.003 lambda^6 there); the half-mass shortcut is off by lambda^2 / 8 m_o r^2 (+ O(lambda^4)),
// the second-order one by lambda^4 / 16 (+ O(lambda^6)).
TEST(TorsionThrowInertia, PistonAloneFollowsTheSeriesAndShowsTheShortcutsErrors) {
  for (double lambda : {0.1, 0.2, 0.3}) {
    Mechanism m = loadWithCrankshaft("single_cylinder.toml", "stiffness = [5.0e5]\n");
    m.crank.mass = m.crank.counterweight_mass = 0.0;
    m.rod.mass = m.rod.inertia_about_wrist_pin = 0.0;
    m.rod.length = m.crank.radius / lambda;
    SCOPED_TRACE("lambda = " + std::to_string(lambda));
    const double unit = m.piston.mass * m.crank.radius * m.crank.radius;
    const ThrowInertia J = calcThrowInertia(m, 0);
    const double l2 = lambda * lambda, series = unit * (0.5 + l2 / 8 + l2 * l2 / 16);
    EXPECT_GE(J.exact, series);
    EXPECT_LE(J.exact, series + 0.05 * l2 * l2 * l2 * unit);
    EXPECT_NEAR(J.exact - J.half_reciprocating, unit * l2 / 8, 0.07 * l2 * l2 * unit);
    EXPECT_NEAR(J.exact - J.second_order, unit * l2 * l2 / 16, 0.05 * l2 * l2 * l2 * unit);
  }
}

// A real engine: the shortcuts against the exact mean (printed for the docs), within a few percent.
TEST(TorsionThrowInertia, ShortcutsOnTheExampleEnginesAreCloseButNotExact) {
  const Mechanism m =
      loadWithCrankshaft("inline4_four_stroke.toml", "throw_inertia = 2.0e-3\nstiffness = [4e5, 5.5e5, 5.5e5, 5.5e5]\n");
  for (int j = 0; j < 4; ++j) {
    const ThrowInertia J = calcThrowInertia(m, j);
    EXPECT_NEAR(J.exact, calcThrowInertia(m, 0).exact, 8 * kEps * J.exact);  // every throw the same mean
    EXPECT_NEAR(J.half_reciprocating / J.exact, 1.0, 0.05);
    EXPECT_NEAR(J.second_order / J.exact, 1.0, 0.05);
    EXPECT_NE(J.half_reciprocating, J.exact);
    if (j == 0)
      std::printf("inline4: J_eq %.10g kg m^2 (N = %d); half-mass %.3e, second-order %.3e relative error\n", J.exact,
                  J.samples, J.half_reciprocating / J.exact - 1.0, J.second_order / J.exact - 1.0);
  }
  // A V pair on one pin: twice a cylinder's mean plus one J_t.
  const Mechanism v8 =
      loadWithCrankshaft("v8_cross_plane.toml", "throw_inertia = 3.0e-3\nstiffness = [4e5, 5e5, 5e5, 6e5]\n");
  Mechanism single = v8;
  single.crankshaft->throw_inertia = 0.0;
  const double pair = calcThrowInertia(v8, 1).exact;
  EXPECT_NEAR(pair, 3.0e-3 + calcThrowInertia(single, 1).exact, 8 * kEps * pair);
  EXPECT_EQ(static_cast<int>(calcTorsionModes(v8).frequencies.size()), 4);
}

// One throw on a section to the clamp: w = sqrt(K / J_eq), the shape 1. Tolerance 4 eps x w: a Cholesky factor, a
// division and a square root, each rounded once.
TEST(TorsionModes, OneThrowIsSqrtKOverJ) {
  const Mechanism m = loadWithCrankshaft("single_cylinder.toml", "throw_inertia = 2.0e-3\nstiffness = [5.0e5]\n");
  const TorsionModes modes = calcTorsionModes(m);
  ASSERT_EQ(modes.frequencies.size(), 1);
  const double w = std::sqrt(5.0e5 / calcThrowInertia(m, 0).exact);
  EXPECT_NEAR(modes.frequencies(0), w, 4 * kEps * w);
  EXPECT_EQ(modes.shapes(0, 0), 1.0);
}

// Two bodies: det(K - w^2 J) = J1 J2 w^4 - (K1 J2 + (K1 + K2) J1) w^2 + K1 K2 = 0, the roots w^2 = (b -+ sqrt(b^2 -
// 4ac)) / 2a (the small one as 2c / (b + sqrt(...)), without cancellation). The generalized symmetric solver is
// normwise backward stable: each w^2 within c n eps of the largest w^2; 16 eps x w^2_max covers c n for n = 2.
TEST(TorsionModes, TwoBodiesMatchTheCharacteristicPolynomial) {
  for (const auto& [J1, J2, K1, K2] : {std::array{4.0e-3, 0.03, 4.0e5, 7.0e5}, std::array{0.5, 0.02, 1.0e6, 2.0e5},
                                       std::array{1.0, 1.0, 1.0, 1.0}}) {
    const TorsionModes modes = calcChainModes({J1, J2}, {K1, K2});
    const double a = J1 * J2, b = K1 * J2 + (K1 + K2) * J1, c = K1 * K2;
    const double root = std::sqrt(b * b - 4 * a * c);
    const double small = 2 * c / (b + root), large = (b + root) / (2 * a);
    ASSERT_EQ(modes.frequencies.size(), 2);
    EXPECT_NEAR(modes.frequencies(0) * modes.frequencies(0), small, 16 * kEps * large);
    EXPECT_NEAR(modes.frequencies(1) * modes.frequencies(1), large, 16 * kEps * large);
    // The first mode: both bodies in phase; the second: in opposition.
    EXPECT_GT(modes.shapes(0, 0) * modes.shapes(1, 0), 0.0);
    EXPECT_LT(modes.shapes(0, 1) * modes.shapes(1, 1), 0.0);
  }
}

// Holzer's table: at a natural frequency w, start at the free end with the mode's amplitude x_0 and no torque;
// body i adds its inertia torque w^2 J_i x_i, and section i twists by the torque it carries: x_{i+1} = x_i - T_i / K_i.
// At the clamp x_n must vanish: the residual torque K_{n-1} x_n against the scale K_max x_max (x_max = 1).
// Tolerance: w^2 carries c n eps w^2_max (backward stability), and the table turns an error d(w^2) into a residual of
// about d(w^2) sum J_i x_i^2 <= n eps w^2_max n J_max; w^2_max <= 4 K_max / J_min (Gershgorin on J^-1/2 K J^-1/2), so
// |residual| <= c n^2 eps 4 (J_max / J_min) K_max: the multiple 64 n^2 (J_max / J_min) keeps c = 16 with the
// table's own roundings (n per step). Worst found: 18 eps K_max (marine six, bound 2304; CRANKCHECK_PRINT_RATIOS=1).
// The modes are also J-orthogonal: x_i^T J x_j = 0 to 16 n eps of sqrt(x_i^T J x_i x_j^T J x_j) (the solver's
// eigenvectors of J^-1/2 K J^-1/2 are orthonormal to c n eps).
TEST(TorsionModes, HolzerTableClosesAndModesAreOrthogonal) {
  const std::vector<Mechanism> scenes = {
      loadWithCrankshaft("inline4_four_stroke.toml", "throw_inertia = 2.0e-3\nfront_inertia = 4.0e-3\n"
                                                     "stiffness = [4.0e5, 5.5e5, 5.5e5, 5.5e5, 7.0e5]\n"),
      loadWithCrankshaft("inline6_two_stroke_marine.toml",
                         "throw_inertia = 50.0\nstiffness = [2e9, 2e9, 2e9, 2e9, 2e9, 3e9]\n"),
      loadWithCrankshaft("v8_cross_plane.toml", "throw_inertia = 3.0e-3\nfront_inertia = 0.02\n"
                                                "stiffness = [3e5, 4e5, 5e5, 5e5, 6e5]\n")};
  for (const Mechanism& m : scenes) {
    SCOPED_TRACE(m.name);
    const TorsionModes modes = calcTorsionModes(m);
    const int n = static_cast<int>(modes.inertias.size());
    ASSERT_EQ(modes.frequencies.size(), n);
    const double J_max = *std::max_element(modes.inertias.begin(), modes.inertias.end());
    const double J_min = *std::min_element(modes.inertias.begin(), modes.inertias.end());
    const double K_max = *std::max_element(modes.stiffness.begin(), modes.stiffness.end());
    for (int i = 0; i < n; ++i) {
      SCOPED_TRACE("mode " + std::to_string(i));
      const double w2 = modes.frequencies(i) * modes.frequencies(i);
      if (i > 0) EXPECT_GT(modes.frequencies(i), modes.frequencies(i - 1));
      EXPECT_EQ(modes.shapes.col(i).cwiseAbs().maxCoeff(), 1.0);
      EXPECT_GT(modes.shapes.col(i).maxCoeff(), 0.0);
      double x = modes.shapes(0, i), torque = 0.0;
      for (int b = 0; b < n; ++b) {
        torque += w2 * modes.inertias[static_cast<size_t>(b)] * x;
        x -= torque / modes.stiffness[static_cast<size_t>(b)];
        if (b + 1 < n) EXPECT_NEAR(x, modes.shapes(b + 1, i), 64.0 * n * n * (J_max / J_min) * kEps);
      }
      const double residual = modes.stiffness.back() * x;
      if (std::getenv("CRANKCHECK_PRINT_RATIOS"))  // the worst found: the comment above
        std::printf("%s mode %d: |residual| = %.2f eps K_max (bound %.0f)\n", m.name.c_str(), i,
                    std::fabs(residual) / (kEps * K_max), 64.0 * n * n * (J_max / J_min));
      EXPECT_LE(std::fabs(residual), 64.0 * n * n * (J_max / J_min) * kEps * K_max) << residual / (kEps * K_max);
      for (int j = 0; j < i; ++j) {
        double cross = 0.0, ii = 0.0, jj = 0.0;
        for (int b = 0; b < n; ++b) {
          const double J = modes.inertias[static_cast<size_t>(b)];
          cross += modes.shapes(b, i) * J * modes.shapes(b, j);
          ii += modes.shapes(b, i) * J * modes.shapes(b, i);
          jj += modes.shapes(b, j) * J * modes.shapes(b, j);
        }
        EXPECT_LE(std::fabs(cross), 16.0 * n * kEps * std::sqrt(ii * jj)) << "modes " << i << ", " << j;
      }
    }
  }
}

TEST(TorsionModes, RefusesWhatHasNoModes) {
  EXPECT_THROW(calcChainModes({}, {}), std::invalid_argument);
  EXPECT_THROW(calcChainModes({1.0, 2.0}, {1.0}), std::invalid_argument);
  EXPECT_THROW(calcChainModes({1.0, 0.0}, {1.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(calcChainModes({1.0, 1.0}, {1.0, -1.0}), std::invalid_argument);
  Mechanism m = loadWithCrankshaft("single_cylinder.toml", "stiffness = [5.0e5]\n");
  EXPECT_THROW(calcThrowInertia(m, 1), std::out_of_range);
  m.crank.mass = m.crank.counterweight_mass = m.rod.mass = m.rod.inertia_about_wrist_pin = m.piston.mass = 0.0;
  EXPECT_THROW(calcTorsionModes(m), std::invalid_argument);  // massless parts and no throw_inertia: J_eq = 0
  m.crankshaft.reset();
  EXPECT_THROW(calcTorsionModes(m), std::invalid_argument);
}

}  // namespace
}  // namespace crankcheck::analytic
