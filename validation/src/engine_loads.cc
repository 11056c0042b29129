#include "crankcheck/validation/engine_loads.h"
#include "crankcheck/validation/variants.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <tuple>

#include "crankcheck/analytic/motion.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/extremum.h"
#include "crankcheck/validation/scales.h"

namespace crankcheck::validation {

GasParams makeExampleGas(Cycle cycle, double bore) {
  GasParams gas;
  gas.bore = bore;
  std::vector<double> degrees;
  if (cycle == Cycle::kFourStroke) {
    gas.cycle = 4.0 * M_PI;
    degrees = {0, 10, 20, 30, 45, 60, 90, 120, 150, 180, 200, 360, 380, 540, 600, 640, 670, 690, 705};
    gas.pressures = {3.2e6, 5.2e6, 5.6e6, 4.8e6, 3.4e6, 2.4e6, 1.3e6, 0.8e6, 0.55e6, 0.35e6,
                     0.05e6, 0.02e6, -0.03e6, -0.02e6, 0.08e6, 0.25e6, 0.6e6, 1.1e6, 1.9e6};
  } else {
    gas.cycle = 2.0 * M_PI;
    degrees = {0, 10, 20, 40, 60, 90, 110, 120, 180, 240, 270, 300, 330, 350};
    gas.pressures = {13e6, 15e6, 14e6, 9e6, 6e6, 3.5e6, 2.5e6, 0.3e6, 0.25e6, 0.3e6, 1.0e6, 2.5e6, 6e6, 10.5e6};
  }
  for (double d : degrees) gas.cycle_angles.push_back(radiansFromDegrees(d));
  return gas;
}

Mechanism withGasAtDeadCentres(const Mechanism& m, const GasParams& gas) {
  Mechanism out = m;
  out.gas = gas;
  out.firing_angles.clear();
  for (double alpha : m.engine.crank_angles) {
    double firing = std::fmod(-alpha, gas.cycle);
    if (firing < 0.0) firing += gas.cycle;
    out.firing_angles.push_back(firing);
  }
  return out;
}

namespace {

std::string num(double x) { return formatNumber(x); }

// An inline engine of k cylinders on m's parts, standing, with eqs (8)-(11)'s phases, without gas.
Mechanism inlineOf(const Mechanism& m, int k, Cycle cycle) { return withGamma(withCylinders(m, k, cycle), 90.0); }

struct Parts {
  double drive, gas, inertia, gravity;
};
Parts splitAt(const Mechanism& m, double phi) {
  return {analytic::calcReactions(m, phi).drive_torque, analytic::calcReactions(withLoads(m, true, false, false), phi).drive_torque,
          analytic::calcReactions(withLoads(m, false, true, false), phi).drive_torque,
          analytic::calcReactions(withLoads(m, false, false, true), phi).drive_torque};
}

}  // namespace

TableSet calcTorqueSplitTables(const Mechanism& car, const Mechanism& marine) {
  Table split, share;
  const std::vector<const Engine*> references = listReferenceEngines();
  std::vector<Column> split_columns = {{"engine", kText}, {"phi_deg", "deg"}, {"drive_torque", "N m"}, {"gas_torque", "N m"},
                                       {"inertia_torque", "N m"}, {"gravity_torque", "N m"}};
  for (const Engine* e : references) split_columns.push_back({e->name + "_drive_torque", "N m"});  // each engine's whole
  split = Table("torque_split", split_columns);
  share = Table("gravity_share", {{"cycle", kText}, {"k", "-"}, {"speed_rpm", "rpm"}, {"mean_abs_drive_torque", "N m"},
                                  {"mean_abs_gravity_torque", "N m"}, {"share", "-"}, {"resolved", kText}});
  const Mechanism car4 = withSpeed(withGasAtDeadCentres(inlineOf(car, 4, Cycle::kFourStroke),
                                                        makeExampleGas(Cycle::kFourStroke, 2.0 * car.crank.radius)), 6000.0);
  const Mechanism ship = withGasAtDeadCentres(inlineOf(marine, marine.engine.cylinders, Cycle::kTwoStroke),
                                              makeExampleGas(Cycle::kTwoStroke, 2.0 * marine.crank.radius / 3.0));
  for (const auto& [name, m] : {std::pair<std::string, const Mechanism&>{"car_inline4_6000rpm", car4},
                                std::pair<std::string, const Mechanism&>{"marine_inline6_two_stroke", ship}}) {
    std::vector<std::unique_ptr<EngineModel>> models;
    for (const Engine* e : references) models.push_back(e->build(m));
    const double cycle_deg = m.engine.cycle == Cycle::kFourStroke ? 720.0 : 360.0;
    for (double d = 0.0; d < cycle_deg; d += 2.5) {
      const double phi = radiansFromDegrees(d);
      const Parts p = splitAt(m, phi);
      std::vector<std::string> row = {name, num(d), num(p.drive), num(p.gas), num(p.inertia), num(p.gravity)};
      for (const auto& model : models) row.push_back(num(model->evaluate(phi).drive_torque));
      split.rows.push_back(row);
    }
  }
  for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke})
    for (int k = 1; k <= 12; ++k)
      for (double rpm : {600.0, 1500.0, 3000.0, 6000.0}) {
        const Mechanism m = withSpeed(withGasAtDeadCentres(inlineOf(car, k, cycle), makeExampleGas(cycle, 2.0 * car.crank.radius)), rpm);
        const double cycle_deg = cycle == Cycle::kFourStroke ? 720.0 : 360.0;
        double drive = 0.0, gravity = 0.0;
        int n = 0;
        for (double d = 0.0; d < cycle_deg; d += 1.0, ++n) {
          const double phi = radiansFromDegrees(d);
          drive += std::fabs(analytic::calcReactions(m, phi).drive_torque);
          gravity += std::fabs(analytic::calcReactions(withLoads(m, false, false, true), phi).drive_torque);
        }
        // A gravity torque below 64 eps of the energy scale is rounding (k = 7, 9, 11 four-stroke: gravity's harmonics
        // cancel up to the 14th), not a torque: marked, not drawn as physics.
        const bool resolved = gravity / n > kAgreementMultiple * kEps * calcEnergyScale(m);
        share.rows.push_back({toString(cycle), std::to_string(k), num(rpm), num(drive / n), num(gravity / n), num(gravity / drive),
                              resolved ? "1" : "0"});
      }
  return {{"torque_split", split}, {"gravity_share", share}};
}

