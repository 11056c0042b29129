#include "crankcheck/scene/gas.h"

#include <algorithm>
#include <cmath>

namespace crankcheck {

double calcGasPressure(const GasParams& gas, double psi) {
  double x = std::fmod(psi, gas.cycle);
  if (x < 0.0) x += gas.cycle;
  if (x >= gas.cycle) x = 0.0;  // fmod of a negative value next to 0 can round up to the cycle itself
  const std::vector<double>& a = gas.cycle_angles;
  // The segment [a_i, a_{i+1}) holding x; after the last point the segment runs to the cycle's end, where p is p_0.
  const size_t i = static_cast<size_t>(std::upper_bound(a.begin(), a.end(), x) - a.begin()) - 1;
  const double x0 = a[i], p0 = gas.pressures[i];
  const double x1 = i + 1 < a.size() ? a[i + 1] : gas.cycle;
  const double p1 = i + 1 < a.size() ? gas.pressures[i + 1] : gas.pressures.front();
  return p0 + (p1 - p0) * (x - x0) / (x1 - x0);
}

double calcBoreArea(const GasParams& gas) { return 0.25 * M_PI * gas.bore * gas.bore; }

}  // namespace crankcheck
