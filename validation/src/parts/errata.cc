// Report part `errata` (8): the sources as printed against what the engines agree on (the details and the tests that
// assert each entry: docs/ERRATA.md). A table and sentences, no figure.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "../campaign_tables.h"
#include "crankcheck/analytic/fourier_series.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/balance.h"
#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/extremum.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/validation/variants.h"

namespace crankcheck::validation {
namespace {

using analytic::Eq5Form;
using analytic::LambdaSource;

// ------------------------------------------------------------------------------------------------------------
// errata: each printed formula against what the engines agree on, at its real size: per layout and engine where
// it is largest, every maximum over a turn from the exact harmonics (or refined, extremum.h). Tables:
//   errata             item,printed,holds,measure,value,verdict
//   eq5_layouts        cycle,k,gamma_deg,max_abs_Q,max_abs_Q_printed,ratio_of_maxima,max_error_rel
//   eq15_coefficients  n,lambda,printed,exact,relative_error
//   eq15_engines       cycle,k,lambda,first_order,max_abs_Q,max_abs_Q_printed,ratio_of_maxima,max_error_rel

TableSet calcErrataTables(const Mechanism& base) {
  Table t("errata", {{"item", kText}, {"printed", kText}, {"holds", kText}, {"measure", kText},
                     {"value", "see measure"}, {"verdict", kText}});
  auto add = [&](const std::string& item, const std::string& printed, const std::string& holds, const std::string& measure,
                 double value, const std::string& verdict) {
    t.rows.push_back({item, printed, holds, measure, formatNumber(value), verdict});
  };
  const Mechanism rest = withSpeed(base, 0.0);
  char text[256];
  {  // eq (5): the coefficients, then Q of every layout
    const analytic::GravityCoefficients c = analytic::calcGravityCoefficients(rest);
    const analytic::GravityCoefficients p = analytic::calcGravityCoefficients(rest, Eq5Form::kAsPrinted);
    std::snprintf(text, sizeof text, "Stanczak eq (5): U1 for the base rod (z_k / l = %.3f)",
                  rest.rod.com_from_wrist_pin / rest.rod.length);
    add(text, "U1 = M_t + l_z M_z, l_z = z_k / l", "U1 with (l - z_k) / l (z_k from the wrist pin, eq 2)",
        "printed / true", p.U1 / c.U1, "error");
    std::snprintf(text, sizeof text, "Stanczak eq (5): U2 for the base rod (z_k / l = %.3f)",
                  rest.rod.com_from_wrist_pin / rest.rod.length);
    add(text, "U2 = M_s - M_sp + l_z* M_z, l_z* = (l - z_k) / l", "U2 with z_k / l", "printed / true", p.U2 / c.U2, "error");
  }
  Table layouts("eq5_layouts", {{"cycle", kText}, {"k", "-"}, {"gamma_deg", "deg"}, {"max_abs_Q", "N m"},
                                {"max_abs_Q_printed", "N m"}, {"ratio_of_maxima", "-"}, {"max_error_rel", "-"}});
  struct Worst {
    double error = -1.0, ratio = 0.0;
    std::string where;
  };
  std::map<double, Worst> worst_single, worst_multi;  // by gamma
  for (double gamma : {90.0, 0.0, -90.0, 37.0})
    for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke})
      for (int k = 1; k <= 12; ++k) {
        if (k == 1 && cycle == Cycle::kFourStroke) continue;  // the same single cylinder
        const Mechanism m = withGamma(withCylinders(rest, k, cycle), gamma);
        const auto exact = exactHarmonics(m), printed = exactHarmonics(m, Eq5Form::kAsPrinted);
        const double q = maxAbsOfHarmonics(exact), q_printed = maxAbsOfHarmonics(printed);
        if (q <= kAgreementMultiple * kEps * calcEnergyScale(m)) continue;  // Q vanishes (or is rounding): nothing to err
        const double error = maxAbsOfHarmonics(harmonicsMinus(printed, exact)) / q;
        layouts.rows.push_back({toString(cycle), std::to_string(k), formatNumber(gamma), formatNumber(q), formatNumber(q_printed), formatNumber(q_printed / q), formatNumber(error)});
        Worst& w = (k == 1 ? worst_single : worst_multi)[gamma];
        if (error > w.error + 1e-12) {
          std::snprintf(text, sizeof text, "k = %d %s", k, toString(cycle).c_str());
          w = {error, q_printed / q, text};
        }
      }
  for (const auto& [which, map] : {std::pair<std::string, const std::map<double, Worst>&>{"single cylinder", worst_single},
                                   std::pair<std::string, const std::map<double, Worst>&>{"multi-cylinder", worst_multi}})
    for (const auto& [gamma, w] : map) {
      const std::string layout = gamma == 90.0 ? "standing" : gamma == 0.0 ? "lying" : gamma == -90.0 ? "hanging" : "inclined 37 deg";
      std::snprintf(text, sizeof text, "Stanczak eq (5): Q of a %s %s, worst: %s", layout.c_str(), which.c_str(),
                    which == "single cylinder" ? "k = 1" : w.where.c_str());
      add(text, "U1, U2 as printed", "U1, U2 from eq (2)", "max |Q_printed - Q| / max |Q|", w.error, "error");
      add(text, "U1, U2 as printed", "U1, U2 from eq (2)", "max |Q_printed| / max |Q|", w.ratio, "error");
    }
  // eq (15): each printed Lambda_n against the exact one, at lambda = 0.4 (the paper's largest) and the base's.
  Table coefficients("eq15_coefficients", {{"n", "-"}, {"lambda", "-"}, {"printed", "-"}, {"exact", "-"},
                                           {"relative_error", "-"}});
  const double base_lambda = lambdaOf(base);
  for (double lambda : {0.4, base_lambda}) {
    const std::vector<double> exact = analytic::calcLambdaCoefficients(lambda, 12);
    const std::vector<double> printed = analytic::calcLambdaCoefficientsAsPrinted(lambda, 12);
    for (int n = 2; n <= 12; n += 2) {
      coefficients.rows.push_back({std::to_string(n), formatNumber(lambda), formatNumber(printed[n]), formatNumber(exact[n]), formatNumber(printed[n] / exact[n] - 1.0)});
      if (n >= 8) {
        std::snprintf(text, sizeof text, "Stanczak eq (15): Lambda_%d at lambda = %.3g", n, lambda);
        add(text, "power series to lambda^11", "exact Lambda_n (fourier_series.h)", "printed / exact - 1", printed[n] / exact[n] - 1.0,
            "truncation");
      }
    }
  }
  {  // the printed coefficients: how many, and how many are the exact rationals rounded to six decimals
    int count = 0, rounded = 0;
    for (int n = 2; n <= 12; n += 2)
      for (int power = 1; power <= 11; power += 2) {
        const double printed = analytic::getLambdaSeriesCoefficientAsPrinted(n, power);
        if (printed == 0.0) continue;
        ++count;
        const double exact = analytic::calcLambdaSeriesCoefficient(n, power).toDouble();
        if (std::fabs(std::round(exact * 1e6) / 1e6 - printed) < 1e-12) ++rounded;
      }
    add("Stanczak eq (15): printed coefficients", "Lambda_2..Lambda_12, lambda^1..lambda^11", "exact rationals",
        "count printed", count, "count");
    add("Stanczak eq (15): printed coefficients", "six decimals", "exact rational rounded to six decimals",
        "count equal to the rounded exact value", rounded, "count");
    const double printed = analytic::getLambdaSeriesCoefficientAsPrinted(2, 9);
    const double exact = analytic::calcLambdaSeriesCoefficient(2, 9).toDouble();
    add("Stanczak eq (15): Lambda_2 coefficient of lambda^9", "0.022432", "735/32768 = 0.02243041992",
        "printed / exact - 1", printed / exact - 1.0, "misprint");
  }
  // eq (15) in the engines where only high harmonics survive: standing engines, every k, both strokes.
  Table engines("eq15_engines", {{"cycle", kText}, {"k", "-"}, {"lambda", "-"}, {"first_order", "-"},
                                 {"max_abs_Q", "N m"}, {"max_abs_Q_printed", "N m"}, {"ratio_of_maxima", "-"},
                                 {"max_error_rel", "-"}});
  for (double lambda : {0.4, base_lambda})
    for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke})
      for (int k = 1; k <= 12; ++k) {
        const Mechanism m = withGamma(withCylinders(withLambda(rest, lambda), k, cycle), 90.0);
        const auto exact = exactHarmonics(m);
        const auto printed = analytic::calcGravityTorqueHarmonics(m, 12, LambdaSource::kAsPrinted);
        const double q = maxAbsOfHarmonics(exact), q_printed = maxAbsOfHarmonics(printed);
        const double error = maxAbsOfHarmonics(harmonicsMinus(printed, exact)) / q;
        engines.rows.push_back({toString(cycle), std::to_string(k), formatNumber(lambda), std::to_string(exact.front().n), formatNumber(q),
                                formatNumber(q_printed), formatNumber(q_printed / q), formatNumber(error)});
        // Engines whose first harmonic the table holds and where the truncation costs more than 1 % (the others:
        // data/eq15_engines.csv; for k = 7, 9, 11 the table has no harmonic at all and gives Q = 0).
        if (exact.front().n <= 12 && error > 0.01) {
          std::snprintf(text, sizeof text, "Stanczak eq (15): Q of a standing k = %d %s at lambda = %.3g", k, toString(cycle).c_str(), lambda);
          add(text, "Lambda_2..Lambda_12 to lambda^11", "exact Lambda_n", "max |Q_printed - Q| / max |Q|", error, "truncation");
        }
      }
  // Section 7: "for example k = 7 first gives a non-zero value at Lambda_14": the first surviving order of k = 7, 9, 11.
  for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke})
    for (int k : {7, 9, 11}) {
      const std::vector<int> survivors = analytic::findSurvivingHarmonics(k, cycle, Acting::kSingle, 4 * k);
      std::snprintf(text, sizeof text, "Stanczak section 7: first surviving order, k = %d %s", k, toString(cycle).c_str());
      add(text, k == 7 ? "for example k = 7: first non-zero at Lambda_14" : "(not stated)", "exact integer analysis",
          "harmonic order", survivors.empty() ? 0 : survivors.front(), "confirmed");
    }
  {  // eq (12): each cylinder referred to its own outer dead centre: a zero level, not an error
    const Mechanism m3 = withCylinders(rest, 3, Cycle::kTwoStroke);
    Mechanism single = withCylinders(rest, 1, Cycle::kTwoStroke);
    double offset = 0.0;
    for (double alpha : m3.engine.crank_angles) offset += analytic::calcPotentialEnergy(single, alpha);
    add("Stanczak eq (12): U_w(0) of a standing three-cylinder two-stroke [J]", "sum of eq (3) per cylinder (U_w(0) != 0)",
        "a choice of zero level; crankcheck uses U = V(phi) - V(0); Q is the same", "U_w(0) [J]", offset, "not an error");
  }
  // eq (13): correct; the naming. Norton 13.3e: an approximation. Each judged against every reference engine.
  for (const Engine* engine : listReferenceEngines()) {
    const std::unique_ptr<EngineModel> model = buildGravityModel(*engine, rest);
    const double value = findMaxAbsOverTurn([&](double phi) {
      return analytic::calcGravityTorque(rest, phi) - model->calcQ(phi); }, 72).value;
    add("Stanczak eq (13): Q* = dU*/dphi, called the Lagrange force", "Q* = dU*/dphi",
        "correct as dU/dphi (the torque that holds the shaft); the force in Lagrange's equation is -dU/dphi",
        "max |Q - " + engine->name + "'s holding torque| / energy scale", value / calcEnergyScale(rest), "correct (naming)");
  }
  for (const Engine* engine : listReferenceEngines()) {
    const std::unique_ptr<EngineModel> model = engine->build(base);
    const double r = base.crank.radius, w = base.engine.speed;
    const double worst = findMaxAbsOverTurn([&](double phi) {
      return analytic::calcPistonKinematicsNorton(base, phi).a_p - model->evaluate(phi).cylinders[0].a_p; }, 72).value;
    std::snprintf(text, sizeof text, "Norton 13.3e: piston acceleration at lambda = %.3g", lambdaOf(base));
    add(text, "-r w^2 (cos + lambda cos 2theta)", "exact (" + engine->name + ")",
        "max |a_two_term - a (" + engine->name + ")| / (r w^2)", worst / (r * w * w), "approximation");
  }
  return {{"errata", t}, {"eq5_layouts", layouts}, {"eq15_coefficients", coefficients}, {"eq15_engines", engines}};
}

