// Scene files: every example scene loads; phase angles follow eqs (8)-(11) exactly; every kind of bad input is
// refused with one message that names the file, the key and the rule.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <utility>
#include <vector>

#include "crankcheck/scene/scene_file.h"

namespace crankcheck {
namespace {

// The parts every test scene shares; the scenes below differ in [engine] and [[cylinder]].
const std::string kParts = R"(
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

const std::string kGoodScene = R"(
[engine]
cylinders = 2
cycle = "four-stroke"
cylinder_angle_deg = 90
speed_rpm = 3000
)" + kParts;

TEST(SceneFile, EveryExampleSceneLoads) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(CRANKCHECK_SCENES_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().string());
    const Mechanism m = loadSceneFile(entry.path());
    EXPECT_EQ(static_cast<int>(m.machine.crank_angles.size()), m.machine.cylinders);
    EXPECT_LT(calcCrankRatio(m), 1.0);
    ++count;
  }
  EXPECT_GE(count, 5);
}

TEST(SceneFile, GoodSceneHasDefaultsAndSiUnits) {
  const Mechanism m = parseScene(kGoodScene, "good.toml");
  EXPECT_EQ(m.machine.cylinders, 2);
  EXPECT_EQ(m.machine.acting, Acting::kSingle);
  EXPECT_EQ(m.machine.gravity, 9.80665);
  EXPECT_EQ(m.machine.cylinder_angle, M_PI_2);
  EXPECT_DOUBLE_EQ(m.machine.speed, 100 * M_PI);
  EXPECT_EQ(m.crank.counterweight_mass, 0.0);
  EXPECT_FALSE(m.flywheel_inertia.has_value());
  EXPECT_EQ(m.machine.crank_angles, (std::vector<double>{0.0, 0.0}));  // four-stroke k = 2: 4 pi / 2 = one full turn
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
  const std::string* base = nullptr;  // the scene edited: kGoodScene when null
};
void PrintTo(const BadScene& c, std::ostream* os) { *os << c.name; }  // stable, readable ctest names

std::string applyEdit(const BadScene& bad, const std::string& base = kGoodScene) {
  if (bad.find.empty()) return bad.replace;
  std::string text = base;
  const size_t at = text.find(bad.find);
  if (at == std::string::npos) throw std::logic_error("test setup: line not found: " + bad.find);
  return text.replace(at, bad.find.size(), bad.replace);
}

// The scene is refused with one line "SOURCE: KEY: rule".
void expectRefused(const std::string& text, const std::string& source, const BadScene& bad) {
  try {
    parseScene(text, source);
    FAIL() << "accepted";
  } catch (const SceneError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(source + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(bad.key), std::string::npos) << message;
    EXPECT_NE(message.find(bad.rule), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
  }
}

class BadSceneTest : public ::testing::TestWithParam<BadScene> {};

TEST_P(BadSceneTest, IsRefusedWithFileKeyAndRule) {
  const BadScene& bad = GetParam();
  expectRefused(applyEdit(bad, bad.base != nullptr ? *bad.base : kGoodScene), "scenes/bad.toml", bad);
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
        BadScene{"wrong_type_string", "cylinders = 2", "cylinders = \"2\"", "[engine].cylinders", "must be an integer (got \"2\")"},
        BadScene{"wrong_type_float_count", "cylinders = 2", "cylinders = 2.5", "[engine].cylinders", "must be an integer"},
        BadScene{"wrong_type_number", "radius = 0.05", "radius = \"5 cm\"", "[crank].radius", "must be a number (got \"5 cm\")"},
        BadScene{"wrong_type_bool", "radius = 0.05", "radius = true", "[crank].radius", "must be a number (got true)"},
        BadScene{"wrong_type_table", "radius = 0.05", "radius = { value = 0.05 }", "[crank].radius",
                 "must be a number (got a table)"},
        BadScene{"zero_cylinders", "cylinders = 2", "cylinders = 0", "[engine].cylinders", "between 1 and 64"},
        BadScene{"absurd_cylinders", "cylinders = 2", "cylinders = 100000", "[engine].cylinders", "between 1 and 64"},
        BadScene{"bad_cycle", "cycle = \"four-stroke\"", "cycle = \"three-stroke\"", "[engine].cycle", "two-stroke"},
        BadScene{"bad_acting", "cycle = \"four-stroke\"", "cycle = \"four-stroke\"\nacting = \"triple\"", "[engine].acting", "single"},
        BadScene{"lambda_one", "radius = 0.05", "radius = 0.2", "[crank].radius", "lambda = r / l must be < 1"},
        BadScene{"negative_mass", "mass = 0.4", "mass = -0.4", "[piston].mass", "must be >= 0"},
        BadScene{"zero_length", "length = 0.2", "length = 0.0", "[rod].length", "must be at least 1e-6 m"},
        BadScene{"nan", "mass = 0.5", "mass = nan", "[rod].mass", "must be finite"},
        BadScene{"inf", "radius = 0.05", "radius = inf", "[crank].radius", "must be finite"},
        BadScene{"huge", "mass = 1.0", "mass = 1e300", "[crank].mass", "must be at most 1e6 kg (1000 t)"},
        BadScene{"inertia_below_point_mass", "inertia_about_wrist_pin = 0.012", "inertia_about_wrist_pin = 0.009",
                 "[rod].inertia_about_wrist_pin", "must be >= m_k z_k^2"},
        BadScene{"com_beyond_rod", "com_from_wrist_pin = 0.14", "com_from_wrist_pin = 0.25", "[rod].com_from_wrist_pin",
                 "0 <= z_k <= l"},
        BadScene{"angles_wrong_length", "cylinders = 2", "cylinders = 2\ncrank_angles_deg = [0, 90, 180]",
                 "[engine].crank_angles_deg", "one angle per cylinder"},
        BadScene{"angles_not_numbers", "cylinders = 2", "cylinders = 2\ncrank_angles_deg = [0, \"x\"]",
                 "[engine].crank_angles_deg[1]", "must be a number (got \"x\")"},
        BadScene{"counterweight_without_radius", "com_radius = 0.02", "com_radius = 0.02\ncounterweight_mass = 1.0",
                 "[crank].counterweight_radius", "missing key"},
        BadScene{"negative_speed", "speed_rpm = 3000", "speed_rpm = -3000", "[engine].speed_rpm", "must be >= 0"},
        // omega^2 underflows below it (5e-324 rpm was an omega of 0, told "must be > 0 (got 5e-324)").
        BadScene{"speed_below_least", "speed_rpm = 3000", "speed_rpm = 5e-324", "[engine].speed_rpm",
                 "must be 0 (static) or at least 1e-6 rpm (got 5e-324)"},
        BadScene{"flywheel_zero", "mass = 0.4", "mass = 0.4\n[flywheel]\ninertia = 0", "[flywheel].inertia", "must be > 0"},
        BadScene{"table_is_value", "", "engine = 3\n", "[engine]", "must be a table"},
        BadScene{"spacing_too_long", "cylinders = 2", "cylinders = 2\ncylinder_spacing = 2e6", "[engine].cylinder_spacing",
                 "within 1e6 m"}),
    [](const auto& info) { return info.param.name; });

// ---------------------------------------------------------------------------------------------------------------
// The top level: format_version, name, description (docs/SCENE-FORMAT.md, "Format version, name, description").

