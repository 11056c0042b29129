#pragma once
/// @file
/// The physical scales of a case and the agreement rule shared by the gate tests and `crankcheck validate`
/// (docs/CONVENTIONS-crankcheck.md, "Tolerances"): two engines agree on a quantity when
///   |a - b| <= kAgreementMultiple x eps x scale x conditioning.

#include <limits>
#include <string>
#include <vector>

#include "crankcheck/scene/evaluation.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/scene/quantities.h"

namespace crankcheck::validation {

constexpr double kEps = std::numeric_limits<double>::epsilon();

/// The worst error seen over the gate's whole sweep is 9.4 eps x scale x conditioning (x_p; forces 4, torques 1);
/// 64 keeps a margin of about 7 for other compilers and libm versions.
constexpr double kAgreementMultiple = 64.0;

/// The largest |sin(beta)| the rods reach, (r + max_j |delta_j|) / l: lambda for centric cylinders. Where lambda
/// appears in a scale or a conditioning below, this stands in for it (an offset pin brings the loop closer to its
/// singularity |sin(beta)| = 1).
double calcLoopRatio(const Mechanism& m);

/// Energy scale [J] for U and Q: k g (r (m_o + m_k) + m_s r_s + m_p r_p).
double calcEnergyScale(const Mechanism& m);
/// Acceleration scale [m/s^2]: g + r omega^2 (1 + (1 - lambda^2)^(-3/2)), plus max |p| A_bore / (m_o + m_k) with
/// [gas] (the acceleration the largest gas force would give the parts it pushes).
double calcAccelerationScale(const Mechanism& m);
/// Force scale [N]: k (m_o + m_k + I_o / l^2 + m_s + m_p) times the acceleration scale (with [gas] this exceeds k
/// times the largest gas force).
double calcForceScale(const Mechanism& m);
/// Torque scale [N m]: force scale times max(r, r_s, r_p).
double calcTorqueScale(const Mechanism& m);

/// Every scale of a case, and the conditioning of the comparison of the two engines.
struct Scales {
  double energy = 0.0;            ///< E [J]: U and Q
  /// E + k g (m_o + m_k)(l + r): the scale of a U that subtracts absolute heights up to l + r (Simbody's, MuJoCo's)
  double absolute_height_energy = 0.0;
  double position = 0.0;          ///< l + r + max |delta_j| [m]
  double velocity = 0.0;          ///< r omega (1 + (1 - lambda^2)^(-1/2)) [m/s]
  double acceleration = 0.0;      ///< calcAccelerationScale [m/s^2]
  double force = 0.0;             ///< calcForceScale [N]
  double torque = 0.0;            ///< calcTorqueScale [N m]
  /// [N m] shaking moment: force scale times (l + r + max |z_j|), the largest moment arm of a moving part about O
  /// (in the plane up to l + r, along the shaft up to |z_j|).
  double moment = 0.0;
  // The conditioning: how much the loop's rounding is amplified near lambda = 1, beyond what the scale already
  // carries, counted once per quantity (docs/CONVENTIONS-crankcheck.md, "Tolerances"). Every exact engine closes the loop
  // through cos(beta) = sqrt(1 - lambda^2 sin^2 theta), whose relative rounding is eps / (1 - lambda^2) at worst;
  // times (l + r) / r because Simbody holds the rod in absolute coordinates (its rounding relative to crank-scale
  // quantities grows like 1 / lambda).
  /// Q (energy scale, which carries no factor of the loop): 1 / (1 - lambda^2) x (l + r) / r. Measured: Q's error
  /// grows like 1 / (1 - lambda^2) (2e-12 of its peak at lambda = 0.99999).
  double conditioning = 1.0;
  /// Velocities (v_p, the rod's angular velocity): the velocity scale already carries the loop's growth
  /// (1 - lambda^2)^(-1/2), so only the closure's amplification of a position rounding is left:
  /// 1 / sqrt(1 - lambda^2) x (l + r) / r.
  double velocity_conditioning = 1.0;
  /// Accelerations, forces, torques, moments (scales built on the acceleration scale A = g + gas + r omega^2 (1 +
  /// (1 - lambda^2)^(-3/2))): each part of A counted once with its own sensitivity. The inertia part's
  /// (1 - lambda^2)^(-3/2) already carries the loop, so it takes the closure factor; the static loads (gravity, gas)
  /// carry none, so they take the full 1 / (1 - lambda^2) (a near-singular linkage at rest amplifies its reactions):
  ///   ((g + gas) / (1 - lambda^2) + r omega^2 (1 + (1 - lambda^2)^(-3/2)) / sqrt(1 - lambda^2)) / A x (l + r) / r.
  /// (Multiplying the whole of A by 1 / (1 - lambda^2) counted the loop twice at speed: at lambda = 0.99999 the drive
  /// torque's tolerance was 4e-4 of its peak; now 2e-6.)
  double acceleration_conditioning = 1.0;
  /// 1 / sqrt(1 - lambda^2): the loop closure's amplification of a position error into x_p, the rod angle and U.
  double closure = 1.0;
};
Scales calcScales(const Mechanism& m);

/// [m/s^2] The scene format's default gravity (docs/SCENE-FORMAT.md), the load calcPositiveScales assumes where a
/// case has none.
constexpr double kStandardGravity = 9.80665;

/// calcScales with every scale positive, for judging values that are not an engine's (`crankcheck grade`): a
/// mechanism at rest has r omega = 0 (velocity, rod_omega's v / l), and with g = 0 and no gas also no acceleration,
/// force, torque, moment or energy scale. Where calcScales gives 0 (or a number below double's normal range) the
/// scale is that of the case's own characteristic motion and load instead:
///   - the static acceleration A_s = g + max |p| A_bore / (m_o + m_k) (calcAccelerationScale at rest) is the load;
///     with none (g = 0, no gas, at rest), standard gravity: the case has no load and no time of its own, so the
///     load it would carry on Earth sets the size of its quantities (all 0 exactly but x_p and the rod angle);
///   - velocity: r omega_c (1 + (1 - lambda^2)^(-1/2)) with omega_c = sqrt(A_s / r), the crank speed whose
///     centripetal acceleration r omega_c^2 is the static load: at speed the velocity and acceleration scales are
///     related by V^2 = r A (V = r omega, A = r omega^2); at rest the only acceleration is A_s, and sqrt(r A_s) is
///     the speed the static loads give the crank pin over one crank radius (a pendulum's), the size of any velocity
///     the mechanism can reach from rest;
///   - acceleration A_s; force, torque and moment calcForceScale's masses (and arms) times it; energy calcEnergyScale
///     with A_s in place of g (the work of the static load over the crank's mass moments).
/// Never below double's smallest normal number, so that no tolerance is 0. The gate and `validate` use calcScales
/// (where two engines give 0 exactly they must agree exactly); a scale that calcScales gives positive (every scale
/// at speed with a load) is used unchanged.
Scales calcPositiveScales(const Mechanism& m);

/// [SI] The scale a QuantityScale names in a case of mechanism m (m's rod length l for the rod's rates).
/// @throws std::invalid_argument for a value outside the enumeration.
double getQuantityScale(const Scales& scales, QuantityScale scale, const Mechanism& m);
/// The conditioning a QuantityConditioning names. @throws std::invalid_argument for a value outside the enumeration.
double getQuantityConditioning(const Scales& scales, QuantityConditioning conditioning);

/// One compared quantity of two Evaluations.
struct Comparison {
  std::string quantity;      ///< the catalogue's name (quantities.h): "U", "Q", "drive_torque", "bearing_force", ...
  int cylinder = -1;         ///< -1 for whole-mechanism quantities
  double a = 0.0, b = 0.0;   ///< the two values
  double scale = 0.0;        ///< the physical scale of the quantity
  double conditioning = 1.0; ///< see Scales
  int component = 0;         ///< 0 for a number; X, Y, Z = 0, 1, 2 for a vector
  double error() const;      ///< |a - b|
  double tolerance() const;  ///< kAgreementMultiple eps scale conditioning
  bool agrees() const { return error() <= tolerance(); }
};

/// Every quantity of two Evaluations at the same angle (the reference's, `a`, and another engine's, `b`), with its
/// scale and conditioning
/// (Q is compared as the static holding torque): the catalogue's whole-mechanism quantities, then each cylinder's
/// (those the mechanism defines: gas_force only with [gas]; shaking_moment's three components always), each vector
/// component by component, X first.
std::vector<Comparison> compareEvaluations(const Mechanism& m, const Evaluation& a, const Evaluation& b);
/// The same with given scales (calcPositiveScales for grade).
std::vector<Comparison> compareEvaluations(const Mechanism& m, const Scales& scales, const Evaluation& a, const Evaluation& b);

}  // namespace crankcheck::validation
