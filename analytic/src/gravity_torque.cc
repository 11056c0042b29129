#include "crankcheck/analytic/gravity_torque.h"

#include "crankcheck/analytic/balance_shafts.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "crankcheck/analytic/exact_trig.h"
#include "crankcheck/analytic/fourier_series.h"
#include "cylinder_terms.h"

namespace crankcheck::analytic {
namespace {

std::vector<double> lambdaCoefficients(double lambda, int order, LambdaSource source) {
  return source == LambdaSource::kExact ? calcLambdaCoefficients(lambda, order)
                                        : calcLambdaCoefficientsAsPrinted(lambda, order);
}

// The coefficients of eq (14): N, N1, N2.
struct Eq14Coefficients {
  double N, N1, N2;
};
// Cylinder j's, in its own bank gamma_j (one value for an inline engine).
Eq14Coefficients calcEq14Coefficients(const Mechanism& m, Eq5Form form, int j = 0) {
  const auto [U1, U2] = calcGravityCoefficients(m, form);
  const SinCos gamma = calcSinCos(getBankAngle(m, j));
  return {U2 * gamma.cos, -U1 * gamma.sin, -U2 * gamma.sin};
}

// S_n = sum_j e^{i n alpha_j}, as (real, imaginary).
SinCos sumOverThrows(const Mechanism& m, int n) {
  SinCos s{0.0, 0.0};
  if (!m.machine.explicit_crank_angles) {
    // Phase angles are exact fractions of a turn: reduce n * numerator modulo the denominator in integers.
    const PhaseTurns turns = calcPhaseTurns(m.machine.cylinders, m.machine.cycle, m.machine.acting);
    for (long long numerator : turns.numerators) {
      const long long reduced = (n * numerator) % turns.denominator;
      const SinCos e = calcSinCos(2.0 * M_PI * static_cast<double>(reduced) / static_cast<double>(turns.denominator));
      s.cos += e.cos;
      s.sin += e.sin;
    }
    return s;
  }
  for (double alpha : m.machine.crank_angles) {
    const SinCos e = calcSinCos(n * alpha);
    s.cos += e.cos;
    s.sin += e.sin;
  }
  return s;
}

}  // namespace

double calcCylinderGravityTorque(const Mechanism& m, int j, const SinCos& theta, const GravityCoefficients& c) {
  return calcCylinderGravityTorque(m, j, theta, calcSinCos(getBankAngle(m, j)), c);
}

double calcCylinderGravityTorque(const Mechanism& m, int j, const SinCos& theta, const SinCos& gamma,
                                 const GravityCoefficients& c) {
  const double lambda = m.crank.radius / m.rod.length;
  // s = sin(beta) = lambda sin - delta / l with the pin offset delta (0: centric, the paper's case).
  const double s = lambda * theta.sin - getPinOffset(m, j) / m.rod.length;
  const double root = std::sqrt((1.0 - s) * (1.0 + s));
  // Stanczak eq (13), dx_p/dtheta / r = -(sin + cos s / root); centric: lambda sin 2theta / (2 root) = lambda sin cos / root.
  return c.U2 * (theta.cos * gamma.cos - theta.sin * gamma.sin) - c.U1 * (theta.sin + s * theta.cos / root) * gamma.sin;
}

double calcGravityTorque(const Mechanism& m, double phi, Eq5Form form) {
  const GravityCoefficients c = calcGravityCoefficients(m, form);
  double Q = 0.0;
  for (int j = 0; j < m.machine.cylinders; ++j)
    Q += calcCylinderGravityTorque(m, j, calcThrowSinCos(phi, m.machine.crank_angles[j]), c);
  return Q + calcBalanceShaftLoads(m, phi).Q;  // the balance shafts' masses (balance_shafts.h)
}

double calcGravityTorqueFourier(const Mechanism& m, double phi, int order, LambdaSource source, Eq5Form form) {
  if (order < 1) throw std::invalid_argument("calcGravityTorqueFourier: order must be >= 1");
  const std::vector<double> big_lambda = lambdaCoefficients(m.crank.radius / m.rod.length, order, source);
  double Q = 0.0;
  for (int j = 0; j < m.machine.cylinders; ++j) {
    const double alpha = m.machine.crank_angles[j];
    const auto [N, N1, N2] = calcEq14Coefficients(m, form, j);
    const SinCos theta = calcThrowSinCos(phi, alpha);
    Q += N * theta.cos + (N1 + N2) * theta.sin;  // Stanczak eq (14), W_1 = N1 + N2
    for (int n = 2; n <= order; n += 2) Q += N1 * big_lambda[n] * calcThrowSinCos(n * phi, n * alpha).sin;
  }
  return Q;
}

std::vector<TorqueHarmonic> calcGravityTorqueHarmonics(const Mechanism& m, int order, LambdaSource source,
                                                       Eq5Form form) {
  if (order < 1) throw std::invalid_argument("calcGravityTorqueHarmonics: order must be >= 1");
  if (!isSingleBank(m))
    throw std::invalid_argument("calcGravityTorqueHarmonics: eqs (16)-(18) are for one bank of cylinders");
  const auto [N, N1, N2] = calcEq14Coefficients(m, form);
  const std::vector<double> big_lambda = lambdaCoefficients(m.crank.radius / m.rod.length, order, source);
  std::vector<int> orders;
  if (m.machine.explicit_crank_angles) {
    orders.push_back(1);
    for (int n = 2; n <= order; n += 2) orders.push_back(n);
  } else {
    orders = findSurvivingHarmonics(m.machine.cylinders, m.machine.cycle, m.machine.acting, order);
  }
  std::vector<TorqueHarmonic> harmonics;
  for (int n : orders) {
    const SinCos S = sumOverThrows(m, n);  // S.cos = Re S_n, S.sin = Im S_n
    TorqueHarmonic h{n, 0.0, 0.0};
    if (n == 1) {
      // N sum_j cos(phi + alpha_j) + W_1 sum_j sin(phi + alpha_j), W_1 = N1 + N2
      const double W1 = N1 + N2;
      h.cos_coefficient = N * S.cos + W1 * S.sin;
      h.sin_coefficient = -N * S.sin + W1 * S.cos;
    } else {
      const double Wn = N1 * big_lambda[n];  // W_n = N1 Lambda_n
      h.cos_coefficient = Wn * S.sin;
      h.sin_coefficient = Wn * S.cos;
    }
    harmonics.push_back(h);
  }
  return harmonics;
}

double evaluateTorqueHarmonics(const std::vector<TorqueHarmonic>& harmonics, double phi) {
  double Q = 0.0;
  for (const TorqueHarmonic& h : harmonics) {
    const SinCos e = calcSinCos(h.n * phi);
    Q += h.cos_coefficient * e.cos + h.sin_coefficient * e.sin;  // Stanczak eq (16)
  }
  return Q;
}

double calcGravityTorqueSummed(const Mechanism& m, double phi, int order, LambdaSource source, Eq5Form form) {
  return evaluateTorqueHarmonics(calcGravityTorqueHarmonics(m, order, source, form), phi);
}

std::vector<int> findSurvivingHarmonics(int cylinders, Cycle cycle, Acting acting, int max_order) {
  if (max_order < 1) throw std::invalid_argument("findSurvivingHarmonics: max_order must be >= 1");
  const PhaseTurns turns = calcPhaseTurns(cylinders, cycle, acting);
  // calcPhaseTurns gives a uniform sequence alpha_j = j * step / denominator turns.
  const long long step = cylinders > 1 ? turns.numerators[1] : 0;
  std::vector<int> survivors;
  for (int n = 1; n <= max_order; n = (n == 1 ? 2 : n + 2)) {
    const long long a = (n * step) % turns.denominator;
    bool survives = true;
    if (a != 0) {
      const long long d = turns.denominator / std::gcd(a, turns.denominator);
      survives = (cylinders % d) != 0;
    }
    if (survives) survivors.push_back(n);
  }
  return survivors;
}

}  // namespace crankcheck::analytic

namespace crankcheck::analytic {

std::optional<bool> getPaperHarmonicClaim(int cylinders, Cycle cycle, int n) {
  if (n < 1 || n > 12 || (n > 1 && n % 2 != 0)) return std::nullopt;
  if (cycle == Cycle::kTwoStroke) {
    // Table 1, transcribed: for each W_n, the k for which it is marked nonzero.
    static const std::vector<std::vector<int>> kTable1 = {
        /* n = 1 */ {1}, /* 2 */ {1, 2}, /* 4 */ {1, 2, 4}, /* 6 */ {1, 2, 3, 6},
        /* 8 */ {1, 2, 4, 8}, /* 10 */ {1, 2, 5, 10}, /* 12 */ {1, 2, 3, 4, 6, 12}};
    const std::vector<int>& ks = kTable1[n == 1 ? 0 : n / 2];
    return std::find(ks.begin(), ks.end(), cylinders) != ks.end();
  }
  // Eq (18): chi = k for k = 1, 2 (the n = 1 terms), orders n = nu k / 2 that are whole numbers.
  if (n == 1) return cylinders <= 2;
  return (2 * n) % cylinders == 0;
}

}  // namespace crankcheck::analytic