TEST(SceneFormatVersion, VersionOneNameAndDescriptionAreAccepted) {
  std::string text = kGoodScene;
  text.replace(text.find("[engine]"), 8,
               "format_version = 1\nname = \"Twin\"\ndescription = \"\"\"Two cylinders,\nstanding.\"\"\"\n[engine]");
  const Mechanism m = parseScene(text, "scenes/twin.toml");
  EXPECT_EQ(m.name, "twin") << "a scene is named by its file's stem; `name` is for people";
  EXPECT_EQ(m.machine.cylinders, 2);
  EXPECT_EQ(kSceneFormatVersion, 1);
}

// A newer format is refused as such (not by the first key it added), with what to do.
TEST(SceneFormatVersion, NewerVersionIsRefusedBeforeAnythingElse) {
  std::string text = kGoodScene;
  text.replace(text.find("[engine]"), 8, "format_version = 2\nmotor = \"electric\"\n[engine]");
  try {
    parseScene(text, "scenes/new.toml");
    FAIL() << "accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()), "scenes/new.toml: format_version: scene format 2 is newer than this crankcheck "
                                     "reads (format 1): use a newer crankcheck");
  }
}

INSTANTIATE_TEST_SUITE_P(
    TopLevel, BadSceneTest,
    ::testing::Values(
        BadScene{"version_zero", "[engine]", "format_version = 0\n[engine]", "format_version", "must be 1 (got 0)"},
        BadScene{"version_fraction", "[engine]", "format_version = 1.5\n[engine]", "format_version",
                 "must be an integer (got 1.5)"},
        BadScene{"version_string", "[engine]", "format_version = \"1\"\n[engine]", "format_version", "must be an integer"},
        BadScene{"name_number", "[engine]", "name = 4\n[engine]", "name", "must be a string"},
        BadScene{"description_table", "[engine]", "[description]\ntext = \"x\"\n[engine]", "description",
                 "must be a string"},
        BadScene{"unknown_top_level", "[engine]", "title = \"x\"\n[engine]", "title", "unknown key (top level"}),
    [](const auto& info) { return info.param.name; });

// ---------------------------------------------------------------------------------------------------------------
// Layouts: [[cylinder]] tables (docs/SCENE-FORMAT.md, "Layouts").

const std::string kLayoutScene = R"(
[engine]
cycle = "four-stroke"
speed_rpm = 3000
[[cylinder]]
bank_angle_deg = 135
throw_angle_deg = 90
axial_position = 0.0
[[cylinder]]
bank_angle_deg = 45
throw_angle_deg = 90
axial_position = 0.02
)" + kParts;

// theta_j = phi + beta_j - gamma_j: alpha_j = throw - bank, exact in degrees; each cylinder in its own bank.
TEST(SceneLayout, CylinderTablesGiveBanksThrowsAndAxialPositions) {
  const Mechanism m = parseScene(kLayoutScene, "v2.toml");
  ASSERT_EQ(m.machine.cylinders, 2);
  EXPECT_EQ(m.machine.bank_angles, (std::vector<double>{radiansFromDegrees(135), radiansFromDegrees(45)}));
  EXPECT_EQ(m.machine.crank_angles, (std::vector<double>{radiansFromDegrees(-45), radiansFromDegrees(45)}));
  EXPECT_EQ(m.machine.axial_positions, (std::vector<double>{0.0, 0.02}));
  EXPECT_EQ(m.machine.cylinder_angle, radiansFromDegrees(135));
  EXPECT_FALSE(isSingleBank(m));
  EXPECT_TRUE(hasAxialPositions(m));
  EXPECT_EQ(getThrowAngle(m, 1), radiansFromDegrees(45) + radiansFromDegrees(45));
}

// pin_offset: in [engine] every cylinder of an inline scene, in a [[cylinder]] table that cylinder (default 0).
TEST(SceneLayout, PinOffsetsPerEngineAndPerCylinder) {
  std::string text = kGoodScene;
  text.replace(text.find("cylinders = 2"), 13, "cylinders = 2\npin_offset = -0.0012");
  const Mechanism m = parseScene(text, "inline2.toml");
  EXPECT_EQ(m.machine.pin_offsets, (std::vector<double>{-0.0012, -0.0012}));
  EXPECT_TRUE(hasPinOffsets(m));
  std::string layout = kLayoutScene;
  layout.replace(layout.find("axial_position = 0.02"), 21, "axial_position = 0.02\npin_offset = 0.0008");
  const Mechanism v = parseScene(layout, "v2.toml");
  EXPECT_EQ(getPinOffset(v, 0), 0.0);
  EXPECT_EQ(getPinOffset(v, 1), 0.0008);
  EXPECT_FALSE(hasPinOffsets(parseScene(kLayoutScene, "v2.toml")));
  EXPECT_TRUE(parseScene(kLayoutScene, "v2.toml").machine.pin_offsets.empty());
}

TEST(SceneLayout, InlineSpacingPlacesCylindersAlongTheShaft) {
  std::string text = kGoodScene;
  text.replace(text.find("cylinders = 2"), 13, "cylinders = 2\ncylinder_spacing = 0.09");
  const Mechanism m = parseScene(text, "inline2.toml");
  EXPECT_EQ(m.machine.axial_positions, (std::vector<double>{0.0, 0.09}));
  EXPECT_TRUE(isSingleBank(m));
  EXPECT_FALSE(hasAxialPositions(parseScene(kGoodScene, "inline2.toml")));
}

