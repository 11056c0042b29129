// Report part `torque_split`: the working torque split into gas, inertia and gravity, and gravity's share against k.
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "../part_math.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/campaign_scenes.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/table.h"
#include "crankcheck/validation/task.h"
#include "crankcheck/validation/example_gas.h"
#include "survey.h"
#include "crankcheck/validation/extremum.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/validation/variants.h"
#include "engine_fields.h"

namespace crankcheck::validation {
namespace {

// torque_split: over one working cycle of an inline four four-stroke on the car's parts (bore 2 r, 6000 rpm) and of
// the marine engine as it is (bore 2 r / 3), the analytic drive torque and its gas, inertia and gravity parts, and each
// reference engine's whole drive torque beside them. `engine` names which of the two engines.
struct TorqueSplitRow {
  std::string engine;
  double phi_deg = 0.0;
  double drive_torque = 0.0, gas_torque = 0.0, inertia_torque = 0.0, gravity_torque = 0.0;  ///< [N m]
  std::vector<double> reference_drive_torque;  ///< [N m] per reference engine (listReferenceEngines' order)
};
std::vector<Field<TorqueSplitRow>> makeTorqueSplitFields() {
  using R = TorqueSplitRow;
  std::vector<Field<R>> fields = {textField("engine", &R::engine), numberField("phi_deg", "deg", &R::phi_deg),
                                  numberField("drive_torque", "N m", &R::drive_torque),
                                  numberField("gas_torque", "N m", &R::gas_torque),
                                  numberField("inertia_torque", "N m", &R::inertia_torque),
                                  numberField("gravity_torque", "N m", &R::gravity_torque)};
  addEngineNumberFields(fields, "_drive_torque", "N m", &R::reference_drive_torque);  // each engine's whole
  return fields;
}
const Schema<TorqueSplitRow>& torqueSplitTable() {
  return getEngineSchema<TorqueSplitRow, makeTorqueSplitFields>("torque_split");
}

// gravity_share: gravity's share of the mean absolute drive torque over the cycle, k = 1..12, both strokes, the car's
// parts with the example pressure table of each stroke, 600 to 6000 rpm; resolved "0" where the gravity torque is
// below 64 eps of the energy scale (rounding, not a torque), else "1".
struct GravityShareRow {
  std::string cycle;
  int k = 1;
  double speed_rpm = 0.0;
  double mean_abs_drive_torque = 0.0, mean_abs_gravity_torque = 0.0;  ///< [N m]
  double share = 0.0;
  std::string resolved;
};
const Schema<GravityShareRow> kGravityShareTable{
    "gravity_share",
    {textField("cycle", &GravityShareRow::cycle), countField("k", &GravityShareRow::k),
     numberField("speed_rpm", "rpm", &GravityShareRow::speed_rpm),
     numberField("mean_abs_drive_torque", "N m", &GravityShareRow::mean_abs_drive_torque),
     numberField("mean_abs_gravity_torque", "N m", &GravityShareRow::mean_abs_gravity_torque),
     numberField("share", "-", &GravityShareRow::share), textField("resolved", &GravityShareRow::resolved)}};

// An inline engine of k cylinders on m's parts, standing, with eqs (8)-(11)'s phases, without gas.
Mechanism inlineOf(const Mechanism& m, int k, Cycle cycle) { return withGamma(withCylinders(m, k, cycle), 90.0); }

// The drive torque at phi and its gas, inertia and gravity parts (each with the other loads off).
struct Parts {
  double drive, gas, inertia, gravity;
};
Parts splitAt(const Mechanism& m, double phi) {
  return {analytic::calcReactions(m, phi).drive_torque, analytic::calcReactions(withLoads(m, true, false, false), phi).drive_torque,
          analytic::calcReactions(withLoads(m, false, true, false), phi).drive_torque,
          analytic::calcReactions(withLoads(m, false, false, true), phi).drive_torque};
}

TableSet calcTorqueSplitTables(const Mechanism& car, const Mechanism& marine) {
  std::vector<TorqueSplitRow> split;
  std::vector<GravityShareRow> share;
  const std::vector<const Engine*> references = listReferenceEngines();
  const Mechanism car4 = withSpeed(withGasAtDeadCentres(inlineOf(car, 4, Cycle::kFourStroke),
                                                        makeExampleGas(Cycle::kFourStroke, 2.0 * car.crank.radius)), 6000.0);
  const Mechanism ship = withGasAtDeadCentres(inlineOf(marine, marine.machine.cylinders, Cycle::kTwoStroke),
                                              makeExampleGas(Cycle::kTwoStroke, 2.0 * marine.crank.radius / 3.0));
  for (const auto& [name, m] : {std::pair<std::string, const Mechanism&>{"car_inline4_6000rpm", car4},
                                std::pair<std::string, const Mechanism&>{"marine_inline6_two_stroke", ship}}) {
    std::vector<std::unique_ptr<EngineModel>> models;
    for (const Engine* e : references) models.push_back(e->build(m));
    const double cycle_deg = m.machine.cycle == Cycle::kFourStroke ? 720.0 : 360.0;
    for (double d = 0.0; d < cycle_deg; d += 2.5) {
      const double phi = radiansFromDegrees(d);
      const Parts p = splitAt(m, phi);
      TorqueSplitRow row{name, d, p.drive, p.gas, p.inertia, p.gravity, {}};
      for (const auto& model : models) row.reference_drive_torque.push_back(model->evaluateMotion(phi).drive_torque);
      split.push_back(std::move(row));
    }
  }
  for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke})
    for (int k = 1; k <= 12; ++k) {
      const Mechanism standing = withGasAtDeadCentres(inlineOf(car, k, cycle), makeExampleGas(cycle, 2.0 * car.crank.radius));
      const double cycle_deg = cycle == Cycle::kFourStroke ? 720.0 : 360.0;
      // The gravity torque alone does not depend on the speed (withLoads stands the engine still): summed once.
      const Mechanism gravity_only = withLoads(standing, false, false, true);
      double gravity = 0.0;
      for (double d = 0.0; d < cycle_deg; d += 1.0)
        gravity += std::fabs(analytic::calcReactions(gravity_only, radiansFromDegrees(d)).drive_torque);
      for (double rpm : {600.0, 1500.0, 3000.0, 6000.0}) {
        const Mechanism m = withSpeed(standing, rpm);
        double drive = 0.0;
        int n = 0;
        for (double d = 0.0; d < cycle_deg; d += 1.0, ++n)
          drive += std::fabs(analytic::calcReactions(m, radiansFromDegrees(d)).drive_torque);
        // A gravity torque below 64 eps of the energy scale is rounding (k = 7, 9, 11 four-stroke: gravity's harmonics
        // cancel up to the 14th), not a torque: marked, not drawn as physics.
        const bool resolved = gravity / n > kAgreementMultiple * kEps * calcEnergyScale(m);
        share.push_back({toString(cycle), k, rpm, drive / n, gravity / n, gravity / drive, resolved ? "1" : "0"});
      }
    }
  return {{torqueSplitTable().name(), torqueSplitTable().table(std::move(split))},
          {kGravityShareTable.name(), kGravityShareTable.table(std::move(share))}};
}


