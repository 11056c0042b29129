// The unit of every column of the report's CSV tables (report.h: writeTables, readTables).
#include <map>
#include <stdexcept>
#include <string>

#include "crankcheck/validation/report.h"

namespace crankcheck::validation {
namespace {

// "" for a text column; "-" for a dimensionless number (ratios, errors relative to a scale, counts, indices);
// "SI" where the unit is the quantity's own (the row's quantity names it: J, N m, N, m, m/s, m/s^2, rad, ...).
const std::map<std::string, std::string>& columnUnits() {
  static const std::map<std::string, std::string> units = {
      // text
      {"acting", ""}, {"case", ""}, {"couple_vanishes", ""}, {"cycle", ""}, {"description", ""}, {"engine", ""},
      {"family", ""}, {"force", ""}, {"force_vanishes", ""}, {"holds", ""}, {"integrator", ""}, {"item", ""},
      {"layout", ""}, {"measure", ""}, {"method", ""}, {"note", ""}, {"paper_negligible", ""}, {"paper_nonzero", ""},
      {"part", ""}, {"pass", ""}, {"quantity", ""}, {"resolved", ""}, {"scene", ""}, {"shafts", ""}, {"status", ""}, {"textbook", ""},
      {"two_mass_delta_I_resolved", ""}, {"vanishes_exactly", ""}, {"variable", ""}, {"verdict", ""},
      {"where_case", ""}, {"errata/printed", ""}, {"regime", ""}, {"largest_where_case", ""},
      // dimensionless
      {"accuracy", "-"}, {"analytic_max_rel_error", "-"}, {"asked", "-"}, {"couple_relative", "-"}, {"cylinder", "-"},
      {"cylinders", "-"}, {"delta_due_to_gravity", "-"}, {"delta_error", "-"}, {"delta_gravity", "-"},
      {"delta_no_gravity", "-"}, {"energy_drift", "-"}, {"first_order", "-"}, {"force_relative", "-"}, {"k", "-"},
      {"lambda", "-"}, {"where_lambda", "-"}, {"offset_over_r", "-"}, {"simbody_max_rel_error", "-"}, {"layout_index", "-"}, {"max_difference_rel", "-"}, {"max_error_rel", "-"},
      {"max_rel_error", "-"}, {"n", "-"}, {"program_max_rel_error", "-"}, {"provided", "-"}, {"ratio_of_maxima", "-"},
      {"ratio_to_inertia", "-"}, {"ratio_to_k1", "-"}, {"rel_error", "-"}, {"relative_amplitude", "-"},
      {"relative_error", "-"}, {"rocking_relative", "-"}, {"scene_index", "-"}, {"share", "-"},
      {"simbody_ratio_to_k1", "-"}, {"tolerance_rel", "-"}, {"two_mass_delta_I_error", "-"}, {"two_mass_error", "-"},
      {"worst_rel_error", "-"},
      {"eq15_coefficients/printed", "-"}, {"exact", "-"}, {"largest_rel_error", "-"}, {"largest_rel_error_simbody", "-"},
      {"largest_rel_error_analytic", "-"}, {"largest_rel_error_mujoco", "-"}, {"rel_error_at_worst_ratio", "-"},
      {"worst_ratio", "-"},
      // with units
      {"I_o", "kg m^2"}, {"I_w", "kg m^2"}, {"m_k", "kg"}, {"m_o", "kg"}, {"m_p", "kg"}, {"m_s", "kg"},
      {"l", "m"}, {"r", "m"}, {"r_p", "m"}, {"r_s", "m"}, {"z_k", "m"}, {"g", "m/s^2"},
      {"x_exact", "m"}, {"x_two_term", "m"}, {"v_exact", "m/s"}, {"v_two_term", "m/s"}, {"a_exact", "m/s^2"},
      {"a_two_term", "m/s^2"},
      {"crank_angle_deg", "deg"}, {"gamma_deg", "deg"}, {"phi_deg", "deg"}, {"phi_deg_at_max", "deg"},
      {"where_phi_deg", "deg"}, {"speed_rpm", "rpm"}, {"where_speed_rpm", "rpm"}, {"largest_where_phi_deg", "deg"},
      {"largest_where_speed_rpm", "rpm"},
      {"ns_per_eval", "ns"}, {"ns_per_revolution", "ns"}, {"ns_per_eval_k1", "ns"}, {"ns_per_eval_k12", "ns"},
      {"flywheel_inertia", "kg m^2"}, {"exact_inertia", "kg m^2"}, {"norton_inertia", "kg m^2"},
      {"exact_delta", "-"}, {"simbody_delta", "-"}, {"norton_error", "-"}, {"norton_delta", "-"},
      {"peak_major_thrust", "N"}, {"peak_minor_thrust", "N"}, {"thrust_reversal_deg", "deg"}, {"max_abs_drive_torque", "N m"},
      {"max_abs_Q", "N m"}, {"max_abs_Q_printed", "N m"}, {"simbody_max_abs_Q", "N m"}, {"simbody_bound", "N m"},
      {"max_inertia_torque", "N m"}, {"mean_abs_drive_torque", "N m"}, {"mean_abs_gravity_torque", "N m"},
      {"drive_torque", "N m"}, {"simbody_drive_torque", "N m"}, {"gas_torque", "N m"}, {"inertia_torque", "N m"},
      {"gravity_torque", "N m"}, {"harmonics/simbody_amplitude", "N m"}, {"analytic_amplitude", "N m"},
      {"bearing_x", "N"}, {"bearing_y", "N"}, {"crank_pin_radial", "N"}, {"crank_pin_tangential", "N"},
      {"max_magnitude", "N"}, {"force_amplitude", "N"},
      // the row says which quantity, and so the unit
      {"max_abs_error", "SI"}, {"program_value", "SI"}, {"simbody_value", "SI"}, {"mujoco_value", "SI"}, {"analytic_value", "SI"},
      {"balance/simbody_amplitude", "SI"}, {"balance/mujoco_amplitude", "SI"}, {"balance_harmonics/simbody_amplitude", "SI"}, {"x", "SI"},
      {"errata/value", "see measure"},
  };
  return units;
}

}  // namespace

std::string getColumnUnit(const std::string& table, const std::string& column) {
  const auto& units = columnUnits();
  auto it = units.find(table + "/" + column);
  if (it == units.end()) it = units.find(column);
  if (it == units.end())
    throw std::logic_error("table " + table + ": column " + column + " has no unit (validation/src/column_units.cc)");
  return it->second;
}

}  // namespace crankcheck::validation
