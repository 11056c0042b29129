#include "crankcheck/validation/report_part.h"

#include <cstdlib>

namespace crankcheck::validation {

std::vector<std::vector<std::string>> formatRows(const TableSet& tables, const std::string& name,
                                                 const std::vector<std::string>& columns, const std::vector<bool>& numeric) {
  std::vector<std::vector<std::string>> rows;
  const auto it = tables.find(name);
  if (it == tables.end()) return rows;
  std::vector<size_t> index;
  for (const auto& c : columns) index.push_back(columnOf(it->second, c));
  for (size_t r = 0; r < it->second.size(); ++r) {
    const std::vector<std::string> row = it->second.formatRow(r);
    std::vector<std::string> out;
    for (size_t i = 0; i < index.size(); ++i) {
      const std::string& field = row[index[i]];
      out.push_back(i < numeric.size() && numeric[i] && !field.empty() ? shortNumber(std::strtod(field.c_str(), nullptr), 4)
                                                                       : field);
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
