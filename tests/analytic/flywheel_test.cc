// The flywheel's gas torque (analytic/flywheel.h, calcGasTorque: virtual work, -sum F_gas dx_p/dphi) against what it
// did not produce: minus the drive torque of the gas alone from the force balance of every body (reactions.h), on the
// example scenes with [gas] (the V8's two banks, the inline four, the pin-offset four), over their whole working cycle.
// Tolerance: both sum k terms of size F_gas,max r (the wrist-pin force times the crank pin's lever); the force balance
// takes about ten roundings per term (rod moment, the two components of F_A, F_B, the cross product), the virtual work
// three: 32 eps x k x F_gas,max r covers both (seen: 0.22 eps x k x F_gas,max r).

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include "crankcheck/analytic/flywheel.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/scene/scene_file.h"

namespace crankcheck::analytic {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

class GasTorqueTest : public ::testing::TestWithParam<std::string> {};

TEST_P(GasTorqueTest, VirtualWorkEqualsMinusTheDriveTorqueOfTheGasAlone) {
  const Mechanism m = loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / GetParam());
  ASSERT_TRUE(m.gas.has_value()) << GetParam() << " has no [gas]";
  const Mechanism gas_only = withLoads(m, true, false, false);
  const double cycle = m.engine.cycle == Cycle::kFourStroke ? 4.0 * M_PI : 2.0 * M_PI;
  // The scale: the largest gas force of any cylinder over the cycle times r, times k.
  double largest = 0.0;
  for (int i = 0; i < 1440; ++i)
    for (int j = 0; j < m.engine.cylinders; ++j) largest = std::max(largest, std::fabs(calcGasForce(m, j, cycle * i / 1440)));
  const double scale = m.engine.cylinders * largest * m.crank.radius;
  ASSERT_GT(scale, 0.0);
  double worst = 0.0;
  for (int i = 0; i <= 1440; ++i) {
    const double phi = cycle * i / 1440 + 1e-3;  // off the pressure table's corners as well as on the grid
    const double virtual_work = calcGasTorque(m, phi);
    const double force_balance = -calcReactions(gas_only, phi).drive_torque;
    worst = std::max(worst, std::fabs(virtual_work - force_balance));
    ASSERT_LE(std::fabs(virtual_work - force_balance), 32.0 * kEps * scale) << "phi = " << phi << " rad";
  }
  RecordProperty("worst_in_eps_of_scale", std::to_string(worst / (kEps * scale)));
}

INSTANTIATE_TEST_SUITE_P(Scenes, GasTorqueTest,
                         ::testing::Values("v8_cross_plane.toml", "inline4_four_stroke.toml", "inline4_pin_offset.toml"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param.substr(0, info.param.find('.'));
                         });

}  // namespace
}  // namespace crankcheck::analytic
