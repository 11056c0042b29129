#pragma once
/// @file
/// The registry of the report's parts (part.h), in report order: validation/src/parts.cc, one line per part, the part
/// itself in validation/src/parts/KEY.cc.

#include <string>
#include <vector>

#include "crankcheck/validation/part.h"

namespace crankcheck::validation {

/// Every registered part, in report order: its place is its number (Part::number).
const std::vector<const Part*>& listParts();

/// The registered part of key `key` (its number: findPart(key).number()). @throws std::logic_error when there is none
/// (a programming error: keys in code are the registry's).
const Part& findPart(const std::string& key);

/// The keys of the parts `validate --parts` chooses from (every part but the always() run ones), in report order.
std::vector<std::string> listPartKeys();

/// Adds `part` after the registered ones, for a test build that shows a new part reaches the report, its CSVs and
/// `validate --parts` with no other change (tests/validation/extra_part_test.cc). Call it before the first listParts().
/// @throws std::logic_error once the registry is in use, or for a key already registered (then at listParts()).
void registerExtraPart(const Part& part);

/// Checks `keys` (validate --parts) against the registry: each a part's key, none twice.
/// @throws std::invalid_argument naming the first unknown or repeated key and the known ones.
void checkPartKeys(const std::vector<std::string>& keys);

}  // namespace crankcheck::validation
