// The batch kernels (batch.h) against the scalar closed forms, angle by angle: Q (eq 13), U (eqs 3, 12), piston
// kinematics (Norton 13.1d and its derivatives), reactions and drive torque (Newton-Euler), shaking force and moment.
// The scalar functions are the reference the kernels must reproduce; both are checked against Simbody and finite
// differences elsewhere (tests/gate, tests/analytic/*_test.cc).
//
// Tolerances are eps times the quantity's physical scale (validation/scales.h: energy for U and Q, l + r for x_p, the
// velocity, acceleration, force, torque and moment scales). Why 4: the kernels repeat the scalar arithmetic in the
// same order (the reactions with the throw's terms gathered, multiply-adds fused where the CPU has FMA: a few
// roundings); what differs most is sin and cos of phi (SLEEF's vector u10 against glibc: measured within 0.5 eps of each
// other) and the exact zeros of quarter turns that only the scalar function snaps to. A difference of one rounding
// in sin or cos moves a quantity by at most its derivative with respect to sin and cos, which every scale bounds
// (they are sums of the magnitudes of the terms) except for the radical's growth near lambda = 1: the derivative of
// a_p carries 1/root^5 where the scale carries 1/root^3, hence the factor 1/(1 - lambda^2) (one more root^2) on the
// lambda sweep; at the benchmark's lambda = 0.3 it is 1.1 and the bound is 4 eps x scale without it.

#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "../../bench/bench_cases.h"
#include "../support/cases.h"
#include "crankcheck/analytic/batch.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/analytic/shaking.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/validation/scales.h"

namespace crankcheck::analytic {
namespace {

using testing::CaseSpec;
using testing::kEps;

// Every output of every kernel, structure of arrays.
struct BatchOutputs {
  size_t n = 0;
  std::vector<double> Q, U, tau, F_X, F_Y, shake_FX, shake_FY, shake_MX, shake_MY, shake_MZ;
  std::vector<std::vector<double>> x_p, v_p, a_p, crank_X, crank_Y, wrist_X, wrist_Y, wall;
  std::vector<PistonKinematicsSpans> kinematics;
  std::vector<CylinderReactionsSpans> cylinders;

