#pragma once
/// @file
/// Every table crankcheck writes, by name: where the CSV edge (csv.h) finds the schema to read a table back with. Above
/// the parts and the grade, which declare the schemas; csv.h itself knows none.

#include <string>

#include "crankcheck/validation/table.h"

namespace crankcheck::validation {

/// The schema of table `name` (a CSV stem): the campaign's notes, a report part's (Part::schemas: the cross-check and
/// the scenes are the core parts'), or one of `crankcheck grade`'s (grade.h); nullptr when none declares it.
const TableSchema* findTableSchema(const std::string& name);

}  // namespace crankcheck::validation
