#pragma once
/// @file
/// What the tests of the report parts share: a table's fixture read from CSV text through its schema (as `report
/// merge` reads a shard), and a paragraph of a described part found by its words.

#include <gtest/gtest.h>

#include <string>

#include "crankcheck/validation/csv.h"
#include "crankcheck/validation/table_schemas.h"
#include "crankcheck/validation/report_part.h"

namespace crankcheck::testing {

/// Table `name` from its CSV text (the header first), typed through its schema as `report merge` reads it.
inline validation::Table readTable(const std::string& name, const std::string& csv) {
  return validation::parseTable(name, validation::parseCsv(csv, name), name, validation::findTableSchema(name));
}

/// The paragraph (of the sentences or the blocks) that contains `needle`, or "" (the test then fails on its
/// expectations).
inline std::string findParagraph(const validation::ReportPart& part, const std::string& needle) {
  for (const std::string& p : part.paragraphs)
    if (p.find(needle) != std::string::npos) return p;
  for (const validation::ReportBlock& b : part.blocks)
    if (b.kind == validation::ReportBlock::kParagraph && b.text.find(needle) != std::string::npos) return b.text;
  ADD_FAILURE() << "no paragraph with \"" << needle << "\"";
  return "";
}

}  // namespace crankcheck::testing
