// Report part `offset`: what the centric formulas cost on an offset (desaxe) engine, and what the offset buys.
//
// The engine: the base scene's parts as one standing cylinder, four-stroke, with the example spark-ignition pressure
// table (bore 2 r) at 6000 rpm and gravity, its pin offset delta swept over delta / r in [-0.5, 0.5] (production pin
// offsets are |delta| / r = 0.01 .. 0.04; desaxe cylinders reach 0.5).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>
#include <stdexcept>

#include <boost/math/tools/toms748_solve.hpp>

#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/validation/example_gas.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/extremum.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/scene/quantities.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/variants.h"
#include "engine_fields.h"
#include "survey.h"

namespace crankcheck::validation {
namespace {

// offset: per quantity (x_p, a_p, wall_force, drive_torque) and offset, the largest error over the working cycle of
// the centric form (delta = 0: the centric engine at the same crank angle) against the offset engine, relative to the
// quantity's scale (x_p: the stroke; a_p: r omega^2; forces: the force scale; torque: the torque scale), and the
// largest |analytic - ENGINE| of the offset engine on the same samples, per reference engine.
struct OffsetCostRow {
  std::string quantity;
  double offset_over_r = 0.0, max_rel_error = 0.0;
  std::vector<double> reference_max_rel_error;  ///< per reference engine (listReferenceEngines' order)
};
// The key column first: the sorted table then holds each series' rows together, in order of delta / r.
std::vector<Field<OffsetCostRow>> makeOffsetCostFields() {
  std::vector<Field<OffsetCostRow>> fields = {textField("quantity", &OffsetCostRow::quantity),
                                              numberField("offset_over_r", "-", &OffsetCostRow::offset_over_r),
                                              numberField("max_rel_error", "-", &OffsetCostRow::max_rel_error)};
  addEngineNumberFields(fields, "_max_rel_error", "-", &OffsetCostRow::reference_max_rel_error);
  return fields;
}
const Schema<OffsetCostRow>& offsetCostTable() {
  return getEngineSchema<OffsetCostRow, makeOffsetCostFields>("offset");
}

// offset_thrust: the side thrust N_w over the working cycle, the closed forms' and each reference engine's: its largest
// value on the major-thrust side (N_w > 0: the wall on -n, docs/CONVENTIONS-crankcheck.md "Pin offset"), its largest on
// the minor side (as a positive number), the crank angle nearest the firing outer dead centre (within 90 degrees) where
// N_w changes sign (the piston crosses over: slap; empty: none), and the largest |drive torque|.
struct OffsetThrustRow {
  std::string engine;
  double offset_over_r = 0.0;
  double peak_major_thrust = 0.0, peak_minor_thrust = 0.0;  ///< [N]
  std::optional<double> thrust_reversal_deg;                ///< [deg]
  double max_abs_drive_torque = 0.0;                        ///< [N m]
};
const Schema<OffsetThrustRow> kOffsetThrustTable{
    "offset_thrust",
    {textField("engine", &OffsetThrustRow::engine), numberField("offset_over_r", "-", &OffsetThrustRow::offset_over_r),
     numberField("peak_major_thrust", "N", &OffsetThrustRow::peak_major_thrust),
     numberField("peak_minor_thrust", "N", &OffsetThrustRow::peak_minor_thrust),
     optionalField("thrust_reversal_deg", "deg", &OffsetThrustRow::thrust_reversal_deg),
     numberField("max_abs_drive_torque", "N m", &OffsetThrustRow::max_abs_drive_torque)}};

// The offsets delta / r of the part: -0.5 .. 0.5 (5 of them with `quick`).
std::vector<double> listOffsetFractions(bool quick) {
  return quick ? std::vector<double>{-0.5, -0.04, 0.0, 0.04, 0.5}
               : std::vector<double>{-0.5, -0.3, -0.2, -0.1, -0.06, -0.04, -0.02, -0.01, 0.0,
                                     0.01, 0.02, 0.04, 0.06, 0.1, 0.2, 0.3, 0.5};
}

// The part's tables on `parts` (its crank, rod, piston and flywheel) at one offset delta / r = `f`, from 1-degree
// samples of one working cycle (2 degrees with `quick`; at 4, N_w's two sign changes near -5.7 degrees at delta / r =
// -0.04 fell in one cell and the reversal was read 80 degrees off): the errors the largest over the samples; each
// engine's thrust peaks and largest drive torque refined from the samples by Brent's method (extremum.h, the two best
// humps) and its thrust reversal by TOMS 748 between the samples that bracket it, each on that engine's own
// evaluations, so that they do not depend on the grid (the 0.25-degree samples of before put the peaks up to 1e-5
// below them).
TableSet calcOffsetTables(const Mechanism& parts, double f, bool quick) {
  const Mechanism single = withSpeed(withGasAtDeadCentres(withGamma(withCylinders(parts, 1, Cycle::kFourStroke), 90.0),
                                                          makeExampleGas(Cycle::kFourStroke, 2.0 * parts.crank.radius)),
                                     6000.0);
  const double r = single.crank.radius;
  const double step = quick ? 2.0 : 1.0;
  std::vector<OffsetCostRow> cost;
  std::vector<OffsetThrustRow> thrust;
  Mechanism m = single;
  m.machine.pin_offsets = {f * r};
  const Scales sc = calcScales(m);
  const double stroke = analytic::calcDeadCentres(m, f * r).stroke;
  // The closed forms first, then each reference engine: the thrust of each, and each one's difference from the exact
  // offset closed forms.
  const std::vector<const Engine*> engines = listComparedEngines();
  std::vector<std::unique_ptr<EngineModel>> models;
  for (const Engine* e : engines) models.push_back(e->build(m));
  std::map<std::string, double> worst;
  std::vector<std::map<std::string, double>> worst_engine(engines.size());
  // Per engine: N_w and the drive torque at every sample, and the samples [deg] that bracket N_w's sign change nearest
  // the firing outer dead centre (phi = 0 here).
  struct Thrust {
    std::vector<double> wall, drive;
    double previous = NAN, previous_deg = 0.0, bracket_a = NAN, bracket_b = NAN, wall_a = 0.0, wall_b = 0.0;
  };
  std::vector<Thrust> by_engine(engines.size());
  for (double d = -360.0; d < 360.0; d += step) {
    const double phi = radiansFromDegrees(d);
    const Evaluation centric = analytic::calcEvaluation(single, phi);
    std::vector<Evaluation> e;
    for (const auto& model : models) e.push_back(model->evaluateMotion(phi));  // no U, no Q read here
    const Evaluation& exact = e[0];
    const CylinderEvaluation& x = exact.cylinders[0];
    const double a_scale = r * m.machine.speed * m.machine.speed;
    // The largest of each quantity's relative differences from the exact engine's (by the catalogue's names).
    auto noteAll = [&](std::map<std::string, double>& into, const Evaluation& other) {
      const CylinderEvaluation& y = other.cylinders[0];
      auto note = [&](QuantityId id, double difference) {
        double& w = into[nameOf(id)];
        w = std::max(w, difference);
      };
      note(QuantityId::kPistonPosition, std::fabs(y.x_p - x.x_p) / stroke);
      note(QuantityId::kPistonAcceleration, std::fabs(y.a_p - x.a_p) / a_scale);
      note(QuantityId::kWallForce, std::fabs(y.wall_force - x.wall_force) / sc.force);
      note(QuantityId::kDriveTorque, std::fabs(other.drive_torque - exact.drive_torque) / sc.torque);
    };
    noteAll(worst, centric);
    for (size_t j = 1; j < engines.size(); ++j) noteAll(worst_engine[j], e[j]);
    for (size_t j = 0; j < engines.size(); ++j) {
      Thrust& t = by_engine[j];
      const double n = e[j].cylinders[0].wall_force;
      t.wall.push_back(n);
      t.drive.push_back(e[j].drive_torque);
      // the sign change nearest the firing outer dead centre, by its nearer sample (refined below)
      if (std::fabs(d) <= 90.0 + step && !std::isnan(t.previous) && (t.previous > 0) != (n > 0) &&
          (std::isnan(t.bracket_a) || std::min(std::fabs(d), std::fabs(t.previous_deg)) <
                                          std::min(std::fabs(t.bracket_a), std::fabs(t.bracket_b)))) {
        t.bracket_a = t.previous_deg;
        t.bracket_b = d;
        t.wall_a = t.previous;
        t.wall_b = n;
      }
      t.previous = n;
      t.previous_deg = d;
    }
  }
  for (const auto& [q, err] : worst) {
    OffsetCostRow row{q, f, err, {}};
    for (size_t j = 1; j < engines.size(); ++j) row.reference_max_rel_error.push_back(worst_engine[j][q]);
    cost.push_back(std::move(row));
  }
  const double angle_tolerance = getAngleTolerance(quick);
  for (size_t j = 0; j < engines.size(); ++j) {
    const Thrust& t = by_engine[j];
    EngineModel& model = *models[j];
    // The cycle [-360, 360) degrees as one turn u in [0, 2 pi) (phi = 2 u - 2 pi), so that the samples are
    // findMaxAbsOverTurn's.
    auto wallAt = [&](double u) { return model.evaluateMotion(2.0 * u - 2.0 * M_PI).cylinders[0].wall_force; };
    std::vector<double> positive, negative, drive;
    for (size_t i = 0; i < t.wall.size(); ++i) {
      positive.push_back(std::max(0.0, t.wall[i]));
      negative.push_back(std::max(0.0, -t.wall[i]));
      drive.push_back(std::fabs(t.drive[i]));
    }
    const double major =
        findMaxAbsOverTurn([&](double u) { return std::max(0.0, wallAt(u)); }, positive, 2, angle_tolerance).value;
    const double minor =
        findMaxAbsOverTurn([&](double u) { return std::max(0.0, -wallAt(u)); }, negative, 2, angle_tolerance).value;
    const double max_drive =
        findMaxAbsOverTurn([&](double u) { return model.evaluateMotion(2.0 * u - 2.0 * M_PI).drive_torque; }, drive, 2,
                           angle_tolerance)
            .value;
    std::optional<double> reversal;
    if (!std::isnan(t.bracket_a)) {
      auto wallAtDeg = [&](double deg) { return model.evaluateMotion(radiansFromDegrees(deg)).cylinders[0].wall_force; };
      // A sample whose N_w is zero to rounding (64 eps of the force scale: the centric engine at phi = 0) is the crossing.
      const double zero = 64.0 * std::numeric_limits<double>::epsilon() * sc.force;
      double crossing = std::fabs(t.wall_a) <= zero ? t.bracket_a : t.bracket_b;
      if (std::fabs(t.wall_a) > zero && std::fabs(t.wall_b) > zero) {
        std::uintmax_t iterations = 64;
        const auto [lo, hi] = boost::math::tools::toms748_solve(wallAtDeg, t.bracket_a, t.bracket_b, t.wall_a, t.wall_b,
                                                                 boost::math::tools::eps_tolerance<double>(48), iterations);
        crossing = 0.5 * (lo + hi);
      }
      if (std::fabs(crossing) <= 90.0) reversal = crossing;
    }
    thrust.push_back({engines[j]->name, f, major, minor, reversal, max_drive});
  }
  return {{offsetCostTable().name(), offsetCostTable().table(std::move(cost))},
          {kOffsetThrustTable.name(), kOffsetThrustTable.table(std::move(thrust))}};
}

// The part as the report shows it under `heading`: caption, sentences read from the data; an empty heading
// without data.
ReportPart describeOffsetPart(const TableSet& tables, const std::string& heading) {
  ReportPart part;
  const std::vector<OffsetCostRow>& cost = getRows(tables, offsetCostTable());
  const std::vector<OffsetThrustRow>& thrust = getRows(tables, kOffsetThrustTable);
  if (cost.empty() || !tables.count(kOffsetThrustTable.name())) return part;
  part.heading = heading;
  part.caption =
      "Left: the largest error over the working cycle of the centric form (the same engine with delta = 0) against the "
      "offset engine, relative to each quantity's scale (x_p: the stroke; a_p: r omega^2; wall force and drive "
      "torque: the force and torque scales), against delta / r; dots: the analytic offset engine against " +
      getReferenceName() + " on the same samples. Right: the largest side thrust on the major side (N_w > 0) and on "
      "the minor side, analytic lines and " + getReferenceName() + " dots, against delta / r (negative: the pin toward the major-thrust side). The base scene's "
      "parts, one standing four-stroke cylinder at 6000 rpm (" + std::string(survey::kNotSceneSpeed) + ") with " +
      survey::kExampleGas + ". Your engines' own offsets, at their speed with their [gas], are in their sections above";
  // What the centric formula costs at a production offset (|delta| / r = 0.04) and at a desaxe one (0.5).
  for (double at : {0.04, 0.5}) {
    std::string s = "At |delta| / r = " + shortNumber(at) + " the centric forms are off by";
    double worst_reference = 0.0;  // each reference engine's difference from the exact offset engine
    bool any = false;
    for (const OffsetCostRow& row : cost) {
      if (std::fabs(std::fabs(row.offset_over_r) - at) > 1e-12 || row.offset_over_r < 0) continue;
      s += std::string(any ? "," : "") + " " + shortNumber(row.max_rel_error) + " in " + row.quantity;
      for (double e : row.reference_max_rel_error) worst_reference = std::max(worst_reference, e);
      any = true;
    }
    if (any)
      part.paragraphs.push_back(s + " (relative to each scale; the exact offset engine agrees with every reference engine to " +
                                shortNumber(worst_reference) + ").");
  }
  std::map<double, const OffsetThrustRow*> analytic;  // delta / r -> the closed forms' row
  for (const OffsetThrustRow& row : thrust)
    if (row.engine == getClosedFormEngine().name) analytic[row.offset_over_r] = &row;
  if (analytic.count(0.0)) {
    const OffsetThrustRow& centric = *analytic[0.0];
    for (double at : {-0.04, 0.04, -0.5}) {
      if (!analytic.count(at)) continue;
      const OffsetThrustRow& row = *analytic[at];
      part.paragraphs.push_back(
          "delta / r = " + shortNumber(at) + ": the peak major thrust is " + shortNumber(row.peak_major_thrust, 4) +
          " N against " + shortNumber(centric.peak_major_thrust, 4) + " N centric (" +
          formatPercent(row.peak_major_thrust / centric.peak_major_thrust - 1.0) + "), the peak minor thrust " +
          shortNumber(row.peak_minor_thrust, 4) + " N against " + shortNumber(centric.peak_minor_thrust, 4) +
          " N, and the side thrust changes sign at " +
          (row.thrust_reversal_deg ? shortNumber(*row.thrust_reversal_deg, 3) + " degrees from"
                                   : std::string("no angle within 90 degrees of")) +
          " the firing outer dead centre (centric: " +
          (centric.thrust_reversal_deg ? shortNumber(*centric.thrust_reversal_deg, 3) : std::string("none within 90")) +
          ").");
    }
  }
  return part;
}

class OffsetPart final : public Part {
 public:
  std::string key() const override { return "offset"; }
  std::string title() const override { return "Pin offset: what the centric formulas cost, what the offset buys"; }
  // One task per offset: the tables add up.
  std::vector<Task> tasks(const PartContext& context) const override {
    std::vector<Task> out;
    for (double f : listOffsetFractions(context.quick)) {
      char id[64];
      std::snprintf(id, sizeof id, "offset delta/r=%g", f);
      out.push_back({id, false, [base = context.base, f, quick = context.quick] { return calcOffsetTables(base, f, quick); },
                     task_cost::kCycleSweep});
    }
    return out;
  }
  ReportPart describe(const TableSet& tables) const override { return describeOffsetPart(tables, heading()); }
  std::vector<const TableSchema*> schemas() const override { return {&offsetCostTable(), &kOffsetThrustTable}; }
};

}  // namespace

namespace parts {
const Part& offset() {
  static const OffsetPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
