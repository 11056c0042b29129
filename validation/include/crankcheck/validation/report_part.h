#pragma once
/// @file
/// A part of the report as its own file describes it (Part::describe, part.h): report.cc only places it, heading,
/// figure, sentences and table in that order.

#include <string>
#include <vector>

namespace crankcheck::validation {

struct ReportPart {
  std::string heading;                         ///< "13. Engines: ..."; empty: the part has no data and is left out
  std::string caption;                         ///< of the part's figure (NAME.png, NAME.svg, data/NAME.csv)
  std::vector<std::string> paragraphs;         ///< sentences whose numbers are read from the data
  std::vector<std::string> header;             ///< a table under the sentences; none when empty
  std::vector<std::vector<std::string>> rows;
};

}  // namespace crankcheck::validation
