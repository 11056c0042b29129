// Topic `loads` of the scene sections: the loads over one working cycle of the scene exactly as given (its speed, its
// [gas] table, gravity), in every engine: the drive torque and its split into gas, inertia and gravity, the crank-pin,
// wrist-pin and main-bearing forces and the side thrust; the closed form's pin-load polar diagrams.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "../part_math.h"
#include "../working_cycle.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/extremum.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/scales.h"
#include "gravity_model.h"
#include "topic.h"

namespace crankcheck::validation::your_engine {
namespace {

// your_engine_loads: per scene, engine and load, the load's peak over one working cycle (refined: the largest |value|;
// the side thrust's largest positive and most negative, signed), where and on which cylinder, the torques' mean over
// the cycle, and the largest |engine - closed form| of the load over the engine's samples relative to the scale.
struct LoadRow {
  std::string scene, engine;
  int gated = 1;                  ///< 0: a soft way, measured and never gated (Engine::gated)
  int order = 0;                  ///< the load's place in the topic's table
  std::string load;               ///< "drive_torque", "gas_torque", ..., "side_thrust_negative"
  std::string unit;               ///< "N m" or "N": the unit of peak, mean and scale
  double peak = 0.0;              ///< [SI] the largest |.| over the cycle; the side thrust's signed (its own side)
  double phi_deg_at_peak = 0.0;   ///< [deg] where, in [0, cycle)
  std::optional<int> cylinder;    ///< the cylinder it is on; empty for the drive torque, its parts and the bearing
  std::optional<double> mean;     ///< [SI] the mean over the cycle (torques); empty for the forces
  double scale = 0.0;             ///< [SI] the torque or force scale (scales.h calcScales)
  double max_difference_rel = 0.0;  ///< [-] max |engine - closed form| over the engine's samples / scale (0: the closed form)
  int resolved = 1;               ///< 0: the peak is at rounding level (part_math.h resolvedToOnePercent), a bound
};
const Schema<LoadRow> kLoadsTable{
    "your_engine_loads",
    {textField("scene", &LoadRow::scene), textField("engine", &LoadRow::engine), countField("gated", &LoadRow::gated),
     countField("order", &LoadRow::order), textField("load", &LoadRow::load), textField("unit", &LoadRow::unit),
     numberField("peak", "SI", &LoadRow::peak), numberField("phi_deg_at_peak", "deg", &LoadRow::phi_deg_at_peak),
     optionalCountField("cylinder", &LoadRow::cylinder), optionalField("mean", "SI", &LoadRow::mean),
     numberField("scale", "SI", &LoadRow::scale), numberField("max_difference_rel", "-", &LoadRow::max_difference_rel),
     countField("resolved", &LoadRow::resolved)}};

// your_engine_pin_loads: the closed form's pin-load polar diagrams, one panel per scene (reports/your_engine_pin_loads.gp):
// the crank-pin force of cylinder 0 in the crank's own frame and the main-bearing force in the frame's X, Y over one
// working cycle. scene_index is the scene's place in the sections (from data/your_engine.csv, set in derive); the
// scene's name last, so that a name with a comma cannot shift the figure's numbers.
struct PinLoadRow {
  int scene_index = 0;
  double phi_deg = 0.0;
  double crank_pin_radial = 0.0, crank_pin_tangential = 0.0, bearing_x = 0.0, bearing_y = 0.0;  ///< [N]
  std::string scene;
};
const Schema<PinLoadRow> kPinLoadsTable{
    "your_engine_pin_loads",
    {countField("scene_index", &PinLoadRow::scene_index), numberField("phi_deg", "deg", &PinLoadRow::phi_deg),
     numberField("crank_pin_radial", "N", &PinLoadRow::crank_pin_radial),
     numberField("crank_pin_tangential", "N", &PinLoadRow::crank_pin_tangential),
     numberField("bearing_x", "N", &PinLoadRow::bearing_x), numberField("bearing_y", "N", &PinLoadRow::bearing_y),
     textField("scene", &PinLoadRow::scene)}};

enum Load { kDrive, kGas, kInertia, kGravity, kCrankPin, kWristPin, kBearing, kThrustPositive, kThrustNegative, kLoadCount };
struct LoadSpec {
  const char* key;
  const char* label;  // in the report's table
  bool torque;
};
constexpr std::array<LoadSpec, kLoadCount> kLoads = {{
    {"drive_torque", "|drive torque|", true},
    {"gas_torque", "|its gas part|", true},
    {"inertia_torque", "|its inertia part|", true},
    {"gravity_torque", "|its gravity part (Q)|", true},
    {"crank_pin_force", "crank-pin force |F|", false},
    {"wrist_pin_force", "wrist-pin force |F|", false},
    {"main_bearing_force", "main-bearing force |F|", false},
    {"side_thrust_positive", "side thrust N_w, largest positive", false},
    {"side_thrust_negative", "side thrust N_w, most negative", false},
}};

struct LoadValue {
  double value = 0.0;
  int cylinder = -1;  // -1: not a cylinder's
};

// The largest (sign +1) or most negative (sign -1) of one number per cylinder, clipped at 0 for the side thrust;
// the largest for magnitudes.
template <class Get>
LoadValue extremeOverCylinders(const Evaluation& e, Get get, int sign, bool clip) {
  LoadValue best{0.0, -1};
  for (size_t j = 0; j < e.cylinders.size(); ++j) {
    const double v = sign * get(e.cylinders[j]);
    if (best.cylinder < 0 || v > best.value) best = {v, static_cast<int>(j)};
  }
  if (clip && best.value < 0.0) best.value = 0.0;  // no thrust on that side at this angle
  best.value *= sign;
  return best;
}

// One engine's models of the scene: the scene as given, the scene without gas (its drive torque is the inertia and
// gravity parts; the gas part is the difference: the drive torque is linear in the loads at a given motion) and the
// gravity model (Q = dU/dphi, the drive torque at rest with gravity alone: the gravity part).
class LoadModels {
 public:
  LoadModels(const Engine& engine, const Mechanism& m) : has_gas_(m.gas.has_value()) {
    full_ = engine.build(m);
    if (has_gas_) no_gas_ = engine.build(withLoads(m, false, true, true));
    gravity_ = buildSceneGravityModel(engine, m);
  }
  // Every load at phi (each model evaluated once), and the evaluation of the scene as given.
  std::array<LoadValue, kLoadCount> all(double phi, Evaluation* full_out = nullptr) {
    const Evaluation e = full_->evaluateMotion(phi);
    const double no_gas = has_gas_ ? no_gas_->evaluateMotion(phi).drive_torque : e.drive_torque;
    const double q = gravity_->calcQ(phi);
    std::array<LoadValue, kLoadCount> out;
    out[kDrive] = {e.drive_torque, -1};
    out[kGas] = {e.drive_torque - no_gas, -1};
    out[kInertia] = {no_gas - q, -1};
    out[kGravity] = {q, -1};
    fillForces(e, out);
    if (full_out) *full_out = e;
    return out;
  }
  // One load at phi, evaluating only the models it needs.
  LoadValue at(Load load, double phi) {
    switch (load) {
      case kGas: return {full_->evaluateMotion(phi).drive_torque - no_gas_->evaluateMotion(phi).drive_torque, -1};
      case kInertia:
        return {(has_gas_ ? no_gas_ : full_)->evaluateMotion(phi).drive_torque - gravity_->calcQ(phi), -1};
      case kGravity: return {gravity_->calcQ(phi), -1};
      default: {
        std::array<LoadValue, kLoadCount> out;
        const Evaluation e = full_->evaluateMotion(phi);
        out[kDrive] = {e.drive_torque, -1};
        fillForces(e, out);
        return out[load];
      }
    }
  }

