#include "crankcheck/validation/work_limit.h"

#include <cmath>
#include <cstdio>

#include "crankcheck/validation/errors.h"

namespace crankcheck::validation {

std::string formatDuration(double seconds) {
  char buffer[64];
  if (!std::isfinite(seconds)) return "without end";
  if (seconds < 1e-3)
    std::snprintf(buffer, sizeof buffer, "%.2g us", seconds * 1e6);
  else if (seconds < 0.1)
    std::snprintf(buffer, sizeof buffer, "%.2g ms", seconds * 1e3);
  else if (seconds < 120.0)
    std::snprintf(buffer, sizeof buffer, "%.2g s", seconds);
  else if (seconds < 7200.0)
    std::snprintf(buffer, sizeof buffer, "%.0f min", seconds / 60.0);
  else if (seconds < 2.0 * 86400.0)
    std::snprintf(buffer, sizeof buffer, "%.2g h", seconds / 3600.0);
  else
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
