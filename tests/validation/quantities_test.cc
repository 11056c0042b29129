// The catalogue of an Evaluation's quantities (scene/quantities.h) held against what it must agree with and does not
// produce: the Evaluation struct's own fields (named here by hand, with their sizes), the names and order eval's
// JSON has always printed (docs/eval.md, the protocol of `crankcheck grade`), and what the analytic engine returns
// for a V6 with axial positions and a pressure table.

#include <gtest/gtest.h>

#include <cstddef>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "crankcheck/scene/quantities.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/evaluation_json.h"
#include "crankcheck/validation/scales.h"

namespace crankcheck {
namespace {

// Every field of Evaluation that is a quantity, by hand: its name as eval's JSON spells it, where it is in an
// Evaluation (cylinder j), and its size in doubles (from its type, not from the catalogue).
struct Field {
  std::string name;
  bool per_cylinder;
  size_t doubles;
  std::function<double*(Evaluation&, size_t)> at;
};

const std::vector<Field>& handFields() {
  static const std::vector<Field> fields = {
      {"U", false, sizeof(Evaluation::U) / sizeof(double), [](Evaluation& e, size_t) { return &e.U; }},
      {"Q", false, sizeof(Evaluation::Q) / sizeof(double), [](Evaluation& e, size_t) { return &e.Q; }},
      {"drive_torque", false, sizeof(Evaluation::drive_torque) / sizeof(double),
       [](Evaluation& e, size_t) { return &e.drive_torque; }},
      {"bearing_force", false, sizeof(Evaluation::bearing_force) / sizeof(double),
       [](Evaluation& e, size_t) { return e.bearing_force.data(); }},
      {"shaking_force", false, sizeof(Evaluation::shaking_force) / sizeof(double),
       [](Evaluation& e, size_t) { return e.shaking_force.data(); }},
      {"shaking_moment", false, sizeof(Evaluation::shaking_moment) / sizeof(double),
       [](Evaluation& e, size_t) { return e.shaking_moment.data(); }},
      {"x_p", true, 1, [](Evaluation& e, size_t j) { return &e.cylinders[j].x_p; }},
      {"v_p", true, 1, [](Evaluation& e, size_t j) { return &e.cylinders[j].v_p; }},
      {"a_p", true, 1, [](Evaluation& e, size_t j) { return &e.cylinders[j].a_p; }},
      {"crank_pin_force", true, sizeof(CylinderEvaluation::crank_pin_force) / sizeof(double),
       [](Evaluation& e, size_t j) { return e.cylinders[j].crank_pin_force.data(); }},
      {"wrist_pin_force", true, sizeof(CylinderEvaluation::wrist_pin_force) / sizeof(double),
       [](Evaluation& e, size_t j) { return e.cylinders[j].wrist_pin_force.data(); }},
      {"wall_force", true, 1, [](Evaluation& e, size_t j) { return &e.cylinders[j].wall_force; }},
      {"gas_force", true, 1, [](Evaluation& e, size_t j) { return &e.cylinders[j].gas_force; }},
      {"rod_angle", true, 1, [](Evaluation& e, size_t j) { return &e.cylinders[j].rod_angle; }},
      {"rod_omega", true, 1, [](Evaluation& e, size_t j) { return &e.cylinders[j].rod_omega; }},
      {"rod_alpha", true, 1, [](Evaluation& e, size_t j) { return &e.cylinders[j].rod_alpha; }},
  };
  return fields;
}

// A 60-degree V6 (banks at 60 and 120 degrees, three throws 120 degrees apart, each shared by a left and a right
// cylinder 0.02 m apart along the shaft) with a pressure table, each cylinder firing at an outer dead centre
// (phi = bank - throw, or 360 degrees later).
const char* const kV6 = R"(format_version = 1
name = "V6 with axial positions"
[engine]
cycle = "four-stroke"
speed_rpm = 4000
[[cylinder]]
bank_angle_deg = 120.0
throw_angle_deg = 0.0
axial_position = 0.0
firing_angle_deg = 120.0
[[cylinder]]
bank_angle_deg = 120.0
throw_angle_deg = 240.0
axial_position = 0.1
firing_angle_deg = 240.0
[[cylinder]]
bank_angle_deg = 120.0
throw_angle_deg = 120.0
axial_position = 0.2
firing_angle_deg = 360.0
[[cylinder]]
bank_angle_deg = 60.0
throw_angle_deg = 0.0
axial_position = 0.02
firing_angle_deg = 420.0
[[cylinder]]
bank_angle_deg = 60.0
throw_angle_deg = 240.0
axial_position = 0.12
firing_angle_deg = 540.0
[[cylinder]]
bank_angle_deg = 60.0
throw_angle_deg = 120.0
axial_position = 0.22
firing_angle_deg = 660.0
[crank]
radius = 0.043
mass = 1.0
com_radius = 0.02
counterweight_mass = 1.1
counterweight_radius = 0.035
[rod]
length = 0.15
mass = 0.55
com_from_wrist_pin = 0.105
inertia_about_wrist_pin = 0.0075
[piston]
mass = 0.4
[flywheel]
inertia = 0.2
[gas]
bore = 0.09
cycle_angle_deg = [0, 20, 60, 180, 360, 540, 700]
pressure_pa = [3e6, 5e6, 2e6, 0.3e6, 0.0, -0.02e6, 1e6]
)";

TEST(QuantityCatalogue, IdsIndexTheCatalogueAndNamesAreUnique) {
  const std::vector<Quantity>& catalogue = getQuantityCatalogue();
  std::set<std::string> names;
  for (size_t i = 0; i < catalogue.size(); ++i) {
    EXPECT_EQ(static_cast<size_t>(catalogue[i].id), i) << catalogue[i].name;
    EXPECT_EQ(&getQuantity(catalogue[i].id), &catalogue[i]);
    EXPECT_EQ(findQuantity(catalogue[i].name), &catalogue[i]);
    EXPECT_TRUE(names.insert(catalogue[i].name).second) << catalogue[i].name << " twice";
    EXPECT_EQ(catalogue[i].whole == nullptr, catalogue[i].per_cylinder) << catalogue[i].name;
    EXPECT_EQ(catalogue[i].cylinder == nullptr, !catalogue[i].per_cylinder) << catalogue[i].name;
  }
  EXPECT_EQ(findQuantity("no_such_quantity"), nullptr);
}

// The names, order, shapes and fields of the catalogue are the hand list's, and each accessor reaches its field.
TEST(QuantityCatalogue, MatchesEvaluationsFieldsOneToOne) {
  const std::vector<Quantity>& catalogue = getQuantityCatalogue();
  ASSERT_EQ(catalogue.size(), handFields().size());
  Evaluation ev;
  ev.cylinders.resize(3);
  for (size_t i = 0; i < catalogue.size(); ++i) {
    const Quantity& q = catalogue[i];
    const Field& f = handFields()[i];
    EXPECT_EQ(q.name, f.name);
    EXPECT_EQ(q.per_cylinder, f.per_cylinder) << f.name;
    EXPECT_EQ(static_cast<size_t>(q.components), f.doubles) << f.name;
    for (size_t j = 0; j < (q.per_cylinder ? ev.cylinders.size() : 1); ++j) {
      EXPECT_EQ(accessQuantity(q, ev, static_cast<int>(j)), f.at(ev, j)) << f.name << " cylinder " << j;
      EXPECT_EQ(readQuantity(q, ev, static_cast<int>(j)), f.at(ev, j)) << f.name << " cylinder " << j;
    }
  }
  EXPECT_THROW(accessQuantity(getQuantity(QuantityId::kPistonPosition), ev, 3), std::out_of_range);
}

// Every double of a CylinderEvaluation, and every double of an Evaluation between phi and the cylinders (its
// quantities), is reached by exactly one component of one catalogue entry: a field added to the struct without its
// catalogue line fails here.
TEST(QuantityCatalogue, EveryFieldReachedExactlyOnce) {
  static_assert(sizeof(CylinderEvaluation) % sizeof(double) == 0, "CylinderEvaluation holds doubles only");
  Evaluation ev;
  ev.cylinders.resize(1);
  const char* cylinder_base = reinterpret_cast<const char*>(&ev.cylinders[0]);
  std::vector<int> cylinder_hits(sizeof(CylinderEvaluation) / sizeof(double), 0);
  const char* first = reinterpret_cast<const char*>(&ev.phi + 1);
  const char* last = reinterpret_cast<const char*>(&ev.cylinders);
  ASSERT_LT(first, last);
  std::vector<int> whole_hits(static_cast<size_t>(last - first) / sizeof(double), 0);
  for (const Quantity& q : getQuantityCatalogue())
    for (int c = 0; c < q.components; ++c) {
      const char* at = reinterpret_cast<const char*>(accessQuantity(q, ev, 0) + c);
      if (q.per_cylinder) {
        ASSERT_GE(at, cylinder_base) << q.name;
        ASSERT_LT(at, cylinder_base + sizeof(CylinderEvaluation)) << q.name;
        ++cylinder_hits[static_cast<size_t>(at - cylinder_base) / sizeof(double)];
      } else {
        ASSERT_GE(at, first) << q.name;
        ASSERT_LT(at, last) << q.name;
        ++whole_hits[static_cast<size_t>(at - first) / sizeof(double)];
      }
    }
  for (size_t i = 0; i < cylinder_hits.size(); ++i) EXPECT_EQ(cylinder_hits[i], 1) << "CylinderEvaluation double " << i;
  for (size_t i = 0; i < whole_hits.size(); ++i) EXPECT_EQ(whole_hits[i], 1) << "Evaluation double " << i << " after phi";
}

// eval's JSON of a real evaluation: the keys, in order, as eval has always printed them (docs/eval.md), and each
// value the field's own (read by hand); shapes as the V6's engine returns them: an array of `components` numbers,
// one object per cylinder.
TEST(QuantityCatalogue, JsonOfTheV6IsTheFieldsByName) {
  const Mechanism m = parseScene(kV6, "v6");
  ASSERT_TRUE(hasAxialPositions(m));
  ASSERT_TRUE(m.gas.has_value());
  Evaluation ev = validation::getClosedFormEngine().build(m)->evaluate(0.7);
  ASSERT_EQ(ev.cylinders.size(), 6u);
  const nlohmann::ordered_json j = validation::evaluationToJson(ev, 40.0, m);
  std::vector<std::string> keys;
  for (const auto& [key, value] : j.items()) keys.push_back(key);
  EXPECT_EQ(keys, (std::vector<std::string>{"engine", "phi_deg", "U", "Q", "drive_torque", "U_star", "Q_star",
                                             "bearing_force", "shaking_force", "shaking_moment", "cylinders"}));
  ASSERT_EQ(j["cylinders"].size(), 6u);
  for (size_t c = 0; c < 6; ++c) {
    std::vector<std::string> cylinder_keys;
    for (const auto& [key, value] : j["cylinders"][c].items()) cylinder_keys.push_back(key);
    EXPECT_EQ(cylinder_keys, (std::vector<std::string>{"x_p", "v_p", "a_p", "crank_pin_force", "wrist_pin_force",
                                                        "wall_force", "gas_force", "rod_angle", "rod_omega", "rod_alpha"}));
  }
  for (const Field& f : handFields())
    for (size_t c = 0; c < (f.per_cylinder ? 6u : 1u); ++c) {
      const nlohmann::ordered_json& value = f.per_cylinder ? j["cylinders"][c][f.name] : j[f.name];
      const double* field = f.at(ev, c);
      if (f.doubles == 1) {
        EXPECT_EQ(value.get<double>(), field[0]) << f.name;
        continue;
      }
      ASSERT_TRUE(value.is_array()) << f.name;
      ASSERT_EQ(value.size(), f.doubles) << f.name;
      for (size_t i = 0; i < f.doubles; ++i) EXPECT_EQ(value[i].get<double>(), field[i]) << f.name << "[" << i << "]";
    }
}

// Without axial positions or [gas]: shaking_moment's X and Y null (Z a number), gas_force absent, and neither compared
// nor the gas force asked of a graded program (compareEvaluations: the catalogue's comparisons).
TEST(QuantityCatalogue, UndefinedComponentsAndQuantities) {
  Mechanism m = parseScene(kV6, "v6");
  m.gas.reset();
  m.machine.axial_positions.clear();  // no placement along the shaft (hasAxialPositions)
  m.firing_angles.clear();
  ASSERT_FALSE(hasAxialPositions(m));
  const Evaluation ev = validation::getClosedFormEngine().build(m)->evaluate(0.3);
  const nlohmann::ordered_json j = validation::evaluationToJson(ev, 17.0, m);
  EXPECT_TRUE(j["shaking_moment"][0].is_null());
  EXPECT_TRUE(j["shaking_moment"][1].is_null());
  EXPECT_EQ(j["shaking_moment"][2].get<double>(), ev.shaking_moment[2]);
  EXPECT_FALSE(j["cylinders"][0].contains("gas_force"));
  size_t per_cylinder = 0, whole = 0;
  for (const validation::Comparison& c : validation::compareEvaluations(m, ev, ev)) {
    EXPECT_NE(c.quantity, "gas_force");
    (c.cylinder < 0 ? whole : per_cylinder) += 1;
  }
  // U, Q, drive torque, two forces of 2 and the moment's 3; per cylinder 3 kinematics, two pin forces of 2, the wall
  // force and the rod's 3.
  EXPECT_EQ(whole, 1u + 1u + 1u + 2u + 2u + 3u);
  EXPECT_EQ(per_cylinder, 6u * (3u + 2u + 2u + 1u + 3u));
}

// Each comparison's scale and conditioning are the members of Scales the gate's rule names for it
// (docs/CONVENTIONS-crankcheck.md, "Tolerances"), written out here by hand.
TEST(QuantityCatalogue, ComparisonsUseTheirScales) {
  const Mechanism m = parseScene(kV6, "v6");
  const validation::Scales s = validation::calcScales(m);
  const double l = m.rod.length, dyn = s.acceleration_conditioning;
  const std::map<std::string, std::pair<double, double>> expected = {
      {"U", {s.absolute_height_energy, s.closure}},      {"Q", {s.energy, s.conditioning}},
      {"drive_torque", {s.torque, dyn}},         {"bearing_force", {s.force, dyn}},
      {"shaking_force", {s.force, dyn}},         {"shaking_moment", {s.moment, dyn}},
      {"x_p", {s.position, s.closure}},          {"v_p", {s.velocity, s.velocity_conditioning}},
      {"a_p", {s.acceleration, dyn}},            {"crank_pin_force", {s.force, dyn}},
      {"wrist_pin_force", {s.force, dyn}},       {"wall_force", {s.force, dyn}},
      {"gas_force", {s.force, 1.0}},             {"rod_angle", {1.0, s.closure}},
      {"rod_omega", {s.velocity / l, s.velocity_conditioning}},
      {"rod_alpha", {s.acceleration / l, dyn}}};
  const Evaluation ev = validation::getClosedFormEngine().build(m)->evaluate(1.1);
  std::set<std::string> seen;
  for (const validation::Comparison& c : validation::compareEvaluations(m, ev, ev)) {
    ASSERT_TRUE(expected.count(c.quantity)) << c.quantity;
    EXPECT_EQ(c.scale, expected.at(c.quantity).first) << c.quantity;
    EXPECT_EQ(c.conditioning, expected.at(c.quantity).second) << c.quantity;
    seen.insert(c.quantity);
  }
  EXPECT_EQ(seen.size(), expected.size());
}

}  // namespace
}  // namespace crankcheck
