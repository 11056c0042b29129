// A fixed amount of work for instruction counting (valgrind --tool=callgrind), which, unlike wall time, repeats
// exactly on a shared machine:
//   valgrind --tool=callgrind build/bin/crankcheck_profile full|reduced K N
// runs the static holding torque of a k-cylinder engine at N angles of a sweep (one System, warm starts).

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "crankcheck/simbody_models/k_crank_gravity_model.h"
#include "crankcheck/simbody_models/k_crank_model.h"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: crankcheck_profile full|reduced K N\n");
    return 2;
  }
  const std::string kind = argv[1];
  const int k = std::atoi(argv[2]), n = std::atoi(argv[3]);
  crankcheck::Mechanism m;  // the benchmark mechanism (bench/crankcheck_bench.cc)
  m.machine.cylinders = k;
  m.machine.cycle = crankcheck::Cycle::kFourStroke;
  m.machine.crank_angles = crankcheck::calcPhaseAngles(k, m.machine.cycle, m.machine.acting);
  m.machine.cylinder_angle = crankcheck::radiansFromDegrees(90.0);
  m.crank = {0.05, 1.7, 0.02, 1.3, 0.04};
  m.rod = {0.05 / 0.3, 0.61, 0.05, 0.61 * (0.05 * 0.05 + 0.045 * 0.045)};
  m.piston.mass = 0.43;
  double sum = 0.0;
  if (kind == "full") {
    crankcheck::simbody_models::KCrankModel model(m);
    for (int i = 0; i < n; ++i) sum += model.calcHoldingTorque(2.0 * M_PI * i / 1024.0);
  } else {
    crankcheck::simbody_models::KCrankGravityModel model(m);
    for (int i = 0; i < n; ++i) sum += model.calcHoldingTorque(2.0 * M_PI * i / 1024.0);
  }
  std::printf("%.17g\n", sum);
  return 0;
}