 private:
  static void fillForces(const Evaluation& e, std::array<LoadValue, kLoadCount>& out) {
    out[kCrankPin] = extremeOverCylinders(e, [](const CylinderEvaluation& c) { return std::hypot(c.crank_pin_force[0], c.crank_pin_force[1]); }, 1, false);
    out[kWristPin] = extremeOverCylinders(e, [](const CylinderEvaluation& c) { return std::hypot(c.wrist_pin_force[0], c.wrist_pin_force[1]); }, 1, false);
    out[kBearing] = {std::hypot(e.bearing_force[0], e.bearing_force[1]), -1};
    out[kThrustPositive] = extremeOverCylinders(e, [](const CylinderEvaluation& c) { return c.wall_force; }, 1, true);
    out[kThrustNegative] = extremeOverCylinders(e, [](const CylinderEvaluation& c) { return c.wall_force; }, -1, true);
  }
  bool has_gas_;
  std::unique_ptr<EngineModel> full_, no_gas_, gravity_;
};

// The closed form's samples per cycle (1 degree, 4 with quick: its maxima refined all the same) and the other engines'
// (6 degrees, 12 with quick: their means and their differences from the closed form; their maxima are refined
// around the closed form's, where an engine that agrees with it has its own).
int closedFormSamples(const Mechanism& m, bool quick) {
  return static_cast<int>(std::lround(degreesFromRadians(calcCycleAngle(m)) / (quick ? 4.0 : 1.0)));
}
int engineSamples(const Mechanism& m, bool quick) {
  return static_cast<int>(std::lround(degreesFromRadians(calcCycleAngle(m)) / (quick ? 12.0 : 6.0)));
}

TableSet calcLoadTables(const Mechanism& m, bool quick) {
  const double cycle = calcCycleAngle(m), tolerance = getAngleTolerance(quick);
  const Scales scales = calcScales(m);
  const bool has_gas = m.gas.has_value();
  std::vector<LoadRow> rows;
  std::vector<PinLoadRow> polar;
  auto makeRow = [&](const Engine& engine, int load, double peak, double phi, int cylinder, std::optional<double> mean,
                     double difference) {
    const LoadSpec& spec = kLoads[static_cast<size_t>(load)];
    const double scale = spec.torque ? scales.torque : scales.force;
    double phi_deg = degreesFromRadians(std::fmod(phi, cycle));
    if (phi_deg < 0.0) phi_deg += degreesFromRadians(cycle);
    rows.push_back({m.name, engine.name, engine.gated ? 1 : 0, load, spec.key, spec.torque ? "N m" : "N", peak, phi_deg,
                    cylinder >= 0 ? std::optional<int>(cylinder) : std::nullopt, mean, scale, difference / scale,
                    resolvedToOnePercent(std::fabs(peak) / scale) ? 1 : 0});
  };

  // The closed form: sampled finely, each load's best four sampled maxima refined.
  const Engine& closed = getClosedFormEngine();
  LoadModels closed_models(closed, m);
  const int n = closedFormSamples(m, quick);
  std::array<std::vector<double>, kLoadCount> samples;
  std::array<double, kLoadCount> sums{};
  for (int i = 0; i < n; ++i) {
    const double phi = cycle * i / n;
    Evaluation e;
    const std::array<LoadValue, kLoadCount> v = closed_models.all(phi, &e);
    for (int l = 0; l < kLoadCount; ++l) {
      samples[l].push_back(v[l].value);
      sums[l] += v[l].value;
    }
    const auto [radial, tangential] = calcCrankPinForceInCrankFrame(m, e, 0);
    polar.push_back({0, degreesFromRadians(phi), radial, tangential, e.bearing_force[0], e.bearing_force[1], m.name});
  }
  std::array<double, kLoadCount> closed_phi{};
  for (int l = 0; l < kLoadCount; ++l) {
    if (l == kGas && !has_gas) continue;
    const Load load = static_cast<Load>(l);
    const TurnMaximum best = findMaxAbsOverCycle([&](double phi) { return closed_models.at(load, phi).value; }, cycle,
                                                 samples[l], 4, tolerance);
    const LoadValue there = closed_models.at(load, best.phi);
    closed_phi[l] = best.phi;
    makeRow(closed, l, l == kThrustNegative ? -best.value : best.value, best.phi, there.cylinder,
            kLoads[l].torque ? std::optional<double>(sums[l] / n) : std::nullopt, 0.0);
  }

  // Every other engine: its samples (its means, its differences from the closed form, a soft way's maxima). Its maxima
  // are refined within one of the closed form's sampling steps either side of the closed form's (the gate holds an
  // exact engine to the closed forms, so its maximum is there); a soft way's also from its own samples, the best two
  // refined, and the larger kept.
  const int n_engine = engineSamples(m, quick);
  const double bracket = cycle / n;
  for (const Engine& engine : listEngines()) {
    if (engine.closed_form) continue;
    LoadModels models(engine, m);
    std::array<double, kLoadCount> engine_sums{}, worst{};
    std::array<std::vector<double>, kLoadCount> engine_samples;
    for (int i = 0; i < n_engine; ++i) {
      const double phi = cycle * i / n_engine;
      const std::array<LoadValue, kLoadCount> v = models.all(phi), c = closed_models.all(phi);
      for (int l = 0; l < kLoadCount; ++l) {
        engine_sums[l] += v[l].value;
        engine_samples[l].push_back(v[l].value);
        worst[l] = std::max(worst[l], std::fabs(v[l].value - c[l].value));
      }
    }
    for (int l = 0; l < kLoadCount; ++l) {
      if (l == kGas && !has_gas) continue;
      const Load load = static_cast<Load>(l);
      const auto f = [&](double phi) { return models.at(load, phi).value; };
      TurnMaximum best = refineMaxAbs(f, closed_phi[l] - bracket, closed_phi[l] + bracket, tolerance);
      if (!engine.gated) {
        const TurnMaximum own = findMaxAbsOverCycle(f, cycle, engine_samples[l], 2, tolerance);
        if (own.value > best.value) best = own;
      }
      const LoadValue there = models.at(load, best.phi);
      makeRow(engine, l, l == kThrustNegative ? -best.value : best.value, best.phi, there.cylinder,
              kLoads[l].torque ? std::optional<double>(engine_sums[l] / n_engine) : std::nullopt, worst[l]);
    }
  }
  return {{kLoadsTable.name(), kLoadsTable.table(std::move(rows))}, {kPinLoadsTable.name(), kPinLoadsTable.table(std::move(polar))}};
}

std::string degreesText(double deg) { return shortNumber(deg, 4) + " deg"; }

class LoadsTopic final : public SceneTopic {
 public:
  std::string title() const override { return "Loads over a working cycle"; }
  std::vector<Task> tasks(const Mechanism& scene, bool quick) const override {
    return {{"your_engine loads " + scene.name, false, [scene, quick] { return calcLoadTables(scene, quick); },
             task_cost::kGateSweep}};
  }
  // The figure's panels in the sections' order: each scene's place from the scenes' facts.
  void derive(TableSet& tables) const override {
    if (!tables.count(kPinLoadsTable.name())) return;
    std::map<std::string, int> index;
    for (const SceneFactsRow& f : getRows(tables, kSceneFactsTable)) index[f.scene] = f.scene_index;
    std::vector<PinLoadRow> rows = getRows(tables, kPinLoadsTable);
    for (PinLoadRow& r : rows)
      if (index.count(r.scene)) r.scene_index = index[r.scene];
    tables.insert_or_assign(kPinLoadsTable.name(), kPinLoadsTable.table(std::move(rows)));
  }
  std::vector<ReportBlock> describe(const TableSet& tables, const std::string& scene) const override {
    std::vector<ReportBlock> out;
    std::vector<LoadRow> rows;
    for (const LoadRow& r : getRows(tables, kLoadsTable))
      if (r.scene == scene) rows.push_back(r);
    if (rows.empty()) return out;
    const std::optional<SceneFactsRow> facts = findSceneFacts(tables, scene);
    const std::string closed = getClosedFormEngine().name;
    auto find = [&](const std::string& load) -> const LoadRow* {
      for (const LoadRow& r : rows)
        if (r.engine == closed && r.load == load) return &r;
      return nullptr;
    };
    const LoadRow* drive = find("drive_torque");
    const LoadRow* gravity = find("gravity_torque");
    const LoadRow* pin = find("crank_pin_force");
    const LoadRow* bearing = find("main_bearing_force");
    if (!drive || !gravity || !pin || !bearing) return out;
    const bool has_gas = facts ? facts->gas != 0 : find("gas_torque") != nullptr;
    // A mean at rounding level (the inertia torque's, whose work over a cycle is zero) reads as such, not as 1e-15 N m.
    auto meanText = [](const LoadRow& r) {
      const double mean = r.mean.value_or(0.0);
      return resolvedToOnePercent(std::fabs(mean) / r.scale) ? shortNumber(mean, 4) + " " + r.unit
                                                              : std::string("0 (rounding)");
    };
    const std::string cycle = facts && facts->cycle == "two-stroke" ? "360" : "720";
    std::string text = "Over one working cycle (" + cycle + " deg)" +
                       (facts ? " at " + shortNumber(facts->speed_rpm, 4) + " rpm" : std::string()) +
                       (has_gas ? " with the scene's [gas] table" : std::string()) +
                       ", the closed forms' largest |drive torque| is " + shortNumber(std::fabs(drive->peak), 4) +
                       " N m at " + degreesText(drive->phi_deg_at_peak) + ", its mean " +
                       meanText(*drive) + ". Gravity's part is at most " +
                       shortNumber(std::fabs(gravity->peak), 3) + " N m, " +
                       formatPercent(std::fabs(gravity->peak) / std::max(std::fabs(drive->peak), 1e-300)) +
                       " of the largest |drive torque|. ";
    const LoadRow* largest = pin->peak >= bearing->peak ? pin : bearing;
    text += "The largest bearing load is the " +
            std::string(largest == pin ? "crank pin's, " : "main bearing's, ") + shortNumber(largest->peak, 4) + " N at " +
            degreesText(largest->phi_deg_at_peak) +
            (largest->cylinder ? " (cylinder " + std::to_string(*largest->cylinder) + ")" : std::string()) + ".";
    out.push_back({ReportBlock::kParagraph, text});
    if (!has_gas)
      out.push_back({ReportBlock::kParagraph,
                     "No [gas] table: the loads are those of inertia and gravity alone; add one (docs/SCENE-FORMAT.md, "
                     "[gas]) to see the gas part, the working torque and its mean."});
    // One row per load: the closed form's, and the largest difference of the exact engines and of the soft ways.
    ReportBlock table{ReportBlock::kTable};
    table.header = {"load", "closed forms", "at [deg]", "cylinder", "mean over the cycle",
                    "exact engines: max |difference| / scale [-]", "soft ways (not gated) [-]"};
    for (const LoadRow& r : rows) {
      if (r.engine != closed) continue;
      double exact = 0.0, soft = 0.0;
      bool any_soft = false;
      for (const LoadRow& o : rows)
        if (o.load == r.load && o.engine != closed) {
          (o.gated ? exact : soft) = std::max(o.gated ? exact : soft, o.max_difference_rel);
          any_soft = any_soft || !o.gated;
        }
      table.rows.push_back({kLoads[static_cast<size_t>(r.order)].label,
                            shortNumber(r.peak, 4) + " " + r.unit + (r.resolved ? "" : " (rounding)"),
                            shortNumber(r.phi_deg_at_peak, 4), r.cylinder ? std::to_string(*r.cylinder) : "",
                            r.mean ? meanText(r) : "", shortNumber(exact, 2),
                            any_soft ? shortNumber(soft, 2) : ""});
    }
    out.push_back(std::move(table));
    out.push_back({ReportBlock::kFigure,
                   "Panel \"" + scene + "\": the closed forms' crank-pin force of cylinder 0 in the crank's own frame (x "
                   "radial outward along the throw, y tangential in the direction of rotation) and the main-bearing "
                   "force (frame on the crankshaft, frame X, Y) over one working cycle at the scene's speed" +
                       std::string(has_gas ? " with its gas" : "") + " and gravity, as the tip of the force vector",
                   {}, {}, kPinLoadsTable.name()});
    return out;
  }
  std::vector<const TableSchema*> schemas() const override { return {&kLoadsTable, &kPinLoadsTable}; }
  std::vector<std::string> figures() const override { return {kPinLoadsTable.name()}; }
  std::vector<ReportedMaximum> maxima() const override {
    return {{kLoadsTable.name(), {"scene", "engine", "load"}, {"peak"}, "resolved", "0"}};
  }
};

}  // namespace

namespace topics {
const SceneTopic& loads() {
  static const LoadsTopic topic;
  return topic;
}
}  // namespace topics

}  // namespace crankcheck::validation::your_engine
