#include "torsion_train.h"

#include "crankcheck/validation/extremum.h"

namespace crankcheck::validation {

analytic::HolzerOptions makeTrainHolzerOptions() {
  analytic::HolzerOptions options;
  options.convergence = 1e-6;
  return options;
}

analytic::SteadyStateOptions makeTrainSteadyStateOptions() {
  analytic::SteadyStateOptions options;
  options.tolerance = 1e-8;
  options.samples = 2048;
  return options;
}

double getOrderStep(const Mechanism& m) { return m.machine.cycle == Cycle::kFourStroke ? 0.5 : 1.0; }

std::vector<double> listMajorOrders(const Mechanism& m, double highest) {
  const double firings = m.machine.cylinders * getOrderStep(m);
  std::vector<double> out;
  for (double p = firings; p <= highest + 1e-9; p += firings) out.push_back(p);
  return out;
}

std::string nameSection(const Mechanism& m, int i, int bodies) {
  const bool front = m.crankshaft->front_inertia > 0.0;
  auto body = [&](int b) {
    if (b >= bodies) return std::string("flywheel");
    if (front && b == 0) return std::string("front");
    return "throw" + std::to_string(b - (front ? 1 : 0));
  };
  return body(i) + "-" + body(i + 1);
}

std::pair<double, double> findThrowInertiaRange(const Mechanism& m, int j) {
  auto J = [&](double psi) { return analytic::calcThrowReducedInertia(m, j, psi); };
  const double top = findMaxAbsOverTurn(J, 720).value;
  const double below = findMaxAbsOverTurn([&](double psi) { return top - J(psi); }, 720).value;
  const double jt = m.crankshaft->throw_inertia;
  return {jt + top - below, jt + top};
}

TorsionModeBand calcTorsionModeBand(const Mechanism& m) {
  TorsionModeBand band;
  band.holzer = analytic::calcTorsionModes(m);
  std::vector<double> low = band.holzer.inertias, high = band.holzer.inertias;
  const bool front = m.crankshaft->front_inertia > 0.0;
  const int throws = static_cast<int>(findThrows(m).size());
  for (int j = 0; j < throws; ++j) {
    band.inertias.push_back(analytic::calcThrowInertia(m, j));
    const auto [jmin, jmax] = findThrowInertiaRange(m, j);
    band.ranges.emplace_back(jmin, jmax);
    low[static_cast<size_t>(j + (front ? 1 : 0))] = jmin;
    high[static_cast<size_t>(j + (front ? 1 : 0))] = jmax;
  }
  // The lightest throws give the highest frequencies.
  band.at_min = analytic::calcChainModes(low, band.holzer.stiffness);
  band.at_max = analytic::calcChainModes(high, band.holzer.stiffness);
  return band;
}

}  // namespace crankcheck::validation
