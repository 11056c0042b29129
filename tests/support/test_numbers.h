#pragma once
/// @file
/// The unit of rounding every test's tolerance is a multiple of, declared once for all tests (a test names it by
/// `using testing::kEps;`).

#include <limits>

namespace crankcheck::testing {

/// The spacing of doubles at 1 (2^-52).
inline constexpr double kEps = std::numeric_limits<double>::epsilon();

}  // namespace crankcheck::testing
