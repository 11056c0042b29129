#pragma once
/// @file
/// An example scene with a `[crankshaft]` table of the test's own (tests of the torsion analysis).

#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <boost/math/quadrature/gauss_kronrod.hpp>

#include "crankcheck/analytic/crank_train.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/scene/scene_file.h"

namespace crankcheck::testing {

/// The scene file `path` with its own `[crankshaft]` table (the example scenes end with it, when they have one)
/// replaced by `crankshaft_table` (the table's keys, without its header).
inline Mechanism loadSceneWithCrankshaft(const std::filesystem::path& path, const std::string& crankshaft_table) {
  std::ifstream in(path);
  std::ostringstream file;
  file << in.rdbuf();
  std::string text = file.str();
  const size_t own = text.find("\n[crankshaft]");
  if (own != std::string::npos) text.resize(own + 1);
  return parseScene(text + "\n[crankshaft]\n" + crankshaft_table, path.filename().string());
}

/// T_p, the p-th complex order of throw `tm`'s rigid torque over the train's cycle (calcRigidThrowTorque), by 61-point
/// Gauss-Kronrod (Boost.Math) on the cycle cut into `pieces` equal parts and at the pressure table's corners (the torque
/// is smooth between them): a reference the code under test did not produce.
inline std::complex<double> calcTorqueOrderByQuadrature(const analytic::CrankTrain& train, const Mechanism& tm, int p,
                                                        int pieces) {
  std::vector<double> cuts;
  for (int d = 0; d <= pieces; ++d) cuts.push_back(train.cycle * d / pieces);
  for (double firing : tm.firing_angles)
    for (double a : tm.gas->cycle_angles) cuts.push_back(std::fmod(firing + a, train.cycle));
  std::sort(cuts.begin(), cuts.end());
  std::complex<double> sum = 0.0;
  auto torque = [&](double psi) { return analytic::calcRigidThrowTorque(tm, psi, train.omega); };
  for (size_t c = 0; c + 1 < cuts.size(); ++c) {
    if (!(cuts[c + 1] > cuts[c])) continue;
    const double re = boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
        [&](double psi) { return torque(psi) * std::cos(2 * M_PI * p * psi / train.cycle); }, cuts[c], cuts[c + 1], 0);
    const double im = boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
        [&](double psi) { return -torque(psi) * std::sin(2 * M_PI * p * psi / train.cycle); }, cuts[c], cuts[c + 1], 0);
    sum += std::complex<double>(re, im);
  }
  return (p == 0 ? 1.0 : 2.0) * sum / train.cycle;  // c_0 is the mean (PeriodicSignal)
}

/// The flywheel section's torque (K + i w C) x its twist's orders p <= 16 (n <= 8) against the rigid engine's drive
/// torque's orders (reactions.h: Newton-Euler on the whole engine, 4096 samples a cycle): the largest difference over
/// those orders relative to the largest drive-torque order. It tends to 0 as the shaft stiffens (the stiff limit).
inline double calcFlywheelTorqueDifference(const Mechanism& m, const analytic::CrankTrain& train,
                                           const analytic::PeriodicSignal& flywheel_twist) {
  std::vector<double> samples;
  for (int k = 0; k < 4096; ++k) samples.push_back(analytic::calcReactions(m, train.cycle * k / 4096).drive_torque);
  const analytic::PeriodicSignal rigid = analytic::calcSignalFromSamples(samples);
  double largest = 0.0, difference = 0.0;
  for (size_t p = 0; p <= 16; ++p) {
    const double w = 2 * M_PI * static_cast<double>(p) / train.cycle * train.omega;
    const std::complex<double> section =
        std::complex<double>(train.stiffness.back(), w * train.section_damping.back()) * flywheel_twist.coefficients[p];
    largest = std::max(largest, std::abs(rigid.coefficients[p]));
    difference = std::max(difference, std::abs(section - rigid.coefficients[p]));
  }
  return difference / largest;
}

}  // namespace crankcheck::testing
