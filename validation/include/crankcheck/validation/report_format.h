#pragma once
/// @file
/// How the report writes numbers in its sentences and tables: one style for every part. (The CSV files write every
/// number exactly, by formatNumber: table.h.)

#include <string>

namespace crankcheck::validation {

/// x to `digits` significant digits (printf %g), for the sentences and tables of the report: 0.012, 3.4e-15.
std::string shortNumber(double x, int digits = 2);

/// `word` as a POSIX shell reads it back as one word: as it is when it holds only characters no shell interprets
/// ([A-Za-z0-9_-./+:=@%,]), else in single quotes (a quote inside as '\''). For the commands a report prints for the
/// user to copy; crankcheck itself never runs a command through a shell.
std::string quoteShellWord(const std::string& word);

/// Today's date in UTC as YYYY-MM-DD, for a report's first lines.
std::string formatToday();

/// A fraction as a percentage to 3 significant digits: 0.0123 -> "1.23 %", 0.5 -> "50 %".
std::string formatPercent(double fraction);

}  // namespace crankcheck::validation
