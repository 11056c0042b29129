#include "crankcheck/analytic/torsion.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "crankcheck/analytic/crank_train.h"
#include "crankcheck/analytic/motion.h"

namespace crankcheck::analytic {
namespace {

// Neumaier's compensated sum: the rounding of the sum stays at about one ulp, whatever N.
struct CompensatedSum {
  double sum = 0.0, compensation = 0.0;
  void add(double x) {
    const double t = sum + x;
    compensation += std::fabs(sum) >= std::fabs(x) ? (sum - t) + x : (x - t) + sum;
    sum = t;
  }
  double value() const { return sum + compensation; }
};

}  // namespace

double calcThrowReducedInertia(const Mechanism& m, int throw_index, double psi) {
  return calcReducedInertia(makeThrowMechanism(m, throw_index), psi).J;
}

ThrowInertia calcThrowInertia(const Mechanism& m, int throw_index) {
  const Mechanism one = makeThrowMechanism(m, throw_index);
  ThrowInertia out;
  const double J_t = m.crankshaft ? m.crankshaft->throw_inertia : 0.0;
  // The mean of the periodic J_j: the trapezoidal sum over N points is exact up to J_j's Fourier terms of order
  // N, 2N, ... (aliasing), which fall geometrically; doubling N adds the N new midpoints to the old sum.
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  CompensatedSum sum;
  int n = 16;
  for (int i = 0; i < n; ++i) sum.add(calcReducedInertia(one, 2.0 * M_PI * i / n).J);
  double mean = sum.value() / n;
  for (;;) {
    for (int i = 0; i < n; ++i) sum.add(calcReducedInertia(one, 2.0 * M_PI * (2 * i + 1) / (2 * n)).J);
    n *= 2;
    const double next = sum.value() / n;
    const bool converged = std::fabs(next - mean) <= 4.0 * kEps * std::fabs(next);
    mean = next;
    if (converged) break;
    if (n >= (1 << 20))
      throw std::runtime_error("torsion: the mean inertia of throw " + std::to_string(throw_index) +
                               " did not converge with 2^20 angles (lambda too close to 1)");
  }
  out.exact = J_t + mean;
  out.samples = n;
  // The textbook's shortcuts: the two-mass rod (eq 2) without Delta_I, the reciprocating mass at half (x' = -r sin)
  // or with Norton's second term (mean of (sin + lambda/2 sin 2 theta)^2 = 1/2 + lambda^2 / 8).
  const double r = m.crank.radius, l = m.rod.length, z = m.rod.com_from_wrist_pin, lambda = r / l;
  const double m_k3 = m.rod.mass * z / l, m_rec = m.piston.mass + m.rod.mass * (l - z) / l;
  const double crank = m.crank.mass * m.crank.com_radius * m.crank.com_radius +
                       m.crank.counterweight_mass * m.crank.counterweight_radius * m.crank.counterweight_radius;
  const double cylinders = one.machine.cylinders;
  out.half_reciprocating = J_t + cylinders * (crank + m_k3 * r * r + 0.5 * m_rec * r * r);
  out.second_order = J_t + cylinders * (crank + m_k3 * r * r + 0.5 * m_rec * r * r * (1.0 + 0.25 * lambda * lambda));
  return out;
}

TorsionModes calcChainModes(const std::vector<double>& inertias, const std::vector<double>& stiffness) {
  const size_t n = inertias.size();
  if (n == 0 || stiffness.size() != n)
    throw std::invalid_argument("torsion: a chain needs one section per body (" + std::to_string(n) + " bodies, " +
                                std::to_string(stiffness.size()) + " sections)");
  for (size_t i = 0; i < n; ++i) {
    if (!(std::isfinite(inertias[i]) && inertias[i] > 0.0))
      throw std::invalid_argument("torsion: body " + std::to_string(i) + " has no positive inertia");
    if (!(std::isfinite(stiffness[i]) && stiffness[i] > 0.0))
      throw std::invalid_argument("torsion: section " + std::to_string(i) + " has no positive stiffness");
  }
  // K tridiagonal: section i pulls body i toward body i + 1 (the clamp for i = n - 1); J diagonal.
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(n); ++i) {
    J(i, i) = inertias[static_cast<size_t>(i)];
    K(i, i) += stiffness[static_cast<size_t>(i)];
    if (i + 1 < static_cast<Eigen::Index>(n)) {
      K(i + 1, i + 1) += stiffness[static_cast<size_t>(i)];
      K(i, i + 1) = K(i + 1, i) = -stiffness[static_cast<size_t>(i)];
    }
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(K, J);
  if (solver.info() != Eigen::Success) throw std::runtime_error("torsion: the eigenproblem K x = w^2 J x failed");
  TorsionModes out;
  out.inertias = inertias;
  out.stiffness = stiffness;
  // K and J are positive definite, so every w^2 > 0; rounding cannot make one negative beyond n eps of the largest.
  out.frequencies = solver.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  out.shapes = solver.eigenvectors();
  for (Eigen::Index c = 0; c < out.shapes.cols(); ++c) {
    Eigen::Index at = 0;
    for (Eigen::Index i = 1; i < out.shapes.rows(); ++i)
      if (std::fabs(out.shapes(i, c)) > std::fabs(out.shapes(at, c))) at = i;
    out.shapes.col(c) /= out.shapes(at, c);
  }
  return out;
}

TorsionModes calcTorsionModes(const Mechanism& m) {
  if (!m.crankshaft) throw std::invalid_argument("torsion: the scene has no [crankshaft] table");
  std::vector<double> inertias;
  if (m.crankshaft->front_inertia > 0.0) inertias.push_back(m.crankshaft->front_inertia);
  const int throws = static_cast<int>(findThrows(m).size());
  for (int j = 0; j < throws; ++j) {
    const double J = calcThrowInertia(m, j).exact;
    if (!(J > 0.0))
      throw std::invalid_argument("torsion: throw " + std::to_string(j) +
                                  " has no inertia (massless parts and [crankshaft].throw_inertia = 0)");
    inertias.push_back(J);
  }
  return calcChainModes(inertias, m.crankshaft->stiffness);
}

}  // namespace crankcheck::analytic
