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

namespace crankcheck::validation {

constexpr double kEps = std::numeric_limits<double>::epsilon();

/// The worst error seen over the gate's whole sweep is 9.4 eps x scale x conditioning (x_p; forces 4, torques 1);
/// 64 keeps a margin of about 7 for other compilers and libm versions.
constexpr double kAgreementMultiple = 64.0;

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
  double simbody_energy = 0.0;    ///< E + k g (m_o + m_k)(l + r): Simbody's U subtracts absolute heights up to l + r
  double position = 0.0;          ///< l + r [m]
  double velocity = 0.0;          ///< r omega (1 + (1 - lambda^2)^(-1/2)) [m/s]
  double acceleration = 0.0;      ///< calcAccelerationScale [m/s^2]
  double force = 0.0;             ///< calcForceScale [N]
  double torque = 0.0;            ///< calcTorqueScale [N m]
  /// [N m] shaking moment: force scale times (l + r + max |z_j|), the largest moment arm of a moving part about O
  /// (in the plane up to l + r, along the shaft up to |z_j|).
  double moment = 0.0;
  /// 1 / (1 - lambda^2) for the loop's condition near lambda = 1, times (l + r) / r because Simbody holds the rod
  /// in absolute coordinates (its rounding relative to crank-scale quantities grows like 1 / lambda).
  double conditioning = 1.0;
  /// 1 / sqrt(1 - lambda^2): the loop closure's amplification of a position error into x_p.
  double closure = 1.0;
};
Scales calcScales(const Mechanism& m);

/// One compared quantity of two Evaluations.
struct Comparison {
  std::string quantity;      ///< "U", "Q", "drive_torque", "bearing_force", "x_p", ... (CONVENTIONS.md names)
  int cylinder = -1;         ///< -1 for whole-mechanism quantities
  double a = 0.0, b = 0.0;   ///< the two values
  double scale = 0.0;        ///< the physical scale of the quantity
  double conditioning = 1.0; ///< see Scales
  double error() const;      ///< |a - b|
  double tolerance() const;  ///< kAgreementMultiple eps scale conditioning
  bool agrees() const { return error() <= tolerance(); }
};

/// Every quantity of an analytic and a Simbody Evaluation at the same angle, with its scale and conditioning
/// (Q is compared as the static holding torque).
std::vector<Comparison> compareEvaluations(const Mechanism& m, const Evaluation& analytic, const Evaluation& simbody);

}  // namespace crankcheck::validation
