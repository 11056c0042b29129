// The holding torque Q of a 4-cylinder inline engine from both engines (the closed form and the Simbody model),
// compared with the harness's own rule: |a - b| <= tol x the case's torque scale. Exit status 0 when they agree.
#include <cmath>
#include <cstdio>
#include <numbers>

#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/simbody_models/k_crank_model.h"
#include "crankcheck/validation/output_folder.h"
#include "crankcheck/validation/scales.h"

int main() {
  const crankcheck::Mechanism m = crankcheck::parseScene(R"(
[engine]
cylinders = 4
cycle = "four-stroke"
cylinder_angle_deg = 60
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
  crankcheck::simbody_models::KCrankModel model(m);
  const double scale = crankcheck::validation::calcTorqueScale(m);
  double worst = 0.0;
  for (int i = 0; i < 24; ++i) {
    const double phi = i * std::numbers::pi / 12.0;
    worst = std::fmax(worst, std::fabs(crankcheck::analytic::calcGravityTorque(m, phi) - model.calcHoldingTorque(phi)));
  }
  std::printf("engines_agree (crankcheck %s): max |Q_analytic - Q_simbody| = %.3g of the torque scale\n",
              crankcheck::validation::getCrankcheckVersion(), worst / scale);
  return worst <= 1e-9 * scale ? 0 : 1;  // the gate's Q agreement is ~1e-13 of the scale; 1e-9 catches any slip
}
