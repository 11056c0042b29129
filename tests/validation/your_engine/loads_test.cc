// The scene sections' loads topic (validation/src/your_engine/loads.cc) against an independent model of each scene
// (independent_loads.h: the drive torque by the energy balance, the forces by each body's momentum, in 50 digits).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "../../../validation/src/your_engine/topic.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/validation/csv.h"
#include "crankcheck/validation/table_schemas.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/report_part.h"
#include "independent_loads.h"
#include "scene_section_fixture.h"

namespace crankcheck {
namespace {

using testing::independent::Hp;
using testing::independent::Model;
using validation::TableSet;
namespace ye = validation::your_engine;

using testing::findTopic;
using testing::loadExample;
using testing::runTopic;

// A 90 degree V-twin, one throw, uneven firing 270 / 450 degrees, spark-ignition pressures.
constexpr const char* kVTwin = R"(format_version = 1
name = "vtwin"
[engine]
cycle = "four-stroke"
speed_rpm = 5000
[[cylinder]]
bank_angle_deg = 135.0
throw_angle_deg = 90.0
firing_angle_deg = 45.0
[[cylinder]]
bank_angle_deg = 45.0
throw_angle_deg = 90.0
firing_angle_deg = 315.0
[crank]
radius = 0.045
mass = 0.9
com_radius = 0.02
counterweight_mass = 1.4
counterweight_radius = 0.035
[rod]
length = 0.15
mass = 0.55
com_from_wrist_pin = 0.105
inertia_about_wrist_pin = 0.0075
[piston]
mass = 0.4
[gas]
bore = 0.094
cycle_angle_deg = [0, 10, 20, 30, 45, 60, 90, 120, 150, 180, 200, 360, 380, 540, 600, 640, 670, 690, 705]
pressure_pa = [3.2e6, 5.2e6, 5.6e6, 4.8e6, 3.4e6, 2.4e6, 1.3e6, 0.8e6, 0.55e6, 0.35e6, 0.05e6, 0.02e6, -0.03e6,
               -0.02e6, 0.08e6, 0.25e6, 0.6e6, 1.1e6, 1.9e6]
)";

// A lying two-stroke single with its piston pin offset 2 mm, with a pressure table.
constexpr const char* kOffsetSingle = R"(format_version = 1
name = "offset_single"
[engine]
cylinders = 1
cycle = "two-stroke"
cylinder_angle_deg = 20
speed_rpm = 3000
pin_offset = 0.002
[crank]
radius = 0.03
mass = 0.5
com_radius = 0.012
counterweight_mass = 0.6
counterweight_radius = 0.022
[rod]
length = 0.11
mass = 0.3
com_from_wrist_pin = 0.075
inertia_about_wrist_pin = 0.0022
[piston]
mass = 0.25
[gas]
bore = 0.056
cycle_angle_deg = [0, 15, 30, 60, 90, 120, 180, 240, 300, 330]
pressure_pa = [2.5e6, 3.1e6, 2.2e6, 1.0e6, 0.5e6, 0.2e6, 0.02e6, 0.05e6, 0.3e6, 1.2e6]
firing_order = [0]
)";

// A bare inline three: no gas, no flywheel, no crankshaft, tilted 60 degrees.
constexpr const char* kBareInline3 = R"(format_version = 1
name = "bare_inline3"
[engine]
cylinders = 3
cycle = "four-stroke"
cylinder_angle_deg = 60
speed_rpm = 2500
[crank]
radius = 0.04
mass = 0.8
com_radius = 0.015
counterweight_mass = 0.7
counterweight_radius = 0.03
[rod]
length = 0.14
mass = 0.5
com_from_wrist_pin = 0.1
inertia_about_wrist_pin = 0.0062
[piston]
mass = 0.35
)";

struct Expected {
  long double drive, drive_mean, crank_pin, wrist_pin, bearing, thrust_positive, thrust_negative, gravity;
};

