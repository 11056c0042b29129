// Loads over one working cycle (working_cycle.h).
#include "working_cycle.h"

#include <cmath>

namespace crankcheck::validation {

double calcCycleAngle(const Mechanism& m) { return m.machine.cycle == Cycle::kFourStroke ? 4.0 * M_PI : 2.0 * M_PI; }

std::pair<double, double> calcCrankPinForceInCrankFrame(const Mechanism& m, const Evaluation& e, int j) {
  const double angle = e.phi + getThrowAngle(m, j);
  const Vec2& F = e.cylinders.at(static_cast<size_t>(j)).crank_pin_force;
  return {F[0] * std::cos(angle) + F[1] * std::sin(angle), -F[0] * std::sin(angle) + F[1] * std::cos(angle)};
}

TurnMaximum findMaxAbsOverCycle(const std::function<double(double)>& f, double cycle, const std::vector<double>& values,
                                int refinements, double tolerance) {
  const auto on_turn = [&](double u) { return f(u * cycle / (2.0 * M_PI)); };
  TurnMaximum best = findMaxAbsOverTurn(on_turn, values, refinements, tolerance);
  best.phi = best.phi * cycle / (2.0 * M_PI);
  return best;
}

}  // namespace crankcheck::validation