  BatchOutputs(int k, size_t count) : n(count) {
    for (auto* v : {&Q, &U, &tau, &F_X, &F_Y, &shake_FX, &shake_FY, &shake_MX, &shake_MY, &shake_MZ}) v->assign(n, 0.0);
    for (auto* v : {&x_p, &v_p, &a_p, &crank_X, &crank_Y, &wrist_X, &wrist_Y, &wall})
      v->assign(static_cast<size_t>(k), std::vector<double>(n, 0.0));
    for (int j = 0; j < k; ++j) {
      kinematics.push_back({x_p[j], v_p[j], a_p[j]});
      cylinders.push_back({crank_X[j], crank_Y[j], wrist_X[j], wrist_Y[j], wall[j]});
    }
  }
  ReactionsSpans reactions() { return {tau, F_X, F_Y, cylinders}; }
  ShakingSpans shaking() { return {shake_FX, shake_FY, shake_MX, shake_MY, shake_MZ}; }
};

BatchOutputs runBatch(const Mechanism& m, const std::vector<double>& phi, RodInertiaForm rod) {
  BatchOutputs b(m.machine.cylinders, phi.size());
  calcGravityTorqueBatch(m, phi, b.Q);
  calcPotentialEnergyBatch(m, phi, b.U);
  calcPistonKinematicsBatch(m, phi, b.kinematics);
  calcReactionsBatch(m, phi, b.reactions(), rod);
  calcShakingBatch(m, phi, b.shaking());
  return b;
}

BatchOutputs runGrid(const Mechanism& m, double phi0, double step, size_t n, RodInertiaForm rod) {
  BatchOutputs b(m.machine.cylinders, n);
  calcGravityTorqueOnGrid(m, phi0, step, b.Q);
  calcPotentialEnergyOnGrid(m, phi0, step, b.U);
  calcPistonKinematicsOnGrid(m, phi0, step, b.kinematics);
  calcReactionsOnGrid(m, phi0, step, b.reactions(), rod);
  calcShakingOnGrid(m, phi0, step, b.shaking());
  return b;
}

// The largest |batch - scalar| / (eps x scale) of each quantity, and where it occurred.
struct Worst {
  double ratio = 0.0;
  double phi = 0.0;
  double batch = 0.0, scalar = 0.0;
};
using WorstByQuantity = std::map<std::string, Worst>;

WorstByQuantity compareWithScalar(const Mechanism& m, const BatchOutputs& b, const std::function<double(size_t)>& angle,
                                  RodInertiaForm rod) {
  const validation::Scales sc = validation::calcScales(m);
  WorstByQuantity worst;
  double phi = 0.0;
  const auto note = [&](const std::string& quantity, double batch, double scalar, double scale) {
    // At rest (omega = 0) the velocity scale is 0 and both sides must be exactly 0.
    const double diff = std::fabs(batch - scalar);
    const double ratio = scale > 0.0 ? diff / (kEps * scale) : (diff == 0.0 ? 0.0 : INFINITY);
    Worst& w = worst[quantity];
    if (!(ratio <= w.ratio)) w = {ratio, phi, batch, scalar};  // NaN lands here too
  };
  for (size_t i = 0; i < b.n; ++i) {
    phi = angle(i);
    note("Q", b.Q[i], calcGravityTorque(m, phi), sc.energy);
    note("U", b.U[i], calcPotentialEnergy(m, phi), sc.energy);
    const std::vector<CylinderMotion> motions = calcCylinderMotions(m, phi);
    const Reactions r = calcReactions(m, phi, motions, rod);
    note("drive_torque", b.tau[i], r.drive_torque, sc.torque);
    note("bearing_force", b.F_X[i], r.bearing_force[0], sc.force);
    note("bearing_force", b.F_Y[i], r.bearing_force[1], sc.force);
    const Shaking s = calcShaking(m, motions, phi);
    note("shaking_force", b.shake_FX[i], s.force[0], sc.force);
    note("shaking_force", b.shake_FY[i], s.force[1], sc.force);
    note("shaking_moment", b.shake_MX[i], s.moment[0], sc.moment);
    note("shaking_moment", b.shake_MY[i], s.moment[1], sc.moment);
    note("shaking_moment", b.shake_MZ[i], s.moment[2], sc.moment);
    for (size_t j = 0; j < motions.size(); ++j) {
      note("x_p", b.x_p[j][i], motions[j].piston.x_p, sc.position);
      note("v_p", b.v_p[j][i], motions[j].piston.v_p, sc.velocity);
      note("a_p", b.a_p[j][i], motions[j].piston.a_p, sc.acceleration);
      note("crank_pin_force", b.crank_X[j][i], r.cylinders[j].crank_pin_force[0], sc.force);
      note("crank_pin_force", b.crank_Y[j][i], r.cylinders[j].crank_pin_force[1], sc.force);
      note("wrist_pin_force", b.wrist_X[j][i], r.cylinders[j].wrist_pin_force[0], sc.force);
      note("wrist_pin_force", b.wrist_Y[j][i], r.cylinders[j].wrist_pin_force[1], sc.force);
      note("wall_force", b.wall[j][i], r.cylinders[j].wall_force, sc.force);
    }
  }
  return worst;
}

// Every quantity within `bound` eps x scale; prints the worst ratio of each (the figures bench/README.md quotes).
void expectWithin(const WorstByQuantity& worst, double bound, const std::string& what) {
  std::string line = what + ":";
  for (const auto& [quantity, w] : worst) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, " %s %.2f", quantity.c_str(), w.ratio);
    line += buffer;
    EXPECT_LE(w.ratio, bound) << what << ": " << quantity << " at phi = " << w.phi << ": batch " << w.batch
                              << ", scalar " << w.scalar;
  }
  std::printf("%s (worst |batch - scalar| / (eps scale), bound %.2f)\n", line.c_str(), bound);
}

double lambdaConditioning(const Mechanism& m) {
  const double lambda = calcCrankRatio(m);
  return 1.0 / ((1.0 - lambda) * (1.0 + lambda));
}

