// The scene sections' topics, in the order of a section, and the tables several of them share (topic.h).
#include <algorithm>
#include <cmath>

#include "crankcheck/validation/report_format.h"
#include "topic.h"

namespace crankcheck::validation::your_engine {

const Schema<SceneFactsRow> kSceneFactsTable{
    "your_engine",
    {countField("scene_index", &SceneFactsRow::scene_index), textField("scene", &SceneFactsRow::scene),
     textField("given", &SceneFactsRow::given), textField("layout", &SceneFactsRow::layout),
     countField("cylinders", &SceneFactsRow::cylinders), textField("cycle", &SceneFactsRow::cycle),
     textField("acting", &SceneFactsRow::acting), numberField("speed_rpm", "rpm", &SceneFactsRow::speed_rpm),
     numberField("lambda", "-", &SceneFactsRow::lambda), countField("gas", &SceneFactsRow::gas),
     countField("flywheel", &SceneFactsRow::flywheel), countField("crankshaft", &SceneFactsRow::crankshaft),
     countField("balance_shafts", &SceneFactsRow::balance_shafts), countField("pin_offsets", &SceneFactsRow::pin_offsets),
     numberField("max_pin_offset", "m", &SceneFactsRow::max_pin_offset)}};

const Schema<FitnessRow> kFitnessTable{
    "your_engine_fitness",
    {textField("scene", &FitnessRow::scene), countField("order", &FitnessRow::order),
     textField("formula", &FitnessRow::formula), textField("quantity", &FitnessRow::quantity),
     textField("reference", &FitnessRow::reference), numberField("max_error_rel", "-", &FitnessRow::max_error_rel),
     textField("scale", &FitnessRow::scale), numberField("scale_value", "SI", &FitnessRow::scale_value),
     textField("scale_unit", &FitnessRow::scale_unit),
     optionalField("phi_deg_at_max", "deg", &FitnessRow::phi_deg_at_max), countField("resolved", &FitnessRow::resolved)}};

const Schema<GravityRow> kGravityTable{
    "your_engine_gravity",
    {textField("scene", &GravityRow::scene), textField("engine", &GravityRow::engine),
     numberField("max_abs_Q", "N m", &GravityRow::max_abs_Q), numberField("phi_deg_at_max", "deg", &GravityRow::phi_deg_at_max),
     numberField("max_abs_inertia_torque", "N m", &GravityRow::max_abs_inertia_torque),
     numberField("ratio", "-", &GravityRow::ratio), countField("gated", &GravityRow::gated),
     countField("resolved", &GravityRow::resolved),
     optionalField("max_abs_working_torque", "N m", &GravityRow::max_abs_working_torque)}};

namespace {

// One line naming m's layout: "inline 3, two-stroke, single-acting, cylinders at 90 deg from +X".
std::string describeLayout(const Mechanism& m) {
  const int k = m.machine.cylinders;
  std::vector<double> banks;  // distinct bank angles [deg], in the order of the cylinders
  for (int j = 0; j < k; ++j) {
    const double gamma = std::remainder(degreesFromRadians(getBankAngle(m, j)), 360.0);
    if (std::none_of(banks.begin(), banks.end(), [&](double b) { return std::abs(b - gamma) < 1e-9; }))
      banks.push_back(gamma);
  }
  std::string out;
  if (banks.size() == 1)
    out = (k == 1 ? std::string("single cylinder") : "inline " + std::to_string(k)) + " at " + shortNumber(banks[0], 4) +
          " deg from +X";
  else {
    std::string list;
    for (size_t i = 0; i < banks.size(); ++i)
      list += (i == 0 ? "" : i + 1 == banks.size() ? " and " : ", ") + shortNumber(banks[i], 4);
    const bool opposed = banks.size() == 2 && std::abs(std::abs(std::remainder(banks[0] - banks[1], 360.0)) - 180.0) < 1e-9;
    out = (opposed ? "opposed " : banks.size() == 2 ? "V" : std::to_string(banks.size()) + "-bank ") + std::to_string(k) +
          ", banks at " + list + " deg from +X";
  }
  return out + ", " + toString(m.machine.cycle) + ", " + toString(m.machine.acting) + "-acting";
}

}  // namespace

SceneFactsRow calcSceneFacts(const Mechanism& m, int index, bool user) {
  double max_offset = 0.0;
  for (int j = 0; j < m.machine.cylinders; ++j) max_offset = std::max(max_offset, std::abs(getPinOffset(m, j)));
  return {index,
          m.name,
          user ? "user" : "example",
          describeLayout(m),
          m.machine.cylinders,
          toString(m.machine.cycle),
          toString(m.machine.acting),
          m.speed_rpm,
          calcCrankRatio(m),
          m.gas ? 1 : 0,
          m.flywheel_inertia ? 1 : 0,
          m.crankshaft ? 1 : 0,
          static_cast<int>(m.balance_shafts.size()),
          hasPinOffsets(m) ? 1 : 0,
          max_offset};
}

std::optional<SceneFactsRow> findSceneFacts(const TableSet& tables, const std::string& scene) {
  for (const SceneFactsRow& row : getRows(tables, kSceneFactsTable))
    if (row.scene == scene) return row;
  return std::nullopt;
}

std::string formatFitness(double max_error_rel, bool resolved) {
  if (!resolved) return "exact to rounding";
  if (max_error_rel < 0.01) return "within 1 %";
  // Beyond the scale itself a percentage misleads ("4.43e+03 %"): the factor reads at a glance.
  if (max_error_rel >= 1.0) return "off by " + shortNumber(max_error_rel, 3) + " times the scale";
  return "off by " + formatPercent(max_error_rel);
}

// The topics, in the order of a section: each defined in its own file of this folder as `const SceneTopic& NAME()`.
namespace topics {
const SceneTopic& fitness();
const SceneTopic& loads();
const SceneTopic& balance();
const SceneTopic& gravity();
const SceneTopic& dynamics();
}  // namespace topics

const std::vector<const SceneTopic*>& listTopics() {
  static const std::vector<const SceneTopic*> all = {&topics::fitness(), &topics::loads(), &topics::balance(),
                                                     &topics::gravity(), &topics::dynamics()};
  return all;
}

}  // namespace crankcheck::validation::your_engine
