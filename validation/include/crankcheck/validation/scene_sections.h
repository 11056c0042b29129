#pragma once
/// @file
/// What the terminal says of the report's scene sections (part your_engine, validation/src/your_engine/topic.h): one
/// line per scene the user gave, its most telling numbers, under the verdict.

#include <string>

#include "crankcheck/validation/table.h"

namespace crankcheck::validation {

/// One line per user scene of `tables` (none in the default campaign, whose sections are the example scenes'), e.g.
///   "  moto: Norton's a_p off by 1.9 % of r omega^2; gravity 0.0003 of the inertia torque\n"
/// read from the sections' tables (the analytic engine's rows; Norton's two-term series); a line longer than 100
/// columns (a long scene name) goes on in a second line. A scene whose numbers are missing (a shard) gets no line. @return the lines, each ended by '\n'; empty when there is none.
std::string formatSceneHeadlines(const TableSet& tables);

}  // namespace crankcheck::validation
