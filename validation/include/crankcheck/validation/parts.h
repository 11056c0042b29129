#pragma once
/// @file
/// The registry of the report's parts (part.h), in report order: validation/src/parts.cc, one line per part, the part
/// itself in validation/src/parts/KEY.cc.

#include <string>
#include <vector>

#include "crankcheck/validation/part.h"

namespace crankcheck::validation {

/// Every registered part, in report order (numbers increasing by one). Parts not yet in this shape are rendered by
/// report.cc directly (docs/contributing.md, "Adding a report part", says which).
const std::vector<const Part*>& listParts();

/// Checks `keys` (validate --parts) against the registry: each a part's key, none twice.
/// @throws std::invalid_argument naming the first unknown or repeated key and the known ones.
void checkPartKeys(const std::vector<std::string>& keys);

}  // namespace crankcheck::validation
