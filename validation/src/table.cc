#include "crankcheck/validation/table.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>

namespace crankcheck::validation {

std::string formatNumber(double x) {
  char buffer[40];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, x + 0.0).ptr;  // shortest round-trip; -0 as 0
  return std::string(buffer, end);
}

std::string formatCell(const Cell& cell) {
  if (const double* x = std::get_if<double>(&cell)) return formatNumber(*x);
  if (const std::string* s = std::get_if<std::string>(&cell)) return *s;
  return {};
}

namespace {

// @throws std::logic_error for a number's column without a unit or a column named twice.
void checkColumns(const std::string& name, const std::vector<Column>& columns) {
  for (size_t i = 0; i < columns.size(); ++i) {
    const Column& c = columns[i];
    if (!c.text && c.unit.empty())
      throw std::logic_error("table " + name + ": column " + c.name + " is a number without a unit (declare its unit, "
                             "or kText for a text column)");
    for (size_t j = 0; j < i; ++j)
      if (columns[j].name == c.name) throw std::logic_error("table " + name + ": column " + c.name + " twice");
  }
}

}  // namespace

TableSchema::TableSchema(std::string name, std::vector<Column> columns)
    : name_(std::move(name)), columns_(std::move(columns)) {
  checkColumns(name_, columns_);
}

Table::Table(const std::string& name, std::vector<Column> columns) : columns_(std::move(columns)) {
  checkColumns(name, columns_);
}

Table::Table(const Table& other)
    : rows(other.rows), columns_(other.columns_), schema_(other.schema_), typed_(other.typed_ ? other.typed_->clone() : nullptr) {}

Table& Table::operator=(const Table& other) {
  if (this != &other) *this = Table(other);
  return *this;
}

std::vector<std::string> Table::names() const {
  std::vector<std::string> out;
  for (const Column& c : columns_) out.push_back(c.name);
  return out;
}

Cell Table::cell(size_t row, size_t column) const {
  if (typed_) return typed_->cell(row, column);
  return Cell(rows.at(row).at(column));
}

std::vector<std::string> Table::formatRow(size_t row) const {
  if (!typed_) return rows.at(row);
  std::vector<std::string> out;
  out.reserve(columns_.size());
  for (size_t c = 0; c < columns_.size(); ++c) out.push_back(formatCell(typed_->cell(row, c)));
  return out;
}

void Table::appendCells(std::vector<Cell> cells) {
  if (cells.size() != columns_.size())
    throw std::invalid_argument("a row of " + std::to_string(cells.size()) + " cells for " +
                                std::to_string(columns_.size()) + " columns");
  for (size_t i = 0; i < cells.size(); ++i) {
    const bool ok = columns_[i].text ? std::holds_alternative<std::string>(cells[i])
                                     : !std::holds_alternative<std::string>(cells[i]);
    if (!ok) throw std::invalid_argument("column " + columns_[i].name + ": a cell of another kind");
  }
  if (typed_) {
    typed_->appendCells(std::move(cells));
    return;
  }
  std::vector<std::string> fields;
  for (const Cell& c : cells) fields.push_back(formatCell(c));
  rows.push_back(std::move(fields));
}

void Table::append(const Table& other, const std::string& name) {
  if (columns_ != other.columns_ || schema_ != other.schema_)
    throw std::runtime_error("table " + name + ": columns differ");
  if (typed_) typed_->appendRows(*other.typed_);
  else rows.insert(rows.end(), other.rows.begin(), other.rows.end());
}

namespace {

// A field of a table of formatted fields, as the sort compares it: a number when it reads as one.
Cell sortKeyOf(const std::string& field) {
  if (field.empty()) return {};
  {
    char* end = nullptr;
    const double x = std::strtod(field.c_str(), &end);
    if (end == field.c_str() + field.size()) return x;
  }
  return field;
}

// a < b: an empty cell first, numbers by value (NaN after every number), text as text; a number and text (a table of
// formatted fields mixes them in a column) as text.
int compareCells(const Cell& a, const Cell& b) {
  if (a.index() != b.index()) {
    if (a.index() == 0 || b.index() == 0) return a.index() < b.index() ? -1 : 1;
    return formatCell(a).compare(formatCell(b));
  }
  if (const double* x = std::get_if<double>(&a)) {
    const double y = std::get<double>(b);
    if (std::isnan(*x) || std::isnan(y)) return std::isnan(*x) == std::isnan(y) ? 0 : std::isnan(*x) ? 1 : -1;
    return *x < y ? -1 : *x > y ? 1 : 0;
  }
  if (const std::string* s = std::get_if<std::string>(&a)) return s->compare(std::get<std::string>(b));
  return 0;
}

}  // namespace

void Table::sort() {
  const size_t n = size();
  if (n < 2) return;
  const size_t width = columns_.size();
  auto keyOf = [&](size_t r, size_t c) { return typed_ ? typed_->cell(r, c) : sortKeyOf(rows[r][c]); };
  auto widthOf = [&](size_t r) { return typed_ ? width : rows[r].size(); };
  // The second sort of a report finds most tables in order already: checked row against row, reading only the cells
  // up to the first that differs.
  bool sorted = true;
  for (size_t r = 1; r < n && sorted; ++r) {
    const size_t common = std::min(widthOf(r), widthOf(r - 1));
    int c = 0;
    for (size_t i = 0; i < common && c == 0; ++i) c = compareCells(keyOf(r - 1, i), keyOf(r, i));
    sorted = c < 0 || (c == 0 && widthOf(r - 1) <= widthOf(r));
  }
  if (sorted) return;
  // Each cell read once, not at every comparison.
  std::vector<std::vector<Cell>> keys(n);
  for (size_t r = 0; r < n; ++r) {
    keys[r].reserve(widthOf(r));
    for (size_t c = 0; c < widthOf(r); ++c) keys[r].push_back(keyOf(r, c));
  }
  auto less = [&](size_t a, size_t b) {
    const size_t common = std::min(keys[a].size(), keys[b].size());
    for (size_t i = 0; i < common; ++i)
      if (const int c = compareCells(keys[a][i], keys[b][i]); c != 0) return c < 0;
    return keys[a].size() < keys[b].size();
  };
  std::vector<size_t> order(n);
  for (size_t r = 0; r < n; ++r) order[r] = r;
  std::stable_sort(order.begin(), order.end(), less);
  if (typed_) {
    typed_->reorder(order);
    return;
  }
  std::vector<std::vector<std::string>> out;
  out.reserve(n);
  for (size_t r : order) out.push_back(std::move(rows[r]));
  rows = std::move(out);
}

void appendTables(TableSet& into, const TableSet& from) {
  for (const auto& [name, table] : from) {
    auto [it, inserted] = into.try_emplace(name, table);
    if (!inserted) it->second.append(table, name);
  }
}

void sortTables(TableSet& tables) {
  for (auto& [name, table] : tables) table.sort();
}

size_t columnOf(const Table& t, const std::string& name) {
  const auto& columns = t.columns();
  const auto it = std::find_if(columns.begin(), columns.end(), [&](const Column& c) { return c.name == name; });
  if (it == columns.end()) throw std::runtime_error("report: table has no column " + name);
  return static_cast<size_t>(it - columns.begin());
}

}  // namespace crankcheck::validation
