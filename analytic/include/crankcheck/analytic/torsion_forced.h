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
///
/// Stiff shafts (the stiff-limit route, taken when 8 x the highest natural frequency's order p_max = w_max cycle /
/// (2 pi omega) exceeds max_harmonics: the plain sum would need harmonics beyond it). The throws' torque is split
/// T(psi) = sum_c e_b s_c f(psi - c) + T_sm(psi): kernels f(u) = u/2 - u^2 / (2L) (L = cycle, u in [0, L)) carrying
/// each pressure-table corner's slope jump s_c [N m/rad], and the C^1 rest T_sm. Then, exactly,
///   x(psi) = K^-1 T(psi)                                    (the quasi-static part, every order at once, closed form)
///          + Re sum_{p <= P} [Z_p^-1 - K^-1] T_sm,p e^{i p tau}  (the smooth part's dynamic remainder, Z_p = K -
///                                                             (p w_1)^2 J + i p w_1 C, terms smaller by (p w_1)^2 J / K)
///          + sum_c s_c Re sum_k V_k g_k,b d_k(u_c)             (each kernel's dynamic response, closed form),
/// with (mu_k, V_k) the eigenpairs of the train's first-order form in psi (y = (x, dx/dpsi): [[0, I], [-J^-1 K /
/// omega^2, -J^-1 C / omega]]), g = V^-1 [0; J^-1 / omega^2], and d_k(u) = (1/mu^2) (u/L - 1/2 + e^{mu u} / (1 -
/// e^{mu L})) + 1 / (L mu^3) the periodic solution of z' = mu z + f minus its quasi-static -f/mu. Neglected: the smooth
/// part's remainder beyond P, whose orders fall as p^-3 (p / p_min)^2 / K below the lowest natural frequency's order
/// p_min (each octave adds about the same): P is doubled until the last doubling's change times (1 + log2(p_min / P))
/// is within `convergence`. The kernels' e^{mu u} terms ring at the natural frequencies (amplitude about omega / w of
/// the twist, decaying at the damping's rate C / 2J within a cycle); a grid cannot resolve them, so the extremes
/// (grid of 8P points and 4096, refined by Brent on the whole function) may sit up to twice their amplitude a_i off on
/// either side: HolzerResponse::stiff_bound = max_i 4 a_i bounds a peak-to-peak's error from it. The order amplitudes
/// (bodies, twists: p <= P) are Z_p^-1 T_p, exact as on the plain route.

#include <complex>
#include <memory>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "crankcheck/analytic/crank_train.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::analytic {

struct HolzerOptions {
  double convergence = 1e-8;      ///< the last doubling's largest change of a peak-to-peak, relative to the largest
  int max_harmonics = 1 << 16;    ///< P at most
};

class StiffLimitResponse;

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
  /// The stiff-limit route (above) was taken: peak_to_peak is read off the closed form, not off `twists` (which then
  /// hold the orders p <= P only).
  bool stiff_limit = false;
  /// [rad] On the stiff-limit route, the bound on each peak-to-peak's error from the natural frequencies' ringing
  /// (4 x its amplitude, above); 0 on the plain route (whose accuracy is `change`).
  double stiff_bound = 0.0;
  /// On the stiff-limit route, the closed form itself (the exact steady state's stiff route reads it, torsion_steady.h).
  std::shared_ptr<const StiffLimitResponse> stiff;
};

/// Holzer's response on the stiff-limit route in closed form (torsion_forced.h, above), evaluated at any phase.
class StiffLimitResponse {
 public:
  struct Impl;
  explicit StiffLimitResponse(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}
  /// [rad] The bodies' deviations x at cycle phase tau = 2 pi psi / cycle [rad].
  Eigen::VectorXd evaluateBodies(double tau) const;
  /// [rad] The same at the N phases tau = 2 pi k / N, k = 0 .. N-1 (the series summed by FFT).
  std::vector<Eigen::VectorXd> sampleBodies(int N) const;
  /// [rad] Each section's twist's extremes over the cycle, of the closed form plus `extra` (the bodies' series, if
  /// given: the exact steady state's correction), by a grid of 8 x its orders points (4096 to 65536) and Brent (full
  /// precision: an extreme at a pressure-table corner is a kink) from the grid's four best local extremes of each kind.
  std::vector<SignalExtremes> findTwistExtremes(const std::vector<PeriodicSignal>* extra = nullptr) const;
  /// [rad] Each section's ringing amplitude a_i (the kernels' e^{mu u} terms, bounded by |.| of each term).
  const std::vector<double>& ringingAmplitudes() const;
  /// The highest natural frequency's order p_max and the lowest's p_min (per cycle: harmonics p).
  double highestOrder() const;
  double lowestOrder() const;

 private:
  std::shared_ptr<const Impl> impl_;
};

/// What the torque orders of a train's throws share across speeds. Throw j's torque in the rigid motion at omega is
/// T(psi) = A(psi) - (1/2) omega^2 B(psi) with A = T_gas - Q and B = J' (crank_train.h, calcThrowLoads), neither of
/// which depends on omega; so are their orders A_p, B_p (the quadrature and FFT above), and T_p = A_p - (1/2) omega^2
/// B_p. An object keeps every A_p, B_p a sum has asked for, for each P, so that a sweep over speed computes them once
/// (the torsion part's speed points, `crankcheck torsion`). Safe to share between threads. It serves the trains of one scene
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
