#include "crankcheck/validation/worst_by_quantity.h"

namespace crankcheck::validation {

bool WorstComparison::note(const Comparison& c, double at_phi_deg, double at_rpm) {
  const double ratio = c.error() / c.tolerance();
  pass = pass && c.agrees();
  if (!(ratio > ratio_to_tolerance)) return false;
  ratio_to_tolerance = ratio;
  rel_error = c.error() / c.scale;
  tolerance_rel = c.tolerance() / c.scale;
  phi_deg = at_phi_deg;
  rpm = at_rpm;
  return true;
}

bool WorstComparison::merge(const WorstComparison& other) {
  pass = pass && other.pass;
  if (!(other.ratio_to_tolerance > ratio_to_tolerance)) return false;
  const bool passes = pass;
  *this = other;
  pass = passes;
  return true;
}

WorstComparison& WorstByQuantity::at(size_t i, const std::string& quantity) {
  if (i < slot_of_.size() && slots_[slot_of_[i]].first == quantity) return slots_[slot_of_[i]].second;
  size_t slot = 0;
  while (slot < slots_.size() && slots_[slot].first != quantity) ++slot;
  if (slot == slots_.size()) slots_.emplace_back(quantity, WorstComparison{});
  if (i >= slot_of_.size()) slot_of_.resize(i + 1, 0);
  slot_of_[i] = slot;
  return slots_[slot].second;
}

}  // namespace crankcheck::validation
