#pragma once
/// @file
/// The bound on work crankcheck starts: every piece of work that can run long (a sweep of stepped runs, the reference
/// runs of a time-stepped grade, a torsion sweep) is estimated before it starts, from the measured cost of a short
/// probe of the same work times how much of it is asked, and refused past the limit with the flag that lifts it
/// (`--work-limit SECONDS`, in validate, stepped, grade --free-run and torsion; `work_limit` in Python). The estimate
/// is a measurement on this machine, not a promise: the work itself may take somewhat less or more.

#include <string>

namespace crankcheck::validation {

/// The longest estimated work [s] crankcheck starts when not told otherwise: 10 minutes.
inline constexpr double kDefaultWorkLimitSeconds = 600.0;

/// The flag that sets the limit, as the messages name it.
inline constexpr const char* kWorkLimitFlag = "--work-limit";

/// Refuses work estimated past the limit.
/// @param what the work, e.g. "the stepped engines' runs on scenes/x.toml"
/// @param estimated_seconds [s] the estimate (probe cost x amount)
/// @param how_estimated how the estimate was made, e.g. "1.3e6 steps at the measured 53 ms a step"
/// @param smaller how to ask for less, e.g. "a larger --dt"
/// @param limit_seconds [s] the limit
/// @throws UsageError "WHAT would take about X (HOW), more than --work-limit L s: SMALLER, or a larger --work-limit"
void checkWorkLimit(const std::string& what, double estimated_seconds, const std::string& how_estimated,
                    const std::string& smaller, double limit_seconds);

/// A duration for a message: "35 us", "0.37 ms", "42 s", "17 min", "3.2 h", "5.1 days".
std::string formatDuration(double seconds);

}  // namespace crankcheck::validation
