#include "crankcheck/analytic/gas_work.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "crankcheck/analytic/motion.h"

namespace crankcheck::analytic {
namespace {

constexpr double kNodes[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                              0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
constexpr double kWeights[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                                0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

// 8-point Gauss-Legendre of the gas torque over [a, b].
double integrate(const Mechanism& m, double a, double b) {
  const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
  double sum = 0.0;
  for (int q = 0; q < 8; ++q) sum += kWeights[q] * calcGasTorque(m, mid + half * kNodes[q]);
  return half * sum;
}

}  // namespace

GasWork::GasWork(const Mechanism& m) : m_(&m) {
  if (!m.gas) throw std::invalid_argument("GasWork: the scene has no [gas]");
  if (!(m.machine.speed > 0.0)) throw std::invalid_argument("GasWork: the scene has no speed");
  cycle_ = m.machine.cycle == Cycle::kFourStroke ? 4.0 * M_PI : 2.0 * M_PI;
  // The cycle's grid: 0.1 degree steps and the pressure table's corners of every cylinder, sorted, from 0 to the cycle.
  std::vector<double> grid;
  const int n = static_cast<int>(std::lround(degreesFromRadians(cycle_) * 10.0));
  for (int i = 0; i <= n; ++i) grid.push_back(cycle_ * i / n);
  for (size_t j = 0; j < m.firing_angles.size(); ++j)
    for (double a : m.gas->cycle_angles) grid.push_back(std::fmod(std::fmod(m.firing_angles[j] + a, cycle_) + cycle_, cycle_));
  std::sort(grid.begin(), grid.end());
  for (double x : grid)
    if (grid_.empty() || x - grid_.back() > 1e-12) grid_.push_back(x);
  work_.assign(grid_.size(), 0.0);
  for (size_t i = 1; i < grid_.size(); ++i) work_[i] = work_[i - 1] + integrate(m, grid_[i - 1], grid_[i]);
}

double GasWork::calcWork(double phi) const {
  const double cycles = std::floor(phi / cycle_);
  const double rest = phi - cycles * cycle_;  // in [0, cycle)
  const size_t i = static_cast<size_t>(std::upper_bound(grid_.begin(), grid_.end(), rest) - grid_.begin()) - 1;
  const size_t node = std::min(i, grid_.size() - 2);
  return cycles * work_.back() + work_[node] + integrate(*m_, grid_[node], rest);
}

}  // namespace crankcheck::analytic