// The figure's caption: the speeds of the right panel read from its table (gravity_share).
std::string makeCaption(const TableSet& tables) {
  std::vector<double> speeds;
  for (const GravityShareRow& row : getRows(tables, kGravityShareTable)) speeds.push_back(row.speed_rpm);
  return std::string("The drive torque over one working cycle of a car inline four (the base scene's parts, bore 2 r, "
                     "with ") + survey::kExampleGas + ", at 6000 rpm, " + survey::kNotSceneSpeed +
         ") and of the built-in marine two-stroke (bore 2 r / 3, an example diesel pressure table, at its own speed), "
         "split into its gas, inertia and gravity parts (each the analytic drive torque with the other loads off; " +
         getReferenceName() + "'s whole drive torque as dots); right: gravity's share of the mean absolute drive torque against k, "
         "inline engines on the base scene's parts with the example pressure table of each stroke " +
         (speeds.empty() ? std::string("at several speeds") : survey::atSurveySpeeds(speeds)) +
         " (the figure draws 600 and 6000 rpm), both strokes (gravity torques below double precision left out): the sources' question answered against the "
         "real working torque. Your engines' own torques, at their speed with their [gas], are in their sections above";
}

class TorqueSplitPart final : public Part {
 public:
  std::string key() const override { return "torque_split"; }
  std::string title() const override { return "The working torque: gas, inertia and gravity"; }
  // On the base scene's parts and the built-in marine engine.
  std::vector<Task> tasks(const PartContext& context) const override {
    return {{"torque_split", false,
             [base = context.base, marine = findMarineScene()] { return calcTorqueSplitTables(base, marine); }}};
  }
  ReportPart describe(const TableSet& tables) const override { return describeFigure(tables, makeCaption(tables)); }
  std::vector<const TableSchema*> schemas() const override { return {&torqueSplitTable(), &kGravityShareTable}; }
};

}  // namespace

namespace parts {
const Part& torqueSplit() {
  static const TorqueSplitPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
