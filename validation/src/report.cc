#include "crankcheck/validation/report.h"

#include <algorithm>
#include <chrono>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <map>
#include <set>
#include <tuple>
#include <nlohmann/json.hpp>
#include <sstream>
#include <exception>
#include <thread>
#include <mutex>
#include <atomic>
#include <stdexcept>

#include "crankcheck/mujoco_models/k_crank_mujoco_model.h"
#include "crankcheck/simbody_models/k_crank_model.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/report_document.h"
#include "crankcheck/validation/output_folder.h"
#include "crankcheck/validation/parts.h"
#include "crankcheck/validation/process.h"
#include "crankcheck/validation/verdict.h"


namespace crankcheck::validation {
namespace fs = std::filesystem;

namespace {

double toDouble(const std::string& s) { return std::strtod(s.c_str(), nullptr); }

}  // namespace

std::vector<SummaryRow> summarize(const TableSet& tables) {
  std::vector<SummaryRow> out;
  const auto it = tables.find("crosscheck");
  if (it == tables.end()) return out;
  const Table& t = it->second;
  const size_t engine = columnOf(t, "engine"), family = columnOf(t, "family"), kase = columnOf(t, "case"), quantity = columnOf(t, "quantity"),
               rel = columnOf(t, "worst_rel_error"), phi = columnOf(t, "where_phi_deg"), rpm = columnOf(t, "where_speed_rpm"),
               tol = columnOf(t, "tolerance_rel"), pass = columnOf(t, "pass");
  std::map<std::tuple<std::string, std::string, std::string>, SummaryRow> rows;
  for (const auto& row : t.rows) {
    if (row[pass] == "reported") continue;  // a soft engine: measured in part engines, never gated
    SummaryRow& s = rows[{row[engine], row[quantity], row[family]}];
    const bool first = s.quantity.empty();
    s.engine = row[engine];
    s.quantity = row[quantity];
    s.family = row[family];
    s.pass = s.pass && row[pass] == "pass";
    const double r = toDouble(row[rel]);
    if (first || r / toDouble(row[tol]) > s.worst_rel_error / s.tolerance_rel) {
      s.worst_rel_error = r;
      s.tolerance_rel = toDouble(row[tol]);
      s.where = row[kase] + ", phi " + row[phi] + " deg, " + row[rpm] + " rpm";
    }
  }
  for (auto& [key, row] : rows) out.push_back(row);
  return out;
}

std::string formatSummary(const std::vector<SummaryRow>& summary) {
  std::ostringstream out;
  char line[400];
  std::snprintf(line, sizeof line, "%-8s %-18s %-38s %11s  %-54s %10s  %s\n", "engine", "quantity", "family of cases",
                "worst/scale", "where", "tol/scale", "result");
  out << line;
  for (const SummaryRow& s : summary) {
    std::snprintf(line, sizeof line, "%-8s %-18s %-38s %11.2e  %-54s %10.2e  %s\n", s.engine.c_str(), s.quantity.c_str(), s.family.c_str(),
                  s.worst_rel_error, s.where.c_str(), s.tolerance_rel, s.pass ? "pass" : "FAIL");
    out << line;
  }
  return out.str();
}

namespace {

// RFC 4180: a field with a comma, a double quote or a line break is quoted, its quotes doubled. Only scene names
// (file names) can hold such characters; the numbers and names the figures read never do.
std::string csvField(const std::string& field) {
  if (field.find_first_of(",\"\r\n") == std::string::npos) return field;
  std::string out = "\"";
  for (char c : field) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// Splits CSV text into records of fields (RFC 4180). @throws std::runtime_error on an unterminated quote.
std::vector<std::vector<std::string>> parseCsv(const std::string& text, const std::string& source) {
  std::vector<std::vector<std::string>> records;
  std::vector<std::string> record;
  std::string field;
  bool quoted = false, any = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') field += '"', ++i;
      else if (c == '"') quoted = false;
      else field += c;
    } else if (c == '"') {
      quoted = any = true;
    } else if (c == ',') {
      record.push_back(std::move(field));
      field.clear();
      any = true;
    } else if (c == '\n') {
      record.push_back(std::move(field));
      field.clear();
      records.push_back(std::move(record));
      record.clear();
      any = false;
    } else if (c != '\r') {
      field += c;
      any = true;
    }
  }
  if (quoted) throw std::runtime_error(source + ": a quoted field is not closed");
  if (any) {
    record.push_back(std::move(field));
    records.push_back(std::move(record));
  }
  return records;
}

}  // namespace

