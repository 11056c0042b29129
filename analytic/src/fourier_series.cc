#include "crankcheck/analytic/fourier_series.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace crankcheck::analytic {
namespace {

void checkArguments(double lambda, int order, const char* who) {
  if (!(lambda >= 0.0 && lambda < 1.0))
    throw std::invalid_argument(std::string(who) + ": lambda must satisfy 0 <= lambda < 1");
  if (order < 0) throw std::invalid_argument(std::string(who) + ": order must be >= 0");
}

// Enough terms for q^{2n} to fall below 1e-17 relative even at lambda = 1 - 1e-12 (q^2 ~ 1 - 6e-6).
constexpr int kMaxTerms = 20'000'000;

// sum_{n >= 0} b_n b_{n+m} q^{2n+m} / scale, with b_n = binomial(p, n) (p = 1/2: the radical; p = -1/2: its
// inverse) and q^m / scale evaluated as one power so that a tiny lambda does not underflow the leading factor.
double sumBinomialProducts(double q, int m, double q_m, double p = 0.5) {
  // b_m by the recurrence b_{n+1} = b_n (p - n) / (n + 1).
  double b_m = 1.0;
  for (int n = 0; n < m; ++n) b_m *= (p - n) / (n + 1);
  double b_n = 1.0, b_nm = b_m, q2n = 1.0;
  double sum = 0.0;
  const double q2 = q * q;
  for (int n = 0; n < kMaxTerms; ++n) {
    const double term = b_n * b_nm * q2n;
    sum += term;
    if (std::fabs(term) <= 0.25 * std::numeric_limits<double>::epsilon() * std::fabs(sum) || q2n == 0.0) break;
    b_n *= (p - n) / (n + 1);
    b_nm *= (p - (n + m)) / (n + m + 1);
    q2n *= q2;
  }
  return sum * q_m;
}

}  // namespace

std::vector<double> calcRadicalFourierCoefficients(double lambda, int order) {
  checkArguments(lambda, order, "calcRadicalFourierCoefficients");
  std::vector<double> a(order + 1, 0.0);
  const double root = std::sqrt((1.0 - lambda) * (1.0 + lambda));  // sqrt(1 - lambda^2) without cancellation
  const double t = lambda / (1.0 + root);
  const double q = t * t;
  const double sqrt_c = 0.5 * (1.0 + root);
  a[0] = sqrt_c * sumBinomialProducts(q, 0, 1.0);
  for (int n = 2; n <= order; n += 2) {
    const int m = n / 2;
    a[n] = 2.0 * sqrt_c * sumBinomialProducts(q, m, std::pow(q, m));
  }
  return a;
}

std::vector<double> calcInverseRadicalFourierCoefficients(double lambda, int order) {
  checkArguments(lambda, order, "calcInverseRadicalFourierCoefficients");
  std::vector<double> b(order + 1, 0.0);
  const double root = std::sqrt((1.0 - lambda) * (1.0 + lambda));
  const double t = lambda / (1.0 + root);
  const double q = t * t;
  const double inverse_sqrt_c = 2.0 / (1.0 + root);  // c^(-1/2)
  b[0] = inverse_sqrt_c * sumBinomialProducts(q, 0, 1.0, -0.5);
  for (int n = 2; n <= order; n += 2) {
    const int m = n / 2;
    b[n] = 2.0 * inverse_sqrt_c * sumBinomialProducts(q, m, std::pow(q, m), -0.5);
  }
  return b;
}

