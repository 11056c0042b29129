// Report part `errata`: the sources as printed against what the engines agree on (the details and the tests that assert
// each entry: docs/ERRATA.md). A table and sentences, no figure.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "../part_math.h"
#include "crankcheck/analytic/fourier_series.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/balance.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/campaign_scenes.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/table.h"
#include "crankcheck/validation/task.h"
#include "crankcheck/validation/extremum.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/validation/variants.h"

namespace crankcheck::validation {
namespace {

using analytic::Eq5Form;
using analytic::LambdaSource;

// errata: each printed formula against what the engines agree on, at its real size: per layout and engine where it is
// largest, every maximum over a turn from the exact harmonics (or refined, extremum.h). A row is identified by its item
// and measure (the item names the entry, e.g. "Stanczak eq (15): Lambda_12 at lambda = 0.4"; made by the functions
// below, which describe() calls to find it again).
struct ErrataRow {
  std::string item, printed, holds, measure;
  double value = 0.0;  ///< in the unit `measure` says
  std::string verdict;
};
const Schema<ErrataRow> kErrataTable{
    "errata",
    {textField("item", &ErrataRow::item), textField("printed", &ErrataRow::printed),
     textField("holds", &ErrataRow::holds), textField("measure", &ErrataRow::measure),
     numberField("value", "see measure", &ErrataRow::value), textField("verdict", &ErrataRow::verdict)}};

// eq5_layouts: Q of every layout (gamma), cycle and k with eq (5)'s U1, U2 as printed against those of eq (2), where Q
// does not vanish.
struct Eq5LayoutRow {
  std::string cycle;
  int k = 1;
  double gamma_deg = 0.0;          ///< [deg]
  double max_abs_Q = 0.0;          ///< [N m]
  double max_abs_Q_printed = 0.0;  ///< [N m]
  double ratio_of_maxima = 0.0;    ///< [-] max_abs_Q_printed / max_abs_Q
  double max_error_rel = 0.0;      ///< [-] max |Q_printed - Q| / max |Q|
};
const Schema<Eq5LayoutRow> kEq5LayoutsTable{
    "eq5_layouts",
    {textField("cycle", &Eq5LayoutRow::cycle), countField("k", &Eq5LayoutRow::k),
     numberField("gamma_deg", "deg", &Eq5LayoutRow::gamma_deg), numberField("max_abs_Q", "N m", &Eq5LayoutRow::max_abs_Q),
     numberField("max_abs_Q_printed", "N m", &Eq5LayoutRow::max_abs_Q_printed),
     numberField("ratio_of_maxima", "-", &Eq5LayoutRow::ratio_of_maxima),
     numberField("max_error_rel", "-", &Eq5LayoutRow::max_error_rel)}};

// eq15_coefficients: each printed Lambda_n (n = 2..12) against the exact one, at lambda = 0.4 and the base's.
struct Eq15CoefficientRow {
  int n = 2;
  double lambda = 0.0, printed = 0.0, exact = 0.0;
  double relative_error = 0.0;  ///< [-] printed / exact - 1
};
const Schema<Eq15CoefficientRow> kEq15CoefficientsTable{
    "eq15_coefficients",
    {countField("n", &Eq15CoefficientRow::n), numberField("lambda", "-", &Eq15CoefficientRow::lambda),
     numberField("printed", "-", &Eq15CoefficientRow::printed), numberField("exact", "-", &Eq15CoefficientRow::exact),
     numberField("relative_error", "-", &Eq15CoefficientRow::relative_error)}};

// eq15_engines: Q of every standing engine (k, cycle) with eq (15)'s printed Lambda_n against the exact ones, at
// lambda = 0.4 and the base's.
struct Eq15EngineRow {
  std::string cycle;
  int k = 1;
  double lambda = 0.0;
  int first_order = 0;             ///< the first harmonic of Q that survives
  double max_abs_Q = 0.0;          ///< [N m]
  double max_abs_Q_printed = 0.0;  ///< [N m]
  double ratio_of_maxima = 0.0;    ///< [-]
  double max_error_rel = 0.0;      ///< [-] max |Q_printed - Q| / max |Q|
};
const Schema<Eq15EngineRow> kEq15EnginesTable{
    "eq15_engines",
    {textField("cycle", &Eq15EngineRow::cycle), countField("k", &Eq15EngineRow::k),
     numberField("lambda", "-", &Eq15EngineRow::lambda), countField("first_order", &Eq15EngineRow::first_order),
     numberField("max_abs_Q", "N m", &Eq15EngineRow::max_abs_Q),
     numberField("max_abs_Q_printed", "N m", &Eq15EngineRow::max_abs_Q_printed),
     numberField("ratio_of_maxima", "-", &Eq15EngineRow::ratio_of_maxima),
     numberField("max_error_rel", "-", &Eq15EngineRow::max_error_rel)}};

// The paper's largest crank ratio, at which eq (15)'s entries are stated.
constexpr double kPapersLambda = 0.4;

// The measures and printed forms that describe() reads rows by.
const char* const kMeasureRatio = "printed / true";
const char* const kMeasureError = "max |Q_printed - Q| / max |Q|";
const char* const kMeasureMaxima = "max |Q_printed| / max |Q|";
const char* const kMeasureTruncation = "printed / exact - 1";
const char* const kMeasureCount = "count printed";
const char* const kMeasureRounded = "count equal to the rounded exact value";
const char* const kMeasureOrder = "harmonic order";
const char* const kPrintedU1 = "U1 = M_t + l_z M_z, l_z = z_k / l";
const char* const kPrintedU2 = "U2 = M_s - M_sp + l_z* M_z, l_z* = (l - z_k) / l";
const char* const kItemCoefficients = "Stanczak eq (15): printed coefficients";

// "k = 4 two-stroke".
std::string formatEngineName(int k, const std::string& cycle) { return "k = " + std::to_string(k) + " " + cycle; }

// The item of eq (5)'s coefficient U1 or U2 (`u`) for a rod whose centre of mass is at z_k / l = `zk_over_l`.
std::string formatEq5CoefficientItem(int u, double zk_over_l) {
  char text[128];
  std::snprintf(text, sizeof text, "Stanczak eq (5): U%d for the base rod (z_k / l = %.3f)", u, zk_over_l);
  return text;
}

// The item of eq (5)'s Q of the layout at `gamma_deg` (90, 0, -90 or 37), a single cylinder or the multi-cylinder
// engines, whose worst engine is `worst` (formatEngineName; "k = 1" for a single cylinder).
std::string formatEq5LayoutItem(double gamma_deg, bool single, const std::string& worst) {
  const std::string layout = gamma_deg == 90.0    ? "standing"
                             : gamma_deg == 0.0   ? "lying"
                             : gamma_deg == -90.0 ? "hanging"
                                                  : "inclined 37 deg";
  return "Stanczak eq (5): Q of a " + layout + (single ? " single cylinder" : " multi-cylinder") + ", worst: " + worst;
}

// The item of eq (15)'s Lambda_n at `lambda`.
std::string formatLambdaItem(int n, double lambda) {
  return "Stanczak eq (15): Lambda_" + std::to_string(n) + " at lambda = " + shortNumber(lambda, 3);
}

// The item of eq (15)'s Q of a standing engine at `lambda`.
std::string formatEq15EngineItem(int k, const std::string& cycle, double lambda) {
  return "Stanczak eq (15): Q of a standing " + formatEngineName(k, cycle) + " at lambda = " + shortNumber(lambda, 3);
}

// The item of section 7's first surviving order of an engine.
std::string formatSection7Item(int k, const std::string& cycle) {
  return "Stanczak section 7: first surviving order, " + formatEngineName(k, cycle);
}

TableSet calcErrataTables(const Mechanism& base) {
  std::vector<ErrataRow> errata;
  auto add = [&](const std::string& item, const std::string& printed, const std::string& holds, const std::string& measure,
                 double value, const std::string& verdict) {
    errata.push_back({item, printed, holds, measure, value, verdict});
  };
  const Mechanism rest = withSpeed(base, 0.0);
  {  // eq (5): the coefficients, then Q of every layout
    const analytic::GravityCoefficients c = analytic::calcGravityCoefficients(rest);
    const analytic::GravityCoefficients p = analytic::calcGravityCoefficients(rest, Eq5Form::kAsPrinted);
    const double zk_over_l = rest.rod.com_from_wrist_pin / rest.rod.length;
    add(formatEq5CoefficientItem(1, zk_over_l), kPrintedU1, "U1 with (l - z_k) / l (z_k from the wrist pin, eq 2)",
        kMeasureRatio, p.U1 / c.U1, "error");
    add(formatEq5CoefficientItem(2, zk_over_l), kPrintedU2, "U2 with z_k / l", kMeasureRatio, p.U2 / c.U2, "error");
  }
  std::vector<Eq5LayoutRow> layouts;
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
        layouts.push_back({toString(cycle), k, gamma, q, q_printed, q_printed / q, error});
        Worst& w = (k == 1 ? worst_single : worst_multi)[gamma];
        if (error > w.error + 1e-12) w = {error, q_printed / q, formatEngineName(k, toString(cycle))};
      }
  for (const auto& [single, map] : {std::pair<bool, const std::map<double, Worst>&>{true, worst_single},
                                     std::pair<bool, const std::map<double, Worst>&>{false, worst_multi}})
    for (const auto& [gamma, w] : map) {
      const std::string item = formatEq5LayoutItem(gamma, single, single ? "k = 1" : w.where);
      add(item, "U1, U2 as printed", "U1, U2 from eq (2)", kMeasureError, w.error, "error");
      add(item, "U1, U2 as printed", "U1, U2 from eq (2)", kMeasureMaxima, w.ratio, "error");
    }
  // eq (15): each printed Lambda_n against the exact one, at lambda = 0.4 (the paper's largest) and the base's.
  std::vector<Eq15CoefficientRow> coefficients;
  const double base_lambda = lambdaOf(base);
  for (double lambda : {kPapersLambda, base_lambda}) {
    const std::vector<double> exact = analytic::calcLambdaCoefficients(lambda, 12);
    const std::vector<double> printed = analytic::calcLambdaCoefficientsAsPrinted(lambda, 12);
    for (int n = 2; n <= 12; n += 2) {
      coefficients.push_back({n, lambda, printed[n], exact[n], printed[n] / exact[n] - 1.0});
      if (n >= 8)
        add(formatLambdaItem(n, lambda), "power series to lambda^11", "exact Lambda_n (fourier_series.h)",
            kMeasureTruncation, printed[n] / exact[n] - 1.0, "truncation");
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
    add(kItemCoefficients, "Lambda_2..Lambda_12, lambda^1..lambda^11", "exact rationals", kMeasureCount, count, "count");
    add(kItemCoefficients, "six decimals", "exact rational rounded to six decimals", kMeasureRounded, rounded, "count");
    const double printed = analytic::getLambdaSeriesCoefficientAsPrinted(2, 9);
    const double exact = analytic::calcLambdaSeriesCoefficient(2, 9).toDouble();
    add("Stanczak eq (15): Lambda_2 coefficient of lambda^9", "0.022432", "735/32768 = 0.02243041992",
        kMeasureTruncation, printed / exact - 1.0, "misprint");
  }
  // eq (15) in the engines where only high harmonics survive: standing engines, every k, both strokes.
  std::vector<Eq15EngineRow> engines;
  for (double lambda : {kPapersLambda, base_lambda})
    for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke})
      for (int k = 1; k <= 12; ++k) {
        const Mechanism m = withGamma(withCylinders(withLambda(rest, lambda), k, cycle), 90.0);
        const auto exact = exactHarmonics(m);
        const auto printed = analytic::calcGravityTorqueHarmonics(m, 12, LambdaSource::kAsPrinted);
        const double q = maxAbsOfHarmonics(exact), q_printed = maxAbsOfHarmonics(printed);
        const double error = maxAbsOfHarmonics(harmonicsMinus(printed, exact)) / q;
        engines.push_back({toString(cycle), k, lambda, exact.front().n, q, q_printed, q_printed / q, error});
        // Engines whose first harmonic the table holds and where the truncation costs more than 1 % (the others:
        // data/eq15_engines.csv; for k = 7, 9, 11 the table has no harmonic at all and gives Q = 0).
        if (exact.front().n <= 12 && error > 0.01)
          add(formatEq15EngineItem(k, toString(cycle), lambda), "Lambda_2..Lambda_12 to lambda^11", "exact Lambda_n",
              kMeasureError, error, "truncation");
      }
  // Section 7: "for example k = 7 first gives a non-zero value at Lambda_14": the first surviving order of k = 7, 9, 11.
  for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke})
    for (int k : {7, 9, 11}) {
      const std::vector<int> survivors = analytic::findSurvivingHarmonics(k, cycle, Acting::kSingle, 4 * k);
      add(formatSection7Item(k, toString(cycle)),
          k == 7 ? "for example k = 7: first non-zero at Lambda_14" : "(not stated)", "exact integer analysis",
          kMeasureOrder, survivors.empty() ? 0 : survivors.front(), "confirmed");
    }
  {  // eq (12): each cylinder referred to its own outer dead centre: a zero level, not an error
    const Mechanism m3 = withCylinders(rest, 3, Cycle::kTwoStroke);
    Mechanism single = withCylinders(rest, 1, Cycle::kTwoStroke);
    double offset = 0.0;
    for (double alpha : m3.machine.crank_angles) offset += analytic::calcPotentialEnergy(single, alpha);
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
    const double r = base.crank.radius, w = base.machine.speed;
    const double worst = findMaxAbsOverTurn([&](double phi) {
      return analytic::calcPistonKinematicsNorton(base, phi).a_p - model->evaluate(phi).cylinders[0].a_p; }, 72).value;
    add("Norton 13.3e: piston acceleration at lambda = " + shortNumber(lambdaOf(base), 3), "-r w^2 (cos + lambda cos 2theta)", "exact (" + engine->name + ")",
        "max |a_two_term - a (" + engine->name + ")| / (r w^2)", worst / (r * w * w), "approximation");
  }
  return {{kErrataTable.name(), kErrataTable.table(std::move(errata))},
          {kEq5LayoutsTable.name(), kEq5LayoutsTable.table(std::move(layouts))},
          {kEq15CoefficientsTable.name(), kEq15CoefficientsTable.table(std::move(coefficients))},
          {kEq15EnginesTable.name(), kEq15EnginesTable.table(std::move(engines))}};
}

