#pragma once
/// @file
/// The CSV edge of the report's tables (table.h): the only place where a table becomes text and text a table. The
/// report writer writes data/NAME.csv by formatCsv; `report merge` reads a shard's files back by parseCsv and
/// parseTable, into typed rows through the table's schema (table_schemas.h), so that a merged report is rendered by
/// the same code as a single run. RFC 4180 fields; each header names its unit: "max_rel_error [-]", a text column bare.

#include <string>
#include <vector>

#include "crankcheck/validation/table.h"

namespace crankcheck::validation {

/// The table as CSV text: the header line, then one line per row (numbers by formatNumber), each ending in "\n".
std::string formatCsv(const Table& table);

/// Splits CSV text into records of fields (RFC 4180). @throws std::runtime_error naming `source` on an unterminated
/// quote.
std::vector<std::vector<std::string>> parseCsv(const std::string& text, const std::string& source);

/// Table `name` from its CSV records (the header first). With a `schema` (the table's: table_schemas.h
/// findTableSchema) it is read into typed rows and must have that schema's columns; without (nullptr) it keeps its
/// fields as text, each column's unit from its header. @throws std::runtime_error naming `source` on an empty table,
/// an empty unit, a row of another length than the header, other columns than the schema's, or a number's field that
/// is not a number.
Table parseTable(const std::string& name, std::vector<std::vector<std::string>> records, const std::string& source,
                 const TableSchema* schema);

}  // namespace crankcheck::validation
