#pragma once
/// @file
/// Generalized gravity torque Q = dU/dphi of the k-crank inline mechanism (Stanczak eqs 13, 14, 16) and the
/// harmonics that survive the sum over throws (the paper's tables 1 and 2), computed, not tabulated.
/// The static torque that holds the shaft against gravity is +Q (CONVENTIONS.md).

#include <optional>
#include <vector>

#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::analytic {

/// Exact Q(phi) [N m], eq (13):
///   Q = sum_j U2 cos(theta_j + gamma) - U1 (sin theta_j + lambda sin 2theta_j / (2 sqrt(1 - lambda^2 sin^2 theta_j))) sin gamma.
double calcGravityTorque(const Mechanism& m, double phi, Eq5Form form = Eq5Form::kDerived);

/// Where the Lambda_n of eq (14) come from.
enum class LambdaSource {
  kExact,      ///< closed form to double precision, any order (fourier_series.h)
  kAsPrinted,  ///< the paper's eq (15) table, truncated at lambda^11 and at Lambda_12
};

/// Eq (14) truncated after harmonic `order` (>= 1), summed over the throws term by term:
///   Q = N sum_j cos theta_j + (N1 + N2) sum_j sin theta_j + N1 sum_{n even <= order} Lambda_n sum_j sin n theta_j,
///   N = U2 cos gamma, N1 = -U1 sin gamma, N2 = -U2 sin gamma.
/// @throws std::invalid_argument if order < 1.
double calcGravityTorqueFourier(const Mechanism& m, double phi, int order,
                                LambdaSource source = LambdaSource::kExact, Eq5Form form = Eq5Form::kDerived);

/// One harmonic of the whole mechanism's Q: Q contains cos_coefficient cos(n phi) + sin_coefficient sin(n phi).
struct TorqueHarmonic {
  int n = 0;
  double cos_coefficient = 0.0;  ///< [N m]
  double sin_coefficient = 0.0;  ///< [N m]
};

/// Harmonics of eq (16): the sums over throws carried out in closed form, sum_j e^{i n alpha_j} = S_n, so that
/// Q = sum_n Re/Im(e^{i n phi} S_n) times (N, W_n). Only n = 1 and even n <= order can appear (eq 14). For
/// phase angles of eqs (8)-(11) only the surviving harmonics (findSurvivingHarmonics) are returned; for
/// explicit crank angles every n = 1, 2, 4, ... <= order is returned with its numerically summed S_n.
/// @throws std::invalid_argument if order < 1, or if the cylinders are not in one bank (isSingleBank).
std::vector<TorqueHarmonic> calcGravityTorqueHarmonics(const Mechanism& m, int order,
                                                       LambdaSource source = LambdaSource::kExact,
                                                       Eq5Form form = Eq5Form::kDerived);

/// sum_n cos_coefficient cos(n phi) + sin_coefficient sin(n phi): eq (16) from harmonics computed once.
double evaluateTorqueHarmonics(const std::vector<TorqueHarmonic>& harmonics, double phi);

/// Eq (16): Q(phi) from calcGravityTorqueHarmonics.
double calcGravityTorqueSummed(const Mechanism& m, double phi, int order, LambdaSource source = LambdaSource::kExact,
                               Eq5Form form = Eq5Form::kDerived);

/// The harmonic orders n in {1, 2, 4, 6, ...}, n <= max_order, whose sum over the throws, sum_j e^{i n alpha_j},
/// does not cancel, for the phase angles of eqs (8)-(11). Decided in exact integer arithmetic on the phase
/// angles as fractions of a turn (calcPhaseTurns): with n alpha_j = a j / d turns in lowest terms, the sum is
/// k when d = 1 and (1 - e^{2 pi i a k / d}) / (1 - e^{2 pi i a / d}) otherwise, zero exactly when d divides k.
/// Two-stroke single-acting: n survives iff k divides n (the paper's table 1).
/// @throws std::invalid_argument if cylinders < 1 or max_order < 1.
std::vector<int> findSurvivingHarmonics(int cylinders, Cycle cycle, Acting acting, int max_order);

/// What the paper claims about harmonic n of a single-acting k-cylinder engine: for two-stroke its table 1, for
/// four-stroke eq (18) (p = k/2, chi = k for k = 1, 2, "half-integer" orders zero; the scan holds no table 2).
/// The paper stops at W_12: returns std::nullopt for n > 12 and for odd n > 1 (not in eq 14).
std::optional<bool> getPaperHarmonicClaim(int cylinders, Cycle cycle, int n);

}  // namespace crankcheck::analytic
