#include "crankcheck/validation/work_limit.h"

#include <cmath>
#include <cstdio>

#include "crankcheck/validation/errors.h"

namespace crankcheck::validation {

std::string formatDuration(double seconds) {
  char buffer[64];
  if (!std::isfinite(seconds)) return "without end";
  // Two significant digits, without an exponent below 1000 of a unit: "5.8 ms", "580 us", "42 s".
  auto in = [&](double value, const char* unit) {
    std::snprintf(buffer, sizeof buffer, value >= 10.0 ? "%.0f %s" : "%.2g %s", value, unit);
    return std::string(buffer);
  };
  if (seconds < 1e-3) return in(seconds * 1e6, "us");
  if (seconds < 0.1) return in(seconds * 1e3, "ms");
  if (seconds < 120.0) return in(seconds, "s");
  if (seconds < 7200.0) return in(seconds / 60.0, "min");
  if (seconds < 2.0 * 86400.0) return in(seconds / 3600.0, "h");
  std::snprintf(buffer, sizeof buffer, "%.2g days", seconds / 86400.0);
  return buffer;
}

void checkWorkLimit(const std::string& what, double estimated_seconds, const std::string& how_estimated,
                    const std::string& smaller, double limit_seconds) {
  if (estimated_seconds <= limit_seconds) return;
  char limit[32];
  std::snprintf(limit, sizeof limit, "%.6g", limit_seconds);
  throw UsageError(what + " would take about " + formatDuration(estimated_seconds) + " (" + how_estimated +
                   "), more than " + kWorkLimitFlag + " " + limit + " s; nothing was run: " + smaller + ", or a larger " +
                   kWorkLimitFlag);
}

}  // namespace crankcheck::validation
