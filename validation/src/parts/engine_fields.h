#pragma once
/// @file
/// Columns per reference engine for a part's Schema (table.h): a table that holds, beside its own columns, one or
/// more columns per reference engine (listReferenceEngines, in the registry's order), named after the engine
/// ("simbody_max_rel_error"). The row keeps them as a vector of one element per reference engine; each column reads
/// and writes its engine's element. A schema with such columns depends on the engine registry, so it is built on
/// first use (a function-local static), never before main() starts (a test build registers its extra engine first).

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

/// One number's column per reference engine, "ENGINE" + `suffix`, backed by element i (the i-th reference engine) of
/// the row's vector `list` of doubles. Appended to `fields`.
template <class Row>
void addEngineNumberFields(std::vector<Field<Row>>& fields, const std::string& suffix, const std::string& unit,
                           std::vector<double> Row::*list) {
  const std::vector<const Engine*> references = listReferenceEngines();
  for (size_t i = 0; i < references.size(); ++i) fields.push_back(elementField(references[i]->name + suffix, unit, list, i));
}

}  // namespace crankcheck::validation