// A field as a number; an empty one as 0.
double toDouble(const std::string& s) { return std::strtod(s.c_str(), nullptr); }

// x as a percentage to 2 significant digits (3 from 10 %): "1.2 %", "13.5 %".

// Part 8: the errata table, and the sentences that read it (every number from the data).
void addErrataPart(ReportPart& part, const TableSet& tables) {
  std::map<std::string, std::map<std::string, double>> value;  // item -> measure -> value
  ReportBlock table{ReportBlock::kTable, "", {"item", "printed", "holds", "measure", "value", "verdict"}};
  for (const auto& r : readRecords(tables, "errata")) {
    value[r.at("item")][r.at("measure")] = toDouble(r.at("value"));
    table.rows.push_back({r.at("item"), r.at("printed"), r.at("holds"), r.at("measure"), shortNumber(toDouble(r.at("value")), 3),
                          r.at("verdict")});
  }
  part.blocks.push_back(table);
  auto find = [&](const std::string& prefix, const std::string& measure, double& out) {
    for (const auto& [item, measures] : value)
      if (item.rfind(prefix, 0) == 0 && measures.count(measure)) return out = measures.at(measure), true;
    return false;
  };
  std::vector<std::string> text;
  double u1, u2, single_error, multi_ratio, lying_ratio;
  if (find("Stanczak eq (5): U1", "printed / true", u1) && find("Stanczak eq (5): U2", "printed / true", u2) &&
      find("Stanczak eq (5): Q of a standing single cylinder", "max |Q_printed - Q| / max |Q|", single_error) &&
      find("Stanczak eq (5): Q of a standing multi-cylinder", "max |Q_printed| / max |Q|", multi_ratio) &&
      find("Stanczak eq (5): Q of a lying single cylinder", "max |Q_printed| / max |Q|", lying_ratio))
    text.push_back("Eq (5) as printed: for the base rod the printed U1 is " + shortNumber(u1, 3) + " x and U2 " + shortNumber(u2, 2) +
                   " x the true values. A standing single cylinder hides it (Q is off by " + formatPercent(single_error) +
                   " of its maximum, U1 + U2 barely changes); a standing engine whose first surviving harmonic is even "
                   "(two-stroke k >= 2, four-stroke k >= 3: Q carries U1 alone) gets max |Q| " + formatPercent(multi_ratio - 1.0) +
                   " too high; a lying single cylinder (Q carries U2 alone) " + formatPercent(1.0 - lying_ratio) +
                   " too low. data/eq5_layouts.csv has every layout.");
  double l12, l12b = 0.0, l10, l8, count, rounded;
  std::string base_lambda;
  for (const auto& [item, measures] : value)
    if (item.rfind("Stanczak eq (15): Lambda_12 at lambda = ", 0) == 0 && item.find("= 0.4") == std::string::npos) {
      l12b = measures.begin()->second;
      base_lambda = item.substr(std::string("Stanczak eq (15): Lambda_12 at lambda = ").size());
    }
  if (find("Stanczak eq (15): Lambda_12 at lambda = 0.4", "printed / exact - 1", l12) &&
      find("Stanczak eq (15): Lambda_10 at lambda = 0.4", "printed / exact - 1", l10) &&
      find("Stanczak eq (15): Lambda_8 at lambda = 0.4", "printed / exact - 1", l8)) {
    std::vector<std::pair<double, std::string>> list;  // the engines where it exceeds 1 %, largest first
    const std::string head = "Stanczak eq (15): Q of a standing ";
    for (const auto& [item, measures] : value)
      if (item.rfind(head, 0) == 0 && item.find("= 0.4") != std::string::npos)
        list.push_back({measures.begin()->second, item.substr(head.size(), item.find(" at lambda") - head.size())});
    std::sort(list.begin(), list.end(), [](const auto& a, const auto& b) { return a.first > b.first || (a.first == b.first && a.second < b.second); });
    std::string engines;
    for (const auto& [error, name] : list) engines += (engines.empty() ? "" : ", ") + name + " " + formatPercent(error);
    text.push_back("Eq (15) is a power series truncated at lambda^11, so each printed Lambda_n falls short of the exact one: "
                   "at lambda = 0.4, the paper's largest crank ratio, Lambda_12 by " + formatPercent(-l12) +
                   (base_lambda.empty() ? "" : " (still " + formatPercent(-l12b) + " at the base's lambda = " + base_lambda + ")") +
                   ", Lambda_10 by " + formatPercent(-l10) + ", Lambda_8 by " + formatPercent(-l8) +
                   " (data/eq15_coefficients.csv). 'A close approximation' holds for the engines dominated by Lambda_2 "
                   "and Lambda_4, not where only high harmonics survive: max |Q_printed - Q| / max |Q| at lambda = 0.4 is " +
                   engines + "; for k = 7, 9, 11 the table holds no surviving harmonic and gives Q = 0 "
                   "(data/eq15_engines.csv, every engine).");
  }
  if (find("Stanczak eq (15): printed coefficients", "count printed", count) &&
      find("Stanczak eq (15): printed coefficients", "count equal to the rounded exact value", rounded))
    text.push_back("Eq (15) prints " + shortNumber(count, 3) + " coefficients; " + shortNumber(rounded, 3) +
                   " of them are the exact rationals rounded to six decimals, the other " + shortNumber(count - rounded, 3) +
                   " is a misprint (Lambda_2, lambda^9).");
  std::string orders;
  for (const char* cycle : {"two-stroke", "four-stroke"})
    for (int k : {7, 9, 11}) {
      const std::string key = "k = " + std::to_string(k) + " " + cycle;
      const auto it = value.find("Stanczak section 7: first surviving order, " + key);
      if (it != value.end()) orders += (orders.empty() ? "" : ", ") + key + ": " + shortNumber(it->second.begin()->second, 3);
    }
  if (!orders.empty())
    text.push_back("Section 7 says that 'for example' k = 7 first gives a non-zero value at Lambda_14. The first surviving "
                   "harmonic order, from the exact integer analysis: " + orders + ".");
  text.push_back("Eq (12) refers each cylinder to its own outer dead centre, so U_w(0) != 0 for k > 1: that is a choice of "
                 "zero level, not an error (Q is the same); crankcheck uses U = V(phi) - V(0). Eq (13) is correct as "
                 "dU/dphi, the torque that holds the shaft against gravity; the paper calls it the generalized (Lagrange) "
                 "force, but the force of gravity in Lagrange's equation is its negative, -dU/dphi.");
  for (const std::string& t : text) part.blocks.push_back({ReportBlock::kParagraph, t});
  part.blocks.push_back({ReportBlock::kParagraph, "Details and the tests that assert each entry: docs/ERRATA.md. Data of every table and "
                                    "figure: data/*.csv."});
}

