#include "crankcheck/validation/scales.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace crankcheck::validation {

double calcEnergyScale(const Mechanism& m) {
  double shafts = 0.0;  // each balance shaft: Q = m g rho ratio cos(psi)
  for (const BalanceShaftParams& b : m.balance_shafts) shafts += b.mass * b.radius * std::fabs(b.ratio);
  return m.machine.gravity * (m.machine.cylinders * (m.crank.radius * (m.piston.mass + m.rod.mass) +
                                                   m.crank.mass * m.crank.com_radius +
                                                   m.crank.counterweight_mass * m.crank.counterweight_radius) +
                             shafts);
}

namespace {

// The part of the acceleration scale from the static loads: g, and the largest gas force over the masses it pushes.
double calcStaticAcceleration(const Mechanism& m) {
  double gas = 0.0;
  if (m.gas && m.piston.mass + m.rod.mass > 0.0)
    for (double p : m.gas->pressures) gas = std::max(gas, std::fabs(p) * calcBoreArea(*m.gas) / (m.piston.mass + m.rod.mass));
  return m.machine.gravity + gas;
}

}  // namespace

double calcLoopRatio(const Mechanism& m) {
  double offset = 0.0;
  for (int j = 0; j < m.machine.cylinders; ++j) offset = std::max(offset, std::fabs(getPinOffset(m, j)));
  return (m.crank.radius + offset) / m.rod.length;
}

double calcAccelerationScale(const Mechanism& m) {
  const double lambda = calcLoopRatio(m);  // lambda for centric cylinders
  const double w = m.machine.speed;
  // Simbody finds accelerations from the forces it balances: with gas, the largest gas force over the masses it
  // pushes sets the size of its rounding (a_p at rest is 0 exactly in the closed form, rounding of that in Simbody).
  return calcStaticAcceleration(m) + m.crank.radius * w * w * (1.0 + std::pow((1.0 - lambda) * (1.0 + lambda), -1.5));
}

double calcForceScale(const Mechanism& m) {
  const double mass = m.piston.mass + m.rod.mass + m.rod.inertia_about_wrist_pin / (m.rod.length * m.rod.length) +
                      m.crank.mass + m.crank.counterweight_mass;
  double shafts = 0.0;  // each balance shaft's mass: its weight and m rho (ratio omega)^2
  for (const BalanceShaftParams& b : m.balance_shafts)
    shafts += b.mass * (m.machine.gravity + b.radius * b.ratio * b.ratio * m.machine.speed * m.machine.speed);
  return m.machine.cylinders * mass * calcAccelerationScale(m) + shafts;
}

double calcTorqueScale(const Mechanism& m) {
  double shafts = 0.0;  // the torque the crank gives the shafts: ratio m g rho
  for (const BalanceShaftParams& b : m.balance_shafts) shafts += std::fabs(b.ratio) * b.mass * m.machine.gravity * b.radius;
  return calcForceScale(m) * std::max({m.crank.radius, m.crank.com_radius, m.crank.counterweight_radius}) + shafts;
}

Scales calcScales(const Mechanism& m) {
  const double r = m.crank.radius, l = m.rod.length;
  // The loop is singular where |sin(beta)| reaches 1: at most lambda + max |delta_j| / l (calcLoopRatio; lambda when
  // centric) is how close it comes.
  const double lambda = calcLoopRatio(m);
  const double stiff = 1.0 / ((1.0 - lambda) * (1.0 + lambda));
  const double offset = lambda * l - r;  // max |delta_j|
  Scales s;
  s.energy = calcEnergyScale(m);
  s.absolute_height_energy = s.energy + m.machine.cylinders * m.machine.gravity * (m.piston.mass + m.rod.mass) * (l + r);
  s.position = l + r + offset;
  s.velocity = r * m.machine.speed * (1.0 + std::sqrt(stiff));
  s.acceleration = calcAccelerationScale(m);
  s.force = calcForceScale(m);
  s.torque = calcTorqueScale(m);
  double z_max = 0.0, shaft_arm = 0.0;
  for (int j = 0; j < m.machine.cylinders; ++j) z_max = std::max(z_max, std::fabs(getAxialPosition(m, j)));
  for (const BalanceShaftParams& b : m.balance_shafts)  // a shaft's mass at up to |(x, y, z)| + rho from O
    shaft_arm = std::max(shaft_arm, std::hypot(b.position[0], b.position[1], b.position[2]) + b.radius);
  s.moment = s.force * (std::max(l + r + offset, shaft_arm) + z_max);
  // Simbody's and MuJoCo's U subtract absolute heights: the shafts' masses at up to their arm from O
  for (const BalanceShaftParams& b : m.balance_shafts) s.absolute_height_energy += m.machine.gravity * b.mass * shaft_arm;
  s.closure = std::sqrt(stiff);
  s.conditioning = stiff * (l + r) / r;
  s.velocity_conditioning = s.closure * (l + r) / r;
  const double inertia = s.acceleration - calcStaticAcceleration(m);  // r omega^2 (1 + (1 - lambda^2)^(-3/2))
  s.acceleration_conditioning =
      s.acceleration > 0.0 ? ((s.acceleration - inertia) * stiff + inertia * s.closure) / s.acceleration * (l + r) / r
                           : s.conditioning;
  return s;
}