INSTANTIATE_TEST_SUITE_P(
    Layouts, BadSceneTest,
    ::testing::Values(
        BadScene{"count_differs", "cycle = \"four-stroke\"", "cycle = \"four-stroke\"\ncylinders = 3", "[engine].cylinders",
                 "must equal the number of [[cylinder]] tables (2)", &kLayoutScene},
        BadScene{"gamma_with_layout", "cycle = \"four-stroke\"", "cycle = \"four-stroke\"\ncylinder_angle_deg = 90",
                 "[engine].cylinder_angle_deg", "must be absent", &kLayoutScene},
        BadScene{"angles_with_layout", "cycle = \"four-stroke\"", "cycle = \"four-stroke\"\ncrank_angles_deg = [0, 0]",
                 "[engine].crank_angles_deg", "must be absent", &kLayoutScene},
        BadScene{"spacing_with_layout", "cycle = \"four-stroke\"", "cycle = \"four-stroke\"\ncylinder_spacing = 0.1",
                 "[engine].cylinder_spacing", "must be absent", &kLayoutScene},
        BadScene{"missing_bank", "bank_angle_deg = 45\n", "", "cylinder[1].bank_angle_deg", "missing key", &kLayoutScene},
        BadScene{"missing_throw", "throw_angle_deg = 90\naxial_position = 0.02", "axial_position = 0.02",
                 "cylinder[1].throw_angle_deg", "missing key", &kLayoutScene},
        BadScene{"axial_for_some", "axial_position = 0.02\n", "", "cylinder[1].axial_position", "every cylinder or for none", &kLayoutScene},
        BadScene{"unknown_cylinder_key", "throw_angle_deg = 90\naxial_position = 0.0",
                 "throw_angle_deg = 90\naxial_position = 0.0\nfiring_deg = 0", "cylinder[0].firing_deg", "unknown key", &kLayoutScene},
        BadScene{"bank_too_large", "bank_angle_deg = 45", "bank_angle_deg = 2e6", "cylinder[1].bank_angle_deg",
                 "at most 1e6 deg", &kLayoutScene},
        BadScene{"throw_far_from_bank", "bank_angle_deg = 45", "bank_angle_deg = -1e6", "cylinder[1].throw_angle_deg",
                 "throw_angle_deg - bank_angle_deg must be at most 1e6 deg in magnitude (got 1000090)", &kLayoutScene},
        BadScene{"axial_too_far", "axial_position = 0.02", "axial_position = 2e6", "cylinder[1].axial_position",
                 "1e6 m", &kLayoutScene},
        BadScene{"single_table", "[[cylinder]]\nbank_angle_deg = 45", "[cylinder2]\nbank_angle_deg = 45", "cylinder2",
                 "unknown key", &kLayoutScene},
        // Pin offsets: l - r = 0.15 m here; beyond it the rod cannot reach the crank pin at every angle.
        BadScene{"pin_offset_in_engine_with_layout", "cycle = \"four-stroke\"", "cycle = \"four-stroke\"\npin_offset = 0.001",
                 "[engine].pin_offset", "give pin_offset in each [[cylinder]]", &kLayoutScene},
        BadScene{"cylinder_pin_offset_beyond_l_minus_r", "axial_position = 0.02", "axial_position = 0.02\npin_offset = -0.16",
                 "cylinder[1].pin_offset", "|pin_offset| must be < l - r = 0.15", &kLayoutScene},
        BadScene{"engine_pin_offset_beyond_l_minus_r", "cylinders = 2", "cylinders = 2\npin_offset = 0.2",
                 "[engine].pin_offset", "no mechanism"},
        BadScene{"engine_pin_offset_not_a_number", "cylinders = 2", "cylinders = 2\npin_offset = \"1 mm\"",
                 "[engine].pin_offset", "must be a number"},
        // Balance shafts.
        BadScene{"shaft_without_mass", "[piston]", "[[balance_shaft]]\nratio = 2\nradius = 0.04\nposition = [0, -0.1, 0]\n[piston]",
                 "balance_shaft[0].mass", "missing key"},
        BadScene{"shaft_mass_zero", "[piston]", "[[balance_shaft]]\nratio = 2\nmass = 0\nradius = 0.04\nposition = [0, -0.1, 0]\n[piston]",
                 "balance_shaft[0].mass", "must be > 0"},
        // The format's least non-zero mass, as for every other mass (1e-300 kg built a scene no engine resolves).
        BadScene{"shaft_mass_tiny", "[piston]", "[[balance_shaft]]\nratio = 2\nmass = 1e-300\nradius = 0.04\nposition = [0, -0.1, 0]\n[piston]",
                 "balance_shaft[0].mass", "must be at least 1e-9 kg (a microgram) (got 1e-300)"},
        BadScene{"shaft_ratio_zero", "[piston]", "[[balance_shaft]]\nratio = 0\nmass = 1\nradius = 0.04\nposition = [0, -0.1, 0]\n[piston]",
                 "balance_shaft[0].ratio", "must be nonzero"},
        // Not a whole number: the motion would not repeat every crank turn (validate failed after seconds of work,
        // balance printed 1e-300 as 0.000000); the value is named as given.
        BadScene{"shaft_ratio_fraction", "[piston]", "[[balance_shaft]]\nratio = 1.5\nmass = 1\nradius = 0.04\nposition = [0, -0.1, 0]\n[piston]",
                 "balance_shaft[0].ratio", "repeats every crank turn (got 1.5)"},
        BadScene{"shaft_ratio_tiny", "[piston]", "[[balance_shaft]]\nratio = 1e-300\nmass = 1\nradius = 0.04\nposition = [0, -0.1, 0]\n[piston]",
                 "balance_shaft[0].ratio", "must be a whole number of shaft turns per crank turn (e.g. 1, -1, 2, -2), so that the mechanism repeats every crank turn (got 1e-300)"},
        BadScene{"shaft_position_of_two", "[piston]", "[[balance_shaft]]\nratio = 2\nmass = 1\nradius = 0.04\nposition = [0, -0.1]\n[piston]",
                 "balance_shaft[0].position", "must be [x, y, z]"},
        BadScene{"shaft_unknown_key", "[piston]", "[[balance_shaft]]\nratio = 2\nmass = 1\nradius = 0.04\nposition = [0, 0, 0]\nteeth = 40\n[piston]",
                 "balance_shaft[0].teeth", "unknown key"}),
    [](const auto& info) { return info.param.name; });

// ---------------------------------------------------------------------------------------------------------------
// Crankshaft (torsion): the [crankshaft] table (docs/SCENE-FORMAT.md, "Crankshaft (torsion)").

// Two inline cylinders (two throws) and a front mass: three sections.
const std::string kCrankshaftScene = kGoodScene + R"(
[crankshaft]
throw_inertia = 2.0e-3
front_inertia = 4.0e-3
stiffness = [4.0e5, 5.5e5, 7.0e5]
section_damping = 1.5
throw_damping = 0.4
)";
// The V twin of kLayoutScene: both cylinders on one pin, one throw; no front mass: one section.
const std::string kCrankshaftLayoutScene = kLayoutScene + R"(
[crankshaft]
stiffness = [7.0e5]
)";

TEST(SceneCrankshaft, TableIsReadWithItsDefaults) {
  const Mechanism m = parseScene(kCrankshaftScene, "inline2.toml");
  ASSERT_TRUE(m.crankshaft.has_value());
  EXPECT_EQ(m.crankshaft->throw_inertia, 2.0e-3);
  EXPECT_EQ(m.crankshaft->front_inertia, 4.0e-3);
  EXPECT_EQ(m.crankshaft->stiffness, (std::vector<double>{4.0e5, 5.5e5, 7.0e5}));
  EXPECT_EQ(m.crankshaft->section_damping, (std::vector<double>{1.5}));
  EXPECT_EQ(getSectionDamping(*m.crankshaft, 2), 1.5);
  EXPECT_EQ(m.crankshaft->throw_damping, 0.4);
  EXPECT_EQ(countShaftSections(m), 3);
  const Mechanism v = parseScene(kCrankshaftLayoutScene, "v2.toml");
  ASSERT_TRUE(v.crankshaft.has_value());
  EXPECT_EQ(v.crankshaft->throw_inertia, 0.0);  // defaults: no own inertia, no front mass, no damping
  EXPECT_EQ(v.crankshaft->front_inertia, 0.0);
  EXPECT_EQ(v.crankshaft->section_damping, (std::vector<double>{0.0}));
  EXPECT_EQ(v.crankshaft->throw_damping, 0.0);
  EXPECT_EQ(findThrows(v), (std::vector<std::vector<int>>{{0, 1}}));
  EXPECT_FALSE(parseScene(kGoodScene, "inline2.toml").crankshaft.has_value());
  std::string list = kCrankshaftScene;
  list.replace(list.find("section_damping = 1.5"), 21, "section_damping = [1, 2, 3]");
  EXPECT_EQ(parseScene(list, "inline2.toml").crankshaft->section_damping, (std::vector<double>{1, 2, 3}));
}

