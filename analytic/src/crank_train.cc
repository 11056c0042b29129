#include "crankcheck/analytic/crank_train.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <boost/math/tools/minima.hpp>
#include <unsupported/Eigen/FFT>

#include "crankcheck/analytic/balance_shafts.h"
#include "crankcheck/analytic/exact_trig.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/analytic/motion.h"
#include "cylinder_terms.h"

namespace crankcheck::analytic {

Mechanism makeThrowMechanism(const Mechanism& m, int throw_index) {
  Mechanism one = selectThrow(m, throw_index);
  one.machine.speed = 1.0;  // v_p is then dx_p/dpsi
  one.speed_rpm = 30.0 / M_PI;
  return one;
}

PreparedThrow prepareThrow(const Mechanism& tm) {
  PreparedThrow p;
  p.mechanism = tm;
  p.unit = makeUnitSpeedCopy(tm);
  p.gravity = calcGravityCoefficients(tm);
  for (int j = 0; j < tm.machine.cylinders; ++j) {
    p.crank_angles.push_back(calcSinCos(tm.machine.crank_angles[static_cast<size_t>(j)]));
    p.bank_angles.push_back(calcSinCos(getBankAngle(tm, j)));
  }
  return p;
}

ThrowLoads calcThrowLoads(const Mechanism& tm, double psi) { return calcThrowLoads(prepareThrow(tm), psi); }

ThrowLoads calcThrowLoads(const PreparedThrow& p, double psi) {
  // calcReducedInertia(tm, psi) and calcGravityTorque(tm, psi), the same sums of the same terms (cylinder_terms.h), with
  // each cylinder's angle and the shafts' loads computed once for both (bit for bit the same: crank_train_test.cc).
  const Mechanism& tm = p.mechanism;
  const BalanceShaftLoads shafts = calcBalanceShaftLoads(tm, psi);
  ReducedInertia J;
  J.J = tm.flywheel_inertia.value_or(0.0) + shafts.inertia;
  double Q = 0.0;
  const SinCos angle = calcSinCos(psi);
  for (int j = 0; j < tm.machine.cylinders; ++j) {
    const SinCos theta = addAngles(angle, p.crank_angles[static_cast<size_t>(j)]);  // calcThrowSinCos
    addCylinderInertia(tm, p.unit, j, theta, RodInertiaForm::kTrueInertia, J);
    Q += calcCylinderGravityTorque(tm, j, theta, p.bank_angles[static_cast<size_t>(j)], p.gravity);
  }
  ThrowLoads out;
  out.J = J.J;
  out.dJ = J.dJ;
  out.gravity_torque = Q + shafts.Q;
  out.gas_torque = calcGasTorque(tm, psi);
  return out;
}

double calcRigidThrowTorque(const Mechanism& tm, double psi, double omega) {
  const ThrowLoads l = calcThrowLoads(tm, psi);
  return l.gas_torque - l.gravity_torque - 0.5 * l.dJ * omega * omega;
}

CrankTrain makeCrankTrain(const Mechanism& m) {
  if (!m.crankshaft) throw std::invalid_argument("torsion: the scene has no [crankshaft] table");
  if (!(m.machine.speed > 0.0 && std::isfinite(m.machine.speed)))
    throw std::invalid_argument("torsion: the crank train needs [engine].speed_rpm > 0 (the flywheel's driven speed)");
  const CrankshaftParams& c = *m.crankshaft;
  CrankTrain t;
  const int throws = static_cast<int>(findThrows(m).size());
  for (int j = 0; j < throws; ++j) t.throws.push_back(makeThrowMechanism(m, j));
  t.has_front = c.front_inertia > 0.0;
  t.front_inertia = c.front_inertia;
  t.throw_inertia = c.throw_inertia;
  t.stiffness = c.stiffness;
  const int sections = countShaftSections(m);
  if (static_cast<int>(t.stiffness.size()) != sections)
    throw std::invalid_argument("torsion: [crankshaft].stiffness has " + std::to_string(t.stiffness.size()) +
                                " values for " + std::to_string(sections) + " sections");
  for (int i = 0; i < sections; ++i) t.section_damping.push_back(getSectionDamping(c, i));
  t.throw_damping = c.throw_damping;
  t.omega = m.machine.speed;
  t.cycle = m.machine.cycle == Cycle::kFourStroke ? 4.0 * M_PI : 2.0 * M_PI;
  return t;
}

namespace {
Eigen::MatrixXd chainMatrix(const std::vector<double>& sections) {
  const Eigen::Index n = static_cast<Eigen::Index>(sections.size());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double k = sections[static_cast<size_t>(i)];
    A(i, i) += k;  // section i pulls body i toward body i + 1 (the clamped flywheel for the last)
    if (i + 1 < n) {
      A(i + 1, i + 1) += k;
      A(i, i + 1) -= k;
      A(i + 1, i) -= k;
    }
  }
  return A;
}
}  // namespace

