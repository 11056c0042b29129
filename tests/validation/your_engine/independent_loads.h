#pragma once
// An independent model of a scene's loads for the scene sections' loads and gravity tests, written from the geometry
// of docs/CONVENTIONS.md alone (no engine, no closed form of the code under test), in any floating type R
// (long double to scan a cycle, boost::multiprecision::cpp_bin_float_50 for the values):
// - the positions of every point mass and rod from the crank angle (the wrist pin on its line A = x e + delta n,
//   |A - B| = l, the far root), their derivatives by central finite differences in R;
// - the drive torque by the energy balance (Lagrange's equation at constant omega): tau = omega^2 dK/dphi + dU/dphi +
//   sum_j p_j A_bore dx_j/dphi, K = T / omega^2 the kinetic energy at unit speed, U the potential energy;
// - the crank-pin force of each cylinder from the momentum of its rod and piston along the cylinder axis and the rod's
//   moment about the wrist pin; the wall force and the wrist-pin force from the piston's and rod's momentum across it;
//   the main-bearing force from the crankshaft's momentum (balance shafts are geared: no force on the main bearing);
// - Q = dU/dphi.
// Maxima over a cycle: a scan of the cycle in long double, the best candidates refined by golden section in R.

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include <boost/math/constants/constants.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>

#include "crankcheck/scene/mechanism.h"

namespace crankcheck::testing::independent {

using Hp = boost::multiprecision::cpp_bin_float_50;

template <class R>
struct P2 {
  R x, y;
};
template <class R> P2<R> operator+(P2<R> a, P2<R> b) { return {a.x + b.x, a.y + b.y}; }
template <class R> P2<R> operator-(P2<R> a, P2<R> b) { return {a.x - b.x, a.y - b.y}; }
template <class R> P2<R> operator*(R s, P2<R> a) { return {s * a.x, s * a.y}; }
template <class R> R dot(P2<R> a, P2<R> b) { return a.x * b.x + a.y * b.y; }
template <class R> R cross(P2<R> a, P2<R> b) { return a.x * b.y - a.y * b.x; }

// The positions of cylinder j's moving points at crank angle phi.
template <class R>
struct CylinderPose {
  P2<R> A, B, G;  // wrist pin, crank pin, rod's centre of mass
  R psi;          // the rod's direction angle (B - A) from +X
  R x;            // the wrist pin's coordinate along e
};

template <class R>
struct Model {
  const Mechanism& m;
  explicit Model(const Mechanism& mech) : m(mech) {}

  static R pi() { return boost::math::constants::pi<R>(); }
  CylinderPose<R> pose(int j, R phi) const {
    using std::cos, std::sin, std::sqrt, std::atan2;
    const R gamma = R(getBankAngle(m, j)), beta = R(getThrowAngle(m, j)), delta = R(getPinOffset(m, j));
    const R r = R(m.crank.radius), l = R(m.rod.length);
    const P2<R> e{cos(gamma), sin(gamma)}, n{-sin(gamma), cos(gamma)};
    const P2<R> B{r * cos(phi + beta), r * sin(phi + beta)};
    const R be = dot(B, e), bn = dot(B, n);
    const R x = be + sqrt(l * l - (delta - bn) * (delta - bn));
    const P2<R> A = x * e + delta * n;
    const P2<R> G = A + (R(m.rod.com_from_wrist_pin) / l) * (B - A);
    return {A, B, G, atan2(B.y - A.y, B.x - A.x), x};
  }

  // Central finite-difference steps for R's precision: first derivatives (cbrt eps), second (eps^1/4), and the
  // derivative of a quantity that itself holds first derivatives (eps^(2/9)).
  static R eps() { return std::numeric_limits<R>::epsilon(); }
  static R hFirst() { using std::pow; return pow(eps(), R(1) / R(3)); }
  static R hSecond() { using std::sqrt; return sqrt(sqrt(eps())); }
  static R hOuter() { using std::pow; return pow(eps(), R(2) / R(9)); }

  // Potential energy [J] (up to a constant): pistons, rods, crank masses, balance shafts' masses, g along -Y.
  R potential(R phi) const {
    using std::cos, std::sin;
    const R g = R(m.machine.gravity);
    R u = 0;
    for (int j = 0; j < m.machine.cylinders; ++j) {
      const CylinderPose<R> p = pose(j, phi);
      const R throw_angle = phi + R(getThrowAngle(m, j));
      u += R(m.piston.mass) * p.A.y + R(m.rod.mass) * p.G.y + R(m.crank.mass) * R(m.crank.com_radius) * sin(throw_angle) -
           R(m.crank.counterweight_mass) * R(m.crank.counterweight_radius) * sin(throw_angle);
    }
    for (const BalanceShaftParams& s : m.balance_shafts)
      u += R(s.mass) * (R(s.position[1]) + R(s.radius) * sin(R(s.ratio) * phi + R(s.phase)));
    return g * u;
  }

