// Report part `error_vs_lambda`: the error of every approximate method against lambda.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "../part_math.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/campaign_scenes.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/table.h"
#include "crankcheck/validation/task.h"
#include "crankcheck/validation/extremum.h"
#include "crankcheck/scene/quantities.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/validation/variants.h"
#include "survey.h"

namespace crankcheck::validation {
namespace {

using analytic::Eq5Form;
using analytic::LambdaSource;

// error_vs_lambda: every approximate method against its exact reference at one lambda, the largest error over a turn.
// Every maximum is found on the same grid in the quick and the full campaign: Q's truncation errors from the exact
// harmonics, the others by refining the best samples (extremum.h); the engines' agreement (rounding) is marked
// unresolved.
struct ErrorVsLambdaRow {
  std::string quantity, method;
  double lambda = 0.0;
  double max_abs_error = 0.0;  ///< [SI] in the quantity's unit
  double max_rel_error = 0.0;  ///< [-] relative to the quantity's scale
  std::string resolved;        ///< "1", or "0": at rounding level, a bound (resolvedToOnePercent)
};
const Schema<ErrorVsLambdaRow> kErrorVsLambdaTable{
    "error_vs_lambda",
    {textField("quantity", &ErrorVsLambdaRow::quantity), textField("method", &ErrorVsLambdaRow::method),
     numberField("lambda", "-", &ErrorVsLambdaRow::lambda),
     numberField("max_abs_error", "SI", &ErrorVsLambdaRow::max_abs_error),
     numberField("max_rel_error", "-", &ErrorVsLambdaRow::max_rel_error),
     textField("resolved", &ErrorVsLambdaRow::resolved)}};

const Part& thisPart();

TableSet calcErrorVsLambdaTables(const Mechanism& base, double lambda) {
  const Mechanism m = withLambda(base, lambda);
  const double r = m.crank.radius, w = m.machine.speed;
  const double E = calcEnergyScale(m);
  const Scales sc = calcScales(m);
  std::vector<ErrorVsLambdaRow> rows;
  auto add = [&](const std::string& quantity, const std::string& method, double max_abs, double scale, bool resolved) {
    rows.push_back({quantity, method, lambda, max_abs, max_abs / scale, resolved ? "1" : "0"});
  };
  auto direct = [&](const std::string& quantity, const std::string& method, double scale,
                    const std::function<double(double)>& error) {
    const double value = findMaxAbsOverTurn(error, 360).value;
    add(quantity, method, value, scale, resolvedToOnePercent(value / scale));
  };
  direct(nameOf(QuantityId::kPistonPosition), "norton_two_term", r, [&](double phi) {
    return analytic::calcPistonKinematicsNorton(m, phi).x_p - analytic::calcPistonKinematics(m, phi).x_p; });
  direct(nameOf(QuantityId::kPistonVelocity), "norton_two_term", r * w, [&](double phi) {
    return analytic::calcPistonKinematicsNorton(m, phi).v_p - analytic::calcPistonKinematics(m, phi).v_p; });
  direct(nameOf(QuantityId::kPistonAcceleration), "norton_two_term", r * w * w, [&](double phi) {
    return analytic::calcPistonKinematicsNorton(m, phi).a_p - analytic::calcPistonKinematics(m, phi).a_p; });
  const auto exact = exactHarmonics(m);
  for (int order : {2, 4, 6, 8, 10, 12}) {
    const double value = maxAbsOfHarmonics(harmonicsAbove(exact, order));  // truncation error, exact to rounding
    add("Q", "fourier_order_" + std::to_string(order), value, E, true);
  }
  {
    const double value = maxAbsOfHarmonics(harmonicsMinus(analytic::calcGravityTorqueHarmonics(m, 12, LambdaSource::kAsPrinted), exact));
    add("Q", "paper_eq15_printed", value, E, resolvedToOnePercent(value / E));
  }
  {
    const double value = maxAbsOfHarmonics(harmonicsMinus(exactHarmonics(m, Eq5Form::kAsPrinted), exact));
    add("Q", "paper_eq5_printed", value, E, resolvedToOnePercent(value / E));
  }
  direct("U", "paper_eq5_printed", E, [&](double phi) {
    return analytic::calcPotentialEnergy(m, phi, Eq5Form::kAsPrinted) - analytic::calcPotentialEnergy(m, phi); });
  // The engines' agreement, against each reference engine: rounding, so a bound (the worst seen at 5 degree steps), never a resolved maximum.
  // An engine that builds the scene but not this lambda's variant of it (Simbody's constraint solve on a scene whose
  // gas dwarfs its masses, at some lambdas) has no row here, and the report's notes say so; the other rows stand.
  std::vector<NoteRow> notes;
  for (const Engine* engine : listReferenceEngines()) {
    std::unique_ptr<EngineModel> model;
    try {
      model = engine->build(m);
    } catch (const std::invalid_argument& e) {
      notes.push_back({"Part " + std::to_string(thisPart().number()) + " (error_vs_lambda): " + engine->name +
                       " is left out at lambda = " + shortNumber(lambda, 4) + ", where it cannot build the scene: " +
                       escapeText(formatOneLine(e.what()))});
      continue;
    }
    std::map<std::string, double> worst;
    for (double phi_deg : anglesDeg(5.0)) {
      const double phi = radiansFromDegrees(phi_deg);
      const Evaluation s = model->evaluate(phi), a = analytic::calcEvaluation(m, phi);
      auto track = [&](const std::string& key, double error) { worst[key] = std::max(worst[key], std::fabs(error)); };
      track("Q", a.Q - s.Q);
      track("U", a.U - s.U);
      track(nameOf(QuantityId::kPistonPosition), a.cylinders[0].x_p - s.cylinders[0].x_p);
      track(nameOf(QuantityId::kPistonVelocity), a.cylinders[0].v_p - s.cylinders[0].v_p);
      track(nameOf(QuantityId::kPistonAcceleration), a.cylinders[0].a_p - s.cylinders[0].a_p);
    }
    for (const auto& [quantity, error] : worst) {
      const double scale = quantity == nameOf(QuantityId::kPistonPosition)       ? r
                                 : quantity == nameOf(QuantityId::kPistonVelocity)     ? r * w
                                 : quantity == nameOf(QuantityId::kPistonAcceleration) ? r * w * w
                                                                                      : E;
      add(quantity, "analytic_vs_" + engine->name, error, scale, resolvedToOnePercent(error / scale, sc.conditioning));
    }
  }
  TableSet out = kErrorVsLambdaTable.tableSet(std::move(rows));
  if (!notes.empty()) appendTables(out, kNotesTable.tableSet(notes));
  return out;
}

// The figure's caption.
std::string makeCaption() {
  return "Max error over the crank turn against lambda, relative to the quantity's scale (r, r w, r w^2 for x, v, a; "
         "the energy scale for Q and U): Norton's two-term x, v, a; Q from Fourier series of order 2-12 with exact "
         "coefficients, from the paper's printed coefficients (eq 15) and with eq (5) as printed; analytic against " +
         getReferenceName() + " (every reference engine in the data)";
}

class ErrorVsLambdaPart final : public Part {
 public:
  std::string key() const override { return "error_vs_lambda"; }
  std::string title() const override { return "Error against lambda"; }
  // 21 lambdas from 0.01 to 0.95, log spaced; the quick campaign takes every fourth, so that each of its rows is also
  // a row of the full campaign (tests/cli/quick_report_test.cc compares them).
  std::vector<Task> tasks(const PartContext& context) const override {
    std::vector<Task> out;
    for (int i = 0; i <= 20; i += context.quick ? 4 : 1) {
      const double lambda = 0.01 * std::pow(95.0, i / 20.0);
      char id[64];
      std::snprintf(id, sizeof id, "error_vs_lambda lambda=%.3g", lambda);
      out.push_back({id, false, [base = context.base, lambda] { return calcErrorVsLambdaTables(base, lambda); }});
    }
    return out;
  }
  // The caption, and where the user's engines sit: the figure marks each one's lambda (reports/error_vs_lambda.gp
  // reads data/your_engine.csv), and the caption names them.
  ReportPart describe(const TableSet& tables) const override {
    std::string caption = makeCaption();
    std::vector<std::string> marks;
    for (const your_engine::SceneFactsRow& f : survey::listUserScenes(tables))
      marks.push_back(f.scene + " at lambda = " + shortNumber(f.lambda, 4));
    if (!marks.empty())
      caption += ". The dash-dotted vertical lines mark your engines' lambda: " + survey::joinNames(marks);
    return describeFigure(tables, caption);
  }
  std::vector<const TableSchema*> schemas() const override { return {&kErrorVsLambdaTable}; }
  std::vector<ReportedMaximum> maxima() const override {
    return {{"error_vs_lambda", {"quantity", "method", "lambda"}, {"max_abs_error", "max_rel_error"}, "resolved", "0"}};
  }
};

const Part& thisPart() {
  static const ErrorVsLambdaPart part;
  return part;
}

}  // namespace

namespace parts {
const Part& errorVsLambda() { return thisPart(); }
}  // namespace parts

}  // namespace crankcheck::validation
