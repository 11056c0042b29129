#include "crankcheck/scene/scene_writer.h"

#include <charconv>
#include <cmath>
#include <sstream>

namespace crankcheck {

std::string formatShortest(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x + 0.0);  // + 0.0: -0 as 0
  std::string text(buffer, result.ptr);
  // TOML floats need a '.' or an exponent to stay floats; integers are accepted for any number key, but the
  // canonical form keeps the type visible.
  if (text.find_first_of(".en") == std::string::npos) text += ".0";
  return text;
}

namespace {

std::string list(const std::vector<double>& values, double (*convert)(double)) {
  std::string out = "[";
  for (size_t i = 0; i < values.size(); ++i) out += (i ? ", " : "") + formatShortest(convert(values[i]));
  return out + "]";
}
double same(double x) { return x; }

// The firing order of an inline scene with [gas]: firing_order[i] fires at phi = i x cycle / k. Empty when the
// firing angles are not of that form.
std::vector<int> findFiringOrder(const Mechanism& m) {
  const int k = m.machine.cylinders;
  const double cycle_deg = m.machine.cycle == Cycle::kFourStroke ? 720.0 : 360.0;
  std::vector<int> order;
  for (int i = 0; i < k; ++i) {
    const double angle = radiansFromDegrees(cycle_deg * static_cast<double>(i) / static_cast<double>(k));
    for (int j = 0; j < k; ++j)
      if (m.firing_angles[static_cast<size_t>(j)] == angle) {
        order.push_back(j);
        break;
      }
    if (order.size() != static_cast<size_t>(i) + 1) return {};
  }
  return order;
}

// The spacing s with z_j = j s exactly (as the parser computes them), or NaN.
double findSpacing(const Mechanism& m) {
  const auto& z = m.machine.axial_positions;
  if (z.size() < 2 || z[0] != 0.0) return std::nan("");
  for (size_t j = 0; j < z.size(); ++j)
    if (z[j] != static_cast<double>(j) * z[1]) return std::nan("");
  return z[1];
}

}  // namespace