  // Kinetic energy at unit crank speed [J s^2] (the constant part of the crank and the shafts left out).
  R kinetic(R phi) const {
    const R h = hFirst();
    R k = 0;
    const R rod_centroidal = R(m.rod.inertia_about_wrist_pin) - R(m.rod.mass) * R(m.rod.com_from_wrist_pin) * R(m.rod.com_from_wrist_pin);
    for (int j = 0; j < m.machine.cylinders; ++j) {
      const CylinderPose<R> a = pose(j, phi + h), b = pose(j, phi - h);
      const P2<R> vA = (R(1) / (2 * h)) * (a.A - b.A), vG = (R(1) / (2 * h)) * (a.G - b.G);
      R dpsi = a.psi - b.psi;
      if (dpsi > pi()) dpsi -= 2 * pi();
      if (dpsi < -pi()) dpsi += 2 * pi();
      dpsi /= 2 * h;
      k += R(m.piston.mass) * dot(vA, vA) + R(m.rod.mass) * dot(vG, vG) + rod_centroidal * dpsi * dpsi;
    }
    return k / 2;
  }

  // [Pa] cylinder j's gauge pressure at phi: piecewise linear in phi - firing_j over the cycle (scene/gas.h).
  R pressure(int j, R phi) const {
    using std::fmod;
    if (!m.gas) return 0;
    const GasParams& gas = *m.gas;
    const R cycle = R(gas.cycle);
    R psi = fmod(phi - R(m.firing_angles[static_cast<size_t>(j)]), cycle);
    if (psi < 0) psi += cycle;
    const size_t n = gas.cycle_angles.size();
    for (size_t i = 0; i < n; ++i) {
      const R a0 = R(gas.cycle_angles[i]), a1 = i + 1 < n ? R(gas.cycle_angles[i + 1]) : cycle;
      if (psi >= a0 && psi <= a1) {
        const R p0 = R(gas.pressures[i]), p1 = R(gas.pressures[i + 1 < n ? i + 1 : 0]);
        return p0 + (p1 - p0) * (psi - a0) / (a1 - a0);
      }
    }
    return R(gas.pressures.back());
  }
  R boreArea() const { return m.gas ? pi() * R(m.gas->bore) * R(m.gas->bore) / 4 : R(0); }

  R omega() const { return R(m.machine.speed); }

  // Q = dU/dphi [N m].
  R Q(R phi) const {
    const R h = hFirst();
    return (potential(phi + h) - potential(phi - h)) / (2 * h);
  }
  // The drive torque [N m] by the energy balance; with_gas, with_inertia, with_gravity select its parts.
  R driveTorque(R phi, bool with_gas = true, bool with_inertia = true, bool with_gravity = true) const {
    R tau = 0;
    if (with_inertia) {
      const R h = hOuter();
      tau += omega() * omega() * (kinetic(phi + h) - kinetic(phi - h)) / (2 * h);
    }
    if (with_gravity) tau += Q(phi);
    if (with_gas && m.gas) {
      const R h = hFirst();
      for (int j = 0; j < m.machine.cylinders; ++j)
        tau += pressure(j, phi) * boreArea() * (pose(j, phi + h).x - pose(j, phi - h).x) / (2 * h);
    }
    return tau;
  }