// The throws: one per cylinder in one bank (an inline four's two middle pins at 180 degrees stay two throws); a V
// pair on one pin is one throw, whether the scene lists the cylinders pin by pin or bank by bank with axial positions
// (the example V8); a flat-plane V8 (pins 0, 180, 180, 0) has four; a radial star one.
TEST(SceneCrankshaft, ThrowsAreTheCrankPinsAlongTheShaft) {
  Mechanism m = parseScene(kGoodScene, "inline2.toml");
  m.machine.cylinders = 4;
  m.machine.crank_angles = {0.0, M_PI, M_PI, 0.0};
  EXPECT_EQ(findThrows(m), (std::vector<std::vector<int>>{{0}, {1}, {2}, {3}}));
  m.machine.axial_positions = {0.0, -0.1, -0.2, -0.3};  // a negative spacing: the front is cylinder 3
  EXPECT_EQ(findThrows(m), (std::vector<std::vector<int>>{{3}, {2}, {1}, {0}}));
  const Mechanism example = loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / "v8_cross_plane.toml");
  EXPECT_EQ(findThrows(example), (std::vector<std::vector<int>>{{0, 4}, {1, 5}, {2, 6}, {3, 7}}));
  Mechanism v8 = m;
  v8.machine.cylinders = 8;
  v8.machine.bank_angles.clear();
  v8.machine.crank_angles.clear();
  v8.machine.axial_positions.clear();
  for (double pin_deg : {0.0, 180.0, 180.0, 0.0})
    for (double bank_deg : {135.0, 45.0}) {
      v8.machine.bank_angles.push_back(radiansFromDegrees(bank_deg));
      v8.machine.crank_angles.push_back(radiansFromDegrees(pin_deg - bank_deg));
    }
  EXPECT_EQ(findThrows(v8), (std::vector<std::vector<int>>{{0, 1}, {2, 3}, {4, 5}, {6, 7}}));
  Mechanism radial = v8;
  radial.machine.cylinders = 5;
  radial.machine.bank_angles.clear();
  radial.machine.crank_angles.clear();
  for (int j = 0; j < 5; ++j) {
    radial.machine.bank_angles.push_back(radiansFromDegrees(72.0 * j));
    radial.machine.crank_angles.push_back(radiansFromDegrees(-72.0 * j));
  }
  EXPECT_EQ(findThrows(radial), (std::vector<std::vector<int>>{{0, 1, 2, 3, 4}}));
}

INSTANTIATE_TEST_SUITE_P(
    Crankshaft, BadSceneTest,
    ::testing::Values(
        BadScene{"crankshaft_unknown_key", "throw_damping = 0.4", "throw_damping = 0.4\nteeth = 3",
                 "[crankshaft].teeth", "unknown key", &kCrankshaftScene},
        BadScene{"crankshaft_without_stiffness", "stiffness = [4.0e5, 5.5e5, 7.0e5]\n", "", "[crankshaft].stiffness",
                 "missing key", &kCrankshaftScene},
        BadScene{"crankshaft_stiffness_zero", "stiffness = [4.0e5, 5.5e5, 7.0e5]", "stiffness = [4.0e5, 0, 7.0e5]",
                 "[crankshaft].stiffness[1]", "must be > 0 (got 0)", &kCrankshaftScene},
        BadScene{"crankshaft_stiffness_negative", "stiffness = [4.0e5, 5.5e5, 7.0e5]", "stiffness = [4.0e5, 5.5e5, -7e5]",
                 "[crankshaft].stiffness[2]", "must be > 0 (got -7e+05)", &kCrankshaftScene},
        BadScene{"crankshaft_stiffness_huge", "stiffness = [4.0e5, 5.5e5, 7.0e5]", "stiffness = [4.0e5, 5.5e5, 2e18]",
                 "[crankshaft].stiffness[2]", "must be at most 1e18 N m/rad (got 2e+18)", &kCrankshaftScene},
        BadScene{"crankshaft_stiffness_not_a_list", "stiffness = [4.0e5, 5.5e5, 7.0e5]", "stiffness = 4.0e5",
                 "[crankshaft].stiffness", "must be an array of numbers", &kCrankshaftScene},
        // Two throws and a front mass: three sections; without the front mass two.
        BadScene{"crankshaft_stiffness_short", "stiffness = [4.0e5, 5.5e5, 7.0e5]", "stiffness = [4.0e5, 5.5e5]",
                 "[crankshaft].stiffness",
                 "must have 3 values, one per section from front to flywheel (2 throws and a front mass: throws + 1) (got 2)",
                 &kCrankshaftScene},
        BadScene{"crankshaft_stiffness_long_without_front", "front_inertia = 4.0e-3", "front_inertia = 0",
                 "[crankshaft].stiffness", "must have 2 values, one per section from front to flywheel (2 throws, no front mass: one per throw) (got 3)",
                 &kCrankshaftScene},
        // A V pair shares its pin: one throw, one section.
        BadScene{"crankshaft_stiffness_per_cylinder_on_a_v_pin", "stiffness = [7.0e5]", "stiffness = [7.0e5, 7.0e5]",
                 "[crankshaft].stiffness", "must have 1 value, one per section from front to flywheel (1 throw, no front mass: one per throw) (got 2)",
                 &kCrankshaftLayoutScene},
        BadScene{"crankshaft_throw_inertia_negative", "throw_inertia = 2.0e-3", "throw_inertia = -2.0e-3",
                 "[crankshaft].throw_inertia", "must be >= 0 (got -0.002)", &kCrankshaftScene},
        BadScene{"crankshaft_front_inertia_negative", "front_inertia = 4.0e-3", "front_inertia = -4.0e-3",
                 "[crankshaft].front_inertia", "must be >= 0 (got -0.004)", &kCrankshaftScene},
        BadScene{"crankshaft_front_inertia_huge", "front_inertia = 4.0e-3", "front_inertia = 1e19",
                 "[crankshaft].front_inertia", "must be at most 1e18 kg m^2", &kCrankshaftScene},
        BadScene{"crankshaft_section_damping_negative", "section_damping = 1.5", "section_damping = -1.5",
                 "[crankshaft].section_damping", "must be >= 0 (got -1.5)", &kCrankshaftScene},
        BadScene{"crankshaft_section_damping_negative_in_list", "section_damping = 1.5", "section_damping = [1, -2, 3]",
                 "[crankshaft].section_damping[1]", "must be >= 0 (got -2)", &kCrankshaftScene},
        BadScene{"crankshaft_section_damping_wrong_length", "section_damping = 1.5", "section_damping = [1.5, 1.5]",
                 "[crankshaft].section_damping", "must be one value for all sections, or a list of 3 (one per section) (got 2)",
                 &kCrankshaftScene},
        BadScene{"crankshaft_section_damping_empty", "section_damping = 1.5", "section_damping = []",
                 "[crankshaft].section_damping", "(got 0)", &kCrankshaftScene},
        BadScene{"crankshaft_throw_damping_negative", "throw_damping = 0.4", "throw_damping = -0.4",
                 "[crankshaft].throw_damping", "must be >= 0 (got -0.4)", &kCrankshaftScene},
        BadScene{"crankshaft_throw_damping_nan", "throw_damping = 0.4", "throw_damping = nan",
                 "[crankshaft].throw_damping", "must be finite", &kCrankshaftScene},
        BadScene{"crankshaft_without_speed", "speed_rpm = 3000", "speed_rpm = 0", "[engine].speed_rpm",
                 "must be > 0 with a [crankshaft] table (its flywheel end turns at the scene's speed) (got 0)",
                 &kCrankshaftScene},
        BadScene{"crankshaft_is_a_value", "[engine]", "crankshaft = 2\n[engine]", "[crankshaft]", "must be a table"}),
    [](const auto& info) { return info.param.name; });

