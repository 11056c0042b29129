// Report part `errata` (8): the sources as printed against what the engines agree on (computed in campaign.cc; the
// details and the tests that assert each entry: docs/ERRATA.md). A table and sentences, no figure.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "../campaign_tables.h"
#include "crankcheck/validation/part.h"

namespace crankcheck::validation {
namespace {

// A field as a number; an empty one as 0.
double toDouble(const std::string& s) { return std::strtod(s.c_str(), nullptr); }

// x as a percentage to 2 significant digits (3 from 10 %): "1.2 %", "13.5 %".
std::string percent(double x) { return shortNumber(100.0 * x, std::fabs(100.0 * x) >= 10.0 ? 3 : 2) + " %"; }

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
                   " x the true values. A standing single cylinder hides it (Q is off by " + percent(single_error) +
                   " of its maximum, U1 + U2 barely changes); a standing engine whose first surviving harmonic is even "
                   "(two-stroke k >= 2, four-stroke k >= 3: Q carries U1 alone) gets max |Q| " + percent(multi_ratio - 1.0) +
                   " too high; a lying single cylinder (Q carries U2 alone) " + percent(1.0 - lying_ratio) +
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
    for (const auto& [error, name] : list) engines += (engines.empty() ? "" : ", ") + name + " " + percent(error);
    text.push_back("Eq (15) is a power series truncated at lambda^11, so each printed Lambda_n falls short of the exact one: "
                   "at lambda = 0.4, the paper's largest crank ratio, Lambda_12 by " + percent(-l12) +
                   (base_lambda.empty() ? "" : " (still " + percent(-l12b) + " at the base's lambda = " + base_lambda + ")") +
                   ", Lambda_10 by " + percent(-l10) + ", Lambda_8 by " + percent(-l8) +
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
  int number() const override { return 8; }
  std::string title() const override { return "Errata: the sources as printed against what the engines agree on"; }
  std::vector<Task> tasks(const PartContext& context) const override {
    return {{"errata", false, [base = context.base] { return calcErrataTables(base); }}};
  }
  // Always shown: an empty table says the campaign had no errata rows.
  ReportPart describe(const TableSet& tables) const override {
    ReportPart part;
    part.heading = heading();
    addErrataPart(part, tables);
    return part;
  }
  std::vector<std::string> tables() const override { return {"errata", "eq5_layouts", "eq15_coefficients", "eq15_engines"}; }
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