  struct Forces {
    std::vector<P2<R>> crank_pin, wrist_pin;  // crank on rod j at B_j; rod on piston j at A_j
    std::vector<R> wall;                      // N_w: the wall pushes piston j with N_w n_j
    P2<R> bearing;                            // frame on the crankshaft at O
  };
  Forces forces(R phi) const {
    using std::cos, std::sin;
    const R h = hSecond(), w2 = omega() * omega(), g = R(m.machine.gravity);
    const P2<R> up{R(0), R(1)};
    Forces f;
    f.bearing = {R(0), R(0)};
    for (int j = 0; j < m.machine.cylinders; ++j) {
      const R gamma = R(getBankAngle(m, j));
      const P2<R> e{cos(gamma), sin(gamma)}, n{-sin(gamma), cos(gamma)};
      const CylinderPose<R> p = pose(j, phi), a = pose(j, phi + h), b = pose(j, phi - h);
      const R s = w2 / (h * h);
      const P2<R> aA = s * (a.A - R(2) * p.A + b.A), aG = s * (a.G - R(2) * p.G + b.G);
      R da = a.psi - p.psi, db = p.psi - b.psi;
      for (R* d : {&da, &db}) {
        if (*d > pi()) *d -= 2 * pi();
        if (*d < -pi()) *d += 2 * pi();
      }
      const R alpha = s * (da - db);
      const R mo = R(m.piston.mass), mk = R(m.rod.mass);
      const R rod_centroidal = R(m.rod.inertia_about_wrist_pin) - mk * R(m.rod.com_from_wrist_pin) * R(m.rod.com_from_wrist_pin);
      const R gas = pressure(j, phi) * boreArea();
      const P2<R> momentum_rate = mo * aA + mk * aG;
      // Along e: F.e - gas - (m_o + m_k) g (Y.e) = e.(m_o a_A + m_k a_G).
      const R c1 = dot(e, momentum_rate) + gas + (mo + mk) * g * dot(up, e);
      // The rod's moment about A: (B - A) x F + (G - A) x (-m_k g Y) = I_G alpha + (G - A) x m_k a_G.
      const P2<R> d = p.B - p.A, ga = p.G - p.A;
      const R c2 = rod_centroidal * alpha + cross(ga, mk * aG) + cross(ga, mk * g * up);
      // Solve F.e = c1, d x F = c2.
      const R det = e.x * d.x + e.y * d.y;  // | e.x e.y ; -d.y d.x |
      const P2<R> F{(c1 * d.x - e.y * c2) / det, (e.x * c2 + d.y * c1) / det};
      // Across: F.n + N_w - (m_o + m_k) g (Y.n) = n.(m_o a_A + m_k a_G).
      const R wall = dot(n, momentum_rate) - dot(F, n) + (mo + mk) * g * dot(up, n);
      // The piston: m_o a_A = F_wp + N_w n - gas e - m_o g Y.
      const P2<R> Fwp = mo * aA - wall * n + gas * e + mo * g * up;
      f.crank_pin.push_back(F);
      f.wrist_pin.push_back(Fwp);
      f.wall.push_back(wall);
      // The crankshaft's masses of this cylinder: F_bearing - F + gravity = sum m a (centripetal).
      const R th = phi + R(getThrowAngle(m, j));
      const P2<R> u{cos(th), sin(th)};
      const R ms = R(m.crank.mass), mp = R(m.crank.counterweight_mass);
      const P2<R> a_crank = (-w2) * ((ms * R(m.crank.com_radius) - mp * R(m.crank.counterweight_radius)) * u);
      f.bearing = f.bearing + F + a_crank + ((ms + mp) * g) * up;
    }
    return f;
  }
};

// max |f| over [0, period): a scan in long double (`scan` samples), the best `candidates` sampled maxima refined by
// golden section in Hp over the two cells around each to an angle of 1e-13 rad.
struct Maximum {
  Hp value;  // the largest |f|
  Hp phi;    // where
};
inline Maximum findMax(const std::function<long double(long double)>& coarse, const std::function<Hp(Hp)>& fine,
                       double period, int scan, int candidates = 3) {
  std::vector<long double> v(static_cast<size_t>(scan));
  for (int i = 0; i < scan; ++i) v[static_cast<size_t>(i)] = std::fabs(coarse(static_cast<long double>(period) * i / scan));
  std::vector<int> peaks;
  for (int i = 0; i < scan; ++i) {
    const long double a = v[static_cast<size_t>((i + scan - 1) % scan)], b = v[static_cast<size_t>((i + 1) % scan)];
    if (v[static_cast<size_t>(i)] >= a && v[static_cast<size_t>(i)] >= b) peaks.push_back(i);
  }
  std::sort(peaks.begin(), peaks.end(), [&](int a, int b) { return v[static_cast<size_t>(a)] > v[static_cast<size_t>(b)]; });
  if (peaks.size() > static_cast<size_t>(candidates)) peaks.resize(static_cast<size_t>(candidates));
  Maximum best{Hp(-1), Hp(0)};
  const Hp step = Hp(period) / scan, golden = (sqrt(Hp(5)) - 1) / 2;
  for (int i : peaks) {
    Hp lo = step * (i - 1), hi = step * (i + 1);
    Hp x1 = hi - golden * (hi - lo), x2 = lo + golden * (hi - lo);
    Hp f1 = abs(fine(x1)), f2 = abs(fine(x2));
    while (hi - lo > Hp(1e-13)) {
      if (f1 > f2) {
        hi = x2; x2 = x1; f2 = f1; x1 = hi - golden * (hi - lo); f1 = abs(fine(x1));
      } else {
        lo = x1; x1 = x2; f1 = f2; x2 = lo + golden * (hi - lo); f2 = abs(fine(x2));
      }
    }
    const Hp phi = (lo + hi) / 2, value = abs(fine(phi));
    if (value > best.value) best = {value, phi};
  }
  return best;
}

}  // namespace crankcheck::testing::independent
