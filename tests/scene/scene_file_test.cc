// Scene files: every example scene loads; phase angles follow eqs (8)-(11) exactly; every kind of bad input is
// refused with one message that names the file, the key and the rule.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "crankcheck/scene/scene_file.h"

namespace crankcheck {
namespace {

const char* kGoodScene = R"(
[engine]
cylinders = 2
cycle = "four-stroke"
cylinder_angle_deg = 90
speed_rpm = 3000
[crank]
radius = 0.05
mass = 1.0
com_radius = 0.02
[rod]
length = 0.2
mass = 0.5
com_from_wrist_pin = 0.14
inertia_about_wrist_pin = 0.012
[piston]
mass = 0.4
)";

TEST(SceneFile, EveryExampleSceneLoads) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(CRANKCHECK_SCENES_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().string());
    const Mechanism m = loadSceneFile(entry.path());
    EXPECT_EQ(static_cast<int>(m.engine.crank_angles.size()), m.engine.cylinders);
    EXPECT_LT(calcCrankRatio(m), 1.0);
    ++count;
  }
  EXPECT_GE(count, 5);
}

TEST(SceneFile, GoodSceneHasDefaultsAndSiUnits) {
  const Mechanism m = parseScene(kGoodScene, "good.toml");
  EXPECT_EQ(m.engine.cylinders, 2);
  EXPECT_EQ(m.engine.acting, Acting::kSingle);
  EXPECT_EQ(m.engine.gravity, 9.80665);
  EXPECT_EQ(m.engine.cylinder_angle, M_PI_2);
  EXPECT_DOUBLE_EQ(m.engine.speed, 100 * M_PI);
  EXPECT_EQ(m.crank.counterweight_mass, 0.0);
  EXPECT_FALSE(m.flywheel_inertia.has_value());
  EXPECT_EQ(m.engine.crank_angles, (std::vector<double>{0.0, 0.0}));  // four-stroke k = 2: 4 pi / 2 = one full turn
}

TEST(PhaseAngles, FollowEquations8To11) {
  // two-stroke single: 2 pi j / k; four-stroke single: 4 pi j / k; double-acting halves them (reduced to a turn)
  EXPECT_EQ(calcPhaseAngles(4, Cycle::kFourStroke, Acting::kSingle), (std::vector<double>{0, M_PI, 0, M_PI}));
  EXPECT_EQ(calcPhaseAngles(4, Cycle::kTwoStroke, Acting::kSingle), (std::vector<double>{0, M_PI_2, M_PI, 3 * M_PI_2}));
  EXPECT_EQ(calcPhaseAngles(2, Cycle::kTwoStroke, Acting::kDouble), (std::vector<double>{0, M_PI_2}));
  EXPECT_EQ(calcPhaseAngles(2, Cycle::kFourStroke, Acting::kDouble), (std::vector<double>{0, M_PI}));
  const std::vector<double> three = calcPhaseAngles(3, Cycle::kTwoStroke, Acting::kSingle);
  EXPECT_DOUBLE_EQ(three[1], 2 * M_PI / 3);
  EXPECT_DOUBLE_EQ(three[2], 4 * M_PI / 3);
  const std::vector<double> six = calcPhaseAngles(6, Cycle::kFourStroke, Acting::kSingle);  // 0, 120, 240, 0, 120, 240
  EXPECT_EQ(six[3], 0.0);
  EXPECT_DOUBLE_EQ(six[4], 2 * M_PI / 3);
  EXPECT_THROW(calcPhaseAngles(0, Cycle::kTwoStroke, Acting::kSingle), std::invalid_argument);
}

TEST(Angles, QuarterTurnsAreExact) {
  EXPECT_EQ(radiansFromDegrees(90), M_PI_2);
  EXPECT_EQ(radiansFromDegrees(180), M_PI);
  EXPECT_EQ(radiansFromDegrees(-270), -3 * M_PI_2);
  EXPECT_EQ(degreesFromRadians(radiansFromDegrees(270)), 270.0);
  EXPECT_EQ(degreesFromRadians(radiansFromDegrees(-90)), -90.0);
  EXPECT_DOUBLE_EQ(radiansFromDegrees(37.5), 37.5 * M_PI / 180);
}

// One bad input, and what its message must name.
struct BadScene {
  std::string name;
  std::string find;     // a line of kGoodScene to replace ("" = use `replace` as the whole text)
  std::string replace;
  std::string key;      // expected in the message
  std::string rule;     // expected in the message
};

std::string applyEdit(const BadScene& bad) {
  if (bad.find.empty()) return bad.replace;
  std::string text = kGoodScene;
  const size_t at = text.find(bad.find);
  if (at == std::string::npos) throw std::logic_error("test setup: line not found: " + bad.find);
  return text.replace(at, bad.find.size(), bad.replace);
}

class BadSceneTest : public ::testing::TestWithParam<BadScene> {};

