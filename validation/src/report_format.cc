#include "crankcheck/validation/report_format.h"

#include <cstdio>

namespace crankcheck::validation {

std::string shortNumber(double x, int digits) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, x);
  return buffer;
}

std::string formatPercent(double fraction) { return shortNumber(100.0 * fraction, 3) + " %"; }

}  // namespace crankcheck::validation