// The independent model's peaks over the working cycle and the drive torque's mean over the topic's 1 degree grid.
Expected computeIndependently(const Mechanism& m) {
  const Model<long double> coarse(m);
  const Model<Hp> fine(m);
  const double cycle = m.machine.cycle == Cycle::kFourStroke ? 4.0 * M_PI : 2.0 * M_PI;
  const int scan = static_cast<int>(std::lround(cycle / M_PI * 360.0));  // 0.5 degree
  auto peak = [&](auto coarse_f, auto fine_f) {
    return static_cast<long double>(testing::independent::findMax(coarse_f, fine_f, cycle, scan).value);
  };
  auto magnitude = [](auto v) {
    using std::sqrt;
    return sqrt(v.x * v.x + v.y * v.y);
  };
  auto overCylinders = [&](auto model, auto phi, auto get) {
    const auto f = model.forces(phi);
    auto best = get(f, 0);
    for (int j = 1; j < m.machine.cylinders; ++j) best = std::max(best, get(f, j), [](auto a, auto b) { return a < b; });
    return best;
  };
  Expected out{};
  out.drive = peak([&](long double p) { return coarse.driveTorque(p); }, [&](Hp p) { return fine.driveTorque(p); });
  out.gravity = peak([&](long double p) { return coarse.Q(p); }, [&](Hp p) { return fine.Q(p); });
  auto pin = [&](const auto& f, int j) { return magnitude(f.crank_pin[static_cast<size_t>(j)]); };
  auto wrist = [&](const auto& f, int j) { return magnitude(f.wrist_pin[static_cast<size_t>(j)]); };
  auto thrust_pos = [&](const auto& f, int j) { return f.wall[static_cast<size_t>(j)]; };
  auto thrust_neg = [&](const auto& f, int j) { return -f.wall[static_cast<size_t>(j)]; };
  out.crank_pin = peak([&](long double p) { return overCylinders(coarse, p, pin); }, [&](Hp p) { return overCylinders(fine, p, pin); });
  out.wrist_pin = peak([&](long double p) { return overCylinders(coarse, p, wrist); }, [&](Hp p) { return overCylinders(fine, p, wrist); });
  out.bearing = peak([&](long double p) { return magnitude(coarse.forces(p).bearing); },
                     [&](Hp p) { return magnitude(fine.forces(p).bearing); });
  // The side thrust's largest positive and most negative: max(0, .) of each side.
  out.thrust_positive = peak([&](long double p) { return std::max(0.0L, overCylinders(coarse, p, thrust_pos)); },
                             [&](Hp p) { Hp v = overCylinders(fine, p, thrust_pos); return v > 0 ? v : Hp(0); });
  out.thrust_negative = -peak([&](long double p) { return std::max(0.0L, overCylinders(coarse, p, thrust_neg)); },
                              [&](Hp p) { Hp v = overCylinders(fine, p, thrust_neg); return v > 0 ? v : Hp(0); });
  const int n = static_cast<int>(std::lround(cycle / M_PI * 180.0));  // the topic's 1 degree grid
  long double sum = 0;
  for (int i = 0; i < n; ++i) sum += coarse.driveTorque(static_cast<long double>(cycle) * i / n);
  out.drive_mean = sum / n;
  return out;
}

// The rows of the loads table: (engine, load) -> record.
std::map<std::pair<std::string, std::string>, std::map<std::string, std::string>> readLoads(const TableSet& tables) {
  std::map<std::pair<std::string, std::string>, std::map<std::string, std::string>> out;
  for (auto& r : validation::readRecords(tables, "your_engine_loads")) out[{r.at("engine"), r.at("load")}] = r;
  return out;
}

// The issue's acceptance: each number within 1e-6 relative of the independent model's. The code refines its maxima to
// 1e-10 rad and the exact engines agree with the closed forms to 64 eps of the scale, so every difference seen is far
// below (the largest about 1e-9, a peak on a kink of the pressure table); the independent model is exact to 1e-18.
constexpr double kAcceptance = 1e-6;

void checkScene(const Mechanism& m) {
  SCOPED_TRACE(m.name);
  const TableSet tables = runTopic(findTopic("Loads over a working cycle"), m);
  const auto rows = readLoads(tables);
  const Expected x = computeIndependently(m);
  const std::map<std::string, long double> expected = {
      {"drive_torque", x.drive},         {"crank_pin_force", x.crank_pin},
      {"wrist_pin_force", x.wrist_pin},  {"main_bearing_force", x.bearing},
      {"side_thrust_positive", x.thrust_positive}, {"side_thrust_negative", x.thrust_negative},
      {"gravity_torque", x.gravity}};
  for (const Engine* engine : validation::listComparedEngines()) {
    SCOPED_TRACE(engine->name);
    for (const auto& [load, value] : expected) {
      SCOPED_TRACE(load);
      const auto it = rows.find({engine->name, load});
      ASSERT_NE(it, rows.end());
      const double peak = std::stod(it->second.at("peak"));
      const double scale = std::stod(it->second.at("scale"));
      // |peak| for the magnitudes and the drive torque (its sign is where it is), signed for the side thrust.
      const double got = load.rfind("side_thrust", 0) == 0 ? peak : std::fabs(peak);
      // A load at rounding level (gravity's torque where the cylinders cancel it) is compared with its scale.
      EXPECT_LE(std::fabs(got - static_cast<double>(value)), kAcceptance * std::max(std::fabs(static_cast<double>(value)), kAcceptance * scale))
          << got << " vs " << static_cast<double>(value);
    }
  }
  const auto drive = rows.at({"analytic", "drive_torque"});
  EXPECT_NEAR(std::stod(drive.at("mean")), static_cast<double>(x.drive_mean), kAcceptance * std::fabs(static_cast<double>(x.drive)));
}

