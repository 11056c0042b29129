#include "crankcheck/analytic/shaking.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "crankcheck/analytic/balance_shafts.h"
#include "crankcheck/analytic/exact_trig.h"
#include "crankcheck/analytic/fourier_series.h"
#include "crankcheck/analytic/kinematics.h"

namespace crankcheck::analytic {

Shaking calcShaking(const Mechanism& m, double phi) { return calcShaking(m, calcCylinderMotions(m, phi), phi); }

Shaking calcShaking(const Mechanism& m, const std::vector<CylinderMotion>& motions, double phi) {
  return calcShaking(m, motions, phi, m.machine.speed, 0.0);
}

Shaking calcShaking(const Mechanism& m, const std::vector<CylinderMotion>& motions, double phi, double omega,
                    double alpha) {
  const double r = m.crank.radius, w = omega;
  const double m_o = m.piston.mass, m_k = m.rod.mass;
  const double I_G = m.rod.inertia_about_wrist_pin - m_k * m.rod.com_from_wrist_pin * m.rod.com_from_wrist_pin;
  const double throw_first_moment = m.crank.mass * m.crank.com_radius - m.crank.counterweight_mass * m.crank.counterweight_radius;
  // dP/dt and dH_O/dt of the moving parts, global X, Y, Z (Eigen vectors; the result is stored in the plain arrays
  // of scene/evaluation.h that every engine fills, see reactions.cc).
  Eigen::Vector3d P_dot = Eigen::Vector3d::Zero(), H_dot = Eigen::Vector3d::Zero();
  for (const CylinderMotion& c : motions) {
    // m a of the piston, the rod and the throw (m_s at r_s, m_p at -r_p on the crank line: a = -omega^2 p), and
    // p x m a about O, all in cylinder j's frame (planar cross products are the same in every rotated frame).
    const Eigen::Vector2d piston = m_o * c.a_A, rod = m_k * c.a_G;
    Eigen::Vector2d crank = (-w * w * throw_first_moment / r) * c.p_OB;
    if (alpha != 0.0) crank += (alpha * throw_first_moment / r) * Eigen::Vector2d{-c.p_OB.y(), c.p_OB.x()};
    const Eigen::Vector2d f_C = piston + rod + crank;
    const double moment_Z = (c.p_OA.x() * piston.y() - c.p_OA.y() * piston.x()) +
                            (c.p_OG.x() * rod.y() - c.p_OG.y() * rod.x()) +
                            I_G * c.psi_ddot;  // the throw's p x m a is parallel: no Z part
    // To global X, Y: e = (cos gamma, sin gamma), n = (-sin gamma, cos gamma); the force acts in the plane z = z_j.
    const Eigen::Vector3d f_W{f_C.x() * c.gamma.cos - f_C.y() * c.gamma.sin, f_C.x() * c.gamma.sin + f_C.y() * c.gamma.cos, 0.0};
    P_dot += f_W;
    H_dot += Eigen::Vector3d{0.0, 0.0, c.z}.cross(f_W) + Eigen::Vector3d{0.0, 0.0, moment_Z};
  }
  if (alpha != 0.0) {
    // The crankshaft's spin: its throws' point masses (their p x m a about O has the Z part m r^2 alpha) and the flywheel.
    const double throw_inertia = m.crank.mass * m.crank.com_radius * m.crank.com_radius +
                                 m.crank.counterweight_mass * m.crank.counterweight_radius * m.crank.counterweight_radius;
    H_dot.z() += (m.flywheel_inertia.value_or(0.0) + m.machine.cylinders * throw_inertia) * alpha;
  }
  const BalanceShaftLoads shafts = calcBalanceShaftLoads(m, phi, omega, alpha);
  Shaking s;
  s.force = {-P_dot.x() + shafts.shaking_force[0], -P_dot.y() + shafts.shaking_force[1]};
  s.moment = {-H_dot.x() + shafts.shaking_moment[0], -H_dot.y() + shafts.shaking_moment[1],
              -H_dot.z() + shafts.shaking_moment[2]};
  return s;
}

}  // namespace crankcheck::analytic

