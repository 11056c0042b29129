// Report part `rod_models`: what the two-mass rod costs against the rigid rod.
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
#include "crankcheck/validation/extremum.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/validation/variants.h"
#include "survey.h"

namespace crankcheck::validation {
namespace {

// rod_models: the largest |drive torque of the two-mass rod - the `reference` engine's rigid rod| over the turn
// (refined, extremum.h; with Delta_I rounding: resolved "0" marks the number as a bound, else "1"), relative to the
// torque scale, without and with the paper's Delta_I, against lambda (variable "lambda") and against Delta_I / I_G
// (variable "delta_I_over_I_G", the rod's central inertia changed), for the car and the marine engine (`engine`) at
// their speeds.
struct RodModelRow {
  std::string engine, variable;
  double x = 0.0;  ///< lambda or Delta_I / I_G, as `variable` says
  double two_mass_error = 0.0, two_mass_delta_I_error = 0.0;
  std::string two_mass_delta_I_resolved;
  std::string reference;
};
const Schema<RodModelRow> kRodModelsTable{
    "rod_models",
    {textField("engine", &RodModelRow::engine), textField("variable", &RodModelRow::variable),
     numberField("x", "SI", &RodModelRow::x), numberField("two_mass_error", "-", &RodModelRow::two_mass_error),
     numberField("two_mass_delta_I_error", "-", &RodModelRow::two_mass_delta_I_error),
     textField("two_mass_delta_I_resolved", &RodModelRow::two_mass_delta_I_resolved),
     textField("reference", &RodModelRow::reference)}};

// The part's table on `car` and `marine`; with `quick` (a smoke test of the part), five of each sweep's points.
TableSet calcRodModelTables(const Mechanism& car, const Mechanism& marine, bool quick) {
  std::vector<RodModelRow> t;
  // The two-mass rod's error is a smooth function of phi: its maximum over the turn is refined from 48 samples
  // (extremum.h). With Delta_I the error is rounding: the worst of the 48 samples, a bound (resolved 0) unless it
  // exceeds 100 times the agreement tolerance.
  // Against each reference engine's rigid rod (the `reference` column).
  auto worst = [angle_tolerance = getAngleTolerance(quick)](const Engine& engine, const Mechanism& m) {
    const std::unique_ptr<EngineModel> model = engine.build(m);
    const Scales scales = calcScales(m);
    // The engine's drive torque at each angle asked, evaluated once: both rod forms read the same 48 samples.
    std::map<double, double> engine_torque;
    auto engineTorque = [&](double phi) {
      const auto [it, added] = engine_torque.try_emplace(phi, 0.0);
      if (added) it->second = model->evaluateMotion(phi).drive_torque;
      return it->second;
    };
    auto error = [&](analytic::RodInertiaForm form) {
      return [&engineTorque, &m, form](double phi) {
        return analytic::calcReactions(m, phi, form).drive_torque - engineTorque(phi);
      };
    };
    const double without =
        findMaxAbsOverTurn(error(analytic::RodInertiaForm::kTwoMassWithoutDeltaI), 48, 4, angle_tolerance).value;
    const double with = findMaxAbsOverTurn(error(analytic::RodInertiaForm::kTwoMassWithDeltaI), 48, 0).value;
    const bool with_resolved = with > 100.0 * kAgreementMultiple * kEps * scales.torque * scales.acceleration_conditioning;
    return std::tuple{without / scales.torque, with / scales.torque, with_resolved};
  };
  for (const auto& [name, base] : {std::pair<std::string, Mechanism>{"car", withSpeed(withGamma(withCylinders(car, 1, Cycle::kFourStroke), 90.0), 6000.0)},
                                   std::pair<std::string, Mechanism>{"marine", withGamma(withCylinders(marine, 1, Cycle::kTwoStroke), 90.0)}}) {
    // Against lambda: the rod lengthened or shortened (r fixed), z_k at the same fraction, gyration radius scaled.
    for (double lambda : quick ? std::vector<double>{0.1, 0.2, 0.3, 0.4, 0.6}
                               : std::vector<double>{0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.5, 0.6}) {
      Mechanism m = base;
      const double scale = (base.crank.radius / lambda) / base.rod.length;
      m.rod.length *= scale;
      m.rod.com_from_wrist_pin *= scale;
      m.rod.inertia_about_wrist_pin *= scale * scale;
      for (const Engine* engine : listReferenceEngines()) {
        const auto [without, with, resolved] = worst(*engine, m);
        t.push_back({name, "lambda", lambda, without, with, resolved ? "1" : "0", engine->name});
      }
    }
    // Against Delta_I / I_G: the rod's central inertia I_G = f m_k z_k (l - z_k) (f = 1: the two-mass value, Delta_I = 0).
    for (double f : quick ? std::vector<double>{0.25, 0.5, 1.0, 2.0, 3.0}
                          : std::vector<double>{0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 2.0, 3.0}) {
      Mechanism m = base;
      const double l = m.rod.length, z = m.rod.com_from_wrist_pin, m_k = m.rod.mass;
      const double I_G = f * m_k * z * (l - z);
      m.rod.inertia_about_wrist_pin = m_k * z * z + I_G;
      const double delta_I = m.rod.inertia_about_wrist_pin - l * z * m_k;
      for (const Engine* engine : listReferenceEngines()) {
        const auto [without, with, resolved] = worst(*engine, m);
        t.push_back({name, "delta_I_over_I_G", delta_I / I_G, without, with, resolved ? "1" : "0", engine->name});
      }
    }
  }
  return kRodModelsTable.tableSet(std::move(t));
}


// The figure's caption.
std::string makeCaption() {
  return std::string("The largest drive-torque error over the turn of the two-mass rod (m_k1 at the wrist pin, m_k3 at the "
                "crank pin) against ") + getReferenceName() + "'s rigid rod, relative to the torque scale, against "
                "lambda and against Delta_I / I_G, for the car (a standing single cylinder on the base scene's parts at 6000 rpm, " +
    survey::kNotSceneSpeed + ", without gas) and the built-in marine engine (at its own speed); dashed: the paper's "
         "two-mass rod with Delta_I, exact to rounding";
}

class RodModelsPart final : public Part {
 public:
  std::string key() const override { return "rod_models"; }
  std::string title() const override { return "What the two-mass rod costs"; }
  // On the base scene's parts and the built-in marine engine.
  std::vector<Task> tasks(const PartContext& context) const override {
    return {{"rod_models", false,
             [base = context.base, marine = findMarineScene(), quick = context.quick] {
               return calcRodModelTables(base, marine, quick);
             }}};
  }
  ReportPart describe(const TableSet& tables) const override { return describeFigure(tables, makeCaption()); }
  std::vector<const TableSchema*> schemas() const override { return {&kRodModelsTable}; }
  std::vector<ReportedMaximum> maxima() const override {
    return {{"rod_models", {"engine", "variable", "x", "reference"}, {"two_mass_error"}, "", ""},
            {"rod_models", {"engine", "variable", "x", "reference"}, {"two_mass_delta_I_error"}, "two_mass_delta_I_resolved", "0"}};
  }
};

}  // namespace

namespace parts {
const Part& rodModels() {
  static const RodModelsPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
