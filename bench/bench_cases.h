#pragma once
/// @file
/// The benchmark's mechanism and angles, shared with the accuracy tests (tests/analytic/batch_test.cc), which check
/// the batch kernels on every angle the benchmark times.

#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include "crankcheck/scene/mechanism.h"

namespace crankcheck::bench {

/// The same mechanism family as the tests: r = 0.05 m, lambda = 0.3, rod centre of mass off the middle, 4500 rpm.
inline Mechanism benchMechanism(int k) {
  Mechanism m;
  m.machine.cylinders = k;
  m.machine.cycle = Cycle::kFourStroke;
  m.machine.crank_angles = calcPhaseAngles(k, m.machine.cycle, m.machine.acting);
  m.machine.cylinder_angle = radiansFromDegrees(90.0);
  m.machine.speed = 4500.0 * M_PI / 30.0;
  m.crank = {0.05, 1.7, 0.02, 1.3, 0.04};
  m.rod = {0.05 / 0.3, 0.61, 0.05, 0.61 * (0.05 * 0.05 + 0.045 * 0.045)};
  m.piston.mass = 0.43;
  return m;
}

/// Batches of 1e6 angles.
constexpr size_t kBatch = 1'000'000;

/// kBatch arbitrary angles, uniform in [-10, 10] rad (seed 42).
inline std::vector<double> benchAngles() {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> angle(-10.0, 10.0);
  std::vector<double> phi(kBatch);
  for (double& p : phi) p = angle(rng);
  return phi;
}

/// The benchmark's uniform grid: phi_i = i step, step = 2 pi / 3600 (a tenth of a degree).
constexpr double kGridPhi0 = 0.0;
constexpr double kGridStep = 2.0 * M_PI / 3600.0;

}  // namespace crankcheck::bench
