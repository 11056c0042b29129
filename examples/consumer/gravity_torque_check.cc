// Q = dU/dphi (Stanczak eq 13) of a standing single cylinder, checked against a central difference of U: the
// smallest program that uses crankcheck::analytic from an install tree. Exit status 0 when they agree.
#include <cmath>
#include <cstdio>
#include <numbers>

#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/scene/scene_file.h"

int main() {
  const crankcheck::Mechanism m = crankcheck::parseScene(R"(
[engine]
cylinders = 1
cycle = "four-stroke"
cylinder_angle_deg = 90
speed_rpm = 0
[crank]
radius = 0.043
mass = 1.2
com_radius = 0.02
[rod]
length = 0.145
mass = 0.55
com_from_wrist_pin = 0.105
inertia_about_wrist_pin = 0.0072
[piston]
mass = 0.35
)", "consumer");
  const double h = 1e-5;  // [rad]; the central difference's error is ~ h^2 |U'''| ~ 1e-10 Q_max, roundoff ~ eps U / h
  double worst = 0.0;
  for (int i = 0; i < 36; ++i) {
    const double phi = i * std::numbers::pi / 18.0;
    const double Q = crankcheck::analytic::calcGravityTorque(m, phi);
    const double dU = (crankcheck::analytic::calcPotentialEnergy(m, phi + h) -
                       crankcheck::analytic::calcPotentialEnergy(m, phi - h)) / (2.0 * h);
    worst = std::fmax(worst, std::fabs(Q - dU));
  }
  std::printf("gravity_torque_check: max |Q - dU/dphi| = %.3g N m\n", worst);
  return worst < 1e-8 ? 0 : 1;  // Q is of order 1 N m here: 1e-8 is far above both errors and far below any slip
}
