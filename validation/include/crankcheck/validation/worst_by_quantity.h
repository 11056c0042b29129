#pragma once
/// @file
/// The worst comparison per quantity: what the cross-check (one row per engine and quantity of a case) and
/// `crankcheck grade` (one row per quantity and regime) report of many comparisons by the gate's rule (scales.h).
/// "Worst" is the largest error / tolerance; the first one met wins a tie.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "crankcheck/validation/scales.h"

namespace crankcheck::validation {

/// The worst of the comparisons of one quantity noted so far, and whether all of them agreed.
struct WorstComparison {
  double ratio_to_tolerance = -1.0;  ///< error / tolerance of the worst; -1 before any comparison
  double rel_error = 0.0;            ///< its error / scale
  double tolerance_rel = 0.0;        ///< its tolerance / scale
  double phi_deg = 0.0;              ///< [deg] where: the crank angle of cylinder 0
  double rpm = 0.0;                  ///< [rpm] where: the case's speed
  bool pass = true;                  ///< every comparison noted agreed

  /// Notes one comparison at (phi_deg, rpm): error / tolerance, error / scale and tolerance / scale of `c`.
  /// Returns true when it is the new worst.
  bool note(const Comparison& c, double phi_deg, double rpm);
  /// Notes another accumulator's worst (and its pass): for results gathered apart (threads, several judges of one
  /// value) and merged. Returns true when `other`'s worst is the new worst (strictly larger ratio).
  bool merge(const WorstComparison& other);
};

/// One engine's worst comparison per quantity (one case), in the order the quantities are first met. The comparisons
/// of an evaluation come in the same order at every angle (compareEvaluations), so the slot of the i-th is
/// remembered and only confirmed by its name (a short string) instead of a map lookup per comparison.
class WorstByQuantity {
 public:
  /// The accumulator of `quantity`, the i-th comparison of an evaluation (created the first time it is met).
  WorstComparison& at(size_t i, const std::string& quantity);
  /// Notes comparison i of an evaluation (at(i, c.quantity).note(c, phi_deg, rpm)).
  void note(size_t i, const Comparison& c, double phi_deg, double rpm) { at(i, c.quantity).note(c, phi_deg, rpm); }
  /// (quantity, its worst) in the order first met.
  const std::vector<std::pair<std::string, WorstComparison>>& slots() const { return slots_; }

 private:
  std::vector<std::pair<std::string, WorstComparison>> slots_;
  std::vector<size_t> slot_of_;
};

}  // namespace crankcheck::validation