// Random angles in [-20, 20], the dead centres and quarter turns, and angles up to 1e6 rad (the scalar function's
// snapping of quarter turns, a window of 2 ulp, catches no random angle there: at 1e15 it would catch half).
std::vector<double> sweepAngles(size_t count) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(-20.0, 20.0), big(-1e6, 1e6);
  std::vector<double> phi;
  for (size_t i = 0; i < count; ++i) phi.push_back(angle(rng));
  for (int q = -8; q <= 8; ++q) phi.push_back(q * M_PI_2);
  for (int i = 0; i < 50; ++i) phi.push_back(big(rng));
  phi.push_back(-0.0);
  return phi;  // 1068 angles: a partial vector at the end for every width
}

// The scalar fallback: the widest instruction set the CPU has, and the portable baseline (HWY_SCALAR) forced.
enum class Path { kWidest, kBaseline };
std::string toString(Path p) { return p == Path::kWidest ? "widest" : "baseline"; }
void PrintTo(Path p, std::ostream* os) { *os << toString(p); }

class ForcePath {
 public:
  explicit ForcePath(Path p) {
    if (p == Path::kBaseline) hwy::SetSupportedTargetsForTest(HWY_SCALAR);
  }
  ~ForcePath() { hwy::SetSupportedTargetsForTest(0); }
};

// ---- The benchmark's own angles and mechanism (bench/crankcheck_bench.cc): every angle it times.

class BatchBenchmarkAnglesTest : public ::testing::TestWithParam<std::tuple<int, Path>> {};

