// formatSceneToml: the scene text of a Mechanism reads back (parseScene) as the same mechanism. Lengths, masses,
// speeds and pressures exactly (shortest round-trip decimal forms); angles through degrees, within the rounding of
// one conversion each way.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "crankcheck/scene/scene_file.h"
#include "crankcheck/scene/scene_writer.h"
#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/layouts.h"

#ifndef CRANKCHECK_SCENES_DIR
#error "CRANKCHECK_SCENES_DIR must be defined by the build"
#endif

namespace crankcheck {
namespace {

// radians -> degrees -> radians: two roundings of at most half an ulp each, and the conversions' own products;
// 4 eps relative (plus 4 eps absolute around 0, where the angle's value is 0 or 2 pi's rounding) bounds them.
void expectSameAngle(double a, double b, const std::string& what) {
  EXPECT_LE(std::fabs(a - b), 4 * 2.220446049250313e-16 * std::max(1.0, std::fabs(a))) << what << ": " << a << " vs " << b;
}

void expectSameMechanism(const Mechanism& a, const Mechanism& b) {
  const int k = a.machine.cylinders;
  ASSERT_EQ(b.machine.cylinders, k);
  EXPECT_EQ(a.machine.cycle, b.machine.cycle);
  EXPECT_EQ(a.machine.acting, b.machine.acting);
  EXPECT_EQ(a.machine.explicit_crank_angles, b.machine.explicit_crank_angles);  // the compressor's [0, 90] was lost
  for (int j = 0; j < k; ++j) {
    expectSameAngle(getBankAngle(a, j), getBankAngle(b, j), "bank " + std::to_string(j));
    expectSameAngle(getThrowAngle(a, j), getThrowAngle(b, j), "throw " + std::to_string(j));
    expectSameAngle(a.machine.crank_angles[j], b.machine.crank_angles[j], "alpha " + std::to_string(j));
    EXPECT_EQ(getAxialPosition(a, j), getAxialPosition(b, j));
    EXPECT_EQ(getPinOffset(a, j), getPinOffset(b, j));
  }
  EXPECT_EQ(hasAxialPositions(a), hasAxialPositions(b));
  EXPECT_EQ(a.machine.speed, b.machine.speed);
  EXPECT_EQ(a.machine.gravity, b.machine.gravity);
  EXPECT_EQ(a.crank.radius, b.crank.radius);
  EXPECT_EQ(a.crank.mass, b.crank.mass);
  EXPECT_EQ(a.crank.com_radius, b.crank.com_radius);
  EXPECT_EQ(a.crank.counterweight_mass, b.crank.counterweight_mass);
  EXPECT_EQ(a.crank.counterweight_radius, b.crank.counterweight_radius);
  EXPECT_EQ(a.rod.length, b.rod.length);
  EXPECT_EQ(a.rod.mass, b.rod.mass);
  EXPECT_EQ(a.rod.com_from_wrist_pin, b.rod.com_from_wrist_pin);
  EXPECT_EQ(a.rod.inertia_about_wrist_pin, b.rod.inertia_about_wrist_pin);
  EXPECT_EQ(a.piston.mass, b.piston.mass);
  EXPECT_EQ(a.flywheel_inertia, b.flywheel_inertia);
  ASSERT_EQ(a.crankshaft.has_value(), b.crankshaft.has_value());
  if (a.crankshaft) {
    EXPECT_EQ(a.crankshaft->throw_inertia, b.crankshaft->throw_inertia);
    EXPECT_EQ(a.crankshaft->front_inertia, b.crankshaft->front_inertia);
    EXPECT_EQ(a.crankshaft->stiffness, b.crankshaft->stiffness);
    EXPECT_EQ(a.crankshaft->section_damping, b.crankshaft->section_damping);
    EXPECT_EQ(a.crankshaft->throw_damping, b.crankshaft->throw_damping);
    EXPECT_EQ(findThrows(a), findThrows(b));
  }
  ASSERT_EQ(a.gas.has_value(), b.gas.has_value());
  if (a.gas) {
    EXPECT_EQ(a.gas->bore, b.gas->bore);
    EXPECT_EQ(a.gas->pressures, b.gas->pressures);
    ASSERT_EQ(a.gas->cycle_angles.size(), b.gas->cycle_angles.size());
    for (size_t i = 0; i < a.gas->cycle_angles.size(); ++i)
      expectSameAngle(a.gas->cycle_angles[i], b.gas->cycle_angles[i], "gas angle");
    for (int j = 0; j < k; ++j) expectSameAngle(a.firing_angles[j], b.firing_angles[j], "firing");
  }
}

TEST(SceneWriterTest, EveryExampleSceneReadsBackAsItself) {
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(CRANKCHECK_SCENES_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().string());
    const Mechanism m = loadSceneFile(entry.path());
    expectSameMechanism(m, parseScene(formatSceneToml(m), "written"));
    ++n;
  }
  EXPECT_GE(n, 7);
}

TEST(SceneWriterTest, BuiltInScenesAndLayoutsReadBackAsThemselves) {
  for (const Mechanism& m : validation::buildDefaultScenes()) {
    SCOPED_TRACE(m.name);
    expectSameMechanism(m, parseScene(formatSceneToml(m), "written"));
  }
  const Mechanism parts = validation::buildDefaultScenes().front();
  for (const validation::Layout& layout : validation::getBalanceLayouts())
    for (double rotation : {0.0, 37.0}) {
      SCOPED_TRACE(layout.name);
      const Mechanism m = validation::makeLayoutMechanism(layout, parts, rotation);
      expectSameMechanism(m, parseScene(formatSceneToml(m), "written"));
    }
  // Pin offsets: one for every cylinder of an inline engine ([engine].pin_offset), one per cylinder of a layout.
  Mechanism inline_offset = parts;
  inline_offset.machine.pin_offsets.assign(static_cast<size_t>(parts.machine.cylinders), -0.0013);
  expectSameMechanism(inline_offset, parseScene(formatSceneToml(inline_offset), "written"));
  EXPECT_NE(formatSceneToml(inline_offset).find("[engine]"), std::string::npos);
  Mechanism shafts = inline_offset;  // and balance shafts
  shafts.balance_shafts = {{2.0, 0.07, 0.04, radiansFromDegrees(-90.0), {0.04, -0.08, 0.0}},
                           {-1.0, 1.3, 0.03, radiansFromDegrees(12.5), {0.0, 0.1, -0.02}}};
  const Mechanism read = parseScene(formatSceneToml(shafts), "written");
  expectSameMechanism(shafts, read);
  ASSERT_EQ(read.balance_shafts.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(read.balance_shafts[i].ratio, shafts.balance_shafts[i].ratio);
    EXPECT_EQ(read.balance_shafts[i].mass, shafts.balance_shafts[i].mass);
    EXPECT_EQ(read.balance_shafts[i].radius, shafts.balance_shafts[i].radius);
    EXPECT_EQ(read.balance_shafts[i].position, shafts.balance_shafts[i].position);
    expectSameAngle(read.balance_shafts[i].phase, shafts.balance_shafts[i].phase, "shaft phase");
  }
  Mechanism mixed = validation::makeLayoutMechanism(validation::getBalanceLayouts().back(), parts);
  for (int j = 0; j < mixed.machine.cylinders; ++j) mixed.machine.pin_offsets.push_back(0.0004 * (j - 1));
  expectSameMechanism(mixed, parseScene(formatSceneToml(mixed), "written"));
}

// [crankshaft] on every layout of the balance table (V pairs share a pin: one stiffness per throw) and on an inline
// engine, with and without a front mass, damping as one value and as a list.
TEST(SceneWriterTest, CrankshaftReadsBackAsItself) {
  Mechanism parts = validation::buildDefaultScenes().front();
  parts.speed_rpm = 3000.0;
  parts.machine.speed = 3000.0 * (M_PI / 30.0);
  std::vector<Mechanism> scenes = {parts};
  for (const validation::Layout& layout : validation::getBalanceLayouts())
    scenes.push_back(validation::makeLayoutMechanism(layout, parts));
  for (Mechanism m : scenes) {
    SCOPED_TRACE(m.name);
    for (double front : {0.0, 4.0e-3}) {
      CrankshaftParams c;
      c.throw_inertia = 2.0e-3;
      c.front_inertia = front;
      c.throw_damping = 0.4;
      m.crankshaft = c;
      const int sections = countShaftSections(m);
      for (int i = 0; i < sections; ++i) m.crankshaft->stiffness.push_back(4.0e5 + 1.5e5 * i);
      m.crankshaft->section_damping = {1.5};
      expectSameMechanism(m, parseScene(formatSceneToml(m), "written"));
      m.crankshaft->section_damping.assign(static_cast<size_t>(sections), 0.1);
      m.crankshaft->section_damping.back() = 0.7;
      expectSameMechanism(m, parseScene(formatSceneToml(m), "written"));
    }
  }
}

TEST(SceneWriterTest, ShortestNumbersReadBackExactly) {
  for (double x : {0.1, -0.35, 1e-6, 0.29655172413793102, 6000.0, 9.80665, 1.0 / 3.0, 5e-324, 1.7976931348623157e308}) {
    const std::string text = formatShortest(x);
    EXPECT_EQ(std::strtod(text.c_str(), nullptr), x) << text;  // strtod: stod refuses subnormals
  }
  EXPECT_EQ(formatShortest(-0.35), "-0.35");
  EXPECT_EQ(formatShortest(3000.0), "3000.0");
}

}  // namespace
}  // namespace crankcheck