TEST_P(BadSceneTest, IsRefusedWithFileKeyAndRule) {
  const BadScene& bad = GetParam();
  try {
    parseScene(applyEdit(bad), "scenes/bad.toml");
    FAIL() << "accepted";
  } catch (const SceneError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("scenes/bad.toml: ", 0), 0u) << message;
    EXPECT_NE(message.find(bad.key), std::string::npos) << message;
    EXPECT_NE(message.find(bad.rule), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Rules, BadSceneTest,
    ::testing::Values(
        BadScene{"unknown_key", "length = 0.2", "lenght = 0.2", "[rod].lenght", "unknown key"},
        BadScene{"unknown_table", "[piston]", "[pistons]", "pistons", "unknown key"},
        BadScene{"missing_key", "mass = 0.4", "", "[piston].mass", "missing key"},
        BadScene{"missing_table", "[piston]\nmass = 0.4", "", "[piston]", "missing table"},
        BadScene{"empty_file", "", " ", "[engine]", "missing table"},
        BadScene{"not_toml", "", "this is = = not toml\n\x01\x02", "line 1", "not valid TOML"},
        BadScene{"wrong_type_string", "cylinders = 2", "cylinders = \"2\"", "[engine].cylinders", "must be an integer"},
        BadScene{"wrong_type_float_count", "cylinders = 2", "cylinders = 2.5", "[engine].cylinders", "must be an integer"},
        BadScene{"wrong_type_number", "radius = 0.05", "radius = \"5 cm\"", "[crank].radius", "must be a number"},
        BadScene{"zero_cylinders", "cylinders = 2", "cylinders = 0", "[engine].cylinders", "between 1 and 64"},
        BadScene{"absurd_cylinders", "cylinders = 2", "cylinders = 100000", "[engine].cylinders", "between 1 and 64"},
        BadScene{"bad_cycle", "cycle = \"four-stroke\"", "cycle = \"three-stroke\"", "[engine].cycle", "two-stroke"},
        BadScene{"bad_acting", "cycle = \"four-stroke\"", "cycle = \"four-stroke\"\nacting = \"triple\"", "[engine].acting", "single"},
        BadScene{"lambda_one", "radius = 0.05", "radius = 0.2", "[crank].radius", "lambda = r / l must be < 1"},
        BadScene{"negative_mass", "mass = 0.4", "mass = -0.4", "[piston].mass", "must be >= 0"},
        BadScene{"zero_length", "length = 0.2", "length = 0.0", "[rod].length", "must be > 0"},
        BadScene{"nan", "mass = 0.5", "mass = nan", "[rod].mass", "must be finite"},
        BadScene{"inf", "radius = 0.05", "radius = inf", "[crank].radius", "must be finite"},
        BadScene{"huge", "mass = 1.0", "mass = 1e300", "[crank].mass", "at most 1e6"},
        BadScene{"inertia_below_point_mass", "inertia_about_wrist_pin = 0.012", "inertia_about_wrist_pin = 0.009",
                 "[rod].inertia_about_wrist_pin", "must be >= m_k z_k^2"},
        BadScene{"com_beyond_rod", "com_from_wrist_pin = 0.14", "com_from_wrist_pin = 0.25", "[rod].com_from_wrist_pin",
                 "0 <= z_k <= l"},
        BadScene{"angles_wrong_length", "cylinders = 2", "cylinders = 2\ncrank_angles_deg = [0, 90, 180]",
                 "[engine].crank_angles_deg", "one angle per cylinder"},
        BadScene{"angles_not_numbers", "cylinders = 2", "cylinders = 2\ncrank_angles_deg = [0, \"x\"]",
                 "[engine].crank_angles_deg[1]", "must be a number"},
        BadScene{"counterweight_without_radius", "com_radius = 0.02", "com_radius = 0.02\ncounterweight_mass = 1.0",
                 "[crank].counterweight_radius", "missing key"},
        BadScene{"negative_speed", "speed_rpm = 3000", "speed_rpm = -3000", "[engine].speed_rpm", "must be >= 0"},
        BadScene{"flywheel_zero", "mass = 0.4", "mass = 0.4\n[flywheel]\ninertia = 0", "[flywheel].inertia", "must be > 0"},
        BadScene{"table_is_value", "", "engine = 3\n", "[engine]", "must be a table"}),
    [](const auto& info) { return info.param.name; });

// Inputs the fuzzer (fuzz/scene_fuzzer.cc, scripts/fuzz.sh) found or that guard what it checks: each must give a
// valid scene or a SceneError, never another exception or a crash.
TEST(SceneFile, FuzzRegressionInputsAreHandled) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(CRANKCHECK_FUZZ_REGRESSIONS_DIR)) {
    SCOPED_TRACE(entry.path().string());
    std::ifstream in(entry.path(), std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    try {
      parseScene(text, entry.path().string());
    } catch (const SceneError&) {
    }
    ++count;
  }
  EXPECT_GE(count, 1);
}

TEST(SceneFile, UnreadableAndBinaryFilesAreRefused) {
  EXPECT_THROW(loadSceneFile("/nonexistent/scene.toml"), SceneError);
  const auto path = std::filesystem::temp_directory_path() / "crankcheck_binary_scene.toml";
  {
    std::ofstream out(path, std::ios::binary);
    out << std::string("\x7f" "ELF\0\0\0garbage", 12);
  }
  try {
    loadSceneFile(path);
    FAIL() << "accepted a binary file";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("binary"), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace crankcheck
