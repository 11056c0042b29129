#include "crankcheck/scene/mechanism.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace crankcheck {

double calcCrankRatio(const Mechanism& m) { return m.crank.radius / m.rod.length; }

double getBankAngle(const Mechanism& m, int j) {
  return m.machine.bank_angles.empty() ? m.machine.cylinder_angle : m.machine.bank_angles.at(static_cast<size_t>(j));
}

double getThrowAngle(const Mechanism& m, int j) {
  return getBankAngle(m, j) + m.machine.crank_angles.at(static_cast<size_t>(j));
}

double getAxialPosition(const Mechanism& m, int j) {
  return m.machine.axial_positions.empty() ? 0.0 : m.machine.axial_positions.at(static_cast<size_t>(j));
}

double getPinOffset(const Mechanism& m, int j) {
  return m.machine.pin_offsets.empty() ? 0.0 : m.machine.pin_offsets.at(static_cast<size_t>(j));
}

bool hasPinOffsets(const Mechanism& m) {
  for (double delta : m.machine.pin_offsets)
    if (delta != 0.0) return true;
  return false;
}

std::vector<std::vector<int>> findThrows(const Mechanism& m) {
  // Angles within 1e-9 rad modulo a turn are the same (beta_j = gamma_j + alpha_j rounds differently for a V pair
  // typed with the same throw_angle_deg); 1e-9 rad is the tolerance of the firing-angle rule as well.
  const auto same = [](double a, double b) { return std::fabs(std::remainder(a - b, 2.0 * M_PI)) <= 1e-9; };
  std::vector<int> along(static_cast<size_t>(std::max(m.machine.cylinders, 0)));
  std::iota(along.begin(), along.end(), 0);
  std::stable_sort(along.begin(), along.end(),
                   [&](int a, int b) { return getAxialPosition(m, a) < getAxialPosition(m, b); });
  std::vector<std::vector<int>> throws;
  for (int j : along) {
    bool joins = !throws.empty() && same(getThrowAngle(m, j), getThrowAngle(m, throws.back().front()));
    if (joins)
      for (int c : throws.back()) joins = joins && !same(getBankAngle(m, j), getBankAngle(m, c));
    if (joins) throws.back().push_back(j);
    else throws.push_back({j});
  }
  return throws;
}

Mechanism selectThrow(const Mechanism& m, int throw_index) {
  const std::vector<std::vector<int>> throws = findThrows(m);
  if (throw_index < 0 || throw_index >= static_cast<int>(throws.size()))
    throw std::out_of_range("torsion: no throw " + std::to_string(throw_index) + " (the scene has " +
                            std::to_string(throws.size()) + ")");
  Mechanism one = m;
  one.flywheel_inertia.reset();
  one.balance_shafts.clear();
  one.crankshaft.reset();
  one.machine.crank_angles.clear();
  one.machine.bank_angles.clear();
  one.machine.axial_positions.clear();
  one.machine.pin_offsets.clear();
  one.firing_angles.clear();
  for (int c : throws[static_cast<size_t>(throw_index)]) {
    one.machine.crank_angles.push_back(m.machine.crank_angles.at(static_cast<size_t>(c)));
    one.machine.bank_angles.push_back(getBankAngle(m, c));
    one.machine.axial_positions.push_back(getAxialPosition(m, c));
    one.machine.pin_offsets.push_back(getPinOffset(m, c));
    if (m.gas) one.firing_angles.push_back(m.firing_angles.at(static_cast<size_t>(c)));
  }
  one.machine.cylinders = static_cast<int>(one.machine.crank_angles.size());
  one.machine.explicit_crank_angles = true;
  return one;
}

int countShaftSections(const Mechanism& m) {
  const int throws = static_cast<int>(findThrows(m).size());
  return m.crankshaft && m.crankshaft->front_inertia > 0.0 ? throws + 1 : throws;
}

