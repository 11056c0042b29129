#pragma once
/// @file
/// Gas pressure: an input of the scene, applied alike by every engine (CONVENTIONS.md, "Layouts, axial positions,
/// gas and shaking"). The gauge pressure above the crankcase is periodic and piecewise linear in the cycle angle
/// phi - firing_j over one working cycle (720 degrees four-stroke, 360 two-stroke): linear between the table's
/// points, and from the last point to the cycle's end, where it meets the first value again. It pushes piston j
/// toward the crank with p A (A the bore area): the force on the piston is -p A e_j.

#include <vector>

namespace crankcheck {

/// The scene's [gas] table in SI.
struct GasParams {
  double bore = 0.0;                 ///< [m]
  std::vector<double> cycle_angles;  ///< [rad] strictly increasing, first 0, last below `cycle`
  std::vector<double> pressures;     ///< [Pa] gauge, above the crankcase, one per cycle angle (>= -101325)
  double cycle = 0.0;                ///< [rad] the working cycle: 4 pi (four-stroke) or 2 pi (two-stroke)
};

/// [Pa] p at cycle angle `psi` [rad], any value (reduced into [0, cycle) first).
double calcGasPressure(const GasParams& gas, double psi);

/// [m^2] the bore area pi bore^2 / 4.
double calcBoreArea(const GasParams& gas);

}  // namespace crankcheck
