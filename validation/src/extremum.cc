#include "crankcheck/validation/extremum.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace crankcheck::validation {

TurnMaximum refineMaxAbs(const std::function<double(double)>& f, double a, double b, double tolerance) {
  // Brent's localmin (Brent, Algorithms for Minimization without Derivatives, 1973, ch. 5) on g = -|f|.
  auto g = [&](double x) { return -std::fabs(f(x)); };
  const double c_golden = 0.5 * (3.0 - std::sqrt(5.0));
  double x = a + c_golden * (b - a), w = x, v = x;
  double fx = g(x), fw = fx, fv = fx;
  double d = 0.0, e = 0.0;
  TurnMaximum best{-fx, x};
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double m = 0.5 * (a + b);
    const double tol1 = 1e-15 * std::fabs(x) + tolerance / 3.0, tol2 = 2.0 * tol1;
    if (std::fabs(x - m) <= tol2 - 0.5 * (b - a)) break;
    double p = 0.0, q = 0.0, r = 0.0;
    if (std::fabs(e) > tol1) {  // a parabola through x, w, v
      r = (x - w) * (fx - fv);
      q = (x - v) * (fx - fw);
      p = (x - v) * q - (x - w) * r;
      q = 2.0 * (q - r);
      if (q > 0.0) p = -p;
      q = std::fabs(q);
      r = e;
      e = d;
    }
    if (std::fabs(p) < std::fabs(0.5 * q * r) && p > q * (a - x) && p < q * (b - x)) {
      d = p / q;  // parabolic step
      const double u = x + d;
      if (u - a < tol2 || b - u < tol2) d = x < m ? tol1 : -tol1;
    } else {  // golden section
      e = (x < m ? b : a) - x;
      d = c_golden * e;
    }
    const double u = std::fabs(d) >= tol1 ? x + d : x + (d > 0.0 ? tol1 : -tol1);
    const double fu = g(u);
    if (-fu > best.value) best = {-fu, u};
    if (fu <= fx) {
      (u < x ? b : a) = x;
      v = w, fv = fw, w = x, fw = fx, x = u, fx = fu;
    } else {
      (u < x ? a : b) = u;
      if (fu <= fw || w == x) {
        v = w, fv = fw, w = u, fw = fu;
      } else if (fu <= fv || v == x || v == w) {
        v = u, fv = fu;
      }
    }
  }
  return best;
}

TurnMaximum findMaxAbsOverTurn(const std::function<double(double)>& f, int samples, int refinements, double tolerance) {
  if (samples < 3) throw std::invalid_argument("findMaxAbsOverTurn: samples must be >= 3");
  if (refinements < 0) throw std::invalid_argument("findMaxAbsOverTurn: refinements must be >= 0");
  if (!(tolerance > 0.0)) throw std::invalid_argument("findMaxAbsOverTurn: tolerance must be > 0");
  std::vector<double> y(samples);
  for (int i = 0; i < samples; ++i) y[i] = f(2.0 * M_PI * i / samples);
  return findMaxAbsOverTurn(f, y, refinements, tolerance);
}

TurnMaximum findMaxAbsOverTurn(const std::function<double(double)>& f, const std::vector<double>& values,
                               int refinements, double tolerance) {
  const int samples = static_cast<int>(values.size());
  if (samples < 3) throw std::invalid_argument("findMaxAbsOverTurn: samples must be >= 3");
  if (refinements < 0) throw std::invalid_argument("findMaxAbsOverTurn: refinements must be >= 0");
  if (!(tolerance > 0.0)) throw std::invalid_argument("findMaxAbsOverTurn: tolerance must be > 0");
  const double h = 2.0 * M_PI / samples;
  std::vector<double> y(samples);
  for (int i = 0; i < samples; ++i) y[i] = std::fabs(values[i]);
  TurnMaximum best{y[0], 0.0};
  std::vector<int> peaks;
  for (int i = 0; i < samples; ++i) {
    if (y[i] > best.value) best = {y[i], i * h};
    const double before = y[(i + samples - 1) % samples], after = y[(i + 1) % samples];
    if (y[i] >= before && y[i] >= after && y[i] > 0.0) peaks.push_back(i);
  }
  std::sort(peaks.begin(), peaks.end(), [&](int a, int b) { return y[a] > y[b]; });
  if (static_cast<int>(peaks.size()) > refinements) peaks.resize(refinements);
  for (int i : peaks) {
    const TurnMaximum refined = refineMaxAbs(f, (i - 1) * h, (i + 1) * h, tolerance);
    if (refined.value > best.value) best = refined;
  }
  best.phi = std::fmod(best.phi, 2.0 * M_PI);
  if (best.phi < 0.0) best.phi += 2.0 * M_PI;
  return best;
}

}  // namespace crankcheck::validation
