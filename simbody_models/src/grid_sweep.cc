// U and Q over a uniform grid by superposing one-cylinder Simbody models (grid_sweep.h). Uses the public KCrankModel
// only: no Simbody header, no analytic formula.

#include "crankcheck/simbody_models/grid_sweep.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace crankcheck::simbody_models {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kTurn = 2.0 * M_PI;

// Cylinder j reads the group's one-cylinder values at grid index i + shift (modulo the period, if any).
struct Member {
  int j = 0;
  long long shift = 0;
};

// Cylinders that share one one-cylinder model and one grid: the same bank angle and the same grid offset.
struct Group {
  double gamma = 0.0;
  double offset = 0.0;  // the group's grid is phi0 + offset + index step
  double pin_offset = 0.0;  // delta of every member [m]
  std::vector<Member> members;
};

// P when P |step| is one turn to 8 eps (indices then repeat every P), else 0.
long long findPeriod(double step) {
  const double steps_per_turn = kTurn / std::fabs(step);
  if (!(steps_per_turn < 1e15)) return 0;
  const double P = std::nearbyint(steps_per_turn);
  if (P < 1.0 || std::fabs(P * std::fabs(step) - kTurn) > 8.0 * kEps * kTurn) return 0;
  return static_cast<long long>(P);
}

std::vector<Group> groupCylinders(const Mechanism& m, double step) {
  if (m.machine.cylinders < 1 || m.machine.crank_angles.size() != static_cast<size_t>(m.machine.cylinders))
    throw std::invalid_argument("grid sweep: the mechanism needs one crank angle per cylinder (k >= 1)");
  if (!m.balance_shafts.empty())
    throw std::invalid_argument("grid sweep: superposing one-cylinder models has no room for balance shafts; use "
                                "KCrankModel angle by angle");
  std::vector<Group> groups;
  for (int j = 0; j < m.machine.cylinders; ++j) {
    const double alpha = m.machine.crank_angles[static_cast<size_t>(j)];
    const double gamma = getBankAngle(m, j);
    const double steps = std::nearbyint(alpha / step);
    // alpha_j a whole number of steps: the group's common grid, shifted; otherwise a grid of its own.
    const bool whole = std::fabs(steps) < 1e15 &&
                       std::fabs(alpha - steps * step) <= 8.0 * kEps * std::max(std::fabs(alpha), kTurn);
    const double offset = whole ? 0.0 : alpha;
    const long long shift = whole ? static_cast<long long>(steps) : 0;
    const double delta = getPinOffset(m, j);  // cylinders with different pin offsets are different one-cylinder models
    auto it = std::find_if(groups.begin(), groups.end(),
                           [&](const Group& g) { return g.gamma == gamma && g.offset == offset && g.pin_offset == delta; });
    if (it == groups.end()) it = groups.insert(groups.end(), Group{gamma, offset, delta, {}});
    it->members.push_back({j, shift});
  }
  return groups;
}

// The one-cylinder mechanism of bank gamma and pin offset delta: the same crank, rod and piston, alpha = 0, no gas (U
// and Q are gravity's).
Mechanism oneCylinder(const Mechanism& m, double gamma, double delta) {
  Mechanism one = m;
  one.machine.pin_offsets.assign(1, delta);
  one.machine.cylinders = 1;
  one.machine.crank_angles = {0.0};
  one.machine.explicit_crank_angles = true;
  one.machine.cylinder_angle = gamma;
  one.machine.bank_angles.clear();
  one.machine.axial_positions.clear();
  one.gas.reset();
  one.firing_angles.clear();
  one.crankshaft.reset();  // rigid: a [crankshaft] has one section per throw of the scene it came with
  return one;
}

long long wrap(long long index, long long period) {
  if (period == 0) return index;
  const long long r = index % period;
  return r < 0 ? r + period : r;
}

enum class Quantity { kHoldingTorque, kPotentialEnergy };

std::vector<double> superpose(Quantity quantity, const Mechanism& m, double phi0, double step, size_t n,
                              const ModelOptions& options, GridSweepStats* stats) {
  if (!std::isfinite(phi0) || !std::isfinite(step) || step == 0.0)
    throw std::invalid_argument("grid sweep: phi0 and step must be finite and step nonzero (phi0 " +
                                std::to_string(phi0) + ", step " + std::to_string(step) + ")");
  std::vector<double> out(n, 0.0);
  GridSweepStats counted;
  const long long period = findPeriod(step);
  const auto evaluate = [&](KCrankModel& model, double phi) {
    ++counted.evaluations;
    return quantity == Quantity::kHoldingTorque ? model.calcHoldingTorque(phi) : model.calcPotentialEnergy(phi);
  };
  for (const Group& group : groupCylinders(m, step)) {
    KCrankModel model(oneCylinder(m, group.gamma, group.pin_offset), options);
    ++counted.models;
    if (n == 0) continue;
    // Every distinct index the group's cylinders read, in increasing order (neighbouring angles: warm starts).
    std::vector<long long> indices;
    for (const Member& member : group.members) {
      if (period != 0 && n >= static_cast<size_t>(period)) {
        for (long long i = 0; i < period; ++i) indices.push_back(i);
      } else {
        for (size_t i = 0; i < n; ++i) indices.push_back(wrap(static_cast<long long>(i) + member.shift, period));
      }
    }
    std::sort(indices.begin(), indices.end());
    indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
    std::vector<double> values(indices.size());
    for (size_t v = 0; v < indices.size(); ++v)
      values[v] = evaluate(model, phi0 + group.offset + static_cast<double>(indices[v]) * step);
    for (const Member& member : group.members) {
      // U_1(theta_j) - U_1(alpha_j): each cylinder's energy relative to phi = 0, as the k-cylinder model's U.
      const double reference =
          quantity == Quantity::kPotentialEnergy ? evaluate(model, m.machine.crank_angles[member.j]) : 0.0;
      for (size_t i = 0; i < n; ++i) {
        const long long index = wrap(static_cast<long long>(i) + member.shift, period);
        const size_t v = static_cast<size_t>(std::lower_bound(indices.begin(), indices.end(), index) - indices.begin());
        out[i] += values[v] - reference;
      }
    }
  }
  if (stats) *stats = counted;
  return out;
}

}  // namespace

std::vector<double> calcHoldingTorqueOnGrid(const Mechanism& m, double phi0, double step, size_t n,
                                            ModelOptions options, GridSweepStats* stats) {
  return superpose(Quantity::kHoldingTorque, m, phi0, step, n, options, stats);
}

std::vector<double> calcPotentialEnergyOnGrid(const Mechanism& m, double phi0, double step, size_t n,
                                              ModelOptions options, GridSweepStats* stats) {
  return superpose(Quantity::kPotentialEnergy, m, phi0, step, n, options, stats);
}

}  // namespace crankcheck::simbody_models