TEST_P(BatchBenchmarkAnglesTest, EveryQuantityWithin4EpsOfScale) {
  const auto [k, path] = GetParam();
  const ForcePath force(path);
  const Mechanism m = bench::benchMechanism(k);
  std::vector<double> phi = bench::benchAngles();
  if (path == Path::kBaseline) phi.resize(100'000);  // the same arithmetic on 2 lanes: a tenth is enough
  const BatchOutputs b = runBatch(m, phi, RodInertiaForm::kTrueInertia);
  expectWithin(compareWithScalar(m, b, [&](size_t i) { return phi[i]; }, RodInertiaForm::kTrueInertia), 4.0,
               std::string("benchmark angles, k = ") + std::to_string(k) + ", " + getBatchTargetName());
  const BatchOutputs g = runGrid(m, bench::kGridPhi0, bench::kGridStep, 100'000, RodInertiaForm::kTrueInertia);
  // The grid's recurrence: at most 15 rotations from an exact sincos, each a few roundings (see the grid test).
  expectWithin(compareWithScalar(
                   m, g, [&](size_t i) { return bench::kGridPhi0 + static_cast<double>(i) * bench::kGridStep; },
                   RodInertiaForm::kTrueInertia),
               1e-13 / kEps, std::string("benchmark grid, k = ") + std::to_string(k) + ", " + getBatchTargetName());
}

INSTANTIATE_TEST_SUITE_P(Batch, BatchBenchmarkAnglesTest,
                         ::testing::Combine(::testing::Values(1, 4), ::testing::Values(Path::kWidest, Path::kBaseline)),
                         [](const auto& info) {
                           return "k" + std::to_string(std::get<0>(info.param)) + "_" +
                                  toString(std::get<1>(info.param));
                         });

TEST(Batch, BaselineIsForcedAndWidestIsRestored) {
  {
    const ForcePath force(Path::kBaseline);
    EXPECT_STREQ(getBatchTargetName(), "SCALAR");
  }
  // This machine has AVX-512 (bench/README.md); elsewhere the widest may differ, but never the baseline's.
  EXPECT_STRNE(getBatchTargetName(), "SCALAR");
}

// ---- The test cases' mechanisms over the lambda sweep, both rod forms of the reactions, both paths.

class BatchSweepTest : public ::testing::TestWithParam<std::tuple<CaseSpec, Path>> {};

TEST_P(BatchSweepTest, ArbitraryAnglesMatchScalar) {
  const auto [spec, path] = GetParam();
  const ForcePath force(path);
  const std::vector<double> phi = sweepAngles(1000);
  for (double lambda : testing::sweepLambdas()) {
    const Mechanism m = testing::makeMechanism(spec, lambda);
    for (RodInertiaForm rod : {RodInertiaForm::kTrueInertia, RodInertiaForm::kTwoMassWithoutDeltaI}) {
      const BatchOutputs b = runBatch(m, phi, rod);
      expectWithin(compareWithScalar(m, b, [&](size_t i) { return phi[i]; }, rod), 4.0 * lambdaConditioning(m),
                   testing::caseName(testing::CaseSpec{spec.cylinders, spec.cycle, spec.acting, lambda,
                                                       spec.gamma_deg, spec.rpm}));
    }
  }
}

// Uniform grid: sin and cos come from rotating each lane by Lanes() steps, re-anchored with an exact sincos every 16
// vectors: at most 15 rotations, each adding about 2 roundings to sin and cos (and the rounded rotation itself), so
// they drift by at most ~50 eps. The bound, 1e-13 of the scale (450 eps), keeps a margin for the derivatives' growth,
// with the same factor 1/(1 - lambda^2) near lambda = 1.
TEST_P(BatchSweepTest, UniformGridMatchesScalarWithin1em13) {
  const auto [spec, path] = GetParam();
  const ForcePath force(path);
  const double phi0 = -1.3, step = 2 * M_PI / 997;
  for (double lambda : testing::sweepLambdas()) {
    const Mechanism m = testing::makeMechanism(spec, lambda);
    const BatchOutputs b = runGrid(m, phi0, step, 2003, RodInertiaForm::kTrueInertia);
    expectWithin(compareWithScalar(
                     m, b, [&](size_t i) { return phi0 + static_cast<double>(i) * step; },
                     RodInertiaForm::kTrueInertia),
                 1e-13 / kEps * lambdaConditioning(m), "grid " + testing::lambdaTag(lambda));
  }
}

INSTANTIATE_TEST_SUITE_P(
    Sweep, BatchSweepTest,
    ::testing::Combine(::testing::Values(CaseSpec{1, Cycle::kFourStroke, Acting::kSingle, 0.3, 90.0, 3000.0},
                                         CaseSpec{3, Cycle::kTwoStroke, Acting::kSingle, 0.3, 37.0, 6000.0},
                                         CaseSpec{4, Cycle::kFourStroke, Acting::kSingle, 0.3, -90.0, 0.0},
                                         CaseSpec{12, Cycle::kTwoStroke, Acting::kSingle, 0.3, 0.0, 3000.0}),
                       ::testing::Values(Path::kWidest, Path::kBaseline)),
    [](const auto& info) {
      const CaseSpec& spec = std::get<0>(info.param);
      return testing::caseNameWithoutLambda(spec) + "_" + std::to_string(static_cast<int>(spec.rpm)) + "rpm_" +
             toString(std::get<1>(info.param));
    });

// ---- Every example scene: V, boxer and explicit layouts, banks, axial positions and gas (reactions read the gas
// force from calcGasForce lane by lane).

class BatchSceneTest : public ::testing::TestWithParam<std::tuple<std::string, Path>> {};

TEST_P(BatchSceneTest, EveryQuantityMatchesScalar) {
  const auto [scene, path] = GetParam();
  const ForcePath force(path);
  const Mechanism m = loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / (scene + ".toml"));
  const std::vector<double> phi = sweepAngles(1000);
  const BatchOutputs b = runBatch(m, phi, RodInertiaForm::kTrueInertia);
  expectWithin(compareWithScalar(m, b, [&](size_t i) { return phi[i]; }, RodInertiaForm::kTrueInertia),
               4.0 * lambdaConditioning(m), scene);
  const double phi0 = 0.1, step = 4 * M_PI / 1001;
  const BatchOutputs g = runGrid(m, phi0, step, 1001, RodInertiaForm::kTrueInertia);
  expectWithin(compareWithScalar(
                   m, g, [&](size_t i) { return phi0 + static_cast<double>(i) * step; }, RodInertiaForm::kTrueInertia),
               1e-13 / kEps * lambdaConditioning(m), scene + " grid");
}

INSTANTIATE_TEST_SUITE_P(Scenes, BatchSceneTest,
                         ::testing::Combine(::testing::Values("single_cylinder", "inline4_four_stroke",
                                                              "inline3_lying_two_stroke", "inline6_two_stroke_marine",
                                                              "compressor2_explicit_angles", "boxer4_four_stroke",
                                                              "v8_cross_plane"),
                                            ::testing::Values(Path::kWidest, Path::kBaseline)),
                         [](const auto& info) {
                           return std::get<0>(info.param) + "_" + toString(std::get<1>(info.param));
                         });

// ---- Bad input.

TEST(Batch, RefusesMismatchedSpans) {
  const Mechanism m = testing::makeMechanism(CaseSpec{2, Cycle::kFourStroke, Acting::kSingle, 0.3, 90.0, 3000.0});
  std::vector<double> phi(3, 0.1), three(3), two(2);
  EXPECT_THROW(calcGravityTorqueBatch(m, phi, two), std::invalid_argument);
  EXPECT_THROW(calcPotentialEnergyBatch(m, phi, two), std::invalid_argument);
  const std::vector<PistonKinematicsSpans> one_cylinder = {{three, three, three}};
  EXPECT_THROW(calcPistonKinematicsBatch(m, phi, one_cylinder), std::invalid_argument);
  const std::vector<PistonKinematicsSpans> short_spans = {{three, three, three}, {three, two, three}};
  EXPECT_THROW(calcPistonKinematicsBatch(m, phi, short_spans), std::invalid_argument);
  EXPECT_THROW(calcReactionsBatch(m, phi, {three, three, two, {}}), std::invalid_argument);
  const std::vector<CylinderReactionsSpans> one = {{three, three, three, three, three}};
  EXPECT_THROW(calcReactionsBatch(m, phi, {three, three, three, one}), std::invalid_argument);
  EXPECT_THROW(calcShakingBatch(m, phi, {three, three, three, three, two}), std::invalid_argument);
  EXPECT_THROW(calcShakingOnGrid(m, 0.0, 0.1, {three, three, three, three, two}), std::invalid_argument);
}

TEST(Batch, RefusesAnglesThatAreNotFinite) {
  const Mechanism m = testing::makeMechanism(CaseSpec{});
  for (double bad : {NAN, INFINITY, -INFINITY}) {
    std::vector<double> phi(37, 0.5), out(37);
    phi[35] = bad;  // in the partial vector at the end for 2, 4 and 8 lanes
    EXPECT_THROW(calcGravityTorqueBatch(m, phi, out), std::invalid_argument);
    EXPECT_THROW(calcPotentialEnergyBatch(m, phi, out), std::invalid_argument);
    EXPECT_THROW(calcShakingBatch(m, phi, {out, out, out, out, out}), std::invalid_argument);
    EXPECT_THROW(calcGravityTorqueOnGrid(m, bad, 0.1, out), std::invalid_argument);
    EXPECT_THROW(calcGravityTorqueOnGrid(m, 0.0, bad, out), std::invalid_argument);
  }
  std::vector<double> out(3);
  EXPECT_THROW(calcGravityTorqueOnGrid(m, 0.0, 1e308, out), std::invalid_argument);  // the last angle overflows
}

// Only the totals when no per-cylinder spans are given; an empty batch is no work.
TEST(Batch, ReactionTotalsWithoutCylinderSpansAndEmptyBatches) {
  const Mechanism m = testing::makeMechanism(CaseSpec{4, Cycle::kFourStroke, Acting::kSingle, 0.3, 90.0, 3000.0});
  const std::vector<double> phi = sweepAngles(100);
  std::vector<double> tau(phi.size()), F_X(phi.size()), F_Y(phi.size());
  calcReactionsBatch(m, phi, {tau, F_X, F_Y, {}});
  const double tol = 4.0 * kEps * validation::calcScales(m).torque;
  for (size_t i = 0; i < phi.size(); ++i)
    ASSERT_TRUE(testing::isClose(tau[i], calcReactions(m, phi[i]).drive_torque, tol)) << "phi " << phi[i];
  std::vector<double> none;
  EXPECT_NO_THROW(calcGravityTorqueBatch(m, none, none));
  EXPECT_NO_THROW(calcReactionsOnGrid(m, 0.0, 0.1, {none, none, none, {}}));
}

}  // namespace
}  // namespace crankcheck::analytic
