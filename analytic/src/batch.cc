#include "crankcheck/analytic/batch.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "crankcheck/analytic/potential_energy.h"

namespace crankcheck::analytic {
namespace {

constexpr int kBlock = 32;  // angles per block: re-anchoring interval of the grid recurrence

struct Throw {
  double cos_alpha, sin_alpha;
};

// The per-angle work after sin and cos of phi are known, for a block of n angles: independent iterations that the
// compiler can vectorize (sqrt and division dominate).
struct Kernel {
  double U1, U2, lambda, cos_gamma, sin_gamma;
  std::vector<Throw> throws;

  void run(const double* s, const double* c, double* Q, int n) const {
    for (int i = 0; i < n; ++i) Q[i] = 0.0;
    for (const Throw& t : throws) {
      for (int i = 0; i < n; ++i) {
        const double st = s[i] * t.cos_alpha + c[i] * t.sin_alpha;   // sin(phi + alpha)
        const double ct = c[i] * t.cos_alpha - s[i] * t.sin_alpha;   // cos(phi + alpha)
        const double root = std::sqrt((1.0 - lambda * st) * (1.0 + lambda * st));
        // Stanczak eq (13)
        Q[i] += U2 * (ct * cos_gamma - st * sin_gamma) - U1 * sin_gamma * (st + lambda * st * ct / root);
      }
    }
  }
};

Kernel makeKernel(const Mechanism& m) {
  if (!isSingleBank(m))
    throw std::invalid_argument("calcGravityTorqueBatch: the batch kernel is for one bank of cylinders (one gamma)");
  const GravityCoefficients g = calcGravityCoefficients(m);
  Kernel k{g.U1, g.U2, m.crank.radius / m.rod.length, std::cos(m.engine.cylinder_angle),
           std::sin(m.engine.cylinder_angle), {}};
  for (double alpha : m.engine.crank_angles) k.throws.push_back({std::cos(alpha), std::sin(alpha)});
  return k;
}

}  // namespace

void calcGravityTorqueBatch(const Mechanism& m, std::span<const double> phi, std::span<double> Q) {
  if (phi.size() != Q.size()) throw std::invalid_argument("calcGravityTorqueBatch: phi and Q differ in size");
  const Kernel kernel = makeKernel(m);
  double s[kBlock], c[kBlock];
  for (size_t start = 0; start < phi.size(); start += kBlock) {
    const int n = static_cast<int>(std::min<size_t>(kBlock, phi.size() - start));
    for (int i = 0; i < n; ++i) ::sincos(phi[start + i], &s[i], &c[i]);
    kernel.run(s, c, &Q[start], n);
  }
}

void calcGravityTorqueOnGrid(const Mechanism& m, double phi0, double step, std::span<double> Q) {
  const Kernel kernel = makeKernel(m);
  double cos_step, sin_step;
  ::sincos(step, &sin_step, &cos_step);
  double s[kBlock], c[kBlock];
  for (size_t start = 0; start < Q.size(); start += kBlock) {
    const int n = static_cast<int>(std::min<size_t>(kBlock, Q.size() - start));
    ::sincos(phi0 + static_cast<double>(start) * step, &s[0], &c[0]);  // re-anchor
    for (int i = 1; i < n; ++i) {
      s[i] = s[i - 1] * cos_step + c[i - 1] * sin_step;
      c[i] = c[i - 1] * cos_step - s[i - 1] * sin_step;
    }
    kernel.run(s, c, &Q[start], n);
  }
}

}  // namespace crankcheck::analytic