std::vector<double> calcLambdaCoefficients(double lambda, int order) {
  checkArguments(lambda, order, "calcLambdaCoefficients");
  std::vector<double> big_lambda(order + 1, 0.0);
  if (lambda == 0.0) return big_lambda;
  const double root = std::sqrt((1.0 - lambda) * (1.0 + lambda));
  const double t = lambda / (1.0 + root);
  const double q = t * t;
  const double sqrt_c = 0.5 * (1.0 + root);
  for (int n = 2; n <= order; n += 2) {
    const int m = n / 2;
    // Lambda_{2m} = 2m A_{2m} / lambda, with q^m / lambda = t^{2m-1} / (1 + root) formed without dividing a tiny
    // power by lambda.
    const double q_m_over_lambda = std::pow(t, 2 * m - 1) / (1.0 + root);
    big_lambda[n] = n * 2.0 * sqrt_c * sumBinomialProducts(q, m, q_m_over_lambda);
  }
  return big_lambda;
}

double getLambdaSeriesCoefficientAsPrinted(int n, int power) {
  if (n < 2 || n > 12 || n % 2 != 0 || power < 1 || power > 11 || power % 2 == 0)
    throw std::invalid_argument("getLambdaSeriesCoefficientAsPrinted: the table has n = 2..12 even, power = 1..11 odd");
  // Stanczak eq (15), transcribed: coefficients of lambda^1, lambda^3, ..., lambda^11 for Lambda_2 .. Lambda_12.
  static constexpr double kPrinted[6][6] = {
      {0.5, 0.125, 0.058594, 0.034180, 0.022432, 0.015862},        // Lambda_2
      {0.0, -0.0625, -0.046875, -0.034180, -0.025635, -0.019827},  // Lambda_4
      {0.0, 0.0, 0.011719, 0.014648, 0.014420, 0.013218},          // Lambda_6
      {0.0, 0.0, 0.0, -0.002441, -0.004272, -0.005287},            // Lambda_8
      {0.0, 0.0, 0.0, 0.0, 0.000534, 0.001202},                    // Lambda_10
      {0.0, 0.0, 0.0, 0.0, 0.0, -0.000120},                        // Lambda_12
  };
  return kPrinted[n / 2 - 1][power / 2];
}

std::vector<double> calcLambdaCoefficientsAsPrinted(double lambda, int order) {
  checkArguments(lambda, order, "calcLambdaCoefficientsAsPrinted");
  std::vector<double> big_lambda(order + 1, 0.0);
  for (int n = 2; n <= std::min(order, 12); n += 2) {
    double sum = 0.0, power = lambda;
    for (int p = 1; p <= 11; p += 2, power *= lambda * lambda) sum += getLambdaSeriesCoefficientAsPrinted(n, p) * power;
    big_lambda[n] = sum;
  }
  return big_lambda;
}

namespace {

Int128 binomial(int n, int k) {
  if (k < 0 || k > n) return 0;
  Int128 c = 1;
  for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;  // exact at every step
  return c;
}

Int128 gcd(Int128 a, Int128 b) {
  if (a < 0) a = -a;
  if (b < 0) b = -b;
  while (b != 0) {
    const Int128 r = a % b;
    a = b;
    b = r;
  }
  return a;
}

}  // namespace

Rational calcLambdaSeriesCoefficient(int n, int power) {
  if (n < 2 || n % 2 != 0) throw std::invalid_argument("calcLambdaSeriesCoefficient: n must be even and >= 2");
  if (power < 1 || power % 2 == 0)
    throw std::invalid_argument("calcLambdaSeriesCoefficient: power must be odd and >= 1");
  if (power > 55) throw std::overflow_error("calcLambdaSeriesCoefficient: power > 55 overflows 128-bit integers");
  const int m = n / 2;
  const int p = (power + 1) / 2;
  if (p < m) return {0, 1};
  const int sign = (m % 2 == 0) ? -1 : 1;  // -(-1)^m
  Int128 numerator = sign * 2 * m * binomial(2 * p, p) * binomial(2 * p, p - m);
  Int128 denominator = (static_cast<Int128>(1) << (4 * p - 1)) * (2 * p - 1);
  const Int128 g = gcd(numerator, denominator);
  return {numerator / g, denominator / g};
}

}  // namespace crankcheck::analytic