std::string calcChecksum(std::string_view bytes) {
  std::uint64_t h = 0xcbf29ce484222325ull;  // FNV-1a 64: offset basis, then xor and multiply by the prime per byte
  for (const unsigned char c : bytes) h = (h ^ c) * 0x100000001b3ull;
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

std::vector<DataFileRecord> writeTables(const TableSet& tables, const fs::path& dir) {
  std::error_code ec;
  if (!fs::create_directory(dir / "data", ec) && ec)
    throw EnvironmentError(quotePath(dir / "data") + ": cannot create the folder: " + ec.message());
  std::vector<DataFileRecord> records;
  for (const auto& [name, table] : tables) {
    std::string text;
    // Each header names its unit: "max_rel_error [-]", "ns_per_eval [ns]"; a text column stays bare.
    for (size_t i = 0; i < table.columns.size(); ++i) {
      const std::string unit = getColumnUnit(name, table.columns[i]);
      text += (i ? "," : "") + csvField(table.columns[i] + (unit.empty() ? "" : " [" + unit + "]"));
    }
    const std::string header = text;
    text += "\n";
    for (const auto& row : table.rows) {
      for (size_t i = 0; i < row.size(); ++i) text += (i ? "," : "") + csvField(row[i]);
      text += "\n";
    }
    writeNewFile(dir / "data" / (name + ".csv"), text);
    records.push_back({"data/" + name + ".csv", header, table.rows.size(), calcChecksum(text)});
  }
  return records;
}

namespace {

// The file's bytes. @throws EnvironmentError when it cannot be read.
std::string readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw EnvironmentError(quotePath(path) + ": cannot read: " + std::strerror(errno));
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A table from its CSV records; the columns are named without their units. @throws std::runtime_error on an empty
// table or a row of another length than the header.
Table toTable(std::vector<std::vector<std::string>> records, const std::string& source) {
  if (records.empty()) throw std::runtime_error(source + ": empty table");
  Table table;
  table.columns = std::move(records.front());
  for (std::string& column : table.columns) column = column.substr(0, column.find(" ["));  // the name, not the unit
  for (size_t i = 1; i < records.size(); ++i) {
    if (records[i].size() != table.columns.size())
      throw std::runtime_error(source + ": a row has " + std::to_string(records[i].size()) + " fields, the header " +
                               std::to_string(table.columns.size()));
    table.rows.push_back(std::move(records[i]));
  }
  return table;
}

}  // namespace

TableSet readTables(const fs::path& dir) {
  TableSet tables;
  if (!fs::is_directory(dir / "data"))
    throw std::runtime_error(quotePath(dir) + ": no data/ folder (not a crankcheck report or shard)");
  for (const auto& entry : fs::directory_iterator(dir / "data")) {
    if (entry.path().extension() != ".csv") continue;
    const std::string source = quotePath(entry.path());
    tables[entry.path().stem().string()] = toTable(parseCsv(readBytes(entry.path()), source), source);
  }
  return tables;
}

namespace {

// ------------------------------------------------------------------------------------------------------------
// A small document model rendered both as Markdown and as HTML.

struct Block {
  enum Kind { kHeading, kParagraph, kTable, kFigure } kind = kParagraph;
  std::string text = {};                       // heading / paragraph / caption
  std::vector<std::string> header = {};        // table
  std::vector<std::vector<std::string>> rows = {};
  std::string name = {};                       // figure stem (name.png, name.svg, data/name.csv); "#" on the title
};

// The blocks as a ReportDocument: index.md as written, index.html rendered from it by cmark-gfm.
ReportDocument toDocument(const std::vector<Block>& blocks, const std::string& title) {
  ReportDocument doc(title);
  for (const Block& b : blocks) {
    switch (b.kind) {
      case Block::kHeading:
        if (b.name != "#") doc.addHeading(b.name.empty() ? 2 : static_cast<int>(b.name.size()), b.text);  // "#": the title
        break;
      case Block::kParagraph: doc.addParagraph(b.text); break;
      case Block::kTable: doc.addTable(b.header, b.rows); break;
      case Block::kFigure: doc.addFigure(b.name, b.text); break;
    }
  }
  return doc;
}

std::vector<std::vector<std::string>> tableRows(const TableSet& tables, const std::string& name,
                                                const std::vector<std::string>& columns,
                                                const std::vector<bool>& numeric = {}) {
  std::vector<std::vector<std::string>> rows;
  const auto it = tables.find(name);
  if (it == tables.end()) return rows;
  std::vector<size_t> index;
  for (const auto& c : columns) index.push_back(columnOf(it->second, c));
  for (const auto& row : it->second.rows) {
    std::vector<std::string> out;
    for (size_t i = 0; i < index.size(); ++i) {
      const std::string& field = row[index[i]];
      out.push_back(i < numeric.size() && numeric[i] && !field.empty() ? shortNumber(toDouble(field), 4) : field);
    }
    rows.push_back(std::move(out));
  }
  return rows;
}

std::string today() {
  const std::time_t now = std::time(nullptr);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  return buffer;
}

// Rows of a table as maps column -> field (empty when the table is missing).
std::vector<std::map<std::string, std::string>> records(const TableSet& tables, const std::string& name) {
  std::vector<std::map<std::string, std::string>> out;
  const auto it = tables.find(name);
  if (it == tables.end()) return out;
  for (const auto& row : it->second.rows) {
    std::map<std::string, std::string> r;
    for (size_t i = 0; i < it->second.columns.size() && i < row.size(); ++i) r[it->second.columns[i]] = row[i];
    out.push_back(std::move(r));
  }
  return out;
}

std::string percent(double x) { return shortNumber(100.0 * x, std::fabs(100.0 * x) >= 10.0 ? 3 : 2) + " %"; }

// Part 4's claims: the paper's dividing line and its practical list, tested with stated thresholds on max |Q|
// relative to the single cylinder of the same cycle (the exact harmonics' maxima, gravity_significance).
void addGravityClaims(std::vector<Block>& doc, const TableSet& tables) {
  std::map<std::string, std::map<int, double>> ratio;  // cycle -> k -> max |Q| / max |Q|(k = 1)
  for (const auto& r : records(tables, "gravity_significance")) ratio[r.at("cycle")][std::stoi(r.at("k"))] = toDouble(r.at("ratio_to_k1"));
  if (ratio.empty()) return;
  const std::vector<int> matters = {1, 2, 3, 4, 5, 6, 8, 10, 12}, negligible = {7, 9, 11};
  auto list = [](const std::vector<int>& ks) {
    std::string s;
    for (int k : ks) s += (s.empty() ? "" : ", ") + std::to_string(k);
    return "{" + s + "}";
  };
  Block claims{Block::kTable, "", {"claim (Stanczak section 7)", "cycle", "test", "paper", "data", "deciding ratios", "verdict"}};
  std::string sentence;
  for (const auto& [cycle, by_k] : ratio) {
    if (by_k.size() < 12) continue;
    // The dividing line holds when every k it says matters has a larger max |Q| than every k it says is negligible.
    int k_low = matters.front(), k_high = negligible.front();
    for (int k : matters) if (by_k.at(k) < by_k.at(k_low)) k_low = k;
    for (int k : negligible) if (by_k.at(k) > by_k.at(k_high)) k_high = k;
    const double margin = by_k.at(k_low) / by_k.at(k_high);
    claims.rows.push_back({"gravity matters for k = 1..6, 8, 10, 12, negligible for 7, 9, 11", cycle,
                           "some threshold separates the two sets (min of the first / max of the second > 1)",
                           list(negligible) + " below all others", "smallest of the first: k = " + std::to_string(k_low) +
                               ", largest of the second: k = " + std::to_string(k_high),
                           "k = " + std::to_string(k_low) + ": " + shortNumber(by_k.at(k_low), 2) + ", k = " +
                               std::to_string(k_high) + ": " + shortNumber(by_k.at(k_high), 2) + " (ratio " +
                               shortNumber(margin, 2) + ")",
                           margin > 1.0 ? "holds, by a factor " + shortNumber(margin, 2) : "does not hold"});
    sentence += (sentence.empty() ? "" : " ") + cycle + ": the weakest engine the paper says gravity matters for (k = " +
                std::to_string(k_low) + ") has " + shortNumber(margin, 2) + " times the max |Q| of the strongest it calls " +
                "negligible (k = " + std::to_string(k_high) + ")" +
                (margin > 1.0 ? ", so the line holds for any threshold between " + shortNumber(by_k.at(k_high), 2) + " and " +
                                    shortNumber(by_k.at(k_low), 2) + " of the single cylinder's max |Q|, far below the "
                                    "thresholds at which the practical list is tested"
                              : ", so no threshold separates them") + ".";
    // The practical list: k = 1, 2, 4 (perhaps 3 and 6), at stated thresholds.
    for (const auto& [threshold, paper] : {std::pair<double, std::vector<int>>{1e-3, {1, 2, 4}},
                                           std::pair<double, std::vector<int>>{1e-5, {1, 2, 3, 4, 6}}}) {
      std::vector<int> data;
      std::string deciding;
      for (const auto& [k, x] : by_k) {
        if (x >= threshold) data.push_back(k);
        const bool in_paper = std::find(paper.begin(), paper.end(), k) != paper.end();
        if ((x >= threshold) != in_paper) deciding += (deciding.empty() ? "" : ", ") + ("k = " + std::to_string(k) + ": " + shortNumber(x, 2));
      }
      claims.rows.push_back({threshold == 1e-3 ? "gravity may matter for k = 1, 2, 4" : "... perhaps also for k = 3, 6", cycle,
                             "max |Q| >= " + shortNumber(threshold, 1) + " of the single cylinder's", list(paper), list(data),
                             deciding.empty() ? "-" : deciding, data == paper ? "holds" : "does not hold"});
    }
  }
  doc.push_back({Block::kParagraph,
                 "The paper (section 7): 'For k = 7, 9, 11 the influence of gravity on the motion can be neglected as "
                 "negligibly small, since, for example, for k = 7 a non-zero value of formula (16) was obtained only at "
                 "Lambda_14.' And its practical list: gravity 'may be significant in particular for heavy, medium- or "
                 "high-speed mechanisms with k = 1, 2, 4 (possibly also k = 3, 6)'. Both tested as claims, on max |Q| "
                 "relative to the single cylinder of the same cycle (the thresholds are stated in each row):"});
  doc.push_back(claims);
  if (!sentence.empty()) doc.push_back({Block::kParagraph, sentence});
}

// Part 8: the errata table, and the sentences that read it (every number from the data).
void addErrataPart(std::vector<Block>& doc, const TableSet& tables) {
  std::map<std::string, std::map<std::string, double>> value;  // item -> measure -> value
  Block table{Block::kTable, "", {"item", "printed", "holds", "measure", "value", "verdict"}};
  for (const auto& r : records(tables, "errata")) {
    value[r.at("item")][r.at("measure")] = toDouble(r.at("value"));
    table.rows.push_back({r.at("item"), r.at("printed"), r.at("holds"), r.at("measure"), shortNumber(toDouble(r.at("value")), 3),
                          r.at("verdict")});
  }
  doc.push_back(table);
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
  for (const std::string& t : text) doc.push_back({Block::kParagraph, t});
  doc.push_back({Block::kParagraph, "Details and the tests that assert each entry: docs/ERRATA.md. Data of every table and "
                                    "figure: data/*.csv."});
}

// Part 9: the balance table (computed, beside the textbook's claims), what the two-term rules miss, the figure.
void addBalancePart(std::vector<Block>& doc, const TableSet& tables, const std::string& heading, const std::string& caption) {
  doc.push_back({Block::kHeading, heading});
  doc.push_back({Block::kParagraph,
                 "Each layout is built on the base scene's crank, rod and piston at 6000 rpm, cylinders spaced along "
                 "the shaft (throws 0.1 m apart, the two cylinders of a shared pin 0.02 m apart, O in the middle). F1, F2: "
                 "primary and secondary shaking force [N]; M1, M2: primary and secondary couple about X and Y [N m]. "
                 "'Vanishes exactly' is decided in integers (sums of roots of unity over the throws), not read off a "
                 "small number; the amplitudes are the closed form's, Simbody's and MuJoCo's (a DFT of each engine's own "
                 "shaking force and moment over one revolution). The textbook column is the claim of the standard balance tables "
                 "(two-term piston motion, both cylinders of a pin in one plane). A DIFFERS is a finding, not a failure "
                 "of the engines (they agree, see the summary): for example the 0.02 m between the two cylinders of a "
                 "shared pin, which the tables ignore, gives a flat-plane V8 a secondary couple."});
  doc.push_back({Block::kTable, "",
                 {"layout", "part", "textbook", "vanishes exactly", "amplitude (closed form)", "amplitude (Simbody)",
                  "amplitude (MuJoCo)", "relative", "verdict"},
                 tableRows(tables, "balance",
                           {"layout", "part", "textbook", "vanishes_exactly", "analytic_amplitude", "simbody_amplitude",
                            "mujoco_amplitude", "relative_amplitude", "verdict"},
                           {false, false, false, false, true, true, true, true, false})});
  // Beyond the two-term rules: the largest harmonic above 2 that the exact motion leaves, per layout.
  const auto it = tables.find("balance_harmonics");
  if (it != tables.end()) {
    const Table& t = it->second;
    const size_t layout = columnOf(t, "layout"), n = columnOf(t, "n"), force = columnOf(t, "force_relative"),
                 couple = columnOf(t, "couple_relative");
    std::map<std::string, std::pair<std::string, double>> worst_force, worst_couple;
    std::vector<std::string> order;
    for (const auto& row : t.rows) {
      if (!worst_force.count(row[layout])) order.push_back(row[layout]);
      auto& wf = worst_force[row[layout]];
      auto& wc = worst_couple[row[layout]];
      if (std::stoi(row[n]) <= 2) continue;
      if (toDouble(row[force]) > wf.second) wf = {row[n], toDouble(row[force])};
      if (toDouble(row[couple]) > wc.second) wc = {row[n], toDouble(row[couple])};
    }
    Block beyond{Block::kTable, "", {"layout", "largest force harmonic above 2", "relative [-]", "largest couple harmonic above 2", "relative [-]"}};
    for (const std::string& name : order) {
      const auto& f = worst_force[name];
      const auto& c = worst_couple[name];
      beyond.rows.push_back({name, f.first.empty() ? "none up to 8" : "n = " + f.first, shortNumber(f.second, 3),
                             c.first.empty() ? "none up to 8" : "n = " + c.first, shortNumber(c.second, 3)});
    }
    doc.push_back({Block::kParagraph,
                   "Where the textbook rules hold only for the two-term approximation: the exact piston motion has "
                   "harmonics 4, 6, 8, ... (and the rod's swing odd ones in the couples), which the tables do not "
                   "consider. The largest that survives each layout's symmetry, relative to the force (moment) scale:"});
    doc.push_back(beyond);
  }
  doc.push_back({Block::kFigure, caption, {}, {}, "balance_harmonics"});
}

}  // namespace

void renderReport(const TableSet& input, const ReportInfo& info, const fs::path& dir) {
  TableSet tables = input;
  sortTables(tables);  // first: the derived tables then do not depend on the order tasks ran in
  for (const Part* part : listParts()) part->derive(tables);
  sortTables(tables);
  writeTables(tables, dir);

  struct Figure {
    std::string name, heading, caption;
  };
  const std::vector<Figure> figures = {
      {"error_vs_lambda", "1. Error against lambda",
       "Max error over the crank turn against lambda, relative to the quantity's scale (r, r w, r w^2 for x, v, a; "
       "the energy scale for Q and U): Norton's two-term x, v, a; Q from Fourier series of order 2-12 with exact "
       "coefficients, from the paper's printed coefficients (eq 15) and with eq (5) as printed; analytic against Simbody"},
      {"speed_vs_error", "2. Speed against error",
       "Cost per evaluation of Q against its error, all measured in one run on this machine: the exact closed form, "
       "Fourier orders, the printed eq (15), Simbody at several projection tolerances; the Pareto front joined"},
      {"harmonics", "3. Harmonics of Q",
       "Harmonics of Q by a DFT of Simbody's Q(phi) (64 angles, lambda = 0.4, standing engines), with the analytic "
       "prediction (circles) and the paper's table 1 / eq (18) (crosses)"},
      {"gravity_significance", "4. When gravity matters",
       "Max |Q| against k, relative to k = 1 and relative to the inertia torque at the base scene's speed"},
      {"norton_fig13_8", "5. Piston motion (after Norton fig. 13-8)",
       "Piston position, velocity and acceleration over two revolutions, exact and Norton's two-term (13.3c-e), for "
       "the base scene"},
      {"delta_vs_k", "6. Speed fluctuation due to gravity in the free run",
       "The free run (released at phi = 0, no drive, no load, standing engines with the base scene's flywheel): "
       "|delta with gravity - delta without| against k at several speeds; dashed: delta of the varying inertia alone. "
       "Where the solid line lies far below the dashed one, gravity can be neglected at that speed"},
      {"integrator_pareto", "7. Simbody's integrators",
       "Simbody's free run by RungeKuttaMerson, CPodes and SemiExplicitEuler2 at accuracies 1e-3 to 1e-10: cost per "
       "simulated revolution (one Google Benchmark run) against the relative error of delta and the energy drift per "
       "revolution, the analytic energy integral as reference"},
      {"balance_harmonics", "9. Balance of engine layouts",
       "The shaking force and the couple about X and Y of every layout of the balance table (and of the campaign's "
       "own scenes, below the layouts, when scene files were given), harmonics 1-8, relative "
       "to the force and moment scales: closed form from the exact Fourier coefficients (Simbody's DFT agrees, see the "
       "summary); white with a dot where the harmonic vanishes exactly by the layout's symmetry"},
      {"torque_split", "10. The working torque: gas, inertia and gravity",
       "The drive torque over one working cycle of a car inline four (the base scene's parts, bore 2 r, the example "
       "spark-ignition pressure table, 6000 rpm) and of the marine two-stroke (bore 2 r / 3, a diesel table), split "
       "into its gas, inertia and gravity parts (each the analytic drive torque with the other loads off; Simbody's "
       "whole drive torque as dots); right: gravity's share of the mean absolute drive torque against k, at 600 and "
       "6000 rpm, both strokes (gravity torques below double precision left out): the sources' question answered "
       "against the real working torque"},
      {"rod_models", "11. What the two-mass rod costs",
       "The largest drive-torque error over the turn of the two-mass rod (m_k1 at the wrist pin, m_k3 at the crank "
       "pin) against Simbody's rigid rod, relative to the torque scale, against lambda and against Delta_I / I_G, for "
       "the car and the marine engine; dashed: the paper's two-mass rod with Delta_I, exact to rounding"},
      {"pin_load_polar", "12. Pin loads over a working cycle (polar diagrams)",
       "The crank-pin force of cylinder 0 (crank on rod, in the crank's own frame: x radial outward along the throw, y "
       "tangential in the direction of rotation) and the main-bearing force (frame on the crankshaft at O, all throws, "
       "frame X, Y) over one working cycle at each scene's speed with its gas and gravity, as the tip of the force "
       "vector (after Norton's Program ENGINE); analytic lines, Simbody dots"},
  };
  // One gnuplot per figure, up to info.jobs at a time (each writes only its own NAME.svg and NAME.png).
  std::vector<std::string> to_draw;
  for (const Figure& f : figures)
    if (tables.count(f.name)) to_draw.push_back(f.name);
  for (const Part* part : listParts())
    for (const std::string& figure : part->figures())
      if (tables.count(figure)) to_draw.push_back(figure);
  std::atomic<size_t> next{0};
  std::mutex error_mutex;
  std::exception_ptr error;
  auto drawer = [&] {
    for (size_t i = next++; i < to_draw.size(); i = next++) {
      try {
        drawFigure(to_draw[i], dir);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
      }
    }
  };
  std::vector<std::thread> drawers;
  for (int j = 1; j < std::min<int>(std::max(info.jobs, 1), static_cast<int>(to_draw.size())); ++j) drawers.emplace_back(drawer);
  drawer();
  for (std::thread& t : drawers) t.join();
  if (error) std::rethrow_exception(error);

  const std::vector<SummaryRow> summary = summarize(tables);
  const bool all_pass = std::all_of(summary.begin(), summary.end(), [](const SummaryRow& s) { return s.pass; });
  std::vector<Block> doc;
  doc.push_back({Block::kHeading, info.title, {}, {}, "#"});
  std::ostringstream meta;
  meta << "Generated " << today() << " by crankcheck " << getCrankcheckVersion() << " with Simbody " << simbody_models::getSimbodyVersion()
       << ", MuJoCo " << mujoco_models::getMujocoVersion()
       << ", compiler " << __VERSION__ << ", " << info.gnuplot_version << ". Campaign: "
       << (info.quick ? "quick" : "full") << ", " << info.jobs << " job(s)" << (info.shards > 1 ? ", merged from " + std::to_string(info.shards) + " shards" : "")
       << (info.seconds > 0 ? ", " + shortNumber(info.seconds, 3) + " s" : "") << ".";
  doc.push_back({Block::kParagraph, meta.str()});

  // The verdict first: one line per engine, the closing line, and the engine x quantity matrix (verdict.h).
  const std::vector<EngineVerdict> verdicts = calcVerdicts(tables);
  doc.push_back({Block::kHeading, "Verdict"});
  std::string closing = formatVerdict(verdicts);
  closing = closing.substr(closing.rfind('\n', closing.size() - 2) + 1);
  closing.pop_back();
  doc.push_back({Block::kParagraph, std::string(allAgree(verdicts) ? "**Pass.** " : "**FAIL.** ") + closing + "."});
  Block verdict_table{Block::kTable, "", {"engine", "gated", "cases", "comparisons", "worst error / tolerance [-]",
                                          "worst error / scale [-]", "of", "result"}};
  std::string where;  // each engine's worst comparison, for the sentence under the matrix
  for (const EngineVerdict& v : verdicts) {
    verdict_table.rows.push_back({v.engine, v.gated ? "gated" : "measured", std::to_string(v.cases),
                                  std::to_string(v.comparisons), v.gated ? formatMatrixCell(v.worst_ratio) : "-",
                                  shortNumber(v.worst_error), v.worst_quantity,
                                  !v.gated ? "reported" : v.failed == 0 ? "pass" : "FAIL (" + std::to_string(v.failed) + ")"});
    where += (where.empty() ? "" : "; ") + v.engine + ": " + v.worst_quantity + " at " + v.worst_where;
  }
  doc.push_back(verdict_table);
  const VerdictMatrix matrix = calcVerdictMatrix(tables);
  doc.push_back({Block::kParagraph, "Worst error / tolerance by quantity and gated engine (green up to 1/8, yellow up to "
                                    "1/2, orange up to 1, red beyond: FAIL):"});
  Block matrix_table{Block::kTable, "", {"quantity"}};
  for (const std::string& e : matrix.engines) matrix_table.header.push_back(e + " [-]");
  for (size_t q = 0; q < matrix.quantities.size(); ++q) {
    std::vector<std::string> row = {matrix.quantities[q]};
    for (size_t e = 0; e < matrix.engines.size(); ++e) row.push_back(formatMatrixCell(matrix.ratio[e][q]));
    matrix_table.rows.push_back(row);
  }
  doc.push_back(matrix_table);
  doc.push_back({Block::kParagraph,
                 "A comparison is one quantity of one case (a scene at one lambda), the worst over its crank angles and "
                 "speeds, judged by the gate's rule |analytic - engine| <= 64 eps x scale x conditioning "
                 "(docs/CONVENTIONS-crankcheck.md); soft engines are measured, never gated. The worst comparisons: " +
                     where + "."});

  doc.push_back({Block::kHeading, "Summary: the analytic engine against every exact engine"});
  doc.push_back({Block::kParagraph,
                 std::string(all_pass ? "Every comparison agrees" : "SOME COMPARISONS FAIL") +
                     " within the gate's rule: |analytic - engine| <= 64 eps x scale x conditioning "
                     "(docs/CONVENTIONS-crankcheck.md), for each exact engine (Simbody, MuJoCo with exact multipliers). "
                     "Errors are relative to the quantity's physical scale. MuJoCo's soft solver is measured in part 13, "
                     "not gated."});
  Block summary_table{Block::kTable, "", {"engine", "quantity", "family", "worst error / scale [-]", "where", "tolerance / scale [-]", "result"}};
  for (const SummaryRow& s : summary)
    summary_table.rows.push_back({s.engine, s.quantity, s.family, shortNumber(s.worst_rel_error), s.where, shortNumber(s.tolerance_rel),
                                  s.pass ? "pass" : "FAIL"});
  doc.push_back(summary_table);

  doc.push_back({Block::kHeading, "Scenes"});
  doc.push_back({Block::kParagraph,
                 "Each scene is cross-checked at its own lambda and, in the full campaign, with the rod lengthened or "
                 "shortened to lambda = 0.1, 0.2, 0.3, 0.4, 0.6, 0.9. The first scene is the base of the figures. SI units."});
  doc.push_back({Block::kTable, "",
                 {"scene", "family", "k", "cycle", "gamma [deg]", "speed [rpm]", "r [m]", "l [m]", "lambda [-]", "m_o [kg]", "m_k [kg]",
                  "z_k [m]", "I_o [kg m^2]", "m_s [kg]", "r_s [m]", "m_p [kg]", "r_p [m]", "g [m/s^2]", "I_w [kg m^2]"},
                 tableRows(tables, "scenes",
                           {"scene", "family", "cylinders", "cycle", "gamma_deg", "speed_rpm", "r", "l", "lambda", "m_o", "m_k", "z_k",
                            "I_o", "m_s", "r_s", "m_p", "r_p", "g", "I_w"},
                           {false, false, false, false, true, true, true, true, true, true, true, true, true, true, true, true, true, true, true})});
  doc.push_back({Block::kParagraph,
                 "Every value used is shown. Where a scene file leaves a key out, crankcheck uses the default of "
                 "docs/SCENE-FORMAT.md: g = 9.80665 m/s^2, single acting, no counterweight (m_p = 0), throw angles from "
                 "eqs (8)-(11). I_w is the flywheel inertia, empty where the scene has none."});
  for (const auto& note : tableRows(tables, "notes", {"note"})) doc.push_back({Block::kParagraph, note[0]});

  for (const Figure& f : figures) {
    const std::string& name = f.name;
    if (!tables.count(name) || name == "balance_harmonics" || name == "torque_split" || name == "rod_models" ||
        name == "pin_load_polar")
      continue;  // parts 9-12 follow the errata
    doc.push_back({Block::kHeading, f.heading});
    doc.push_back({Block::kFigure, f.caption, {}, {}, name});
    if (name == "integrator_pareto")
      doc.push_back({Block::kTable, "", {"integrator", "accuracy [-]", "time per revolution [ns]", "delta error [-]", "energy drift [-]", "status"},
                     tableRows(tables, name, {"integrator", "accuracy", "ns_per_revolution", "delta_error", "energy_drift", "status"},
                               {false, true, true, true, true, false})});
    if (name == "speed_vs_error") {
      doc.push_back({Block::kTable, "", {"method", "time per evaluation [ns]", "max error / energy scale [-]", "resolved"},
                     tableRows(tables, name, {"method", "ns_per_eval", "max_rel_error", "resolved"}, {false, true, true, false})});
      doc.push_back({Block::kParagraph,
                     "Each error is the maximum over the turn (the Fourier series' from the exact harmonics they leave "
                     "out, the others refined from 72 samples by Brent's method). resolved = 0: the error is at rounding "
                     "level (below 100 x 64 eps of the energy scale), the number is a bound, not a measured maximum."});
    }
    if (name == "gravity_significance") {
      doc.push_back({Block::kParagraph,
                     "max |Q| is the maximum over the turn of Q's exact harmonics (no cancellation, so it is exact however "
                     "small); Simbody's is found on the same grid (6 samples per period of the first surviving harmonic, at least 48) "
                     "and refined the same way (Brent's method). Where Simbody's max |Q| is below its rounding bound (64 eps "
                     "of the energy scale) it shows only that |Q| is below the bound: 'Simbody resolves' = no, and the "
                     "figure draws the bound as an arrow down."});
      doc.push_back({Block::kTable, "", {"cycle", "k", "first order", "max |Q| [N m]", "/ k = 1", "max inertia torque [N m]", "max |Q| / inertia", "Simbody max |Q| [N m]", "Simbody resolves", "rounding bound [N m]"},
                     tableRows(tables, name, {"cycle", "k", "first_order", "max_abs_Q", "ratio_to_k1", "max_inertia_torque", "ratio_to_inertia", "simbody_max_abs_Q", "resolved", "simbody_bound"},
                               {false, false, false, true, true, true, true, true, false, true})});
      addGravityClaims(doc, tables);
    }
  }
  doc.push_back({Block::kHeading, "8. Errata: the sources as printed against what the engines agree on"});
  addErrataPart(doc, tables);
  for (const Figure& f : figures) {
    if (!tables.count(f.name)) continue;
    if (f.name == "balance_harmonics") addBalancePart(doc, tables, f.heading, f.caption);
    if (f.name == "torque_split" || f.name == "rod_models" || f.name == "pin_load_polar") {
      doc.push_back({Block::kHeading, f.heading});
      doc.push_back({Block::kFigure, f.caption, {}, {}, f.name});
    }
    if (f.name == "pin_load_polar") {
      doc.push_back({Block::kParagraph,
                     "The largest force over the cycle, each engine (the samples, the best two refined by Brent's method), and the "
                     "largest difference of the two engines over the samples relative to the force scale:"});
      doc.push_back({Block::kTable, "", {"scene", "engine", "force", "max |F| [N]", "max |analytic - Simbody| / force scale [-]"},
                     tableRows(tables, "pin_load_polar_summary", {"scene", "engine", "force", "max_magnitude", "max_difference_rel"},
                               {false, false, false, true, true})});
    }
  }
  // The registered parts (parts.h), each described by its own file.
  for (const Part* part : listParts()) {
    const ReportPart described = part->describe(tables);
    if (described.heading.empty()) continue;
    doc.push_back({Block::kHeading, described.heading});
    doc.push_back({Block::kFigure, described.caption, {}, {}, part->key()});
    for (const std::string& paragraph : described.paragraphs) doc.push_back({Block::kParagraph, paragraph});
    if (!described.header.empty()) doc.push_back({Block::kTable, "", described.header, described.rows});
  }

  const ReportDocument page = toDocument(doc, info.title);
  writeNewFile(dir / "index.md", page.toMarkdown());
  writeNewFile(dir / "index.html", page.toHtml());
}

namespace {

// shard.json's format: 2 added the campaign's identity (version, scenes' content) and the data files' records.
constexpr int kShardFormat = 2;

}  // namespace

void writeShardManifest(const ShardManifest& manifest, const fs::path& dir) {
  nlohmann::json scenes = nlohmann::json::array(), files = nlohmann::json::array();
  for (const ShardScene& scene : manifest.scenes) scenes.push_back({{"name", scene.name}, {"fnv1a64", scene.checksum}});
  for (const DataFileRecord& f : manifest.files)
    files.push_back({{"path", f.path}, {"header", f.header}, {"rows", f.rows}, {"fnv1a64", f.checksum}});
  nlohmann::json j = {{"crankcheck_shard", kShardFormat}, {"version", manifest.version}, {"index", manifest.index},
                      {"count", manifest.count},          {"quick", manifest.quick},     {"scenes", scenes},
                      {"tasks", manifest.tasks},          {"files", files}};
  writeNewFile(dir / "shard.json", j.dump(2) + "\n");
}

ShardManifest readShardManifest(const fs::path& dir) {
  std::ifstream in(dir / "shard.json");
  if (!in) throw std::runtime_error(quotePath(dir) + ": no shard.json (not a shard written by crankcheck validate --shard)");
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    const int format = j.at("crankcheck_shard").get<int>();
    if (format != kShardFormat)
      throw std::runtime_error(quotePath(dir / "shard.json") + ": a shard of format " + std::to_string(format) +
                               ", written by another crankcheck; this one (" + getCrankcheckVersion() +
                               ") merges format " + std::to_string(kShardFormat) + ": run the shard again");
    ShardManifest m;
    m.version = j.at("version").get<std::string>();
    m.index = j.at("index").get<int>();
    m.count = j.at("count").get<int>();
    m.quick = j.at("quick").get<bool>();
    for (const auto& scene : j.at("scenes"))
      m.scenes.push_back({scene.at("name").get<std::string>(), scene.at("fnv1a64").get<std::string>()});
    m.tasks = j.at("tasks").get<int>();
    for (const auto& f : j.at("files"))
      m.files.push_back({f.at("path").get<std::string>(), f.at("header").get<std::string>(), f.at("rows").get<size_t>(),
                         f.at("fnv1a64").get<std::string>()});
    if (m.count < 2 || m.index < 0 || m.index >= m.count)
      throw std::runtime_error(quotePath(dir / "shard.json") + ": malformed: shard " + std::to_string(m.index) +
                               " of " + std::to_string(m.count));
    return m;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(quotePath(dir / "shard.json") + ": malformed: " + e.what());
  }
}

