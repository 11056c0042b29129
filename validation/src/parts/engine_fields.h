#pragma once
/// @file
/// Columns per reference engine for a part's Schema (table.h): a table that holds, beside its own columns, one or
/// more columns per reference engine (listReferenceEngines, in the registry's order), named after the engine
/// ("simbody_max_rel_error"). The row keeps them as a vector of one element per reference engine; each column reads
/// and writes its engine's element. A schema with such columns depends on the engines in play (the registry, less
/// those a SatOutScope leaves out), so it is got through getEngineSchema: built on first use for each set of engines,
/// never before main() starts (a test build registers its extra engine first).

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/table.h"

namespace crankcheck::validation {

/// The column of reference engine `index` backed by member `member` of element `index` of the row's vector `list`
/// (double: a number's column of unit `unit`; std::string: a text column, `unit` ignored). A row whose vector is shorter
/// gives an empty cell; writing a cell grows the vector.
template <class Row, class Element, class Value>
Field<Row> engineElementField(std::string name, const std::string& unit, std::vector<Element> Row::*list, size_t index,
                              Value Element::*member) {
  Column column = [&] {
    if constexpr (std::is_same_v<Value, std::string>) return Column(std::move(name), kText);
    else return Column(std::move(name), unit);
  }();
  return {std::move(column),
          [list, index, member](const Row& r) {
            const std::vector<Element>& v = r.*list;
            return index < v.size() ? Cell(v[index].*member) : Cell();
          },
          [list, index, member](Row& r, Cell c) {
            std::vector<Element>& v = r.*list;
            if (v.size() <= index) v.resize(index + 1);
            if (auto* x = std::get_if<Value>(&c)) v[index].*member = std::move(*x);
          }};
}

/// The schema `name` of rows `Row` with the fields MakeFields() gives for the engines in play (listEngines()): made on
/// first use for each set of engines and kept for the program's life (a Table points to its schema). Thread-safe.
template <class Row, std::vector<Field<Row>> (*MakeFields)()>
const Schema<Row>& getEngineSchema(const char* name) {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<const Schema<Row>>> by_engines;
  const std::string engines = joinEngineNames(",");
  const std::lock_guard<std::mutex> lock(mutex);
  std::unique_ptr<const Schema<Row>>& schema = by_engines[engines];
  if (!schema) schema = std::make_unique<const Schema<Row>>(name, MakeFields());
  return *schema;
}

/// One number's column per reference engine, "ENGINE" + `suffix`, backed by element i (the i-th reference engine) of
/// the row's vector `list` of doubles. Appended to `fields`.
template <class Row>
void addEngineNumberFields(std::vector<Field<Row>>& fields, const std::string& suffix, const std::string& unit,
                           std::vector<double> Row::*list) {
  const std::vector<const Engine*> references = listReferenceEngines();
  for (size_t i = 0; i < references.size(); ++i) fields.push_back(elementField(references[i]->name + suffix, unit, list, i));
}

}  // namespace crankcheck::validation