// The limits of each unit (docs/SCENE-FORMAT.md, "Limits"): a value just beyond each is refused with a message
// that names the file, the key, the limit and the value. kLimitScene is kGoodScene with every key written out, so
// that each edit below changes exactly one value.
const char* kLimitScene = R"(
[engine]
cylinders = 2
cycle = "four-stroke"
crank_angles_deg = [0, 90]
cylinder_angle_deg = 90
speed_rpm = 3000
gravity = 9.80665
[crank]
radius = 0.05
mass = 1.0
com_radius = 0.02
counterweight_mass = 0.8
counterweight_radius = 0.04
[rod]
length = 0.2
mass = 0.5
com_from_wrist_pin = 0.14
inertia_about_wrist_pin = 0.012
[piston]
mass = 0.4
[flywheel]
inertia = 0.1
)";

std::string withLine(const char* scene, const std::string& find, const std::string& replace) {
  std::string text = scene;
  const size_t at = text.find(find);
  if (at == std::string::npos) throw std::logic_error("test setup: line not found: " + find);
  return text.replace(at, find.size(), replace);
}

struct BeyondLimit {
  std::string name;
  std::string find;     // a line of kLimitScene
  std::string replace;  // the same key just beyond its limit (a large rod where the limit needs one)
  std::string message;  // expected after "scenes/limit.toml: "
};
void PrintTo(const BeyondLimit& c, std::ostream* os) { *os << c.name; }  // stable, readable ctest names

class BeyondLimitTest : public ::testing::TestWithParam<BeyondLimit> {};

