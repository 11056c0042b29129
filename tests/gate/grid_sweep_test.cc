// The Simbody grid sweep by superposition (simbody_models/grid_sweep.h) against the k-cylinder KCrankModel itself,
// angle by angle: Q (holding torque) and U. Both sides are Simbody; the sweep sums one-cylinder models at shifted
// angles, the full model solves all k loops at once, so agreement shows that superposition holds for a rigid
// shaft at a prescribed angle, for one bank, for several banks and for crank angles that are not whole steps.
//
// Tolerance: the gate's rule (validation/scales.h), |a - b| <= 64 eps x scale x conditioning, with the scales the
// gate uses for Simbody's U and Q (absolute_height_energy for U, Simbody subtracts absolute heights; energy for Q). Each side
// rounds at the level of a few eps of the scale plus its position projection; the sum over k one-cylinder values
// adds k roundings, which the scale (k times one cylinder's) covers.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "../support/cases.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/simbody_models/grid_sweep.h"
#include "crankcheck/simbody_models/k_crank_model.h"
#include "crankcheck/validation/scales.h"

namespace crankcheck {
namespace {

using validation::Comparison;
using validation::calcScales;

struct SweepCase {
  std::string name;
  Mechanism mechanism;
  double phi0 = 0.0, step = 0.0;
  size_t n = 0;
  int expected_models = 0;          // one-cylinder models the sweep should build
  size_t expected_evaluations = 0;  // one-cylinder evaluations of Q
};
void PrintTo(const SweepCase& c, std::ostream* os) { *os << c.name; }

Mechanism scene(const std::string& name) {
  return loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / (name + ".toml"));
}

std::vector<SweepCase> sweepCases() {
  using testing::CaseSpec;
  using testing::makeMechanism;
  const double five_degrees = 2.0 * M_PI / 72.0;
  return {
      // One bank, phases whole multiples of 5 degrees, a whole turn: one model, 72 evaluations for any k.
      {"k1_four_turn", makeMechanism(CaseSpec{1, Cycle::kFourStroke, Acting::kSingle, 0.3, 90.0, 0.0}), 0.0,
       five_degrees, 72, 1, 72},
      {"k4_four_turn", makeMechanism(CaseSpec{4, Cycle::kFourStroke, Acting::kSingle, 0.3, 90.0, 0.0}), 0.0,
       five_degrees, 72, 1, 72},
      {"k12_two_gamma37_turn", makeMechanism(CaseSpec{12, Cycle::kTwoStroke, Acting::kSingle, 0.4, 37.0, 0.0}), 0.0,
       five_degrees, 72, 1, 72},
      // Part of a turn, starting off the origin: shifted windows, wrapped around the turn.
      {"k3_two_window", makeMechanism(CaseSpec{3, Cycle::kTwoStroke, Acting::kSingle, 0.3, -90.0, 0.0}), -0.7,
       five_degrees, 20, 1, 60},
      // A step that divides no phase and no turn: each cylinder its own grid.
      {"k4_four_odd_step", makeMechanism(CaseSpec{4, Cycle::kFourStroke, Acting::kSingle, 0.3, 90.0, 0.0}), 0.1,
       2.0 * M_PI / 97.0, 40, 2, 80},
      // Layouts: two banks (V8, axial positions irrelevant to U and Q, its [gas] ignored), opposed banks, explicit
      // crank angles.
      {"v8_cross_plane", scene("v8_cross_plane"), 0.0, five_degrees, 72, 2, 144},
      {"boxer4_four_stroke", scene("boxer4_four_stroke"), 0.0, five_degrees, 72, 2, 144},
      {"compressor2_explicit_angles", scene("compressor2_explicit_angles"), 0.0, five_degrees, 72, 1, 72},
  };
}

class GridSweepGateTest : public ::testing::TestWithParam<SweepCase> {};

TEST_P(GridSweepGateTest, SuperpositionAgreesWithTheFullModel) {
  const SweepCase& c = GetParam();
  const Mechanism& m = c.mechanism;
  simbody_models::GridSweepStats q_stats, u_stats;
  const std::vector<double> Q = simbody_models::calcHoldingTorqueOnGrid(m, c.phi0, c.step, c.n, {}, &q_stats);
  const std::vector<double> U = simbody_models::calcPotentialEnergyOnGrid(m, c.phi0, c.step, c.n, {}, &u_stats);
  ASSERT_EQ(Q.size(), c.n);
  ASSERT_EQ(U.size(), c.n);
  EXPECT_EQ(q_stats.models, c.expected_models);
  EXPECT_EQ(q_stats.evaluations, c.expected_evaluations);
  const validation::Scales sc = calcScales(m);
  simbody_models::KCrankModel full(m);
  double worst_q = 0.0, worst_u = 0.0;  // |difference| / (eps scale), printed for docs/contributing.md
  for (size_t i = 0; i < c.n; ++i) {
    const double phi = c.phi0 + static_cast<double>(i) * c.step;
    const Comparison q{"Q", -1, Q[i], full.calcHoldingTorque(phi), sc.energy, sc.conditioning};
    EXPECT_TRUE(q.agrees()) << "phi " << phi << ": superposed " << q.a << ", full " << q.b << ", |difference| "
                            << q.error() << " > " << q.tolerance();
    const Comparison u{"U", -1, U[i], full.calcPotentialEnergy(phi), sc.absolute_height_energy, 1.0};
    EXPECT_TRUE(u.agrees()) << "phi " << phi << ": superposed " << u.a << ", full " << u.b << ", |difference| "
                            << u.error() << " > " << u.tolerance();
    worst_q = std::max(worst_q, q.error() / (validation::kEps * q.scale));
    worst_u = std::max(worst_u, u.error() / (validation::kEps * u.scale));
  }
  std::printf("%s: worst |superposed - full| / (eps scale): Q %.2f, U %.2f; %d models, %zu evaluations for %zu angles\n",
              c.name.c_str(), worst_q, worst_u, q_stats.models, q_stats.evaluations, c.n);
}

INSTANTIATE_TEST_SUITE_P(Gate, GridSweepGateTest, ::testing::ValuesIn(sweepCases()),
                         [](const auto& info) { return info.param.name; });

TEST(GridSweep, RefusesABadGrid) {
  const Mechanism m = testing::makeMechanism(testing::CaseSpec{});
  EXPECT_THROW(simbody_models::calcHoldingTorqueOnGrid(m, 0.0, 0.0, 10), std::invalid_argument);
  EXPECT_THROW(simbody_models::calcHoldingTorqueOnGrid(m, NAN, 0.1, 10), std::invalid_argument);
  EXPECT_THROW(simbody_models::calcPotentialEnergyOnGrid(m, 0.0, INFINITY, 10), std::invalid_argument);
}

}  // namespace
}  // namespace crankcheck