namespace crankcheck::analytic {

double ShakingHarmonic::calcForceAmplitude() const {
  // As complex numbers X + iY: F(phi) = c cos + s sin = F+ e^{i phi n} + F- e^{-i phi n} with
  // F+ = (c - i s) / 2, F- = (c + i s) / 2 (c, s complex): the ellipse's semi-major axis is |F+| + |F-|.
  const double cr = force_cos[0], ci = force_cos[1], sr = force_sin[0], si = force_sin[1];
  const double forward = 0.5 * std::hypot(cr + si, ci - sr), backward = 0.5 * std::hypot(cr - si, ci + sr);
  return forward + backward;
}

double ShakingHarmonic::calcMomentAmplitude(int axis) const {
  return std::hypot(moment_cos.at(static_cast<size_t>(axis)), moment_sin.at(static_cast<size_t>(axis)));
}

namespace {

// Harmonics 1..order of the exact F_s and M_s (calcShaking) by a DFT over N equally spaced angles. The coefficients
// of the offset motion decay geometrically; N is doubled until harmonics N/4 and N/4 + 1 are below 4 eps of the
// largest value, so that what the DFT folds onto harmonics 1..order <= N/4 (harmonics N - n and beyond) is below
// rounding.
std::vector<ShakingHarmonic> calcShakingHarmonicsByDft(const Mechanism& m, int order) {
  int N = 64;
  while (N < 4 * order) N *= 2;
  for (; N <= (1 << 20); N *= 2) {
    std::vector<Shaking> samples(static_cast<size_t>(N));
    double largest = 0.0;
    for (int i = 0; i < N; ++i) {
      samples[static_cast<size_t>(i)] = calcShaking(m, 2.0 * M_PI * i / N);
      for (double f : samples[static_cast<size_t>(i)].force) largest = std::max(largest, std::fabs(f));
      for (double f : samples[static_cast<size_t>(i)].moment) largest = std::max(largest, std::fabs(f));
    }
    auto harmonic = [&](int n) {
      ShakingHarmonic x;
      x.n = n;
      for (int i = 0; i < N; ++i) {
        // n i mod N keeps the angle exact
        const SinCos e = calcSinCos(2.0 * M_PI * static_cast<double>((static_cast<long long>(n) * i) % N) / N);
        const Shaking& f = samples[static_cast<size_t>(i)];
        for (int k = 0; k < 2; ++k) {
          x.force_cos[k] += 2.0 / N * f.force[k] * e.cos;
          x.force_sin[k] += 2.0 / N * f.force[k] * e.sin;
        }
        for (int k = 0; k < 3; ++k) {
          x.moment_cos[k] += 2.0 / N * f.moment[k] * e.cos;
          x.moment_sin[k] += 2.0 / N * f.moment[k] * e.sin;
        }
      }
      return x;
    };
    auto size = [](const ShakingHarmonic& x) {
      double v = 0.0;
      for (int k = 0; k < 3; ++k) {
        if (k < 2) v = std::max({v, std::fabs(x.force_cos[k]), std::fabs(x.force_sin[k])});
        v = std::max({v, std::fabs(x.moment_cos[k]), std::fabs(x.moment_sin[k])});
      }
      return v;
    };
    if (std::max(size(harmonic(N / 4)), size(harmonic(N / 4 + 1))) > 4.0 * std::numeric_limits<double>::epsilon() * largest)
      continue;  // not resolved yet
    std::vector<ShakingHarmonic> h;
    for (int n = 1; n <= order; ++n) h.push_back(harmonic(n));
    return h;
  }
  throw std::runtime_error("calcShakingHarmonics: the harmonics of this offset motion do not fall below the DFT's "
                           "rounding (4 eps of the largest force or moment) within 2^20 samples (a loop close to its "
                           "singularity, (r + max |delta|) / l near 1, or masses many orders apart); refused");
}

}  // namespace

std::vector<ShakingHarmonic> calcShakingHarmonics(const Mechanism& m, int order) {
  if (order < 1) throw std::invalid_argument("calcShakingHarmonics: order must be >= 1");
  if (hasPinOffsets(m) || !m.balance_shafts.empty()) {
    // the cylinders' harmonics (by DFT when offset), and each shaft's exact harmonic added
    Mechanism cylinders = m;
    cylinders.balance_shafts.clear();
    std::vector<ShakingHarmonic> h = hasPinOffsets(m) ? calcShakingHarmonicsByDft(cylinders, order)
                                                      : calcShakingHarmonics(cylinders, order);
    for (ShakingHarmonic& x : h)
      for (const BalanceShaftParams& b : m.balance_shafts) {
        const ShaftHarmonic s = calcBalanceShaftHarmonic(m, b, x.n);
        for (int k = 0; k < 2; ++k) {
          x.force_cos[k] += s.force_cos[k];
          x.force_sin[k] += s.force_sin[k];
        }
        for (int k = 0; k < 3; ++k) {
          x.moment_cos[k] += s.moment_cos[k];
          x.moment_sin[k] += s.moment_sin[k];
        }
      }
    return h;
  }
  const double r = m.crank.radius, l = m.rod.length, lambda = r / l, w2 = m.machine.speed * m.machine.speed;
  const double m_o = m.piston.mass, m_k = m.rod.mass, mu = m.rod.com_from_wrist_pin / l;
  const double I_G = m.rod.inertia_about_wrist_pin - m_k * m.rod.com_from_wrist_pin * m.rod.com_from_wrist_pin;
  const double M_t = (m.crank.mass * m.crank.com_radius - m.crank.counterweight_mass * m.crank.counterweight_radius) / r;
  const std::vector<double> A = calcRadicalFourierCoefficients(lambda, order + 2);
  const std::vector<double> B = calcInverseRadicalFourierCoefficients(lambda, order + 2);

  // Per-cylinder series in theta (index h = 0..order): e-force cosines, n-force sines, Z-moment sines.
  std::vector<double> f_e(order + 1, 0.0), f_n(order + 1, 0.0), m_z(order + 1, 0.0);
  f_e[1] = -w2 * (m_o + m_k + M_t) * r;
  f_n[1] = -w2 * (mu * m_k + M_t) * r;
  for (int h = 2; h <= order; h += 2) f_e[h] = -w2 * (m_o + (1.0 - mu) * m_k) * l * h * h * A[h];
  // -(p_OG x m_k a_G) = K sin(theta) sum_h (1 - h^2) A_h cos(h theta); sin cos(h .) = (sin((h+1) .) - sin((h-1) .)) / 2.
  const double K = m_k * (1.0 - mu) * mu * r * l * w2;
  m_z[1] += K * A[0];
  for (int h = 2; h <= order + 1; h += 2) {
    const double c = 0.5 * K * (1.0 - h * h) * A[h];
    if (h + 1 <= order) m_z[h + 1] += c;
    m_z[h - 1] -= c;
  }
  // -I_G psi_ddot = -I_G omega^2 sum_h h C_h sin(h theta), C_h the cosine series of beta'.
  for (int h = 1; h <= order; h += 2) {
    const double C = h == 1 ? lambda * (B[0] + 0.5 * B[2]) : 0.5 * lambda * (B[h - 1] + B[h + 1]);
    m_z[h] -= I_G * w2 * h * C;
  }

  std::vector<ShakingHarmonic> out;
  for (int n = 1; n <= order; ++n) {
    ShakingHarmonic s;
    s.n = n;
    for (int j = 0; j < m.machine.cylinders; ++j) {
      const SinCos gamma = calcSinCos(getBankAngle(m, j));
      const SinCos phase = calcSinCos(n * m.machine.crank_angles[j]);  // n alpha_j
      const double z = getAxialPosition(m, j);
      // m a (the mass times acceleration sums) in the cylinder frame: cos(n phi) and sin(n phi) parts.
      //   f_e cos(n theta) = f_e (cos n phi cos n alpha - sin n phi sin n alpha); f_n sin theta = f_n (sin phi cos alpha + cos phi sin alpha)
      const double e_cos = f_e[n] * phase.cos, e_sin = -f_e[n] * phase.sin;
      const double n_cos = n == 1 ? f_n[1] * phase.sin : 0.0, n_sin = n == 1 ? f_n[1] * phase.cos : 0.0;
      const double X_cos = e_cos * gamma.cos - n_cos * gamma.sin, Y_cos = e_cos * gamma.sin + n_cos * gamma.cos;
      const double X_sin = e_sin * gamma.cos - n_sin * gamma.sin, Y_sin = e_sin * gamma.sin + n_sin * gamma.cos;
      // F_s = -sum m a; M_X = z (m a)_Y, M_Y = -z (m a)_X (calcShaking); m_z is already the moment, negated.
      s.force_cos[0] -= X_cos;
      s.force_cos[1] -= Y_cos;
      s.force_sin[0] -= X_sin;
      s.force_sin[1] -= Y_sin;
      s.moment_cos[0] += z * Y_cos;
      s.moment_sin[0] += z * Y_sin;
      s.moment_cos[1] -= z * X_cos;
      s.moment_sin[1] -= z * X_sin;
      // m_z sin(n theta) = m_z (sin n phi cos n alpha + cos n phi sin n alpha)
      s.moment_cos[2] += m_z[n] * phase.sin;
      s.moment_sin[2] += m_z[n] * phase.cos;
    }
    out.push_back(s);
  }
  return out;
}

bool isZeroSumOfRootsOfUnity(const std::vector<long long>& exponents, const std::vector<long long>& weights,
                             long long parts_per_turn) {
  if (exponents.size() != weights.size()) throw std::invalid_argument("isZeroSumOfRootsOfUnity: spans differ in length");
  // N = 2^a 3^b 5^c (a, b, c >= 1) has radical 30, so Phi_N(x) = Phi_30(x^(N / 30)), and 1, z, ..., z^(N/30 - 1)
  // are a basis of Q(z) over Q(z^(N/30)).
  long long rest = parts_per_turn;
  for (long long p : {2, 3, 5}) {
    if (rest % p != 0) rest = -1;
    while (rest > 0 && rest % p == 0) rest /= p;
  }
  if (rest != 1 || parts_per_turn > 100000)
    throw std::invalid_argument("isZeroSumOfRootsOfUnity: parts_per_turn must be 2^a 3^b 5^c with a, b, c >= 1");
  const long long M = parts_per_turn / 30;
  // Coefficient of x^k, k = 0..N-1, grouped by k mod M into polynomials in y = x^M of degree < 30.
  std::vector<std::array<Int128, 30>> poly(static_cast<size_t>(M), std::array<Int128, 30>{});
  for (size_t j = 0; j < exponents.size(); ++j) {
    const long long k = ((exponents[j] % parts_per_turn) + parts_per_turn) % parts_per_turn;
    poly[static_cast<size_t>(k % M)][static_cast<size_t>(k / M)] += weights[j];
  }
  static constexpr int kPhi30[9] = {1, 1, 0, -1, -1, -1, 0, 1, 1};  // coefficients of y^0 .. y^8
  for (auto& p : poly) {
    for (int top = 29; top >= 8; --top) {  // long division by the monic Phi_30
      const Int128 c = p[top];
      if (c == 0) continue;
      for (int t = 0; t <= 8; ++t) p[top - 8 + t] -= c * kPhi30[t];
    }
    for (int t = 0; t < 8; ++t)
      if (p[t] != 0) return false;
  }
  return true;
}

namespace {

// x in whole units of `unit` (degrees: 1; nanometres: 1e-9), if it is one to rounding of the conversion.
bool toWhole(double x, double unit, long long& out) {
  const double scaled = x / unit, rounded = std::nearbyint(scaled);
  if (!(std::fabs(scaled - rounded) <= 1e-6 * std::max(1.0, std::fabs(scaled))) || std::fabs(rounded) > 1e15) return false;
  out = static_cast<long long>(rounded);
  return true;
}

}  // namespace

HarmonicSymmetry findHarmonicSymmetry(const Mechanism& m, int n) {
  // Angles in eighths of a degree (a V of 45 degrees has banks at 90 +- 22.5), one turn = 2880 parts.
  constexpr long long kTurn = 2880;
  HarmonicSymmetry s;
  const int k = m.machine.cylinders;
  // The centric cylinder's orders (calcShakingHarmonics' series: f_e at 1 and even h, f_n at 1, m_z at odd h).
  bool shaft_at_n = false, centric = true;
  for (const BalanceShaftParams& b : m.balance_shafts) shaft_at_n = shaft_at_n || std::fabs(b.ratio) == n;
  for (int j = 0; j < k; ++j) centric = centric && getPinOffset(m, j) == 0.0;
  s.force_order_absent = centric && !shaft_at_n && n >= 3 && n % 2 == 1;
  s.moment_z_order_absent = centric && !shaft_at_n && n % 2 == 0;
  // The sideways force is order 1 alone with a pin offset too (the rod's centre moves sideways as a constant plus
  // sin(theta)): from order 2 on each cylinder's force lies along its axis; with every axis along Y (standing, or
  // opposed at 90 and 270 degrees) there is no X part, with every axis along X (lying, a boxer) no Y part (cos and
  // sin are exact at quarter turns).
  if (!shaft_at_n && n >= 2) {
    bool along_x = true, along_y = true;
    for (int j = 0; j < k; ++j) {
      const SinCos bank = calcSinCos(getBankAngle(m, j));
      along_x = along_x && bank.sin == 0.0;
      along_y = along_y && bank.cos == 0.0;
    }
    s.moment_y_direction_absent = along_y;  // M_Y = -z F_X
    s.moment_x_direction_absent = along_x;  // M_X = z F_Y
  }
  // The sums below hold when every cylinder has the same harmonic in its own frame: the same pin offset for all; and
  // when no balance shaft adds to harmonic n (then the masses decide, not the symmetry).
  for (int j = 1; j < k; ++j)
    if (getPinOffset(m, j) != getPinOffset(m, 0)) return s;
  for (const BalanceShaftParams& b : m.balance_shafts)
    if (std::fabs(b.ratio) == n) return s;
  std::vector<long long> gamma(k), beta(k), z(k), ones(k, 1);
  for (int j = 0; j < k; ++j) {
    const double gamma_deg = degreesFromRadians(getBankAngle(m, j));
    if (!toWhole(gamma_deg, 0.125, gamma[j]) ||
        !toWhole(gamma_deg + degreesFromRadians(m.machine.crank_angles[j]), 0.125, beta[j]) ||
        !toWhole(getAxialPosition(m, j), 1e-9, z[j]))
      return s;
  }
  std::vector<long long> forward(k), backward(k), alpha(k);
  for (int j = 0; j < k; ++j) {
    forward[j] = n * beta[j] - (n - 1) * gamma[j];
    backward[j] = (n + 1) * gamma[j] - n * beta[j];
    alpha[j] = n * (beta[j] - gamma[j]);
  }
  s.decided = true;
  s.force_cancels = isZeroSumOfRootsOfUnity(forward, ones, kTurn) && isZeroSumOfRootsOfUnity(backward, ones, kTurn);
  s.moment_xy_cancels = isZeroSumOfRootsOfUnity(forward, z, kTurn) && isZeroSumOfRootsOfUnity(backward, z, kTurn);
  s.moment_z_cancels = isZeroSumOfRootsOfUnity(alpha, ones, kTurn);
  return s;
}

}  // namespace crankcheck::analytic