class ErrataPart final : public Part {
 public:
  std::string key() const override { return "errata"; }
  std::string title() const override { return "Errata: the sources as printed against what the engines agree on"; }
  std::vector<Task> tasks(const PartContext& context) const override {
    return {{"errata", false, [base = context.base] { return calcErrataTables(base); }}};
  }
  // Always shown: an empty table says the campaign had no errata rows.
  ReportPart describe(const TableSet& tables) const override {
    ReportPart part;
    if (!tables.count("errata")) return part;  // not run (validate --parts): left out
    part.heading = heading();
    addErrataPart(part, tables);
    return part;
  }
  std::vector<std::string> tables() const override { return {"errata", "eq5_layouts", "eq15_coefficients", "eq15_engines"}; }
  std::vector<ReportedMaximum> maxima() const override {
    return {{"errata", {"item", "measure"}, {"value"}, "", ""},
            {"eq5_layouts", {"cycle", "k", "gamma_deg"}, {"max_abs_Q", "max_abs_Q_printed", "max_error_rel"}, "", ""},
            {"eq15_engines", {"cycle", "k", "lambda"}, {"max_abs_Q", "max_abs_Q_printed", "max_error_rel"}, "", ""}};
  }
  std::vector<std::string> figures() const override { return {}; }
};

}  // namespace

namespace parts {
const Part& errata() {
  static const ErrataPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