TableSet calcRodModelTables(const Mechanism& car, const Mechanism& marine) {
  Table t("rod_models", {{"engine", kText}, {"variable", kText}, {"x", "SI"}, {"two_mass_error", "-"},
                         {"two_mass_delta_I_error", "-"}, {"two_mass_delta_I_resolved", kText}, {"reference", kText}});
  // The two-mass rod's error is a smooth function of phi: its maximum over the turn is refined from 48 samples
  // (extremum.h). With Delta_I the error is rounding: the worst of the 48 samples, a bound (resolved 0) unless it
  // exceeds 100 times the agreement tolerance.
  // Against each reference engine's rigid rod (the `reference` column).
  auto worst = [](const Engine& engine, const Mechanism& m) {
    const std::unique_ptr<EngineModel> model = engine.build(m);
    const Scales scales = calcScales(m);
    auto error = [&](analytic::RodInertiaForm form) {
      return [&model, &m, form](double phi) {
        return analytic::calcReactions(m, phi, form).drive_torque - model->evaluate(phi).drive_torque;
      };
    };
    const double without = findMaxAbsOverTurn(error(analytic::RodInertiaForm::kTwoMassWithoutDeltaI), 48).value;
    const double with = findMaxAbsOverTurn(error(analytic::RodInertiaForm::kTwoMassWithDeltaI), 48, 0).value;
    const bool with_resolved = with > 100.0 * kAgreementMultiple * kEps * scales.torque * scales.acceleration_conditioning;
    return std::tuple{without / scales.torque, with / scales.torque, with_resolved};
  };
  for (const auto& [name, base] : {std::pair<std::string, Mechanism>{"car", withSpeed(inlineOf(car, 1, Cycle::kFourStroke), 6000.0)},
                                   std::pair<std::string, Mechanism>{"marine", inlineOf(marine, 1, Cycle::kTwoStroke)}}) {
    // Against lambda: the rod lengthened or shortened (r fixed), z_k at the same fraction, gyration radius scaled.
    for (double lambda : {0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.5, 0.6}) {
      Mechanism m = base;
      const double scale = (base.crank.radius / lambda) / base.rod.length;
      m.rod.length *= scale;
      m.rod.com_from_wrist_pin *= scale;
      m.rod.inertia_about_wrist_pin *= scale * scale;
      for (const Engine* engine : listReferenceEngines()) {
        const auto [without, with, resolved] = worst(*engine, m);
        t.rows.push_back({name, "lambda", num(lambda), num(without), num(with), resolved ? "1" : "0", engine->name});
      }
    }
    // Against Delta_I / I_G: the rod's central inertia I_G = f m_k z_k (l - z_k) (f = 1: the two-mass value, Delta_I = 0).
    for (double f : {0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 2.0, 3.0}) {
      Mechanism m = base;
      const double l = m.rod.length, z = m.rod.com_from_wrist_pin, m_k = m.rod.mass;
      const double I_G = f * m_k * z * (l - z);
      m.rod.inertia_about_wrist_pin = m_k * z * z + I_G;
      const double delta_I = m.rod.inertia_about_wrist_pin - l * z * m_k;
      for (const Engine* engine : listReferenceEngines()) {
        const auto [without, with, resolved] = worst(*engine, m);
        t.rows.push_back({name, "delta_I_over_I_G", num(delta_I / I_G), num(without), num(with), resolved ? "1" : "0", engine->name});
      }
    }
  }
  return {{"rod_models", t}};
}

