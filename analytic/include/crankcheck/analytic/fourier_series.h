#pragma once
/// @file
/// Fourier coefficients of the slider-crank's radical, exact to double precision for any lambda < 1 and any
/// order, and the exact rational power-series coefficients of the paper's Lambda_n (Stanczak eq 15).
///
/// sqrt(1 - lambda^2 sin^2 theta) = A_0 + sum_{m >= 1} A_{2m} cos(2 m theta).
/// Closed form used here: 1 - lambda^2 sin^2 theta = c |1 + q e^{2 i theta}|^2 with
/// q = (lambda / (1 + sqrt(1 - lambda^2)))^2 and sqrt(c) = (1 + sqrt(1 - lambda^2)) / 2, so that with
/// b_n = binomial(1/2, n):  A_0 = sqrt(c) sum_n b_n^2 q^{2n},  A_{2m} = 2 sqrt(c) sum_n b_n b_{n+m} q^{2n+m}.
/// The sums converge like q^{2n} (q = 0.044 at lambda = 0.4, 0.91 at lambda = 0.999) and are summed to
/// double precision.
///
/// Lambda_n (eq 14): lambda sin(theta) cos(theta) / sqrt(1 - lambda^2 sin^2 theta) = sum_{n even} Lambda_n sin(n theta),
/// and since that function is -(1/lambda) d/dtheta of the radical, Lambda_{2m} = 2 m A_{2m} / lambda.

#include <cstdint>
#include <vector>

namespace crankcheck::analytic {

/// A_0, A_1, ..., A_order of the radical (odd ones are zero), computed from the closed form above.
/// @throws std::invalid_argument unless 0 <= lambda < 1 and order >= 0.
std::vector<double> calcRadicalFourierCoefficients(double lambda, int order);

/// B_0, ..., B_order of the inverse radical, 1 / sqrt(1 - lambda^2 sin^2 theta) = B_0 + sum_{m >= 1} B_{2m} cos(2 m theta)
/// (odd ones are zero), from the same closed form with b_n = binomial(-1/2, n) and c^(-1/2):
/// B_0 = c^(-1/2) sum_n b_n^2 q^{2n}, B_{2m} = 2 c^(-1/2) sum_n b_n b_{n+m} q^{2n+m}. The rod's angular velocity per
/// radian of crank, beta' = lambda cos(theta) / sqrt(1 - lambda^2 sin^2 theta), is a cosine series built from them
/// (shaking.h). @throws std::invalid_argument unless 0 <= lambda < 1 and order >= 0.
std::vector<double> calcInverseRadicalFourierCoefficients(double lambda, int order);

/// Lambda_0 .. Lambda_order (odd and zero entries are zero) from the closed form: Lambda_n = n A_n / lambda
/// (for lambda = 0 the limit: Lambda_2 = lambda/2 -> 0, all zero).
/// @throws std::invalid_argument unless 0 <= lambda < 1 and order >= 0.
std::vector<double> calcLambdaCoefficients(double lambda, int order);

/// The paper's eq (15) table as printed (OCR corrected only where it lost a symbol: Lambda_2 starts with
/// 0.5 lambda), truncated at lambda^11, Lambda_2..Lambda_12; entries above 12 are zero.
/// Printed coefficients are six decimals; one of them (lambda^9 in Lambda_2: 0.022432) differs from the exact
/// 735/32768 = 0.0224304 (see docs/ERRATA.md).
std::vector<double> calcLambdaCoefficientsAsPrinted(double lambda, int order);

/// The printed coefficient of lambda^power in Lambda_n in the paper's eq (15) table (n = 2..12 even,
/// power = 1..11 odd; zero where the table has no entry).
/// @throws std::invalid_argument outside that range.
double getLambdaSeriesCoefficientAsPrinted(int n, int power);

/// A 128-bit integer (a GCC/Clang extension), enough for the binomials of calcLambdaSeriesCoefficient.
__extension__ typedef __int128 Int128;

/// An exact rational number (numerator / denominator, denominator > 0, in lowest terms).
struct Rational {
  Int128 numerator = 0;
  Int128 denominator = 1;
  double toDouble() const { return static_cast<double>(numerator) / static_cast<double>(denominator); }
};

/// The exact coefficient of lambda^power in the power series of Lambda_n (n even >= 2, power odd), from the
/// binomial series of the radical:  coefficient of lambda^{2p-1} in Lambda_{2m} is
///   -2m (-1)^m C(2p, p) C(2p, p-m) / (2^{4p-1} (2p - 1)),  p >= m   (zero for p < m).
/// @throws std::invalid_argument for odd n, n < 2 or even power; std::overflow_error if power > 55.
Rational calcLambdaSeriesCoefficient(int n, int power);

}  // namespace crankcheck::analytic