double getSectionDamping(const CrankshaftParams& c, int i) {
  return c.section_damping.size() == 1 ? c.section_damping.front() : c.section_damping.at(static_cast<size_t>(i));
}

bool isSingleBank(const Mechanism& m) {
  for (double gamma : m.machine.bank_angles)
    if (gamma != m.machine.cylinder_angle) return false;
  return true;
}

bool hasAxialPositions(const Mechanism& m) { return !m.machine.axial_positions.empty(); }

Mechanism withLoads(const Mechanism& m, bool gas, bool inertia, bool gravity) {
  Mechanism out = m;
  if (!gas) {
    out.gas.reset();
    out.firing_angles.clear();
  }
  if (!inertia) out.machine.speed = out.speed_rpm = 0.0;
  if (!gravity) out.machine.gravity = 0.0;
  return out;
}

double calcGasForce(const Mechanism& m, int j, double phi) {
  if (!m.gas) return 0.0;
  return calcGasPressure(*m.gas, phi - m.firing_angles.at(static_cast<size_t>(j))) * calcBoreArea(*m.gas);
}

PhaseTurns calcPhaseTurns(int cylinders, Cycle cycle, Acting acting) {
  if (cylinders < 1) throw std::invalid_argument("calcPhaseTurns: cylinders must be >= 1");
  // alpha_j / (2 pi) = (T / 2 pi) j / k, eqs (8)-(11). In units of 1/(2k) turn: T/(2 pi) = 1 or 2, halved
  // for double-acting, so the step is t / (2k) turn with t = 2 (two-stroke), 4 (four-stroke), halved.
  long long t = (cycle == Cycle::kTwoStroke) ? 2 : 4;
  if (acting == Acting::kDouble) t /= 2;
  PhaseTurns turns;
  turns.denominator = 2LL * cylinders;
  for (int j = 0; j < cylinders; ++j) turns.numerators.push_back((t * j) % turns.denominator);
  return turns;
}

std::vector<double> calcPhaseAngles(int cylinders, Cycle cycle, Acting acting) {
  const PhaseTurns turns = calcPhaseTurns(cylinders, cycle, acting);
  std::vector<double> alpha;
  alpha.reserve(turns.numerators.size());
  for (long long num : turns.numerators) {
    // 360 * num / (2k) degrees; exact whenever the result is a whole number of degrees.
    const double degrees = 180.0 * static_cast<double>(num) / static_cast<double>(cylinders);
    alpha.push_back(radiansFromDegrees(degrees));
  }
  return alpha;
}

double radiansFromDegrees(double degrees) {
  if (std::isfinite(degrees) && std::fmod(degrees, 90.0) == 0.0) return (degrees / 90.0) * M_PI_2;
  return degrees * (M_PI / 180.0);
}

double reduceCrankAngle(double phi) {
  if (!(std::fabs(phi) > 4.0 * M_PI)) return phi;  // also NaN
  if (!std::isfinite(phi)) return phi;
  const double half = 0.5 * phi;  // exact
  return 2.0 * std::atan2(std::sin(half), std::cos(half));
}

double crankAngleFromDegrees(double degrees) {
  if (std::fabs(degrees) > 720.0 && std::isfinite(degrees)) degrees = std::fmod(degrees, 720.0);  // exact
  return radiansFromDegrees(degrees);
}

double degreesFromRadians(double radians) {
  if (std::isfinite(radians) && radians != 0.0) {
    const double quarter_turns = std::nearbyint(radians / M_PI_2);
    if (quarter_turns * M_PI_2 == radians) return quarter_turns * 90.0;
  }
  return radians * (180.0 / M_PI);
}

std::string toString(Cycle cycle) { return cycle == Cycle::kTwoStroke ? "two-stroke" : "four-stroke"; }
std::string toString(Acting acting) { return acting == Acting::kSingle ? "single" : "double"; }

}  // namespace crankcheck