Scales calcPositiveScales(const Mechanism& m) {
  Scales s = calcScales(m);
  const double tiny = std::numeric_limits<double>::min();  // smallest normal double
  auto zero = [tiny](double scale) { return !(scale >= tiny); };
  if (!zero(s.energy) && !zero(s.absolute_height_energy) && !zero(s.velocity) && !zero(s.acceleration) && !zero(s.force) &&
      !zero(s.torque) && !zero(s.moment))
    return s;
  // The case's static load A_s (standard gravity when it has none), and the same mechanism with A_s as its gravity
  // and no gas, at rest: its calcScales are A_s times the masses and arms of each scale (see scales.h).
  const double static_load = calcStaticAcceleration(m);
  const double load = zero(static_load) ? kStandardGravity : static_load;
  Mechanism loaded = m;
  loaded.machine.gravity = load;
  loaded.machine.speed = 0.0;
  loaded.gas.reset();
  const Scales at_rest = calcScales(loaded);
  auto floor = [&](double& scale, double value) {
    if (zero(scale)) scale = std::max(value, tiny);
  };
  floor(s.energy, at_rest.energy);
  floor(s.absolute_height_energy, at_rest.absolute_height_energy);
  floor(s.velocity, std::sqrt(m.crank.radius * load) * (1.0 + s.closure));  // r omega_c (1 + (1 - lambda^2)^(-1/2))
  floor(s.acceleration, load);
  floor(s.force, at_rest.force);
  floor(s.torque, at_rest.torque);
  floor(s.moment, at_rest.moment);
  return s;
}

double Comparison::error() const { return std::fabs(a - b); }
double Comparison::tolerance() const { return kAgreementMultiple * kEps * scale * conditioning; }

std::vector<Comparison> compareEvaluations(const Mechanism& m, const Evaluation& a, const Evaluation& b) {
  return compareEvaluations(m, calcScales(m), a, b);
}

double getQuantityScale(const Scales& sc, QuantityScale scale, const Mechanism& m) {
  switch (scale) {
    case QuantityScale::kAbsoluteHeightEnergy: return sc.absolute_height_energy;
    case QuantityScale::kEnergy: return sc.energy;
    case QuantityScale::kTorque: return sc.torque;
    case QuantityScale::kForce: return sc.force;
    case QuantityScale::kMoment: return sc.moment;
    case QuantityScale::kPosition: return sc.position;
    case QuantityScale::kVelocity: return sc.velocity;
    case QuantityScale::kAcceleration: return sc.acceleration;
    case QuantityScale::kRadian: return 1.0;
    case QuantityScale::kRodVelocity: return sc.velocity / m.rod.length;
    case QuantityScale::kRodAcceleration: return sc.acceleration / m.rod.length;
  }
  throw std::invalid_argument("getQuantityScale: not a QuantityScale");
}

double getQuantityConditioning(const Scales& sc, QuantityConditioning conditioning) {
  switch (conditioning) {
    case QuantityConditioning::kNone: return 1.0;
    // U is a position-level quantity (heights of the bodies): the closure's amplification, as x_p. (With 1 for U,
    // it failed at lambda = 0.99999 on a 0.1-degree grid: 1.2 x the tolerance.)
    case QuantityConditioning::kClosure: return sc.closure;
    case QuantityConditioning::kLoop: return sc.conditioning;
    case QuantityConditioning::kVelocity: return sc.velocity_conditioning;
    case QuantityConditioning::kAcceleration: return sc.acceleration_conditioning;
  }
  throw std::invalid_argument("getQuantityConditioning: not a QuantityConditioning");
}

std::vector<Comparison> compareEvaluations(const Mechanism& m, const Scales& sc, const Evaluation& a, const Evaluation& s) {
  std::vector<Comparison> out;
  const std::vector<Quantity>& catalogue = getQuantityCatalogue();
  auto add = [&](const Quantity& q, int cylinder) {
    const double *va = readQuantity(q, a, cylinder), *vs = readQuantity(q, s, cylinder);
    const double scale = getQuantityScale(sc, q.scale, m), conditioning = getQuantityConditioning(sc, q.conditioning);
    for (int i = 0; i < q.components; ++i) out.push_back({q.name, cylinder, va[i], vs[i], scale, conditioning, i});
  };
  for (const Quantity& q : catalogue)
    if (!q.per_cylinder && isQuantityDefined(q, m)) add(q, -1);
  const size_t k = std::min(a.cylinders.size(), s.cylinders.size());
  for (size_t j = 0; j < k; ++j)
    for (const Quantity& q : catalogue)
      if (q.per_cylinder && isQuantityDefined(q, m)) add(q, static_cast<int>(j));
  return out;
}

}  // namespace crankcheck::validation