TableSet readShardTables(const fs::path& dir, const ShardManifest& manifest) {
  // Every file crankcheck-manifest.json lists (what the shard wrote, shard.json among them) must be there.
  const fs::path listing = dir / kManifestName;
  std::set<std::string> listed;
  try {
    std::ifstream in(listing);
    if (!in) throw std::runtime_error(quotePath(listing) + ": missing: every shard crankcheck writes has it");
    const nlohmann::json j = nlohmann::json::parse(in);
    if (j.at("tool").get<std::string>() != "crankcheck" || j.at("kind").get<std::string>() != "shard")
      throw std::runtime_error(quotePath(listing) + ": not a shard's manifest (tool " + j.at("tool").dump() + ", kind " +
                               j.at("kind").dump() + ")");
    for (const auto& f : j.at("files")) listed.insert(f.get<std::string>());
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(quotePath(listing) + ": malformed: " + e.what());
  }
  std::error_code ec;
  for (const std::string& rel : listed)
    if (!fs::is_regular_file(fs::symlink_status(dir / rel, ec)))
      throw std::runtime_error(quotePath(dir / rel) + ": missing, though the shard's " + kManifestName + " lists it");
  // shard.json records exactly the data files listed, and data/ holds no other.
  std::set<std::string> recorded;
  for (const DataFileRecord& f : manifest.files) {
    const fs::path path(f.path);
    if (!recorded.insert(f.path).second || !listed.count(f.path) || path.parent_path() != "data" ||
        path.extension() != ".csv")
      throw std::runtime_error(quotePath(dir / "shard.json") + ": records " + quotePath(f.path) + ", which the shard's " +
                               kManifestName + " does not list as a data file");
  }
  for (const std::string& rel : listed)
    if (rel.rfind("data/", 0) == 0 && !recorded.count(rel))
      throw std::runtime_error(quotePath(dir / rel) + ": not listed in the shard's shard.json");
  if (!fs::is_directory(dir / "data")) throw std::runtime_error(quotePath(dir / "data") + ": missing");
  for (const auto& entry : fs::directory_iterator(dir / "data")) {
    const std::string rel = "data/" + entry.path().filename().string();
    if (!recorded.count(rel))
      throw std::runtime_error(quotePath(entry.path()) + ": not listed in the shard's manifest: not written by the shard");
  }
  // Each data file as the shard wrote it: its header, its rows, its checksum.
  TableSet tables;
  for (const DataFileRecord& f : manifest.files) {
    const fs::path path = dir / f.path;
    const std::string source = quotePath(path);
    const std::string text = readBytes(path);
    std::vector<std::vector<std::string>> records = parseCsv(text, source);
    const std::string header = text.substr(0, text.find('\n'));
    if (header != f.header)
      throw std::runtime_error(source + ": header " + quotePath(header.substr(0, 80)) + ", the shard wrote " +
                               quotePath(f.header.substr(0, 80)));
    const size_t rows = records.empty() ? 0 : records.size() - 1;
    if (rows != f.rows)
      throw std::runtime_error(source + ": " + std::to_string(rows) + " rows, the shard wrote " + std::to_string(f.rows));
    const std::string checksum = calcChecksum(text);
    if (checksum != f.checksum)
      throw std::runtime_error(source + ": not the content the shard wrote (FNV-1a 64 " + checksum + ", shard.json records " +
                               f.checksum + ")");
    tables[fs::path(f.path).stem().string()] = toTable(std::move(records), source);
  }
  return tables;
}

std::string checkGnuplot() {
  if (findProgram("gnuplot").empty())
    throw EnvironmentError("gnuplot: not found on PATH; the report's figures need it (Debian package gnuplot-nox, "
                           "which ./run.sh installs)");
  ProgramCall call{{"gnuplot", "--version"}};
  call.timeout_seconds = kGnuplotVersionSeconds;
  const ProgramResult r = runProgram(call);
  if (r.timed_out)
    throw EnvironmentError("gnuplot: 'gnuplot --version' did not answer within " + formatNumber(kGnuplotVersionSeconds) +
                           " s; gnuplot was ended");
  std::string version = r.out;
  while (!version.empty() && (version.back() == '\n' || version.back() == '\r')) version.pop_back();
  if (r.exit_status != 0 || version.empty())
    throw EnvironmentError("gnuplot: 'gnuplot --version' failed: " + r.err);
  return version;
}

}  // namespace crankcheck::validation
