#pragma once
/// @file
/// The registry of the report's parts (part.h), in report order: validation/src/parts.cc, one line per part, the part
/// itself in validation/src/parts/KEY.cc.

#include <vector>

#include "crankcheck/validation/part.h"

namespace crankcheck::validation {

/// Every registered part, in report order (numbers increasing by one). Parts not yet in this shape are rendered by
/// report.cc directly (README.md, "Adding a report part", says which).
const std::vector<const Part*>& listParts();

}  // namespace crankcheck::validation