// The value of the errata row that `match` picks (the first), or none.
template <class Match>
std::optional<double> findErrataValue(const std::vector<ErrataRow>& rows, const Match& match) {
  for (const ErrataRow& row : rows)
    if (match(row)) return row.value;
  return std::nullopt;
}

// The errata table, and the sentences that read it (every number from the data): rows found by their item and measure.
void addErrataPart(ReportPart& part, const TableSet& tables) {
  const std::vector<ErrataRow>& rows = getRows(tables, kErrataTable);
  ReportBlock table{ReportBlock::kTable, "", {"item", "printed", "holds", "measure", "value", "verdict"}};
  for (const ErrataRow& row : rows)
    table.rows.push_back({row.item, row.printed, row.holds, row.measure, shortNumber(row.value, 3), row.verdict});
  part.blocks.push_back(table);
  auto find = [&](const std::string& item, const std::string& measure) {
    return findErrataValue(rows, [&](const ErrataRow& r) { return r.item == item && r.measure == measure; });
  };
  auto findPrinted = [&](const std::string& printed, const std::string& measure) {  // U1, U2: the printed form names them
    return findErrataValue(rows, [&](const ErrataRow& r) { return r.printed == printed && r.measure == measure; });
  };
  std::vector<std::string> text;
  // Eq (5): the standing multi-cylinder engines' row names the worst of them, one of eq5_layouts' standing engines.
  std::optional<double> multi_ratio;
  for (const Eq5LayoutRow& layout : getRows(tables, kEq5LayoutsTable))
    if (!multi_ratio && layout.gamma_deg == 90.0 && layout.k > 1)
      multi_ratio = find(formatEq5LayoutItem(90.0, false, formatEngineName(layout.k, layout.cycle)), kMeasureMaxima);
  const std::optional<double> u1 = findPrinted(kPrintedU1, kMeasureRatio), u2 = findPrinted(kPrintedU2, kMeasureRatio);
  const std::optional<double> single_error = find(formatEq5LayoutItem(90.0, true, "k = 1"), kMeasureError);
  const std::optional<double> lying_ratio = find(formatEq5LayoutItem(0.0, true, "k = 1"), kMeasureMaxima);
  if (u1 && u2 && single_error && multi_ratio && lying_ratio)
    text.push_back("Eq (5) as printed: for the base rod the printed U1 is " + shortNumber(*u1, 3) + " x and U2 " + shortNumber(*u2, 2) +
                   " x the true values. A standing single cylinder hides it (Q is off by " + formatPercent(*single_error) +
                   " of its maximum, U1 + U2 barely changes); a standing engine whose first surviving harmonic is even "
                   "(two-stroke k >= 2, four-stroke k >= 3: Q carries U1 alone) gets max |Q| " + formatPercent(*multi_ratio - 1.0) +
                   " too high; a lying single cylinder (Q carries U2 alone) " + formatPercent(1.0 - *lying_ratio) +
                   " too low. data/eq5_layouts.csv has every layout.");
  // Eq (15): Lambda_n at the paper's lambda and at the base's (eq15_coefficients' other lambda).
  const std::optional<double> l12 = find(formatLambdaItem(12, kPapersLambda), kMeasureTruncation);
  const std::optional<double> l10 = find(formatLambdaItem(10, kPapersLambda), kMeasureTruncation);
  const std::optional<double> l8 = find(formatLambdaItem(8, kPapersLambda), kMeasureTruncation);
  std::optional<double> l12b;
  std::string base_lambda;
  for (const Eq15CoefficientRow& row : getRows(tables, kEq15CoefficientsTable))
    if (!l12b && formatLambdaItem(12, row.lambda) != formatLambdaItem(12, kPapersLambda)) {
      l12b = find(formatLambdaItem(12, row.lambda), kMeasureTruncation);
      if (l12b) base_lambda = shortNumber(row.lambda, 3);
    }
  if (l12 && l10 && l8) {
    std::map<std::string, double> over;  // the standing engines where the truncation costs more than 1 %: their rows
    for (const Eq15EngineRow& row : getRows(tables, kEq15EnginesTable))
      if (row.lambda == kPapersLambda)
        if (const std::optional<double> error = find(formatEq15EngineItem(row.k, row.cycle, row.lambda), kMeasureError))
          over[formatEngineName(row.k, row.cycle)] = *error;
    std::vector<std::pair<double, std::string>> list;  // largest first
    for (const auto& [name, error] : over) list.push_back({error, name});
    std::sort(list.begin(), list.end(), [](const auto& a, const auto& b) { return a.first > b.first || (a.first == b.first && a.second < b.second); });
    std::string engines;
    for (const auto& [error, name] : list) engines += (engines.empty() ? "" : ", ") + name + " " + formatPercent(error);
    text.push_back("Eq (15) is a power series truncated at lambda^11, so each printed Lambda_n falls short of the exact one: "
                   "at lambda = 0.4, the paper's largest crank ratio, Lambda_12 by " + formatPercent(-*l12) +
                   (base_lambda.empty() ? "" : " (still " + formatPercent(-*l12b) + " at the base's lambda = " + base_lambda + ")") +
                   ", Lambda_10 by " + formatPercent(-*l10) + ", Lambda_8 by " + formatPercent(-*l8) +
                   " (data/eq15_coefficients.csv). 'A close approximation' holds for the engines dominated by Lambda_2 "
                   "and Lambda_4, not where only high harmonics survive: max |Q_printed - Q| / max |Q| at lambda = 0.4 is " +
                   engines + "; for k = 7, 9, 11 the table holds no surviving harmonic and gives Q = 0 "
                   "(data/eq15_engines.csv, every engine).");
  }
  const std::optional<double> count = find(kItemCoefficients, kMeasureCount), rounded = find(kItemCoefficients, kMeasureRounded);
  if (count && rounded)
    text.push_back("Eq (15) prints " + shortNumber(*count, 3) + " coefficients; " + shortNumber(*rounded, 3) +
                   " of them are the exact rationals rounded to six decimals, the other " + shortNumber(*count - *rounded, 3) +
                   " is a misprint (Lambda_2, lambda^9).");
  std::string orders;
  for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke})
    for (int k : {7, 9, 11})
      if (const std::optional<double> order = find(formatSection7Item(k, toString(cycle)), kMeasureOrder))
        orders += (orders.empty() ? "" : ", ") + formatEngineName(k, toString(cycle)) + ": " + shortNumber(*order, 3);
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
    if (!tables.count(kErrataTable.name())) return part;  // not run (validate --parts): left out
    part.heading = heading();
    addErrataPart(part, tables);
    return part;
  }
  std::vector<const TableSchema*> schemas() const override {
    return {&kErrataTable, &kEq5LayoutsTable, &kEq15CoefficientsTable, &kEq15EnginesTable};
  }
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