Eigen::MatrixXd calcStiffnessMatrix(const CrankTrain& t) { return chainMatrix(t.stiffness); }

Eigen::MatrixXd calcDampingMatrix(const CrankTrain& t) {
  Eigen::MatrixXd C = chainMatrix(t.section_damping);
  for (int j = 0; j < static_cast<int>(t.throws.size()); ++j) C(t.getThrowBody(j), t.getThrowBody(j)) += t.throw_damping;
  return C;
}

Eigen::VectorXd calcSectionTwists(const Eigen::VectorXd& x) {
  const Eigen::Index n = x.size();
  Eigen::VectorXd twist(n);
  for (Eigen::Index i = 0; i + 1 < n; ++i) twist(i) = x(i + 1) - x(i);
  twist(n - 1) = -x(n - 1);
  return twist;
}

double PeriodicSignal::evaluate(double tau) const {
  // Re sum c_p e^{i p tau}, the powers of e^{i tau} by recurrence, renormalized every 64 terms against drift.
  double sum = 0.0;
  const std::complex<double> step(std::cos(tau), std::sin(tau));
  std::complex<double> z(1.0, 0.0);
  for (size_t p = 0; p < coefficients.size(); ++p) {
    if (p % 64 == 0) z = std::polar(1.0, static_cast<double>(p) * tau);
    sum += (coefficients[p] * z).real();
    z *= step;
  }
  return sum;
}

SignalExtremes findSignalExtremes(const PeriodicSignal& s) {
  // The grid by an inverse FFT (M > 2P points, at least 8 per coefficient and 256), the best samples then refined.
  const size_t P = s.coefficients.size();
  size_t M = 256;
  while (M < 8 * P) M *= 2;
  std::vector<std::complex<double>> X(M, 0.0);
  const double Md = static_cast<double>(M);
  if (P > 0) X[0] = Md * s.coefficients[0].real();
  for (size_t p = 1; p < P; ++p) {
    X[p] = 0.5 * Md * s.coefficients[p];
    X[M - p] = std::conj(X[p]);
  }
  std::vector<double> v;
  thread_local Eigen::FFT<double> fft;  // kept: its plans (twiddles) are made once per size, not at every call
  fft.inv(v, X);
  const int grid = static_cast<int>(M);
  const double h = 2.0 * M_PI / grid;
  int i_min = 0, i_max = 0;
  for (int i = 0; i < grid; ++i) {
    if (v[static_cast<size_t>(i)] < v[static_cast<size_t>(i_min)]) i_min = i;
    if (v[static_cast<size_t>(i)] > v[static_cast<size_t>(i_max)]) i_max = i;
  }
  constexpr int kBits = std::numeric_limits<double>::digits / 2;
  SignalExtremes e;
  // Brent in [tau_i - h, tau_i + h]: the grid's best sample has the extreme within one step on either side.
  const auto lowest = boost::math::tools::brent_find_minima([&](double tau) { return s.evaluate(tau); },
                                                            (i_min - 1) * h, (i_min + 1) * h, kBits);
  e.tau_min = lowest.first;
  e.min = std::min(lowest.second, v[static_cast<size_t>(i_min)]);
  const auto highest = boost::math::tools::brent_find_minima([&](double tau) { return -s.evaluate(tau); },
                                                             (i_max - 1) * h, (i_max + 1) * h, kBits);
  e.tau_max = highest.first;
  e.max = std::max(-highest.second, v[static_cast<size_t>(i_max)]);
  return e;
}

PeriodicSignal calcSignalFromSamples(const std::vector<double>& samples) {
  const size_t N = samples.size();
  if (N < 2 || N % 2 != 0) throw std::invalid_argument("calcSignalFromSamples: an even number of samples is needed");
  thread_local Eigen::FFT<double> fft;  // kept: its plans (twiddles) are made once per size, not at every call
  std::vector<std::complex<double>> X;
  fft.fwd(X, samples);
  PeriodicSignal s;
  s.coefficients.resize(N / 2 + 1);
  const double n = static_cast<double>(N);
  s.coefficients[0] = X[0].real() / n;
  for (size_t p = 1; p < N / 2; ++p) s.coefficients[p] = 2.0 * X[p] / n;
  s.coefficients[N / 2] = X[N / 2].real() / n;
  return s;
}

}  // namespace crankcheck::analytic
