// Report part `pin_load_polar`: pin loads over a working cycle as polar diagrams, of the user's scenes or the
// example scenes.
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "crankcheck/analytic/reactions.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/campaign_scenes.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/table.h"
#include "crankcheck/validation/task.h"
#include "crankcheck/validation/example_gas.h"
#include "crankcheck/validation/extremum.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/validation/variants.h"
#include "../working_cycle.h"

namespace crankcheck::validation {
namespace {

// pin_load_polar: over one working cycle (step_deg steps) at the scene's speed, with its gas and gravity: the
// crank-pin force (crank on rod 0 at its crank pin) in the crank's own frame (radial: outward along the throw of
// cylinder 0, tangential: 90 degrees ahead of it, the direction of rotation), and the main-bearing force (frame on the
// crankshaft at O, all throws) in the frame's X, Y: Norton's polar diagrams (Program ENGINE), the closed forms and each
// reference engine. The scene's name last, so that a name with a comma cannot shift the figure's numbers.
struct PinLoadRow {
  int scene_index = 0;
  std::string engine;
  double phi_deg = 0.0;
  double crank_pin_radial = 0.0, crank_pin_tangential = 0.0, bearing_x = 0.0, bearing_y = 0.0;  ///< [N]
  std::string scene;
};
const Schema<PinLoadRow> kPinLoadTable{
    "pin_load_polar",
    {countField("scene_index", &PinLoadRow::scene_index), textField("engine", &PinLoadRow::engine),
     numberField("phi_deg", "deg", &PinLoadRow::phi_deg), numberField("crank_pin_radial", "N", &PinLoadRow::crank_pin_radial),
     numberField("crank_pin_tangential", "N", &PinLoadRow::crank_pin_tangential),
     numberField("bearing_x", "N", &PinLoadRow::bearing_x), numberField("bearing_y", "N", &PinLoadRow::bearing_y),
     textField("scene", &PinLoadRow::scene)}};

// pin_load_polar_summary: per scene, engine and force ("crank_pin" | "bearing"), the largest |force| over the cycle
// (refined, extremum.h) and where, and the largest |analytic - engine| over the samples relative to the force scale
// (the analytic row: the largest over the reference engines).
struct PinLoadSummaryRow {
  std::string scene, engine, force;
  double max_magnitude = 0.0;   ///< [N]
  double phi_deg_at_max = 0.0;  ///< [deg]
  double max_difference_rel = 0.0;
};
const Schema<PinLoadSummaryRow> kPinLoadSummaryTable{
    "pin_load_polar_summary",
    {textField("scene", &PinLoadSummaryRow::scene), textField("engine", &PinLoadSummaryRow::engine),
     textField("force", &PinLoadSummaryRow::force), numberField("max_magnitude", "N", &PinLoadSummaryRow::max_magnitude),
     numberField("phi_deg_at_max", "deg", &PinLoadSummaryRow::phi_deg_at_max),
     numberField("max_difference_rel", "-", &PinLoadSummaryRow::max_difference_rel)}};

// The part's tables of `scenes`: scene_index counts from first_index (so that scenes computed one per task keep their places); step_deg is the
// sampling step (the campaign: 2 degrees, 8 with --quick; the maxima are refined, so they do not depend on it),
// angle_tolerance Brent's (extremum.h, getAngleTolerance).
TableSet calcPinLoadTables(const std::vector<Mechanism>& scenes, int first_index, double step_deg, double angle_tolerance) {
  std::vector<PinLoadRow> polar;
  std::vector<PinLoadSummaryRow> summary;
  for (size_t index = 0; index < scenes.size(); ++index) {
    const Mechanism& m = scenes[index];
    // The closed forms first, then each reference engine (engines.h).
    const std::vector<const Engine*> engines = listComparedEngines();
    std::vector<std::unique_ptr<EngineModel>> models;
    for (const Engine* e : engines) models.push_back(e->build(m));
    const double cycle = calcCycleAngle(m);
    const double scale = calcScales(m).force;
    // The largest |closed form - engine| over the samples, per engine (the closed form's own row: the largest of them).
    std::vector<double> worst_pin(engines.size(), 0.0), worst_bearing(engines.size(), 0.0);
    const int samples = static_cast<int>(std::lround(degreesFromRadians(cycle) / step_deg));
    std::vector<std::map<std::string, std::vector<double>>> magnitudes(engines.size());  // force -> |F| at the samples
    for (int i = 0; i < samples; ++i) {
      const double d = step_deg * i, phi = radiansFromDegrees(d);
      std::vector<Evaluation> e;
      for (const auto& model : models) e.push_back(model->evaluateMotion(phi));  // forces alone: no U, no Q
      for (size_t j = 0; j < engines.size(); ++j) {
        const auto [radial, tangential] = calcCrankPinForceInCrankFrame(m, e[j], 0);
        polar.push_back({first_index + static_cast<int>(index), engines[j]->name, d, radial, tangential,
                         e[j].bearing_force[0], e[j].bearing_force[1], m.name});
        magnitudes[j]["crank_pin"].push_back(std::hypot(e[j].cylinders[0].crank_pin_force[0], e[j].cylinders[0].crank_pin_force[1]));
        magnitudes[j]["bearing"].push_back(std::hypot(e[j].bearing_force[0], e[j].bearing_force[1]));
        if (j == 0) continue;
        const Evaluation& a = e[0];
        const double pin = std::hypot(a.cylinders[0].crank_pin_force[0] - e[j].cylinders[0].crank_pin_force[0],
                                      a.cylinders[0].crank_pin_force[1] - e[j].cylinders[0].crank_pin_force[1]);
        const double bearing = std::hypot(a.bearing_force[0] - e[j].bearing_force[0], a.bearing_force[1] - e[j].bearing_force[1]);
        for (size_t into : {size_t{0}, j}) {
          worst_pin[into] = std::max(worst_pin[into], pin);
          worst_bearing[into] = std::max(worst_bearing[into], bearing);
        }
      }
    }
    // The largest |force| over the working cycle, each engine alike: the samples, the best two refined by
    // Brent's method (the cycle mapped onto [0, 2 pi) for findMaxAbsOverTurn).
    for (size_t j = 0; j < engines.size(); ++j)
      for (const char* force : {"crank_pin", "bearing"}) {
        const bool is_pin = std::string(force) == "crank_pin";
        const auto magnitude = [&](double phi) {
          const Evaluation e = models[j]->evaluateMotion(phi);
          const Vec2& F = is_pin ? e.cylinders[0].crank_pin_force : e.bearing_force;
          return std::hypot(F[0], F[1]);
        };
        const TurnMaximum best = findMaxAbsOverCycle(magnitude, cycle, magnitudes[j][force], 2, angle_tolerance);
        summary.push_back({m.name, engines[j]->name, force, best.value, degreesFromRadians(best.phi),
                           (is_pin ? worst_pin[j] : worst_bearing[j]) / scale});
      }
  }
  return {{kPinLoadTable.name(), kPinLoadTable.table(std::move(polar))},
          {kPinLoadSummaryTable.name(), kPinLoadSummaryTable.table(std::move(summary))}};
}


class PinLoadPolarPart final : public Part {
 public:
  std::string key() const override { return "pin_load_polar"; }
  std::string title() const override { return "Pin loads over a working cycle (polar diagrams)"; }
  // One task per scene, at 2 degree steps (8 with quick: a smoke test of the part, its maxima refined all the same).
  std::vector<Task> tasks(const PartContext& context) const override {
    std::vector<Task> out;
    for (size_t i = 0; i < context.scenes.size(); ++i)
      out.push_back({"pin_load_polar " + context.scenes[i].name, false,
                     [m = context.scenes[i], i, quick = context.quick] {
                       return calcPinLoadTables({m}, static_cast<int>(i), quick ? 8.0 : 2.0, getAngleTolerance(quick));
                     }});
    return out;
  }
  ReportPart describe(const TableSet& tables) const override {
    ReportPart part;
    if (!tables.count(key())) return part;
    part.heading = heading();
    part.caption =
        "The crank-pin force of cylinder 0 (crank on rod, in the crank's own frame: x radial outward along the throw, y "
        "tangential in the direction of rotation) and the main-bearing force (frame on the crankshaft at O, all throws, "
        "frame X, Y) over one working cycle at each scene's speed with its gas and gravity, as the tip of the force "
        "vector (after Norton's Program ENGINE); analytic lines, " + getReferenceName() + " dots";
    part.paragraphs.push_back(
        "The largest force over the cycle, each engine (the samples, the best two refined by Brent's method), and the "
        "largest difference of the two engines over the samples relative to the force scale:");
    part.header = {"scene", "engine", "force", "max |F| [N]", "max |analytic - engine| / force scale [-]"};
    for (const PinLoadSummaryRow& r : getRows(tables, kPinLoadSummaryTable))
      part.rows.push_back({r.scene, r.engine, r.force, shortNumber(r.max_magnitude, 4), shortNumber(r.max_difference_rel, 4)});
    return part;
  }
  std::vector<const TableSchema*> schemas() const override { return {&kPinLoadTable, &kPinLoadSummaryTable}; }
  std::vector<ReportedMaximum> maxima() const override {
    return {{"pin_load_polar_summary", {"scene", "engine", "force"}, {"max_magnitude"}, "", ""}};
  }
};

}  // namespace

namespace parts {
const Part& pinLoadPolar() {
  static const PinLoadPolarPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