TEST(YourEngineLoadsTest, VTwinWithGasAgreesWithTheIndependentModel) { checkScene(parseScene(kVTwin, "vtwin.toml")); }
TEST(YourEngineLoadsTest, OffsetSingleWithGasAgreesWithTheIndependentModel) {
  checkScene(parseScene(kOffsetSingle, "offset_single.toml"));
}
TEST(YourEngineLoadsTest, BareInlineThreeAgreesWithTheIndependentModel) {
  checkScene(parseScene(kBareInline3, "bare_inline3.toml"));
}
TEST(YourEngineLoadsTest, ExampleScenesAgreeWithTheIndependentModel) {
  for (const char* stem : {"v8_cross_plane", "inline4_pin_offset", "single_cylinder"}) checkScene(loadExample(stem));
}

// The gas part and the drive torque's parts: without [gas] no gas row; with it the parts add up to the drive torque's
// mean (inertia and gravity are conservative: their means vanish over the cycle).
TEST(YourEngineLoadsTest, TheSplitsMeansAddUp) {
  const Mechanism twin = parseScene(kVTwin, "vtwin.toml");
  const auto rows = readLoads(runTopic(findTopic("Loads over a working cycle"), twin, true));
  const double drive = std::stod(rows.at({"analytic", "drive_torque"}).at("mean"));
  const double gas = std::stod(rows.at({"analytic", "gas_torque"}).at("mean"));
  const double scale = std::stod(rows.at({"analytic", "drive_torque"}).at("scale"));
  // Rounding of 180 sums of torques of the scale: 1e-12 of the scale is a thousand times above it.
  EXPECT_NEAR(drive, gas, 1e-12 * scale);
  EXPECT_NEAR(std::stod(rows.at({"analytic", "inertia_torque"}).at("mean")), 0.0, 1e-12 * scale);
  const auto bare = readLoads(runTopic(findTopic("Loads over a working cycle"), parseScene(kBareInline3, "bare_inline3.toml"), true));
  EXPECT_EQ(bare.count({"analytic", "gas_torque"}), 0u);
}

// describe of a scene without [gas]: the one line saying what is missing and how to add it, and the table.
TEST(YourEngineLoadsTest, DescribeSaysWhatIsMissing) {
  const Mechanism m = parseScene(kBareInline3, "bare_inline3.toml");
  TableSet tables = runTopic(findTopic("Loads over a working cycle"), m, true);
  tables.insert_or_assign("your_engine",
                          validation::parseTable("your_engine",
                                                 validation::parseCsv("scene_index [-],scene,given,layout,cylinders [-],cycle,acting,"
                                                                      "speed_rpm [rpm],lambda [-],gas [-],flywheel [-],crankshaft [-],"
                                                                      "balance_shafts [-],pin_offsets [-],max_pin_offset [m]\n"
                                                                      "0,bare_inline3,user,inline 3,3,four-stroke,single,2500,0.2857,"
                                                                      "0,0,0,0,0,0\n",
                                                                      "your_engine"),
                                                 "your_engine", validation::findTableSchema("your_engine")));
  const std::vector<validation::ReportBlock> blocks = findTopic("Loads over a working cycle").describe(tables, "bare_inline3");
  bool missing = false, table = false, figure = false;
  for (const validation::ReportBlock& b : blocks) {
    missing = missing || (b.kind == validation::ReportBlock::kParagraph && b.text.rfind("No [gas] table", 0) == 0 &&
                          b.text.find("docs/SCENE-FORMAT.md") != std::string::npos);
    table = table || (b.kind == validation::ReportBlock::kTable && !b.rows.empty());
    figure = figure || (b.kind == validation::ReportBlock::kFigure && b.figure == "your_engine_pin_loads" &&
                        b.text.find("\"bare_inline3\"") != std::string::npos);
  }
  EXPECT_TRUE(missing);
  EXPECT_TRUE(table);
  EXPECT_TRUE(figure);
  EXPECT_TRUE(findTopic("Loads over a working cycle").describe(tables, "another_scene").empty());
}

// Both tables read back through their schemas (as `report merge` reads a shard).
TEST(YourEngineLoadsTest, TablesReadBackThroughTheirSchemas) {
  const TableSet tables = runTopic(findTopic("Loads over a working cycle"), parseScene(kOffsetSingle, "offset_single.toml"), true);
  for (const validation::TableSchema* schema : findTopic("Loads over a working cycle").schemas()) {
    SCOPED_TRACE(schema->name());
    const validation::Table& table = tables.at(schema->name());
    const std::string csv = validation::formatCsv(table);
    const validation::Table back = validation::parseTable(schema->name(), validation::parseCsv(csv, schema->name()), schema->name(), validation::findTableSchema(schema->name()));
    EXPECT_EQ(validation::formatCsv(back), csv);
    EXPECT_GT(back.size(), 0u);
  }
}

}  // namespace
}  // namespace crankcheck