TableSet calcPinLoadTables(const std::vector<Mechanism>& scenes, int first_index, double step_deg) {
  Table polar, summary;
  polar = Table("pin_load_polar", {{"scene_index", "-"}, {"engine", kText}, {"phi_deg", "deg"},
                                   {"crank_pin_radial", "N"}, {"crank_pin_tangential", "N"}, {"bearing_x", "N"},
                                   {"bearing_y", "N"}, {"scene", kText}});
  summary = Table("pin_load_polar_summary", {{"scene", kText}, {"engine", kText}, {"force", kText},
                                             {"max_magnitude", "N"}, {"phi_deg_at_max", "deg"},
                                             {"max_difference_rel", "-"}});
  for (size_t index = 0; index < scenes.size(); ++index) {
    const Mechanism& m = scenes[index];
    // The closed forms first, then each reference engine (engines.h).
    std::vector<const Engine*> engines = {&getClosedFormEngine()};
    for (const Engine* e : listReferenceEngines()) engines.push_back(e);
    std::vector<std::unique_ptr<EngineModel>> models;
    for (const Engine* e : engines) models.push_back(e->build(m));
    const double cycle = m.engine.cycle == Cycle::kFourStroke ? 4.0 * M_PI : 2.0 * M_PI;
    // The crank pin of cylinder 0 is at angle phi + beta_0 from +X (CONVENTIONS.md, layouts).
    auto crankFrame = [&m](const Evaluation& e) {
      const double angle = e.phi + getThrowAngle(m, 0);
      const Vec2& F = e.cylinders[0].crank_pin_force;
      return std::pair{F[0] * std::cos(angle) + F[1] * std::sin(angle), -F[0] * std::sin(angle) + F[1] * std::cos(angle)};
    };
    const double scale = calcScales(m).force;
    // The largest |closed form - engine| over the samples, per engine (the closed form's own row: the largest of them).
    std::vector<double> worst_pin(engines.size(), 0.0), worst_bearing(engines.size(), 0.0);
    const int samples = static_cast<int>(std::lround(degreesFromRadians(cycle) / step_deg));
    std::vector<std::map<std::string, std::vector<double>>> magnitudes(engines.size());  // force -> |F| at the samples
    for (int i = 0; i < samples; ++i) {
      const double d = step_deg * i, phi = radiansFromDegrees(d);
      std::vector<Evaluation> e;
      for (const auto& model : models) e.push_back(model->evaluate(phi));
      for (size_t j = 0; j < engines.size(); ++j) {
        const auto [radial, tangential] = crankFrame(e[j]);
        polar.rows.push_back({std::to_string(first_index + static_cast<int>(index)), engines[j]->name, num(d),
                              num(radial), num(tangential), num(e[j].bearing_force[0]), num(e[j].bearing_force[1]), m.name});
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
        const auto magnitude = [&](double u) {
          const double phi = u * cycle / (2.0 * M_PI);
          const Evaluation e = models[j]->evaluate(phi);
          const Vec2& F = is_pin ? e.cylinders[0].crank_pin_force : e.bearing_force;
          return std::hypot(F[0], F[1]);
        };
        const TurnMaximum best = findMaxAbsOverTurn(magnitude, magnitudes[j][force], 2);
        summary.rows.push_back({m.name, engines[j]->name, force, num(best.value),
                                num(degreesFromRadians(best.phi * cycle / (2.0 * M_PI))),
                                num((is_pin ? worst_pin[j] : worst_bearing[j]) / scale)});
      }
  }
  return {{"pin_load_polar", polar}, {"pin_load_polar_summary", summary}};
}

}  // namespace crankcheck::validation
