// An engine that sits out (engines.h: findSatOut, SatOutScope): the scenes an exact engine refuses are found by its
// own build, before any work; while a scope holds it, the registry's lists and the tables with a column per engine
// leave it out, and the registry is whole again after. Held against the scenes themselves: a rod of 1e-9 kg, which
// Simbody's constraint solve cannot resolve (simbody_models/src/engine.cc), and a massless piston, which MuJoCo
// refuses on a joint (the gate's hard cases show both engines' values there).

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "../../validation/src/parts/engine_fields.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/errors.h"

namespace crankcheck::validation {
namespace {

Mechanism loadExample(const std::string& file) {
  Mechanism m = loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / file);
  m.crankshaft.reset();
  return m;
}

// The inline four with its rod scaled to 1e-9 kg (its inertia with it).
Mechanism makeLightRodScene() {
  Mechanism m = loadExample("inline4_four_stroke.toml");
  const double scale = 1e-9 / m.rod.mass;
  m.rod.mass *= scale;
  m.rod.inertia_about_wrist_pin *= scale;
  m.name = "light_rod";
  return m;
}

Mechanism makeMasslessPistonScene() {
  Mechanism m = loadExample("single_cylinder.toml");
  m.piston.mass = 0.0;
  m.name = "massless_piston";
  return m;
}

std::vector<std::string> listNames(const std::vector<const Engine*>& engines) {
  std::vector<std::string> names;
  for (const Engine* e : engines) names.push_back(e->name);
  return names;
}

struct Row {
  std::vector<double> values;
};
std::vector<Field<Row>> makeFields() {
  std::vector<Field<Row>> fields;
  addEngineNumberFields(fields, "_value", "-", &Row::values);
  return fields;
}

TEST(SatOut, AnEngineThatCannotBuildAScenesSitsOutWhileTheScopeLives) {
  const std::vector<SatOut> sat_out = findSatOut({loadExample("single_cylinder.toml"), makeLightRodScene()},
                                                 {"single.toml", "light.toml"});
  ASSERT_EQ(sat_out.size(), 1u);
  EXPECT_EQ(sat_out[0].engine, "simbody");
  EXPECT_EQ(sat_out[0].scene, "light_rod");
  EXPECT_NE(sat_out[0].reason.find("cannot hold its accuracy on this scene"), std::string::npos) << sat_out[0].reason;
  const std::vector<std::string> all = listNames(listReferenceEngines());
  ASSERT_NE(std::find(all.begin(), all.end(), "simbody"), all.end());
  const auto schemaOf = [] { return &getEngineSchema<Row, makeFields>("sat_out_test"); };
  const std::string full = schemaOf()->columns().front().name;
  {
    const SatOutScope scope(sat_out);
    for (const Engine& e : listEngines()) EXPECT_NE(e.name, "simbody");
    EXPECT_EQ(listNames(listReferenceEngines()), (std::vector<std::string>{"mujoco"}));
    EXPECT_EQ(listNames(listBothEngines()), (std::vector<std::string>{"analytic", "mujoco"}));
    EXPECT_THROW(findEngine("simbody"), std::invalid_argument);
    const Schema<Row>& schema = *schemaOf();
    ASSERT_EQ(schema.columns().size(), 1u);
    EXPECT_EQ(schema.columns()[0].name, "mujoco_value");
    EXPECT_THROW(SatOutScope{sat_out}, std::logic_error);  // one at a time
  }
  EXPECT_EQ(listNames(listReferenceEngines()), all);
  EXPECT_EQ(schemaOf()->columns().size(), all.size());
  EXPECT_EQ(schemaOf()->columns().front().name, full);
}

TEST(SatOut, TheClosedFormsAndTheLastExactEngineNeverSitOut) {
  const size_t engines = listEngines().size();
  // Simbody refuses the light rod, MuJoCo the massless piston: no exact engine is left to compare the formulas with.
  try {
    findSatOut({makeLightRodScene(), makeMasslessPistonScene()}, {"light.toml", "piston.toml"});
    ADD_FAILURE() << "no exact engine builds both scenes";
  } catch (const UsageError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("light.toml: --engine simbody: "), std::string::npos) << what;
    EXPECT_NE(what.find("piston.toml: --engine mujoco: "), std::string::npos) << what;
  }
  EXPECT_THROW(SatOutScope({{"simbody", "a", "-"}, {"mujoco", "b", "-"}}), std::invalid_argument);
  EXPECT_THROW(SatOutScope({{"analytic", "a", "-"}}), std::invalid_argument);
  EXPECT_THROW(SatOutScope({{"no-such-engine", "a", "-"}}), std::invalid_argument);
  EXPECT_EQ(listEngines().size(), engines);  // no scope was left alive
}

}  // namespace
}  // namespace crankcheck::validation
