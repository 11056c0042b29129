#pragma once
/// @file
/// Holzer's forced response of the crank train (docs/CONVENTIONS-crankcheck.md, "Holzer's model"): every throw a constant
/// inertia J_eq,j (torsion.h, ThrowInertia::exact), the throws' torque in the rigid motion psi = omega t
/// (crank_train.h, calcRigidThrowTorque: gas, inertia and gravity) expanded by order, and for each order n = p 2 pi /
/// cycle (a multiple of 1/2 four-stroke, of 1 two-stroke)
///   (K - (n omega)^2 J_eq + i n omega C) X_n = T_n,
/// the bodies' deviations x(t) = Re sum_n X_n e^{i n omega t} summed over every order until the sum converges.
///
/// Convergence: the torque orders p = 0 .. P per cycle (to about rounding: quadrature split at the pressure table's
/// corners, torsion_forced.cc), P doubled from 64 until every section's peak-to-peak twist changes by at most
/// HolzerOptions::convergence (1e-8) of the largest one (the corners make T_n fall as n^-2, so the response falls as
/// n^-4 and the tail beyond P as P^-3: the last doubling's change bounds it). The lower the speed, the more orders
/// lie below the natural frequencies: the example inline four needs P = 4096 at 6000 rpm, 16384 at 2000 rpm. The
/// textbook's sum cut at order 24 is given beside it.

#include <complex>
#include <memory>
#include <vector>

#include <Eigen/Dense>

#include "crankcheck/analytic/crank_train.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::analytic {

struct HolzerOptions {
  double convergence = 1e-8;      ///< the last doubling's largest change of a peak-to-peak, relative to the largest
  int max_harmonics = 1 << 16;    ///< P at most
};

struct HolzerResponse {
  std::vector<double> inertias;             ///< [kg m^2] J of the bodies: front mass, then J_eq,j
  int orders = 0;                           ///< P, the harmonics per cycle summed (order P 2 pi / cycle)
  double change = 0.0;                      ///< the last doubling's change (HolzerOptions::convergence)
  /// Body i's deviation x_i [rad] over the cycle phase tau = 2 pi omega t / cycle.
  std::vector<PeriodicSignal> bodies;
  /// Section i's twist [rad] (crank_train.h), every order summed.
  std::vector<PeriodicSignal> twists;
  std::vector<double> peak_to_peak;         ///< [rad] per section, every order summed
  std::vector<double> peak_to_peak_order24; ///< [rad] per section, the orders n <= 24 alone (the textbook's cut)
  /// The throws' torque orders T_p [N m] (rows p = 0 .. P, columns the throws): T(psi) = Re sum_p T_p e^{i p tau}.
  Eigen::MatrixXcd torque_orders;
};

/// What the torque orders of a train's throws share across speeds. Throw j's torque in the rigid motion at omega is
/// T(psi) = A(psi) - (1/2) omega^2 B(psi) with A = T_gas - Q and B = J' (crank_train.h, calcThrowLoads), neither of
/// which depends on omega; so are their orders A_p, B_p (the quadrature and FFT above), and T_p = A_p - (1/2) omega^2
/// B_p. An object keeps every A_p, B_p a sum has asked for, for each P, so that a sweep over speed computes them once
/// (part 17's speed points, `crankcheck torsion`). Safe to share between threads. It serves the trains of one scene
/// at any speed: the first train it serves fixes its throws; another's (other loads at two test angles, another cycle
/// or count of throws) is refused.
class ThrowLoadOrders {
 public:
  ThrowLoadOrders();
  ~ThrowLoadOrders();
  ThrowLoadOrders(const ThrowLoadOrders&) = delete;
  ThrowLoadOrders& operator=(const ThrowLoadOrders&) = delete;

  struct Orders {
    std::vector<std::complex<double>> A, B;  ///< [N m], [kg m^2/rad]: p = 0 .. P (A(psi) = Re sum_p A_p e^{i p tau})
  };
  /// Throw j's orders p = 0 .. P of `train` (computed at the first call for that P and kept).
  /// @throws std::invalid_argument if `train` is not a train of the scene this object serves.
  const Orders& getOrders(const CrankTrain& train, int j, int P);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// @throws std::invalid_argument as makeCrankTrain, or if a body has no inertia;
///         std::runtime_error if the sum has not converged with P = max_harmonics.
HolzerResponse calcHolzerResponse(const Mechanism& m, const HolzerOptions& options = {});

/// The same, the torque orders' speed-free parts read from (and added to) `shared`, an object that serves m's scene.
/// @throws std::invalid_argument also if `shared` serves another scene.
HolzerResponse calcHolzerResponse(const Mechanism& m, const HolzerOptions& options, ThrowLoadOrders& shared);

/// The same on a train already built (the J_eq of its throws given, front first as the bodies are).
HolzerResponse calcHolzerResponse(const CrankTrain& train, const std::vector<double>& inertias,
                                  const HolzerOptions& options = {});
HolzerResponse calcHolzerResponse(const CrankTrain& train, const std::vector<double>& inertias,
                                  const HolzerOptions& options, ThrowLoadOrders& shared);

}  // namespace crankcheck::analytic
