#pragma once
/// @file
/// The work of the gas forces on the crankshaft, W(phi) = integral from 0 to phi of the gas torque (motion.h's
/// calcGasTorque) [J]: what a run under gas gains from the pistons, the energy integral's gas term
/// (1/2) J(phi) phi_dot^2 + U(phi) - W(phi) + T_L phi = const under a constant load torque T_L. The gas torque is smooth
/// between the pressure table's corners and periodic over the working cycle (4 pi four-stroke, 2 pi two-stroke): W is
/// integrated once over the cycle, by 8-point Gauss-Legendre on every interval of a 0.1-degree grid split at every
/// cylinder's corners (to rounding on a smooth interval), and read at any phi as whole cycles plus a grid node plus the
/// same rule on the rest of its interval. The flywheel's steady run (flywheel.h) and the time-stepped grade's loaded
/// runs read W here.

#include <vector>

#include "crankcheck/scene/mechanism.h"

namespace crankcheck::analytic {

/// W over the working cycle of a scene with [gas].
class GasWork {
 public:
  /// @throws std::invalid_argument if the scene has no [gas] or no speed (calcGasTorque needs one).
  explicit GasWork(const Mechanism& m);

  double getCycle() const { return cycle_; }              ///< [rad] the working cycle
  const std::vector<double>& getGrid() const { return grid_; }  ///< [rad] the nodes from 0 to the cycle, corners included
  const std::vector<double>& getNodeWork() const { return work_; }  ///< [J] W at each node
  double getCycleWork() const { return work_.back(); }    ///< [J] W over one cycle
  /// [N m] The cycle mean of the gas torque: the constant load that makes a run under gas periodic over the cycle.
  double getMeanTorque() const { return work_.back() / cycle_; }
  /// [J] W(phi) at any phi [rad] (negative phi: minus the work from phi to 0).
  double calcWork(double phi) const;

 private:
  const Mechanism* m_;
  double cycle_ = 0.0;
  std::vector<double> grid_, work_;
};

}  // namespace crankcheck::analytic