std::string formatSceneToml(const Mechanism& m) {
  const int k = m.machine.cylinders;
  const bool with_gas = m.gas.has_value();
  const std::vector<int> firing_order = with_gas ? findFiringOrder(m) : std::vector<int>{};
  const double spacing = hasAxialPositions(m) ? findSpacing(m) : 0.0;
  bool same_offsets = true;  // [engine].pin_offset gives every cylinder the same one
  for (double delta : m.machine.pin_offsets) same_offsets = same_offsets && delta == m.machine.pin_offsets.front();
  const bool inline_form = isSingleBank(m) && m.machine.bank_angles.empty() && !std::isnan(spacing) &&
                           (!with_gas || !firing_order.empty()) && same_offsets;
  const double speed_rpm = m.machine.speed * (30.0 / M_PI) == m.speed_rpm || m.speed_rpm * (M_PI / 30.0) == m.machine.speed
                               ? m.speed_rpm
                               : m.machine.speed * (30.0 / M_PI);
  std::ostringstream out;
  out << "# Written by crankcheck (SI units, angles in degrees: docs/SCENE-FORMAT.md).\n";
  out << "format_version = 1\n\n";
  out << "[engine]\n";
  out << "cylinders = " << k << "\n";
  out << "cycle = \"" << toString(m.machine.cycle) << "\"\n";
  out << "acting = \"" << toString(m.machine.acting) << "\"\n";
  if (inline_form) {
    out << "cylinder_angle_deg = " << formatShortest(degreesFromRadians(m.machine.cylinder_angle)) << "\n";
    // Explicit angles are written even where they equal eqs (8)-(11)'s: the scene read back must be the same scene
    // (which harmonics the closed forms list depends on whether the angles are the formulas' or the scene's own).
    if (m.machine.explicit_crank_angles || m.machine.crank_angles != calcPhaseAngles(k, m.machine.cycle, m.machine.acting))
      out << "crank_angles_deg = " << list(m.machine.crank_angles, degreesFromRadians) << "\n";
    if (hasAxialPositions(m)) out << "cylinder_spacing = " << formatShortest(spacing) << "\n";
    if (!m.machine.pin_offsets.empty()) out << "pin_offset = " << formatShortest(getPinOffset(m, 0)) << "\n";
  }
  out << "speed_rpm = " << formatShortest(speed_rpm) << "\n";
  out << "gravity = " << formatShortest(m.machine.gravity) << "\n";
  out << "\n[crank]\n";
  out << "radius = " << formatShortest(m.crank.radius) << "\n";
  out << "mass = " << formatShortest(m.crank.mass) << "\n";
  out << "com_radius = " << formatShortest(m.crank.com_radius) << "\n";
  out << "counterweight_mass = " << formatShortest(m.crank.counterweight_mass) << "\n";
  out << "counterweight_radius = " << formatShortest(m.crank.counterweight_radius) << "\n";
  out << "\n[rod]\n";
  out << "length = " << formatShortest(m.rod.length) << "\n";
  out << "mass = " << formatShortest(m.rod.mass) << "\n";
  out << "com_from_wrist_pin = " << formatShortest(m.rod.com_from_wrist_pin) << "\n";
  out << "inertia_about_wrist_pin = " << formatShortest(m.rod.inertia_about_wrist_pin) << "\n";
  out << "\n[piston]\n";
  out << "mass = " << formatShortest(m.piston.mass) << "\n";
  if (m.flywheel_inertia) out << "\n[flywheel]\ninertia = " << formatShortest(*m.flywheel_inertia) << "\n";
  if (m.crankshaft) {
    const CrankshaftParams& c = *m.crankshaft;
    out << "\n[crankshaft]\n";
    out << "throw_inertia = " << formatShortest(c.throw_inertia) << "\n";
    out << "front_inertia = " << formatShortest(c.front_inertia) << "\n";
    out << "stiffness = " << list(c.stiffness, same) << "\n";
    out << "section_damping = "
        << (c.section_damping.size() == 1 ? formatShortest(c.section_damping.front()) : list(c.section_damping, same))
        << "\n";
    out << "throw_damping = " << formatShortest(c.throw_damping) << "\n";
  }
  if (with_gas) {
    out << "\n[gas]\n";
    out << "bore = " << formatShortest(m.gas->bore) << "\n";
    out << "cycle_angle_deg = " << list(m.gas->cycle_angles, degreesFromRadians) << "\n";
    out << "pressure_pa = " << list(m.gas->pressures, same) << "\n";
    if (inline_form) {
      out << "firing_order = [";
      for (size_t i = 0; i < firing_order.size(); ++i) out << (i ? ", " : "") << firing_order[i];
      out << "]\n";
    }
  }
  for (const BalanceShaftParams& b : m.balance_shafts) {
    out << "\n[[balance_shaft]]\n";
    out << "ratio = " << formatShortest(b.ratio) << "\n";
    out << "mass = " << formatShortest(b.mass) << "\n";
    out << "radius = " << formatShortest(b.radius) << "\n";
    out << "phase_deg = " << formatShortest(degreesFromRadians(b.phase)) << "\n";
    out << "position = [" << formatShortest(b.position[0]) << ", " << formatShortest(b.position[1]) << ", "
        << formatShortest(b.position[2]) << "]\n";
  }
  if (!inline_form)
    for (int j = 0; j < k; ++j) {
      out << "\n[[cylinder]]\n";
      out << "bank_angle_deg = " << formatShortest(degreesFromRadians(getBankAngle(m, j))) << "\n";
      out << "throw_angle_deg = " << formatShortest(degreesFromRadians(getThrowAngle(m, j))) << "\n";
      if (hasAxialPositions(m)) out << "axial_position = " << formatShortest(getAxialPosition(m, j)) << "\n";
      if (!m.machine.pin_offsets.empty()) out << "pin_offset = " << formatShortest(getPinOffset(m, j)) << "\n";
      if (with_gas)
        out << "firing_angle_deg = " << formatShortest(degreesFromRadians(m.firing_angles[static_cast<size_t>(j)])) << "\n";
    }
  return out.str();
}

}  // namespace crankcheck