TEST_P(BeyondLimitTest, IsRefusedNamingFileKeyAndLimit) {
  const BeyondLimit& c = GetParam();
  try {
    parseScene(withLine(kLimitScene, c.find, c.replace), "scenes/limit.toml");
    FAIL() << "accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()), "scenes/limit.toml: " + c.message);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Limits, BeyondLimitTest,
    ::testing::Values(
        // lengths [m]: at most 1e6 m; r and l at least 1e-6 m; r_s and r_p may be 0
        BeyondLimit{"rod_length_above_1e6_m", "length = 0.2\nmass = 0.5\ncom_from_wrist_pin = 0.14",
                    "length = 1.000001e6\nmass = 0.5\ncom_from_wrist_pin = 0.14",
                    "[rod].length: must be at most 1e6 m (1000 km) (got 1000001)"},
        BeyondLimit{"com_radius_above_1e6_m", "com_radius = 0.02", "com_radius = 1.000001e6",
                    "[crank].com_radius: must be at most 1e6 m (1000 km) (got 1000001)"},
        BeyondLimit{"counterweight_radius_above_1e6_m", "counterweight_radius = 0.04",
                    "counterweight_radius = 1.000001e6",
                    "[crank].counterweight_radius: must be at most 1e6 m (1000 km) (got 1000001)"},
        BeyondLimit{"crank_radius_below_a_micrometre", "radius = 0.05", "radius = 9.99e-7",
                    "[crank].radius: must be at least 1e-6 m (a micrometre) (got 9.99e-07)"},
        BeyondLimit{"rod_length_below_a_micrometre",
                    "length = 0.2\nmass = 0.5\ncom_from_wrist_pin = 0.14\ninertia_about_wrist_pin = 0.012",
                    "length = 9.99e-7\nmass = 0.5\ncom_from_wrist_pin = 0\ninertia_about_wrist_pin = 0",
                    "[rod].length: must be at least 1e-6 m (a micrometre) (got 9.99e-07)"},
        // masses [kg]: 0, or from a microgram to 1e6 kg
        BeyondLimit{"crank_mass_above_1e6_kg", "mass = 1.0", "mass = 1.000001e6",
                    "[crank].mass: must be at most 1e6 kg (1000 t) (got 1000001)"},
        BeyondLimit{"counterweight_mass_above_1e6_kg", "counterweight_mass = 0.8", "counterweight_mass = 1.000001e6",
                    "[crank].counterweight_mass: must be at most 1e6 kg (1000 t) (got 1000001)"},
        BeyondLimit{"rod_mass_above_1e6_kg", "mass = 0.5\ncom_from_wrist_pin = 0.14\ninertia_about_wrist_pin = 0.012",
                    "mass = 1.000001e6\ncom_from_wrist_pin = 0\ninertia_about_wrist_pin = 0",
                    "[rod].mass: must be at most 1e6 kg (1000 t) (got 1000001)"},
        BeyondLimit{"piston_mass_above_1e6_kg", "mass = 0.4", "mass = 1.000001e6",
                    "[piston].mass: must be at most 1e6 kg (1000 t) (got 1000001)"},
        BeyondLimit{"piston_mass_below_a_microgram", "mass = 0.4", "mass = 9.99e-10",
                    "[piston].mass: must be 0 or at least 1e-9 kg (a microgram) (got 9.99e-10)"},
        BeyondLimit{"counterweight_mass_below_a_microgram", "counterweight_mass = 0.8", "counterweight_mass = 1e-12",
                    "[crank].counterweight_mass: must be 0 or at least 1e-9 kg (a microgram) "
                    "(got 1e-12)"},
        // inertias [kg m^2]: at most 1e18 (1e6 kg at 1e6 m)
        BeyondLimit{"rod_inertia_above_1e18",
                    "length = 0.2\nmass = 0.5\ncom_from_wrist_pin = 0.14\ninertia_about_wrist_pin = 0.012",
                    "length = 1e6\nmass = 1e6\ncom_from_wrist_pin = 1e6\ninertia_about_wrist_pin = 1.000001e18",
                    "[rod].inertia_about_wrist_pin: must be at most 1e18 kg m^2 (1e6 kg at 1e6 m) (got 1.000001e+18)"},
        BeyondLimit{"flywheel_inertia_above_1e18", "inertia = 0.1", "inertia = 2e18",
                    "[flywheel].inertia: must be at most 1e18 kg m^2 (1e6 kg at 1e6 m) (got 2e+18)"},
        // an integer just above 1e18, whose nearest double is 1e18: refused (SCENE-FORMAT.md, "Limits")
        BeyondLimit{"flywheel_inertia_integer_just_above_1e18", "inertia = 0.1", "inertia = 1000000000000000001",
                    "[flywheel].inertia: must be at most 1e18 kg m^2 (1e6 kg at 1e6 m) (got 1000000000000000001)"},
        // the largest integer TOML holds, whose nearest double is 2^63 (beyond it): quoted as typed too
        BeyondLimit{"flywheel_inertia_largest_integer", "inertia = 0.1", "inertia = 9223372036854775807",
                    "[flywheel].inertia: must be at most 1e18 kg m^2 (1e6 kg at 1e6 m) (got 9223372036854775807)"},
        BeyondLimit{"piston_mass_integer_beyond_2p53", "mass = 0.4", "mass = -9007199254740993",
                    "[piston].mass: must be >= 0 (got -9007199254740993)"},
        // speed, gravity, angles
        BeyondLimit{"speed_above_1e6_rpm", "speed_rpm = 3000", "speed_rpm = 1.000001e6",
                    "[engine].speed_rpm: must be at most 1e6 rpm (got 1000001)"},
        BeyondLimit{"gravity_above_1e5_g", "gravity = 9.80665", "gravity = 1.000001e6",
                    "[engine].gravity: must be at most 1e6 m/s^2 (1e5 g) (got 1000001)"},
        BeyondLimit{"cylinder_angle_above_1e6_deg", "cylinder_angle_deg = 90", "cylinder_angle_deg = -1.000001e6",
                    "[engine].cylinder_angle_deg: magnitude must be at most 1e6 deg (got -1000001)"},
        BeyondLimit{"crank_angle_above_1e6_deg", "crank_angles_deg = [0, 90]", "crank_angles_deg = [0, 1.000001e6]",
                    "[engine].crank_angles_deg[1]: magnitude must be at most 1e6 deg (got 1000001)"}),
    [](const auto& info) { return info.param.name; });

// Each limit itself is accepted: every length, mass, inertia, speed, gravity and angle at its bound at once.
TEST(SceneLimits, ValuesAtTheLimitsAreAccepted) {
  std::string text = withLine(kLimitScene,
                              "length = 0.2\nmass = 0.5\ncom_from_wrist_pin = 0.14\ninertia_about_wrist_pin = 0.012",
                              "length = 1e6\nmass = 1e6\ncom_from_wrist_pin = 1e6\ninertia_about_wrist_pin = 1e18");
  text = withLine(text.c_str(), "radius = 0.05", "radius = 1e-6");
  text = withLine(text.c_str(), "com_radius = 0.02", "com_radius = 1e6");
  text = withLine(text.c_str(), "counterweight_mass = 0.8\ncounterweight_radius = 0.04",
                  "counterweight_mass = 1e-9\ncounterweight_radius = 1e6");
  text = withLine(text.c_str(), "[piston]\nmass = 0.4", "[piston]\nmass = 1e6");
  text = withLine(text.c_str(), "inertia = 0.1", "inertia = 1e18");
  text = withLine(text.c_str(), "speed_rpm = 3000", "speed_rpm = 1e6");
  text = withLine(text.c_str(), "gravity = 9.80665", "gravity = 1e6");
  text = withLine(text.c_str(), "cylinder_angle_deg = 90", "cylinder_angle_deg = -1e6");
  text = withLine(text.c_str(), "crank_angles_deg = [0, 90]", "crank_angles_deg = [1e6, -1e6]");
  const Mechanism m = parseScene(text, "limits.toml");
  EXPECT_EQ(m.rod.inertia_about_wrist_pin, 1e18);
  EXPECT_EQ(m.crank.radius, 1e-6);
  EXPECT_EQ(m.crank.counterweight_mass, 1e-9);
  EXPECT_EQ(m.speed_rpm, 1e6);
  // Zero masses and zero radii stay accepted (a massless part, a point at the centre).
  std::string zeros = withLine(kLimitScene,
                               "mass = 1.0\ncom_radius = 0.02\ncounterweight_mass = 0.8\ncounterweight_radius = 0.04",
                               "mass = 0\ncom_radius = 0\ncounterweight_mass = 0\ncounterweight_radius = 0");
  zeros = withLine(zeros.c_str(), "[piston]\nmass = 0.4", "[piston]\nmass = 0");
  EXPECT_NO_THROW(parseScene(zeros, "zeros.toml"));
}

// A large two-stroke marine engine: 2 m crank, 12 m rod of 33 t with I_o = 2.5e6 kg m^2 about its wrist pin, and a
// ship's shafting and propeller of 5e6 kg m^2 on the flywheel. The old single cap of 1e6 refused it.
TEST(SceneLimits, MarineRodIsAccepted) {
  std::string text = withLine(kLimitScene, "radius = 0.05", "radius = 2");
  text = withLine(text.c_str(), "length = 0.2\nmass = 0.5\ncom_from_wrist_pin = 0.14\ninertia_about_wrist_pin = 0.012",
                  "length = 12\nmass = 33000\ncom_from_wrist_pin = 8\ninertia_about_wrist_pin = 2.5e6");
  text = withLine(text.c_str(), "inertia = 0.1", "inertia = 5e6");
  text = withLine(text.c_str(), "speed_rpm = 3000", "speed_rpm = 80");
  const Mechanism m = parseScene(text, "marine.toml");
  EXPECT_EQ(m.rod.inertia_about_wrist_pin, 2.5e6);
  EXPECT_EQ(m.flywheel_inertia.value_or(0.0), 5e6);
  EXPECT_EQ(m.rod.mass, 33000.0);
}

// The tiny-lambda stress case: lambda = 1e-6 on a 0.2 m crank, a 200 km rod of 1 kg with its centre of mass at its
// middle and I_o = 1.4e10 kg m^2 (a uniform rod would have l^2 / 3 = 1.33e10; >= m_k z_k^2 = 1e10).
TEST(SceneLimits, TinyLambdaIsAccepted) {
  std::string text = withLine(kLimitScene, "radius = 0.05", "radius = 0.2");
  text = withLine(text.c_str(), "length = 0.2\nmass = 0.5\ncom_from_wrist_pin = 0.14\ninertia_about_wrist_pin = 0.012",
                  "length = 2e5\nmass = 1\ncom_from_wrist_pin = 1e5\ninertia_about_wrist_pin = 1.4e10");
  const Mechanism m = parseScene(text, "tiny_lambda.toml");
  EXPECT_DOUBLE_EQ(calcCrankRatio(m), 1e-6);
  EXPECT_EQ(m.rod.inertia_about_wrist_pin, 1.4e10);
}

// Integers for float keys stay accepted, at any accepted magnitude.
TEST(SceneLimits, IntegersForFloatKeysAreAccepted) {
  std::string text = withLine(kLimitScene, "inertia = 0.1", "inertia = 1000000000000000000");
  text = withLine(text.c_str(), "speed_rpm = 3000", "speed_rpm = 1000000");
  const Mechanism m = parseScene(text, "integers.toml");
  EXPECT_EQ(m.flywheel_inertia.value_or(0.0), 1e18);
  EXPECT_EQ(m.speed_rpm, 1e6);
}

// A programmatically built Mechanism obeys the same limits as a scene (validateMechanism applies them), with the
// limit checked in the unit of the rule: the speed in rpm, angles in degrees.
TEST(SceneLimits, BuiltMechanismsObeyTheSameLimits) {
  const Mechanism good = parseScene(kLimitScene, "good.toml");
  EXPECT_NO_THROW(validateMechanism(good, "built"));
  const auto message = [](const Mechanism& m) {
    try {
      validateMechanism(m, "built");
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  Mechanism fast = good;
  fast.speed_rpm = 0;  // not set by whoever built it: the limit is checked on omega
  fast.machine.speed = 2e6 * (M_PI / 30.0);
  EXPECT_EQ(message(fast).rfind("built: [engine].speed_rpm: must be at most 1e6 rpm (got ", 0), 0u)
      << message(fast);
  Mechanism turned = good;
  turned.machine.cylinder_angle = radiansFromDegrees(-2e6);
  EXPECT_EQ(message(turned).rfind("built: [engine].cylinder_angle_deg: magnitude must be at most 1e6 deg (got ", 0), 0u)
      << message(turned);
  Mechanism heavy = good;
  heavy.piston.mass = 2e6;
  EXPECT_EQ(message(heavy), "built: [piston].mass: must be at most 1e6 kg (1000 t) (got 2e+06)");
  Mechanism tiny = good;
  tiny.crank.mass = 1e-12;
  EXPECT_EQ(message(tiny),
            "built: [crank].mass: must be 0 or at least 1e-9 kg (a microgram) (got 1e-12)");
  Mechanism nan_angle = good;
  nan_angle.machine.crank_angles[1] = std::nan("");
  EXPECT_EQ(message(nan_angle), "built: [engine].crank_angles_deg[1]: must be finite (got nan)");
}

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

// ---------------------------------------------------------------------------------------------------------------
// Gas: the [gas] table (docs/SCENE-FORMAT.md, "Gas pressure").

namespace crankcheck {
namespace {

const std::string kGasScene = kGoodScene + R"(
[gas]
bore = 0.08
cycle_angle_deg = [0, 90, 360]
pressure_pa = [4.0e6, 1.0e6, 0.0]
firing_order = [1, 0]
)";

// Piecewise linear between the points, from the last point to the cycle's end back to the first value, periodic:
// values worked out by hand (exact in binary: the breakpoints and pressures are chosen so).
TEST(Gas, PressureIsPiecewiseLinearAndPeriodic) {
  const Mechanism m = parseScene(kGasScene, "gas.toml");
  ASSERT_TRUE(m.gas.has_value());
  const GasParams& g = *m.gas;
  EXPECT_EQ(g.cycle, 4.0 * M_PI);
  auto at = [&](double deg) { return calcGasPressure(g, radiansFromDegrees(deg)); };
  EXPECT_EQ(at(0), 4.0e6);
  EXPECT_EQ(at(90), 1.0e6);
  EXPECT_NEAR(at(45), 2.5e6, 1e-9 * 4e6);
  EXPECT_NEAR(at(225), 0.5e6, 1e-9 * 4e6);   // halfway from 90 (1e6) to 360 (0)
  EXPECT_NEAR(at(540), 2.0e6, 1e-9 * 4e6);   // halfway from 360 (0) to 720, where it meets 4e6 again
  EXPECT_NEAR(at(720 + 45), at(45), 1e-9 * 4e6);
  EXPECT_NEAR(at(-675), at(45), 1e-9 * 4e6);
  EXPECT_NEAR(calcBoreArea(g), M_PI * 0.0016, 1e-15);
  // firing_order [1, 0]: cylinder 1 fires at 0, cylinder 0 at 360 (every 720 / 2 degrees); both are at their outer
  // dead centre there (phase angles 0 and 360 -> 0 of eq 10).
  EXPECT_EQ(m.firing_angles, (std::vector<double>{radiansFromDegrees(360), 0.0}));
  EXPECT_NEAR(calcGasForce(m, 1, radiansFromDegrees(45)), 2.5e6 * calcBoreArea(g), 1e-9 * 4e6 * calcBoreArea(g));
  EXPECT_EQ(calcGasForce(parseScene(kGoodScene, "no_gas.toml"), 0, 0.3), 0.0);
}

INSTANTIATE_TEST_SUITE_P(
    Gas, BadSceneTest,
    ::testing::Values(
        BadScene{"unsorted", "cycle_angle_deg = [0, 90, 360]", "cycle_angle_deg = [0, 360, 90]", "[gas].cycle_angle_deg[2]",
                 "strictly increasing", &kGasScene},
        BadScene{"first_not_zero", "cycle_angle_deg = [0, 90, 360]", "cycle_angle_deg = [10, 90, 360]",
                 "[gas].cycle_angle_deg[0]", "must be 0", &kGasScene},
        BadScene{"beyond_cycle", "cycle_angle_deg = [0, 90, 360]", "cycle_angle_deg = [0, 90, 720]",
                 "[gas].cycle_angle_deg[2]", "below the cycle's 720", &kGasScene},
        BadScene{"lengths_differ", "pressure_pa = [4.0e6, 1.0e6, 0.0]", "pressure_pa = [4.0e6, 1.0e6]", "[gas].pressure_pa",
                 "one pressure per cycle angle", &kGasScene},
        // Issue 59: a table typed in bar, not pascal (6.987 bar peak): 1e5 times too small, refused by its peak.
        BadScene{"in_bar", "pressure_pa = [4.0e6, 1.0e6, 0.0]", "pressure_pa = [6.987, 1.2, 0.0]", "[gas].pressure_pa",
                 "its largest |pressure| is 6.987 Pa, below 1e4 Pa (0.1 bar), which no engine or compressor cylinder "
                 "works at: the table is in pascal (one typed in bar is 1e5 times too small: 6.987 bar is 698700 Pa)",
                 &kGasScene},
        BadScene{"below_vacuum", "pressure_pa = [4.0e6, 1.0e6, 0.0]", "pressure_pa = [4.0e6, 1.0e6, -2e5]",
                 "[gas].pressure_pa[2]", "at least -101325 Pa", &kGasScene},
        BadScene{"no_firing_order", "firing_order = [1, 0]", "", "[gas].firing_order", "missing key", &kGasScene},
        BadScene{"order_repeats", "firing_order = [1, 0]", "firing_order = [1, 1]", "[gas].firing_order[1]", "each once", &kGasScene},
        BadScene{"not_at_dead_centre", "cylinder_angle_deg = 90", "cylinder_angle_deg = 90\ncrank_angles_deg = [0, 90]",
                 "[gas].firing_order", "not at its outer dead centre at its firing angle (its own crank angle theta is 90 deg); it is there at phi = 270 or 630 deg", &kGasScene},
        BadScene{"double_acting", "cycle = \"four-stroke\"", "cycle = \"four-stroke\"\nacting = \"double\"", "[gas]",
                 "single-acting", &kGasScene},
        BadScene{"no_bore", "bore = 0.08\n", "", "[gas].bore", "missing key", &kGasScene}),
    [](const auto& info) { return info.param.name; });

TEST(Gas, FiringAngleBelongsWithAGasTable) {
  std::string text = kLayoutScene;
  text.replace(text.find("axial_position = 0.0"), 20, "axial_position = 0.0\nfiring_angle_deg = 0");
  expectRefused(text, "scenes/v2.toml", BadScene{"", "", "", "cylinder[0].firing_angle_deg", "belongs with a [gas] table"});
}

// ---------------------------------------------------------------------------------------------------------------
// Integer keys (docs/SCENE-FORMAT.md, "What is refused"): format_version, [engine].cylinders and the indices of
// [gas].firing_order take a float whose value is an exact integer as that integer (the JSON Schema that editors check
// scenes with cannot tell 2.0 from 2); a fraction, NaN, infinity or a value beyond the key's range is refused with
// one line naming the file and the key.

std::string replaced(std::string text, const std::string& find, const std::string& replace) {
  const size_t at = text.find(find);
  if (at == std::string::npos) throw std::logic_error("test setup: line not found: " + find);
  return text.replace(at, find.size(), replace);
}

TEST(SceneIntegers, IntegralFloatIsTheInteger) {
  const Mechanism m = parseScene(replaced(kGoodScene, "cylinders = 2", "cylinders = 2.0"), "scenes/float.toml");
  EXPECT_EQ(m.machine.cylinders, 2);
  EXPECT_EQ(m.machine.crank_angles, parseScene(kGoodScene, "scenes/int.toml").machine.crank_angles)
      << "the phase angles of 2 cylinders, as with cylinders = 2";
  const std::string version = replaced(kGoodScene, "[engine]", "format_version = 1.0\n[engine]");
  EXPECT_EQ(parseScene(version, "scenes/version.toml").machine.cylinders, 2);
  // With [[cylinder]] tables the count equals their number, 2.0 as 2.
  EXPECT_EQ(parseScene(replaced(kLayoutScene, "speed_rpm = 3000", "speed_rpm = 3000\ncylinders = 2.0"), "v2.toml")
                .machine.cylinders,
            2);
  // firing_order [1.0, 0.0] is [1, 0]: cylinder 1 fires at 0, cylinder 0 at 360 degrees.
  const std::string order = replaced(kGasScene, "firing_order = [1, 0]", "firing_order = [1.0, 0.0]");
  EXPECT_EQ(parseScene(order, "scenes/gas.toml").firing_angles,
            (std::vector<double>{radiansFromDegrees(360), 0.0}));
}

TEST(SceneIntegers, FractionIsRefusedNamingTheKey) {
  try {
    parseScene(replaced(kGoodScene, "cylinders = 2", "cylinders = 2.5"), "scenes/float.toml");
    FAIL() << "accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()), "scenes/float.toml: [engine].cylinders: must be an integer (got 2.5)");
  }
}

INSTANTIATE_TEST_SUITE_P(
    Integers, BadSceneTest,
    ::testing::Values(
        // the next double after 2: not an integer
        BadScene{"cylinders_next_to_2", "cylinders = 2", "cylinders = 2.0000000000000004", "[engine].cylinders",
                 "must be an integer (got 2.0000000000000004)"},
        BadScene{"cylinders_nan", "cylinders = 2", "cylinders = nan", "[engine].cylinders",
                 "must be an integer (got nan)"},
        BadScene{"cylinders_inf", "cylinders = 2", "cylinders = -inf", "[engine].cylinders",
                 "must be an integer (got -inf)"},
        BadScene{"cylinders_65_as_float", "cylinders = 2", "cylinders = 65.0", "[engine].cylinders",
                 "must be between 1 and 64 (got 65)"},
        BadScene{"cylinders_beyond_64_bits", "cylinders = 2", "cylinders = 1e300", "[engine].cylinders",
                 "must be between 1 and 64 (got 1e+300)"},
        BadScene{"cylinders_negative_zero", "cylinders = 2", "cylinders = -0.0", "[engine].cylinders",
                 "must be between 1 and 64 (got 0)"},
        BadScene{"version_2_as_float", "[engine]", "format_version = 2.0\n[engine]", "format_version",
                 "scene format 2 is newer than this crankcheck reads (format 1): use a newer crankcheck"},
        BadScene{"version_0_as_float", "[engine]", "format_version = 0.0\n[engine]", "format_version",
                 "must be 1 (got 0)"},
        BadScene{"firing_order_fraction", "firing_order = [1, 0]", "firing_order = [1, 0.5]", "[gas].firing_order[1]",
                 "must be an integer (got 0.5)", &kGasScene},
        BadScene{"firing_order_beyond_k_as_float", "firing_order = [1, 0]", "firing_order = [1, 2.0]",
                 "[gas].firing_order[1]", "must be a cylinder index 0..1, each once (got 2)", &kGasScene},
        BadScene{"firing_order_repeats_as_float", "firing_order = [1, 0]", "firing_order = [1, 1.0]",
                 "[gas].firing_order[1]", "must be a cylinder index 0..1, each once (got 1 again)", &kGasScene},
        BadScene{"firing_order_string", "firing_order = [1, 0]", "firing_order = [1, \"0\"]", "[gas].firing_order[1]",
                 "must be an integer", &kGasScene}),
    [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace crankcheck

namespace crankcheck {
namespace {

// A round of attacks: 10 000 balance shafts ran eval past 300 s in 1.65 GB (the cylinders are capped at 64 for that
// reason; now the shafts too), and a 2 GB scene file was read whole before being judged (now refused by its size).
TEST(SceneLimits, BalanceShaftsAndTheFileAreBounded) {
  std::string text = kGoodScene;
  for (int i = 0; i < 65; ++i)
    text += "[[balance_shaft]]\nratio = 1\nmass = 0.1\nradius = 0.02\nposition = [0.0, 0.0, 0.0]\n";
  try {
    parseScene(text, "shafts.toml");
    ADD_FAILURE() << "65 balance shafts were accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("shafts.toml: [[balance_shaft]]: must have at most 64 tables (got 65)"),
              std::string::npos) << e.what();
  }
  const std::filesystem::path big = std::filesystem::temp_directory_path() / "crankcheck_scene_17MiB.toml";
  {
    std::ofstream(big) << kGoodScene;
  }
  std::filesystem::resize_file(big, 17u << 20);  // sparse: no 17 MiB written
  try {
    loadSceneFile(big);
    ADD_FAILURE() << "a 17 MiB scene file was read";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(": file: is 17825792 bytes, more than 16 MiB: no scene needs as much"),
              std::string::npos) << e.what();
  }
  std::filesystem::remove(big);
}

}  // namespace
}  // namespace crankcheck

namespace crankcheck {
namespace {

// A scene is named by its file's stem in every heading and table: a stem that would not print as itself on one line
// names the scene with those characters escaped (a newline as \n, U+202E as \u202e); the file is read all the same.
TEST(SceneFile, AFileNameThatIsNotOneLineOfTextNamesTheSceneEscaped) {
  for (const auto& [path, name] : std::vector<std::pair<std::string, std::string>>{
           {"dir/two\nlines.toml", "two\\nlines"},
           {"txt\xe2\x80\xae" "lmot.toml", "txt\\u202elmot"},
           {"esc\x1b[2J.toml", "esc\\x1b[2J"},
           {"latin1\xe9.toml", "latin1\\xe9"},
           {"scenes/my engine \"\xc3\xa9t\xc3\xa9\".toml", "my engine \"\xc3\xa9t\xc3\xa9\""}})  // UTF-8, quotes: text
    EXPECT_EQ(parseScene(kGoodScene, path).name, name);
}

// What a refusal echoes of the scene (a quoted key, a string value) is shown escaped: a NUL in a key no longer cuts the
// message, an escape sequence in a value does not reach the terminal.
TEST(SceneFile, AValueOrKeyItEchoesIsShownEscaped) {
  std::string text = kGoodScene;
  text.insert(text.find("[engine]\n") + 9, "\"bad\\u0000key\\u001b\" = 1\n");
  try {
    parseScene(text, "s.toml");
    ADD_FAILURE() << "an unknown key was accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("s.toml: [engine].bad\\x00key\\x1b: unknown key", 0), 0u) << e.what();
  }
  text = kGoodScene;
  text.replace(text.find("\"four-stroke\""), 13, "\"four\\u202e\\n\"");
  try {
    parseScene(text, "s.toml");
    ADD_FAILURE() << "a bad cycle was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("(got \"four\\u202e\\n\")"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace crankcheck
