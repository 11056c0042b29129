#include "crankcheck/validation/example_gas.h"

#include <cmath>
#include <vector>

#include "crankcheck/validation/variants.h"

namespace crankcheck::validation {

GasParams makeExampleGas(Cycle cycle, double bore) {
  GasParams gas;
  gas.bore = bore;
  std::vector<double> degrees;
  if (cycle == Cycle::kFourStroke) {
    gas.cycle = 4.0 * M_PI;
    degrees = {0, 10, 20, 30, 45, 60, 90, 120, 150, 180, 200, 360, 380, 540, 600, 640, 670, 690, 705};
    gas.pressures = {3.2e6, 5.2e6, 5.6e6, 4.8e6, 3.4e6, 2.4e6, 1.3e6, 0.8e6, 0.55e6, 0.35e6,
                     0.05e6, 0.02e6, -0.03e6, -0.02e6, 0.08e6, 0.25e6, 0.6e6, 1.1e6, 1.9e6};
  } else {
    gas.cycle = 2.0 * M_PI;
    degrees = {0, 10, 20, 40, 60, 90, 110, 120, 180, 240, 270, 300, 330, 350};
    gas.pressures = {13e6, 15e6, 14e6, 9e6, 6e6, 3.5e6, 2.5e6, 0.3e6, 0.25e6, 0.3e6, 1.0e6, 2.5e6, 6e6, 10.5e6};
  }
  for (double d : degrees) gas.cycle_angles.push_back(radiansFromDegrees(d));
  return gas;
}

Mechanism withGasAtDeadCentres(const Mechanism& m, const GasParams& gas) {
  Mechanism out = m;
  out.gas = gas;
  out.firing_angles.clear();
  for (double alpha : m.machine.crank_angles) {
    double firing = std::fmod(-alpha, gas.cycle);
    if (firing < 0.0) firing += gas.cycle;
    out.firing_angles.push_back(firing);
  }
  return out;
}

}  // namespace crankcheck::validation
