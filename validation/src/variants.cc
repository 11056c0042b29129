#include "crankcheck/validation/variants.h"

#include <cmath>
#include <vector>

namespace crankcheck::validation {

Mechanism withLambda(const Mechanism& base, double lambda) {
  Mechanism m = base;
  const double scale = (base.crank.radius / lambda) / base.rod.length;
  m.rod.length = base.crank.radius / lambda;
  m.rod.com_from_wrist_pin = base.rod.com_from_wrist_pin * scale;
  m.rod.inertia_about_wrist_pin = base.rod.inertia_about_wrist_pin * scale * scale;
  return m;
}

Mechanism withSpeed(const Mechanism& base, double rpm) {
  Mechanism m = base;
  m.speed_rpm = rpm;
  m.machine.speed = rpm * (M_PI / 30.0);
  return m;
}

Mechanism withCylinders(const Mechanism& base, int k, Cycle cycle) {
  Mechanism m = base;
  m.machine.cylinders = k;
  m.machine.cycle = cycle;
  m.machine.acting = Acting::kSingle;
  m.machine.explicit_crank_angles = false;
  m.machine.crank_angles = calcPhaseAngles(k, cycle, Acting::kSingle);
  m.machine.bank_angles.clear();      // one bank, at cylinder_angle
  m.machine.axial_positions.clear();  // in one plane
  // An offset shared by every cylinder ([engine].pin_offset) stays with every new cylinder; per-cylinder ones cannot.
  bool common = !m.machine.pin_offsets.empty();
  for (double delta : m.machine.pin_offsets) common = common && delta == m.machine.pin_offsets.front();
  m.machine.pin_offsets = common ? std::vector<double>(static_cast<size_t>(k), base.machine.pin_offsets.front())
                                : std::vector<double>{};
  m.gas.reset();                     // a pressure table needs a firing angle per cylinder: none for the new k
  m.firing_angles.clear();
  m.crankshaft.reset();              // a [crankshaft] has one section per throw of the base: none for the new k
  return m;
}

Mechanism withGamma(const Mechanism& base, double gamma_deg) {
  Mechanism m = base;
  m.machine.cylinder_angle = radiansFromDegrees(gamma_deg);
  for (double& bank : m.machine.bank_angles) bank += m.machine.cylinder_angle - base.machine.cylinder_angle;
  return m;
}

std::vector<double> anglesDeg(double step) {
  std::vector<double> v;
  for (double a = 0.0; a < 360.0 - 1e-9; a += step) v.push_back(a);
  return v;
}

std::string gammaTag(double gamma_deg) {
  return "gamma" + std::string(gamma_deg < 0 ? "m" : "") + std::to_string(static_cast<int>(std::fabs(gamma_deg)));
}

}  // namespace crankcheck::validation
