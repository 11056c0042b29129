#pragma once
/// @file
/// The elastic crank train of a scene's `[crankshaft]` (docs/CONVENTIONS-crankcheck.md, "Torsion"), built once and shared by
/// Holzer's forced response (torsion_forced.h) and the exact periodic steady state (torsion_steady.h): the bodies along
/// the shaft, front first (the front mass F when front_inertia > 0, then the throws of findThrows), each section's
/// stiffness and damping, each throw's loads as functions of its own angle psi_j, and the twist's Fourier series.
///
/// Coordinates: x_i = psi_i - omega t, the bodies' deviations from the flywheel's driven motion psi_W = omega t.
/// Section i joins body i and body i + 1 (the last one: the flywheel, x_W = 0); its twist is x_{i+1} - x_i (the last:
/// -x_{n-1}). The exact equation of throw j (CONVENTIONS):
///   (J_t + J_j(psi_j)) psi_j'' + (1/2) J_j'(psi_j) psi_j'^2 = T_gas,j(psi_j) - Q_j(psi_j) - c_t x_j' + elastic_j,
///   elastic_j = sum over its sections of K_s (x_b - x_a) + C_s (x_b' - x_a') on a, the opposite on b.

#include <complex>
#include <vector>

#include <Eigen/Dense>

#include "crankcheck/analytic/exact_trig.h"
#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::analytic {

/// The cylinders of throw `throw_index` (selectThrow, scene/mechanism.h) at crank speed 1 rad/s: its J(phi), Q(phi),
/// gas forces and kinematics are throw j's at psi = phi.
/// @throws std::out_of_range if there is no such throw.
Mechanism makeThrowMechanism(const Mechanism& m, int throw_index);

/// What acts on one throw at its angle psi [rad].
struct ThrowLoads {
  double J = 0.0;               ///< [kg m^2] J_j(psi), the cylinders' reduced inertia (without J_t)
  double dJ = 0.0;              ///< [kg m^2/rad] dJ_j/dpsi
  double gas_torque = 0.0;      ///< [N m] T_gas,j: the gas forces' torque on the throw about +Z, -sum p A dx_p/dpsi
  double gravity_torque = 0.0;  ///< [N m] Q_j = dU_j/dpsi (so gravity's torque on the throw is -Q_j)
};

/// A throw mechanism (makeThrowMechanism) with what its loads read of it at every angle worked out once: the copy at
/// unit speed its kinematics use, gravity's coefficients (Stanczak eq 5) and each cylinder's crank angle alpha_j and
/// bank angle as sine and cosine. The crank train's integrations evaluate the loads at every step
/// (torsion_steady.h, torsion_forced.h).
struct PreparedThrow {
  Mechanism mechanism;                  ///< the throw mechanism
  Mechanism unit;                       ///< its kinematics' copy at unit speed
  GravityCoefficients gravity;          ///< calcGravityCoefficients(mechanism)
  std::vector<SinCos> crank_angles;     ///< alpha_j per cylinder
  std::vector<SinCos> bank_angles;      ///< getBankAngle per cylinder
};
PreparedThrow prepareThrow(const Mechanism& throw_mechanism);

/// Throw loads of a throw mechanism (makeThrowMechanism) at psi.
ThrowLoads calcThrowLoads(const Mechanism& throw_mechanism, double psi);
/// The same, bit for bit, from its prepared form.
ThrowLoads calcThrowLoads(const PreparedThrow& prepared, double psi);

/// [N m] The torque the throw's cylinders put on the shaft in the rigid motion psi = omega t at constant omega:
/// T_gas - Q - (1/2) J' omega^2 (minus the drive torque that would hold the throw alone at omega, reactions.h).
double calcRigidThrowTorque(const Mechanism& throw_mechanism, double psi, double omega);

/// The crank train of a scene, built once.
struct CrankTrain {
  std::vector<Mechanism> throws;        ///< makeThrowMechanism of each throw, front first
  bool has_front = false;               ///< body 0 is the front mass
  double front_inertia = 0.0;           ///< [kg m^2]
  double throw_inertia = 0.0;           ///< J_t [kg m^2]
  std::vector<double> stiffness;        ///< K_s [N m/rad], one per section
  std::vector<double> section_damping;  ///< C_s [N m s/rad], one per section
  double throw_damping = 0.0;           ///< c_t [N m s/rad]
  double omega = 0.0;                   ///< [rad/s] the flywheel's speed (the scene's)
  double cycle = 0.0;                   ///< [rad] the working cycle: 4 pi (four-stroke), 2 pi (two-stroke)
  /// Bodies (= sections).
  int countBodies() const { return static_cast<int>(stiffness.size()); }
  /// The body index of throw j.
  int getThrowBody(int j) const { return j + (has_front ? 1 : 0); }
};

/// @throws std::invalid_argument if the scene has no [crankshaft], its speed is not > 0, or the stiffness list does
///         not have one value per section (countShaftSections).
CrankTrain makeCrankTrain(const Mechanism& m);

/// K [N m/rad] and C [N m s/rad] of the linear part of the train (n x n, clamped at the flywheel): sections' springs
/// and dampers, and c_t on the throws' diagonal.
Eigen::MatrixXd calcStiffnessMatrix(const CrankTrain& train);
Eigen::MatrixXd calcDampingMatrix(const CrankTrain& train);

/// The sections' twists [rad] from the bodies' deviations x (section i: x_{i+1} - x_i, the last -x_{n-1}).
Eigen::VectorXd calcSectionTwists(const Eigen::VectorXd& x);

/// A real periodic signal of the cycle phase tau = 2 pi omega t / cycle in [0, 2 pi), by its complex Fourier
/// coefficients: s(tau) = Re sum_p c_p e^{i p tau}, p = 0, 1, ... (c_0 real: the mean). Order n = p 2 pi / cycle.
struct PeriodicSignal {
  std::vector<std::complex<double>> coefficients;
  double evaluate(double tau) const;
};

/// The signal's extremes over a period: sampled by an inverse FFT on a grid of at least 8 points per coefficient (and
/// 256), the best
/// sample's neighbourhood refined by Brent's method (Boost.Math, half the double's digits in tau: the value then to
/// rounding, as the extreme is quadratic).
struct SignalExtremes {
  double min = 0.0, max = 0.0;          ///< [unit of the signal]
  double tau_min = 0.0, tau_max = 0.0;  ///< [rad] where
  double peakToPeak() const { return max - min; }
};
SignalExtremes findSignalExtremes(const PeriodicSignal& s);

/// The Fourier coefficients (PeriodicSignal) of N equally spaced samples of a period, by Eigen's FFT: p = 0 .. N/2
/// (the last halved: the Nyquist term). N must be even.
PeriodicSignal calcSignalFromSamples(const std::vector<double>& samples);

}  // namespace crankcheck::analytic
