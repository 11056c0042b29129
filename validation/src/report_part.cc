#include "crankcheck/validation/report_part.h"

#include <cstdlib>

#include "crankcheck/validation/report_format.h"

namespace crankcheck::validation {

std::vector<std::vector<std::string>> formatRows(const TableSet& tables, const std::string& name,
                                                 const std::vector<std::string>& columns, const std::vector<bool>& numeric) {
  std::vector<std::vector<std::string>> rows;
  const auto it = tables.find(name);
  if (it == tables.end()) return rows;
  std::vector<size_t> index;
  for (const auto& c : columns) index.push_back(columnOf(it->second, c));
  const Table& table = it->second;
  for (size_t r = 0; r < table.size(); ++r) {
    std::vector<std::string> out;
    for (size_t i = 0; i < index.size(); ++i) {
      const Cell cell = table.cell(r, index[i]);
      const std::string* text = std::get_if<std::string>(&cell);
      const bool as_number = i < numeric.size() && numeric[i];
      if (const double* x = std::get_if<double>(&cell); x && as_number) out.push_back(shortNumber(*x, 4));
      else if (text && as_number && !text->empty()) out.push_back(shortNumber(std::strtod(text->c_str(), nullptr), 4));  // a table without a schema
      else out.push_back(formatCell(cell));
    }
    rows.push_back(std::move(out));
  }
  return rows;
}

std::vector<std::map<std::string, std::string>> readRecords(const TableSet& tables, const std::string& name) {
  std::vector<std::map<std::string, std::string>> out;
  const auto it = tables.find(name);
  if (it == tables.end()) return out;
  for (size_t k = 0; k < it->second.size(); ++k) {
    const std::vector<std::string> row = it->second.formatRow(k);
    std::map<std::string, std::string> r;
    for (size_t i = 0; i < it->second.columns().size() && i < row.size(); ++i) r[it->second.columns()[i].name] = row[i];
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace crankcheck::validation
