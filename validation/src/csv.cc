#include "crankcheck/validation/csv.h"

#include <charconv>
#include <string_view>
#include <stdexcept>


namespace crankcheck::validation {

namespace {

// RFC 4180: a field with a comma, a double quote or a line break is quoted, its quotes doubled. Only scene names
// (file names) can hold such characters; the numbers and names the figures read never do.
std::string csvField(const std::string& field) {
  if (field.find_first_of(",\"\r\n") == std::string::npos) return field;
  std::string out = "\"";
  for (char c : field) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// A text cell as a spreadsheet will not run it: a cell that begins with = + - @ (a formula), a tab or a carriage return
// gets a leading ' (OWASP's "CSV injection"), and so does one that begins with ' itself, so that parseCell's removal
// of one leading ' gives back exactly what was written. A lone "-" or "+" (an empty value's mark) is no formula and
// stays as it is. Number columns are never touched: a number's "-1.5" is a number to every reader.
std::string protectText(std::string text) {
  if (text.empty() || text == "-" || text == "+") return text;
  if (std::string_view("=+-@'\t\r").find(text.front()) != std::string_view::npos) text.insert(text.begin(), '\'');
  return text;
}

// What protectText wrote, read back: one leading ' removed.
std::string unprotectText(std::string text) {
  if (!text.empty() && text.front() == '\'') text.erase(text.begin());
  return text;
}

}  // namespace

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

namespace {

// A column's CSV header: "max_rel_error [-]", a text column's bare name.
std::string formatHeader(const Column& column) {
  return column.text ? column.name : column.name + " [" + column.unit + "]";
}

// The column a CSV header declares: "name [unit]" a number's, a bare name a text column's (formatHeader's inverse).
// @throws std::runtime_error on an empty unit, "name []".
Column parseHeader(const std::string& header, const std::string& source) {
  const size_t open = header.find(" [");
  if (open == std::string::npos || header.back() != ']') return Column(header, kText);
  const std::string unit = header.substr(open + 2, header.size() - open - 3);
  if (unit.empty()) throw std::runtime_error(source + ": column " + header.substr(0, open) + " has an empty unit");
  return Column(header.substr(0, open), unit);
}

std::string joinHeaders(const std::vector<Column>& columns) {
  std::string out;
  for (const Column& c : columns) out += (out.empty() ? "" : ",") + formatHeader(c);
  return out;
}

// A CSV field as a cell of `column`: text as it is; a number read back exactly (std::from_chars reads what
// formatNumber wrote, nan and inf too); an empty number field an empty cell.
Cell parseCell(const Column& column, std::string field, const std::string& source) {
  if (column.text) return unprotectText(std::move(field));
  if (field.empty()) return {};
  double x = 0.0;
  const char* first = field.data();
  const char* last = field.data() + field.size();
  const auto [end, error] = std::from_chars(first, last, x);
  if (error != std::errc() || end != last)
    throw std::runtime_error(source + ": column " + column.name + ": \"" + field.substr(0, 40) + "\" is not a number");
  return x;
}

}  // namespace

std::string formatCsv(const Table& table) {
  std::string text;
  for (size_t i = 0; i < table.columns().size(); ++i) text += (i ? "," : "") + csvField(formatHeader(table.columns()[i]));
  text += "\n";
  for (size_t r = 0; r < table.size(); ++r) {
    const std::vector<std::string> row = table.formatRow(r);
    for (size_t i = 0; i < row.size(); ++i)
      text += (i ? "," : "") + csvField(table.columns()[i].text ? protectText(row[i]) : row[i]);
    text += "\n";
  }
  return text;
}

// Table `name` from its CSV records; each column's unit from its header (parseHeader). @throws std::runtime_error on an
// empty table, an empty unit or a row of another length than the header.
Table parseTable(const std::string& name, std::vector<std::vector<std::string>> records, const std::string& source,
                 const TableSchema* schema) {
  if (records.empty()) throw std::runtime_error(source + ": empty table");
  std::vector<Column> columns;
  for (const std::string& header : records.front()) columns.push_back(parseHeader(header, source));
  if (schema) {
    if (columns != schema->columns())
      throw std::runtime_error(source + ": columns " + joinHeaders(columns) + "; this crankcheck's table " + name +
                               " has " + joinHeaders(schema->columns()));
    Table table = schema->makeTable();
    for (size_t i = 1; i < records.size(); ++i) {
      if (records[i].size() != columns.size())
        throw std::runtime_error(source + ": a row has " + std::to_string(records[i].size()) + " fields, the header " +
                                 std::to_string(columns.size()));
      std::vector<Cell> cells;
      for (size_t c = 0; c < columns.size(); ++c) cells.push_back(parseCell(columns[c], std::move(records[i][c]), source));
      table.appendCells(std::move(cells));
    }
    return table;
  }
  Table table(name, std::move(columns));
  for (size_t i = 1; i < records.size(); ++i) {
    if (records[i].size() != table.columns().size())
      throw std::runtime_error(source + ": a row has " + std::to_string(records[i].size()) + " fields, the header " +
                               std::to_string(table.columns().size()));
    for (size_t c = 0; c < records[i].size(); ++c)
      if (table.columns()[c].text) records[i][c] = unprotectText(std::move(records[i][c]));
    table.rows.push_back(std::move(records[i]));
  }
  return table;
}


}  // namespace crankcheck::validation
