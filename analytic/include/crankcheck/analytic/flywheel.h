#pragma once
/// @file
/// Flywheel sizing (Norton, Design of Machinery, 13.9) for an engine with gas: the flywheel inertia I_f at which the
/// steady run at the scene's mean speed under a constant load torque has the speed fluctuation
/// delta = (omega_max - omega_min) / omega_mean = C, exactly and by Norton's method.
///
/// The steady run (gravity on): with the mechanism's own reduced inertia J(phi) (motion.h; the scene's flywheel
/// replaced by I_f, not added) the energy integral
///   (1/2) (J(phi) + I_f) phi_dot^2 = (1/2) (J(0) + I_f) phi_dot(0)^2 + W(phi) - T_L phi - U(phi),
/// W(phi) the work of the gas on the shaft since phi = 0 (the integral of the gas's torque, motion.h's calcGasTorque),
/// U the potential (potential_energy.h), T_L the load: the cycle mean of the gas torque, so that the run is periodic
/// over the working cycle (720 degrees four-stroke, 360 two-stroke). phi_dot(0) is chosen so that the mean speed
/// (cycle angle over cycle time) is the scene's omega. No time stepping: W by 8-point
/// Gauss-Legendre on every interval of a 0.1-degree grid split at the pressure table's corners (the gas torque is smooth
/// between them), the cycle time by Simpson's rule on the same grid, the extremes of phi_dot refined by a parabola
/// through the best sample and its neighbours. The root in I_f (delta falls as I_f grows) and the one in phi_dot(0) are
/// found by the secant method to rounding.
/// Norton's method: at constant speed omega the engine's torque T(phi) (gas, inertia and gravity: minus the drive
/// torque) has the cycle mean T_L; the energy E between the extremes of the integral of T - T_L over the cycle gives
/// I = E / (C omega^2) (13.9). Its real delta is the steady run's with that I_f.

#include <vector>

#include "crankcheck/scene/mechanism.h"

namespace crankcheck::analytic {

/// The steady run with flywheel I_f [kg m^2] and load T_L [N m], at the scene's mean speed.
struct SteadyRun {
  double omega0 = 0.0;       ///< [rad/s] phi_dot at phi = 0
  double omega_mean = 0.0;   ///< [rad/s] cycle angle / cycle time (the scene's omega)
  double omega_min = 0.0, omega_max = 0.0;  ///< [rad/s]
  double delta = 0.0;        ///< (omega_max - omega_min) / omega_mean
  double phi_at_omega_min = 0.0, phi_at_omega_max = 0.0;  ///< [rad] where, in [0, cycle) (the parabola's vertex)
};

struct FlywheelSizing {
  double load_torque = 0.0;         ///< [N m] T_L, the cycle mean of the gas torque
  double exact_inertia = 0.0;       ///< [kg m^2] I_f for delta = C
  SteadyRun exact;                  ///< the steady run with it
  double norton_inertia = 0.0;      ///< [kg m^2] E / (C omega^2)
  double norton_energy = 0.0;       ///< [J] E
  SteadyRun norton;                 ///< the steady run with Norton's I_f: the delta it really gives
};

/// @throws std::invalid_argument if the scene has no [gas], omega <= 0, or C is not in (0, 1);
///         std::domain_error if no flywheel >= 0 gives delta = C (the mechanism alone already runs at delta <= C, or
///         the speed cannot stay positive); std::runtime_error if the root does not converge.
FlywheelSizing calcFlywheelSizing(const Mechanism& m, double fluctuation);

/// A given flywheel judged (the report's scene sections): the steady run with flywheel_inertia [kg m^2] in place of
/// the scene's under the load T_L (the cycle mean of the gas torque, as calcFlywheelSizing), and the delta Norton's
/// method predicts for it, E / (I_f omega^2) (13.9 solved for C), from one computation of the cycle's integrals.
struct FlywheelFluctuation {
  double load_torque = 0.0;    ///< [N m] T_L
  SteadyRun exact;             ///< the steady run with flywheel_inertia
  double norton_energy = 0.0;  ///< [J] E
  double norton_delta = 0.0;   ///< [-] E / (flywheel_inertia omega^2)
};

/// @throws std::invalid_argument if the scene has no [gas], omega <= 0 or flywheel_inertia <= 0;
///         std::domain_error if the energy integral leaves no positive speed.
FlywheelFluctuation calcFlywheelFluctuation(const Mechanism& m, double flywheel_inertia);

/// The steady run of m with flywheel_inertia in place of the scene's and load_torque.
/// @throws std::domain_error if the energy integral leaves no positive speed.
SteadyRun calcSteadyRun(const Mechanism& m, double flywheel_inertia, double load_torque);

/// calcSteadyRun at each of flywheel_inertias, the cycle's integrals (what does not depend on I_f) computed once.
/// @throws as calcSteadyRun.
std::vector<SteadyRun> calcSteadyRuns(const Mechanism& m, const std::vector<double>& flywheel_inertias,
                                      double load_torque);

}  // namespace crankcheck::analytic
