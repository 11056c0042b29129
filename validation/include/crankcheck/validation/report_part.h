#pragma once
/// @file
/// A part of the report as its own file describes it (Part::describe, part.h): report.cc only places it, heading,
/// figure, sentences and table in that order, or its blocks in their order.

#include <map>
#include <string>
#include <vector>

#include "crankcheck/validation/table.h"

namespace crankcheck::validation {

/// One piece of a part's content under its heading.
struct ReportBlock {
  enum Kind { kParagraph, kTable, kFigure, kHeading } kind = kParagraph;
  std::string text = {};                          ///< the paragraph, the figure's caption or the heading
  std::vector<std::string> header = {};           ///< the table's
  std::vector<std::vector<std::string>> rows = {};
  std::string figure = {};                        ///< the figure's stem (NAME.png, NAME.svg, data/NAME.csv)
  int level = 3;                                  ///< a heading's level, below the part's (2): 3, 4, ...
  std::string id = {};                            ///< a heading's anchor; empty: made of its text
};

struct ReportPart {
  std::string heading;                         ///< "13. Engines: ..."; empty: the part has no data and is left out
  std::string caption;                         ///< of the part's figure (NAME.png, NAME.svg, data/NAME.csv)
  std::vector<std::string> paragraphs;         ///< sentences whose numbers are read from the data
  std::vector<std::string> header;             ///< a table under the sentences; none when empty
  std::vector<std::vector<std::string>> rows;
  /// When not empty: the part's content in this order, instead of caption, paragraphs and table (a part with several
  /// tables, sentences after a table, or no figure).
  std::vector<ReportBlock> blocks;
};

/// The rows of table `name` with the fields of `columns` in that order; a field of a column marked in `numeric` (and
/// not empty) to 4 significant digits (shortNumber). None when the table is missing.
std::vector<std::vector<std::string>> formatRows(const TableSet& tables, const std::string& name,
                                                 const std::vector<std::string>& columns,
                                                 const std::vector<bool>& numeric = {});

/// The rows of table `name` as maps column -> field; none when the table is missing.
std::vector<std::map<std::string, std::string>> readRecords(const TableSet& tables, const std::string& name);

}  // namespace crankcheck::validation
