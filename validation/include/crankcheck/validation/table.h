#pragma once
/// @file
/// The report's tables as typed values. A table is declared once, as a plain row type and its Schema (each column's
/// name, unit and member); tasks return typed rows, a part's derive() and describe() read the rows' members, and text
/// exists only at the edge: the CSV files the report writes and `report merge` reads back (csv.h), through the same
/// schema. After Google Benchmark's reporters: typed values inside, text only where they are written.
///
///   struct TorsionRow { std::string scene; double speed_rpm = 0; double twist = 0; };
///   const Schema<TorsionRow> kTorsionTable{"torsion", {
///       textField("scene", &TorsionRow::scene),
///       numberField("speed_rpm", "rpm", &TorsionRow::speed_rpm),
///       numberField("twist", "rad", &TorsionRow::twist)}};
///   TableSet out = {{"torsion", kTorsionTable.table(rows)}};
///   for (const TorsionRow& row : getRows(tables, kTorsionTable)) ...

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace crankcheck::validation {

/// The unit of a text column (names, verdicts, flags): no unit, the CSV header names the column bare.
struct TextUnit {
  bool operator==(const TextUnit&) const = default;
};
/// A text column's unit: `Column{"engine", kText}`.
inline constexpr TextUnit kText{};

/// One column of a table: its name and its unit together. A number's unit is written in the CSV header,
/// "max_rel_error [-]": "-" for a dimensionless number (ratios, errors relative to a scale, counts, indices), "SI" where
/// the unit is the quantity's own (the row's quantity names it: J, N m, N, m, m/s, m/s^2, rad, ...), else the unit
/// ("N m", "deg", "rpm", "ns", ...). There is no column without a unit: a text column says kText.
struct Column {
  /// A number's column; `unit` must not be empty (Table refuses it).
  Column(std::string name, std::string unit) : name(std::move(name)), unit(std::move(unit)) {}
  /// A text column.
  Column(std::string name, TextUnit) : name(std::move(name)), text(true) {}

  std::string name;
  std::string unit;   ///< "" only for a text column
  bool text = false;  ///< a text column (kText): its header is the bare name

  bool operator==(const Column&) const = default;
};

/// One field of a row as the edge formats see it: empty (an absent optional number), a number, or text.
using Cell = std::variant<std::monostate, double, std::string>;

/// x in its shortest form that reads back to the same double (std::to_chars): 0.1, not 0.10000000000000001; -0 as 0.
std::string formatNumber(double x);

/// The CSV text of a cell: a number by formatNumber, empty for an empty cell.
std::string formatCell(const Cell& cell);

/// One column of a row type: its Column, and how to read its cell from a row and write a cell into one.
template <class Row>
struct Field {
  Column column;
  std::function<Cell(const Row&)> read;
  std::function<void(Row&, Cell)> write;  ///< the cell holds the column's kind (the CSV reader checked it)
};

/// A text column backed by a std::string member.
template <class Row>
Field<Row> textField(std::string name, std::string Row::*member) {
  return {Column(std::move(name), kText), [member](const Row& r) { return Cell(r.*member); },
          [member](Row& r, Cell c) { r.*member = std::get<std::string>(std::move(c)); }};
}

/// A number's column backed by a double member; `unit` as Column's.
template <class Row>
Field<Row> numberField(std::string name, std::string unit, double Row::*member) {
  return {Column(std::move(name), std::move(unit)), [member](const Row& r) { return Cell(r.*member); },
          [member](Row& r, Cell c) { r.*member = std::get<double>(c); }};
}

/// A count's or an index's column (unit "-") backed by an int member.
template <class Row>
Field<Row> countField(std::string name, int Row::*member) {
  return {Column(std::move(name), "-"), [member](const Row& r) { return Cell(static_cast<double>(r.*member)); },
          [member](Row& r, Cell c) { r.*member = static_cast<int>(std::get<double>(c)); }};
}

/// A number's column that may be empty (the scene has no flywheel: no I_w), backed by a std::optional<double>.
template <class Row>
Field<Row> optionalField(std::string name, std::string unit, std::optional<double> Row::*member) {
  return {Column(std::move(name), std::move(unit)),
          [member](const Row& r) { return r.*member ? Cell(*(r.*member)) : Cell(); },
          [member](Row& r, Cell c) {
            if (const double* x = std::get_if<double>(&c)) r.*member = *x;
            else r.*member = std::nullopt;
          }};
}

/// An index's column (unit "-") that may be empty, backed by a std::optional<int>.
template <class Row>
Field<Row> optionalCountField(std::string name, std::optional<int> Row::*member) {
  return {Column(std::move(name), "-"),
          [member](const Row& r) { return r.*member ? Cell(static_cast<double>(*(r.*member))) : Cell(); },
          [member](Row& r, Cell c) {
            if (const double* x = std::get_if<double>(&c)) r.*member = static_cast<int>(*x);
            else r.*member = std::nullopt;
          }};
}

/// A number's column backed by element `index` of a vector member (one column per engine, per judge, ...): a row whose
/// vector is shorter gives an empty cell; writing a cell grows the vector.
template <class Row>
Field<Row> elementField(std::string name, std::string unit, std::vector<double> Row::*list, size_t index) {
  return {Column(std::move(name), std::move(unit)),
          [list, index](const Row& r) { return index < (r.*list).size() ? Cell((r.*list)[index]) : Cell(); },
          [list, index](Row& r, Cell c) {
            std::vector<double>& v = r.*list;
            if (v.size() <= index) v.resize(index + 1);
            if (const double* x = std::get_if<double>(&c)) v[index] = *x;
          }};
}

/// elementField of a vector of optional numbers: an absent element gives an empty cell, an empty cell an absent one.
template <class Row>
Field<Row> elementField(std::string name, std::string unit, std::vector<std::optional<double>> Row::*list, size_t index) {
  return {Column(std::move(name), std::move(unit)),
          [list, index](const Row& r) {
            const auto& v = r.*list;
            return index < v.size() && v[index] ? Cell(*v[index]) : Cell();
          },
          [list, index](Row& r, Cell c) {
            auto& v = r.*list;
            if (v.size() <= index) v.resize(index + 1);
            if (const double* x = std::get_if<double>(&c)) v[index] = *x;
            else v[index] = std::nullopt;
          }};
}

/// A table's rows behind the type-erased Table: what the edge (CSV), the sort and the merge need of them.
class TableRows {
 public:
  virtual ~TableRows() = default;
  virtual std::unique_ptr<TableRows> clone() const = 0;
  virtual size_t size() const = 0;
  virtual Cell cell(size_t row, size_t column) const = 0;
  /// Appends a row made of cells, one per column, each of its column's kind.
  virtual void appendCells(std::vector<Cell> cells) = 0;
  /// Appends `other`'s rows (the same row type: Table checks the schema first).
  virtual void appendRows(const TableRows& other) = 0;
  /// Puts the rows in the order of `order` (a permutation of 0..size-1).
  virtual void reorder(const std::vector<size_t>& order) = 0;
};

class Table;

/// A table's declaration, whatever its row type: its name (the CSV stem) and its columns. Schema<Row> is the one to
/// declare; this base lets the CSV reader (`report merge`) make an empty table of a stem it reads.
class TableSchema {
 public:
  virtual ~TableSchema() = default;
  const std::string& name() const { return name_; }
  const std::vector<Column>& columns() const { return columns_; }
  /// An empty table of this schema (the CSV reader fills it).
  virtual Table makeTable() const = 0;

 protected:
  /// @throws std::logic_error naming the table and the column for a number's column with an empty unit, or a column
  ///         named twice.
  TableSchema(std::string name, std::vector<Column> columns);

 private:
  std::string name_;
  std::vector<Column> columns_;
};

template <class Row>
class Schema;

/// One table of the report: its columns (each with its unit) and its rows, typed (a Schema's) or, for the tables not
/// yet declared by a schema, rows of already formatted fields (`rows`, numbers by formatNumber). A value: copying it
/// copies its rows.
class Table {
 public:
  Table() = default;
  /// A table of formatted fields. @param name the table's name (the CSV stem), for the message only.
  /// @throws std::logic_error naming the table and the column for a number's column with an empty unit.
  Table(const std::string& name, std::vector<Column> columns);
  Table(const Table& other);
  Table& operator=(const Table& other);
  Table(Table&&) noexcept = default;
  Table& operator=(Table&&) noexcept = default;

  const std::vector<Column>& columns() const { return columns_; }
  /// The columns' names, in order.
  std::vector<std::string> names() const;
  /// The schema of a typed table; nullptr for a table of formatted fields.
  const TableSchema* schema() const { return schema_; }

  /// The number of rows.
  size_t size() const { return typed_ ? typed_->size() : rows.size(); }
  /// Row `row`'s cell in column `column` (a field of `rows`: as text).
  Cell cell(size_t row, size_t column) const;
  /// Row `row` as the CSV writes it: each cell by formatCell.
  std::vector<std::string> formatRow(size_t row) const;
  /// Appends a row of cells, one per column, each of its column's kind. @throws std::invalid_argument otherwise.
  void appendCells(std::vector<Cell> cells);
  /// Appends `other`'s rows. @throws std::runtime_error naming `name` if the columns or the row types differ.
  void append(const Table& other, const std::string& name);
  /// Sorts the rows column by column (numbers by value, text as text, an empty cell first): the report is the same
  /// whatever the order its tasks ran in, on one thread, several, or in shards.
  void sort();

  /// The typed rows. @throws std::logic_error if the table is not of `schema` (a programming error, never a user's).
  template <class Row>
  const std::vector<Row>& getRows(const Schema<Row>& schema) const;
  template <class Row>
  std::vector<Row>& getRows(const Schema<Row>& schema);

  /// The formatted fields of a table without a schema (empty for a typed one).
  std::vector<std::vector<std::string>> rows;

 private:
  template <class Row>
  friend class Schema;
  std::vector<Column> columns_;
  const TableSchema* schema_ = nullptr;
  std::unique_ptr<TableRows> typed_;
};

/// Tables by name (the CSV file stem).
using TableSet = std::map<std::string, Table>;

/// A table declared by its row type: the schema every table of the report is declared by, once.
template <class Row>
class Schema final : public TableSchema {
 public:
  Schema(std::string name, std::vector<Field<Row>> fields)
      : TableSchema(std::move(name), columnsOf(fields)), fields_(std::move(fields)) {}
  const std::vector<Field<Row>>& fields() const { return fields_; }

  /// A table of this schema holding `rows`.
  Table table(std::vector<Row> rows = {}) const {
    Table t;
    t.columns_ = columns();
    t.schema_ = this;
    t.typed_ = std::make_unique<Rows>(this, std::move(rows));
    return t;
  }
  Table makeTable() const override { return table(); }
  /// A TableSet holding one table of this schema, under its name.
  TableSet tableSet(std::vector<Row> rows) const { return {{name(), table(std::move(rows))}}; }

 private:
  static std::vector<Column> columnsOf(const std::vector<Field<Row>>& fields) {
    std::vector<Column> out;
    for (const Field<Row>& f : fields) out.push_back(f.column);
    return out;
  }
  std::vector<Field<Row>> fields_;

 public:
  /// The rows behind a table of this schema (Table::getRows reads them).
  class Rows final : public TableRows {
   public:
    Rows(const Schema* schema, std::vector<Row> rows) : schema_(schema), rows(std::move(rows)) {}
    std::unique_ptr<TableRows> clone() const override { return std::make_unique<Rows>(*this); }
    size_t size() const override { return rows.size(); }
    Cell cell(size_t row, size_t column) const override { return schema_->fields_[column].read(rows[row]); }
    void appendCells(std::vector<Cell> cells) override {
      Row row{};
      for (size_t i = 0; i < cells.size(); ++i) schema_->fields_[i].write(row, std::move(cells[i]));
      rows.push_back(std::move(row));
    }
    void appendRows(const TableRows& other) override {
      const auto& from = static_cast<const Rows&>(other).rows;
      rows.insert(rows.end(), from.begin(), from.end());
    }
    void reorder(const std::vector<size_t>& order) override {
      std::vector<Row> out;
      out.reserve(rows.size());
      for (size_t i : order) out.push_back(std::move(rows[i]));
      rows = std::move(out);
    }
    const Schema* schema_;
    std::vector<Row> rows;
  };
};

template <class Row>
const std::vector<Row>& Table::getRows(const Schema<Row>& schema) const {
  if (schema_ != &schema) throw std::logic_error("table " + schema.name() + ": read with another schema");
  return static_cast<const typename Schema<Row>::Rows&>(*typed_).rows;
}

template <class Row>
std::vector<Row>& Table::getRows(const Schema<Row>& schema) {
  if (schema_ != &schema) throw std::logic_error("table " + schema.name() + ": read with another schema");
  return static_cast<typename Schema<Row>::Rows&>(*typed_).rows;
}

/// The rows of `schema`'s table in `tables`; none when the table is missing.
template <class Row>
const std::vector<Row>& getRows(const TableSet& tables, const Schema<Row>& schema) {
  static const std::vector<Row> kNone;
  const auto it = tables.find(schema.name());
  return it == tables.end() ? kNone : it->second.getRows(schema);
}

/// Appends `rows` to `schema`'s table in `tables` (made when missing).
template <class Row>
void addRows(TableSet& tables, const Schema<Row>& schema, std::vector<Row> rows) {
  auto [it, inserted] = tables.try_emplace(schema.name(), schema.table());
  auto& into = it->second.getRows(schema);
  into.insert(into.end(), std::make_move_iterator(rows.begin()), std::make_move_iterator(rows.end()));
}

/// Appends `from`'s rows to `into`. @throws std::runtime_error if a table's columns differ.
void appendTables(TableSet& into, const TableSet& from);

/// Sorts every table's rows (Table::sort).
void sortTables(TableSet& tables);

/// The index of the column `name` in t. @throws std::runtime_error if t has no such column (a report part read a
/// table it did not build: a programming error, never a user's).
size_t columnOf(const Table& t, const std::string& name);

}  // namespace crankcheck::validation
