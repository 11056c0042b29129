// The batch kernels (batch.h), written once with Highway and compiled for every x86 target by foreach_target.h:
// this file is included once per target; the parts outside HWY_NAMESPACE are guarded to appear once.
//
// The kinematics, Q, U and the shaking mirror their scalar closed forms operation for operation (same constants, same
// order of the additions and multiplications; GCC fuses multiply-adds where the instruction set has them, as C++
// allows), so that the batch and scalar values differ by little more than what the vector sin/cos leave. The reactions' Newton-Euler part is the same equations with the throw's terms
// gathered (they are linear in the crank pin's position) and fused multiply-adds, a quarter fewer operations: a few
// roundings of the force scale apart. The accuracy tests compare every output angle by angle.

#ifndef CRANKCHECK_ANALYTIC_BATCH_SHARED
#define CRANKCHECK_ANALYTIC_BATCH_SHARED

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "crankcheck/analytic/batch.h"
#include "crankcheck/analytic/exact_trig.h"
#include "crankcheck/analytic/potential_energy.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
// SLEEF 3.5's vector sincos with a 1-ulp bound. sleef.h declares each only when the translation unit is compiled for
// its instruction set (e.g. -mavx512f); here each is called from code compiled for that set by Highway's target
// attributes, so they are declared by hand with SLEEF's own types (a struct of two vectors).
extern "C" {
struct CrankcheckSleefD8x2 {
  __m512d x, y;
};
struct CrankcheckSleefD4x2 {
  __m256d x, y;
};
struct CrankcheckSleefD2x2 {
  __m128d x, y;
};
CrankcheckSleefD8x2 Sleef_sincosd8_u10avx512f(__m512d);
CrankcheckSleefD4x2 Sleef_sincosd4_u10avx2(__m256d);
CrankcheckSleefD2x2 Sleef_sincosd2_u10sse4(__m128d);
CrankcheckSleefD2x2 Sleef_sincosd2_u10sse2(__m128d);
}
#endif  // x86: elsewhere every target takes sin and cos from the C library, lane by lane

namespace crankcheck::analytic::batch_detail {

// One cylinder's constants.
struct Cylinder {
  int j = 0;
  double sin_alpha = 0.0, cos_alpha = 1.0;  // alpha_j, as calcSinCos gives them (exact quarter turns)
  double sin_gamma = 0.0, cos_gamma = 1.0;  // gamma_j
  double z = 0.0;                           // z_j [m]
  double root_alpha = 1.0;                  // sqrt(1 - lambda^2 sin^2 alpha_j), for U
  double U1_sin_gamma = 0.0;                // U1 sin gamma_j, for U
};

// Everything the kernels read, computed once per call with the scalar functions' expressions.
struct Params {
  const Mechanism* m = nullptr;
  double lambda = 0.0, r = 0.0, l = 0.0, w = 0.0, g = 0.0;
  double U1 = 0.0, U2 = 0.0;
  double mu = 0.0;                         // z_k / l
  double m_o = 0.0, m_k = 0.0, I_o = 0.0, I_G = 0.0, m_s = 0.0, m_p = 0.0;
  double throw_first_moment = 0.0;          // m_s r_s - m_p r_p
  bool gas = false;
  std::vector<Cylinder> cylinders;
};

// Where the angles come from: phi[0 .. n) (phi != nullptr), or the grid phi0 + i step.
struct Angles {
  const double* phi = nullptr;
  double phi0 = 0.0, step = 0.0;
  size_t n = 0;
};

struct ReactionPointers {
  double *tau = nullptr, *F_X = nullptr, *F_Y = nullptr;
  std::vector<std::array<double*, 5>> cylinders;  // crank pin X, Y, wrist pin X, Y, wall; empty: totals only
};

}  // namespace crankcheck::analytic::batch_detail

#endif  // CRANKCHECK_ANALYTIC_BATCH_SHARED

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "src/batch.cc"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace crankcheck::analytic::batch_detail::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<double>;
using V = hn::Vec<D>;

constexpr size_t kMaxLanes = HWY_MAX_BYTES / sizeof(double);
// Re-anchoring interval of the grid recurrence, in vectors: each lane takes at most 15 rotations from an exact sincos.
constexpr size_t kAnchorVectors = 16;

const char* TargetName() { return hwy::TargetName(HWY_TARGET); }

// sin and cos of every lane: SLEEF's 1-ulp functions for the vector width, the C library on the baseline.
HWY_INLINE void SinCos(D d, V x, V& s, V& c) {
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX3
  const CrankcheckSleefD8x2 r = Sleef_sincosd8_u10avx512f(x.raw);
  s.raw = r.x;
  c.raw = r.y;
#elif HWY_ARCH_X86 && HWY_TARGET == HWY_AVX2
  const CrankcheckSleefD4x2 r = Sleef_sincosd4_u10avx2(x.raw);
  s.raw = r.x;
  c.raw = r.y;
#elif HWY_ARCH_X86 && HWY_TARGET == HWY_SSE4
  const CrankcheckSleefD2x2 r = Sleef_sincosd2_u10sse4(x.raw);
  s.raw = r.x;
  c.raw = r.y;
#elif HWY_ARCH_X86 && HWY_TARGET == HWY_SSSE3
  const CrankcheckSleefD2x2 r = Sleef_sincosd2_u10sse2(x.raw);
  s.raw = r.x;
  c.raw = r.y;
#else
  HWY_ALIGN double xs[kMaxLanes], ss[kMaxLanes], cs[kMaxLanes];
  hn::Store(x, d, xs);
  for (size_t i = 0; i < hn::Lanes(d); ++i) {
    ss[i] = std::sin(xs[i]);
    cs[i] = std::cos(xs[i]);
  }
  s = hn::Load(d, ss);
  c = hn::Load(d, cs);
#endif
}

// Loads count <= Lanes(d) values (the rest zero) and stores count lanes: the tail of a batch.
HWY_INLINE V LoadTail(D d, const double* p, size_t count) {
  if (HWY_LIKELY(count == hn::Lanes(d))) return hn::LoadU(d, p);
  HWY_ALIGN double buffer[kMaxLanes] = {};
  std::copy(p, p + count, buffer);
  return hn::Load(d, buffer);
}
HWY_INLINE void StoreTail(D d, V v, double* p, size_t count) {
  if (HWY_LIKELY(count == hn::Lanes(d))) {
    hn::StoreU(v, d, p);
    return;
  }
  HWY_ALIGN double buffer[kMaxLanes];
  hn::Store(v, d, buffer);
  std::copy(buffer, buffer + count, p);
}

// Arbitrary angles: sin and cos of scale phi[i] (scale 1, or 1/2 for U's half angles) with the vector sincos.
class ArbitraryAngles {
 public:
  ArbitraryAngles(D d, const Angles& angles, double scale)
      : phi_(angles.phi), scale_(hn::Set(d, scale)), finite_(hn::Zero(d)) {}
  HWY_INLINE void get(D d, size_t i, size_t count, V& s, V& c) {
    const V phi = LoadTail(d, phi_ + i, count);
    finite_ = finite_ + phi * hn::Zero(d);  // stays 0 unless an angle is NaN or infinite
    SinCos(d, phi * scale_, s, c);
  }
  double angle(size_t i) const { return phi_[i]; }
  bool allFinite(D d) const {
    HWY_ALIGN double lanes[kMaxLanes];
    hn::Store(finite_, d, lanes);
    for (size_t i = 0; i < hn::Lanes(d); ++i)
      if (lanes[i] != 0.0) return false;
    return true;
  }

 private:
  const double* phi_;
  V scale_, finite_;
};

// The grid phi0 + i step: every kAnchorVectors vectors, sin and cos of the lanes' exact angles (the doubles
// phi0 + i step that the scalar functions see); in between, each lane turns by Lanes() steps (angle addition).
class GridAngles {
 public:
  GridAngles(D d, const Angles& angles, double scale)
      : phi0_(angles.phi0), step_(angles.step), scale_(scale), s_(hn::Zero(d)), c_(hn::Zero(d)) {
    const double turn = static_cast<double>(hn::Lanes(d)) * step_ * scale_;  // exact: Lanes and scale are powers of 2
    sin_turn_ = hn::Set(d, std::sin(turn));
    cos_turn_ = hn::Set(d, std::cos(turn));
  }
  HWY_INLINE void get(D d, size_t i, size_t /*count*/, V& s, V& c) {
    if ((i / hn::Lanes(d)) % kAnchorVectors == 0) {
      const V index = hn::Set(d, static_cast<double>(i)) + hn::Iota(d, 0.0);
      SinCos(d, (hn::Set(d, phi0_) + index * hn::Set(d, step_)) * hn::Set(d, scale_), s_, c_);
    } else {
      const V s_next = s_ * cos_turn_ + c_ * sin_turn_;
      c_ = c_ * cos_turn_ - s_ * sin_turn_;
      s_ = s_next;
    }
    s = s_;
    c = c_;
  }
  double angle(size_t i) const { return phi0_ + static_cast<double>(i) * step_; }
  bool allFinite(D) const { return true; }  // checked before the pass

 private:
  double phi0_, step_, scale_;
  V s_, c_, sin_turn_, cos_turn_;
};

// sin and cos of theta_j = phi + alpha_j from those of phi: addAngles (exact_trig.h).
HWY_INLINE void throwAngle(D d, V s, V c, const Cylinder& cyl, V& ts, V& tc) {
  const V sa = hn::Set(d, cyl.sin_alpha), ca = hn::Set(d, cyl.cos_alpha);
  ts = s * ca + c * sa;
  tc = c * ca - s * sa;
}

// Piston and rod kinematics of one cylinder (calcPistonKinematics, calcRodKinematics, calcCylinderMotion).
struct Motion {
  V root, root3;  // sqrt(1 - lambda^2 sin^2 theta) = cos(beta), and its cube
  V x_p, v_p, a_p;
  V psi_ddot;     // -beta_ddot
  V B_e, B_n;     // crank pin
  V G_e, G_n;     // the rod's centre of mass
  V aG_e, aG_n;   // its acceleration
};

struct MotionConstants {
  V one, two, four, lambda, lambda3, r, l, v_factor, a_factor, beta_factor, mu, one_minus_mu, minus_w2;
  MotionConstants(D d, const Params& p)
      : one(hn::Set(d, 1.0)),
        two(hn::Set(d, 2.0)),
        four(hn::Set(d, 4.0)),
        lambda(hn::Set(d, p.lambda)),
        lambda3(hn::Set(d, p.lambda * p.lambda * p.lambda)),
        r(hn::Set(d, p.r)),
        l(hn::Set(d, p.l)),
        v_factor(hn::Set(d, -p.r * p.w)),
        a_factor(hn::Set(d, -p.r * p.w * p.w)),
        beta_factor(hn::Set(d, -p.w * p.w * p.lambda * (1.0 - p.lambda) * (1.0 + p.lambda))),
        mu(hn::Set(d, p.mu)),
        one_minus_mu(hn::Set(d, 1.0 - p.mu)),
        minus_w2(hn::Set(d, -p.w * p.w)) {}
};

// x_p, v_p, a_p only (what calcPistonKinematicsBatch returns).
HWY_INLINE void pistonKinematics(const MotionConstants& k, V s1, V c1, Motion& o) {
  const V s2 = k.two * s1 * c1;
  const V c2 = (c1 - s1) * (c1 + s1);
  o.root = hn::Sqrt((k.one - k.lambda * s1) * (k.one + k.lambda * s1));
  o.root3 = o.root * o.root * o.root;
  o.x_p = k.r * c1 + k.l * o.root;                                                                 // Norton 13.1d
  o.v_p = k.v_factor * (s1 + k.lambda * s2 / (k.two * o.root));
  o.a_p = k.a_factor * (c1 + k.lambda * c2 / o.root + k.lambda3 * s2 * s2 / (k.four * o.root3));
}

// Everything calcCylinderMotion gives that the reactions and the shaking read.
HWY_INLINE void cylinderMotion(const MotionConstants& k, V s1, V c1, Motion& o) {
  pistonKinematics(k, s1, c1, o);
  o.psi_ddot = hn::Neg(k.beta_factor * s1 / o.root3);
  o.B_e = k.r * c1;
  o.B_n = k.r * s1;
  o.G_e = o.x_p + k.mu * (o.B_e - o.x_p);
  o.G_n = k.mu * o.B_n;
  o.aG_e = k.one_minus_mu * o.a_p + k.mu * (k.minus_w2 * o.B_e);
  o.aG_n = k.mu * (k.minus_w2 * o.B_n);
}

template <class Source>
bool gravityTorque(const Params& p, Source& source, size_t n, double* Q) {
  const D d;
  const size_t N = hn::Lanes(d);
  const V one = hn::Set(d, 1.0), lambda = hn::Set(d, p.lambda), U1 = hn::Set(d, p.U1), U2 = hn::Set(d, p.U2);
  for (size_t i = 0; i < n; i += N) {
    const size_t count = std::min(N, n - i);
    V s, c;
    source.get(d, i, count, s, c);
    V q = hn::Zero(d);
    for (const Cylinder& cyl : p.cylinders) {
      V ts, tc;
      throwAngle(d, s, c, cyl, ts, tc);
      const V gs = hn::Set(d, cyl.sin_gamma), gc = hn::Set(d, cyl.cos_gamma);
      const V root = hn::Sqrt((one - lambda * ts) * (one + lambda * ts));
      // Stanczak eq (13)
      q = q + (U2 * (tc * gc - ts * gs) - U1 * (ts + lambda * ts * tc / root) * gs);
    }
    StoreTail(d, q, Q + i, count);
  }
  return source.allFinite(d);
}

// Source gives sin and cos of phi / 2.
template <class Source>
bool potentialEnergy(const Params& p, Source& source, size_t n, double* U) {
  const D d;
  const size_t N = hn::Lanes(d);
  const V one = hn::Set(d, 1.0), two = hn::Set(d, 2.0), minus_two = hn::Set(d, -2.0), lambda = hn::Set(d, p.lambda);
  const V two_U2 = hn::Set(d, p.U2 * 2.0);
  for (size_t i = 0; i < n; i += N) {
    const size_t count = std::min(N, n - i);
    V hs, hc;
    source.get(d, i, count, hs, hc);
    const V sin_phi = two * hs * hc;
    V u = hn::Zero(d);
    for (const Cylinder& cyl : p.cylinders) {
      const V sa = hn::Set(d, cyl.sin_alpha), ca = hn::Set(d, cyl.cos_alpha);
      const V gs = hn::Set(d, cyl.sin_gamma), gc = hn::Set(d, cyl.cos_gamma);
      // x = alpha + phi/2 and theta = x + phi/2 by angle addition (calcPotentialEnergy)
      const V xs = sa * hc + ca * hs, xc = ca * hc - sa * hs;
      const V ts = xs * hc + xc * hs;
      const V root_theta = hn::Sqrt((one - lambda * ts) * (one + lambda * ts));
      const V crank_term = two_U2 * hs * (xc * gc - xs * gs);
      const V stroke = minus_two * xs * hs - lambda * sin_phi * two * xs * xc / (root_theta + hn::Set(d, cyl.root_alpha));
      u = u + (crank_term + hn::Set(d, cyl.U1_sin_gamma) * stroke);
    }
    StoreTail(d, u, U + i, count);
  }
  return source.allFinite(d);
}

template <class Source>
bool pistonKinematicsBatch(const Params& p, Source& source, size_t n,
                           const std::vector<std::array<double*, 3>>& out) {
  const D d;
  const size_t N = hn::Lanes(d);
  const MotionConstants k(d, p);
  for (size_t i = 0; i < n; i += N) {
    const size_t count = std::min(N, n - i);
    V s, c;
    source.get(d, i, count, s, c);
    for (size_t j = 0; j < p.cylinders.size(); ++j) {
      V ts, tc;
      throwAngle(d, s, c, p.cylinders[j], ts, tc);
      Motion o;
      pistonKinematics(k, ts, tc, o);
      StoreTail(d, o.x_p, out[j][0] + i, count);
      StoreTail(d, o.v_p, out[j][1] + i, count);
      StoreTail(d, o.a_p, out[j][2] + i, count);
    }
  }
  return source.allFinite(d);
}

// calcReactions, per cylinder in its frame (e, n), then to global X, Y.
template <class Source>
bool reactions(const Params& p, Source& source, size_t n, const ReactionPointers& out) {
  const D d;
  const size_t N = hn::Lanes(d);
  const MotionConstants k(d, p);
  const V m_o = hn::Set(d, p.m_o), m_k = hn::Set(d, p.m_k), I_o = hn::Set(d, p.I_o);
  const double throw_moment = p.throw_first_moment / p.r;  // (m_s r_s - m_p r_p) / r
  const V throw_inertia = hn::Set(d, -p.w * p.w * throw_moment);
  const bool per_cylinder = !out.cylinders.empty();
  for (size_t i = 0; i < n; i += N) {
    const size_t count = std::min(N, n - i);
    V s, c;
    source.get(d, i, count, s, c);
    V tau_sum = hn::Zero(d), FO_X = hn::Zero(d), FO_Y = hn::Zero(d);
    for (size_t j = 0; j < p.cylinders.size(); ++j) {
      const Cylinder& cyl = p.cylinders[j];
      V ts, tc;
      throwAngle(d, s, c, cyl, ts, tc);
      Motion o;
      cylinderMotion(k, ts, tc, o);
      const V gs = hn::Set(d, cyl.sin_gamma), gc = hn::Set(d, cyl.cos_gamma);
      const double gCe_s = -p.g * cyl.sin_gamma, gCn_s = -p.g * cyl.cos_gamma;  // gravity in the cylinder frame
      const V gCe = hn::Set(d, gCe_s), gCn = hn::Set(d, gCn_s);
      const V AB_e = o.B_e - o.x_p, AB_n = o.B_n;
      const V AG_e = o.G_e - o.x_p, AG_n = o.G_n;
      // Piston along e: F_A.e (with the gas force toward the crank).
      V FA_e = m_o * (o.a_p - gCe);
      if (p.gas) {
        HWY_ALIGN double gas[kMaxLanes] = {};
        for (size_t lane = 0; lane < count; ++lane)
          gas[lane] = calcGasForce(*p.m, cyl.j, source.angle(i + lane));
        FA_e = FA_e + hn::Load(d, gas);
      }
      const V RN_e = m_k * (o.aG_e - gCe), RN_n = m_k * (o.aG_n - gCn);  // F_B - F_A
      // Rod moments about A: I_o psi_ddot + (G - A) x m_k a_A - (G - A) x m_k g - (B - A) x (F_B - F_A)
      const V moment = hn::NegMulAdd(AG_n, m_k * o.a_p, I_o * o.psi_ddot) -
                       hn::MulSub(AG_e, hn::Set(d, p.m_k * gCn_s), AG_n * hn::Set(d, p.m_k * gCe_s)) -
                       hn::MulSub(AB_e, RN_n, AB_n * RN_e);
      const V FA_n = hn::MulAdd(AB_n, FA_e, moment) / AB_e;
      const V FB_e = RN_e + FA_e, FB_n = RN_n + FA_n;
      // Crank throw (m_s at r_s, m_p at -r_p on the crank line, turning at omega), linear in B:
      //   F_O = F_B + (m_s r_s - m_p r_p) / r (-omega^2) B - (m_s + m_p) g,
      //   tau = B x F_B - (m_s r_s - m_p r_p) / r B x g.
      const V FO_e = hn::MulAdd(throw_inertia, o.B_e, FB_e + hn::Set(d, -(p.m_s + p.m_p) * gCe_s));
      const V FO_n = hn::MulAdd(throw_inertia, o.B_n, FB_n + hn::Set(d, -(p.m_s + p.m_p) * gCn_s));
      const V tau = hn::MulSub(o.B_e, FB_n - hn::Set(d, throw_moment * gCn_s),
                               o.B_n * (FB_e - hn::Set(d, throw_moment * gCe_s)));
      // e = (cos gamma, sin gamma), n = (-sin gamma, cos gamma) in X, Y
      const V minus_gs = hn::Set(d, -cyl.sin_gamma);
      if (per_cylinder) {
        const std::array<double*, 5>& o_j = out.cylinders[j];
        StoreTail(d, hn::MulAdd(FB_e, gc, FB_n * minus_gs), o_j[0] + i, count);
        StoreTail(d, hn::MulAdd(FB_e, gs, FB_n * gc), o_j[1] + i, count);
        StoreTail(d, hn::MulAdd(FA_e, gc, FA_n * minus_gs), o_j[2] + i, count);
        StoreTail(d, hn::MulAdd(FA_e, gs, FA_n * gc), o_j[3] + i, count);
        StoreTail(d, hn::Set(d, -p.m_o * gCn_s) - FA_n, o_j[4] + i, count);
      }
      FO_X = FO_X + hn::MulAdd(FO_e, gc, FO_n * minus_gs);
      FO_Y = FO_Y + hn::MulAdd(FO_e, gs, FO_n * gc);
      tau_sum = tau_sum + tau;
    }
    StoreTail(d, tau_sum, out.tau + i, count);
    StoreTail(d, FO_X, out.F_X + i, count);
    StoreTail(d, FO_Y, out.F_Y + i, count);
  }
  return source.allFinite(d);
}

// calcShaking: -dP/dt and -dH_O/dt of pistons, rods and throws.
template <class Source>
bool shaking(const Params& p, Source& source, size_t n, const std::array<double*, 5>& out) {
  const D d;
  const size_t N = hn::Lanes(d);
  const MotionConstants k(d, p);
  const V m_o = hn::Set(d, p.m_o), m_k = hn::Set(d, p.m_k), I_G = hn::Set(d, p.I_G);
  const V crank_factor = hn::Set(d, -p.w * p.w * p.throw_first_moment / p.r);
  for (size_t i = 0; i < n; i += N) {
    const size_t count = std::min(N, n - i);
    V s, c;
    source.get(d, i, count, s, c);
    V P_X = hn::Zero(d), P_Y = hn::Zero(d), H_X = hn::Zero(d), H_Y = hn::Zero(d), H_Z = hn::Zero(d);
    for (const Cylinder& cyl : p.cylinders) {
      V ts, tc;
      throwAngle(d, s, c, cyl, ts, tc);
      Motion o;
      cylinderMotion(k, ts, tc, o);
      const V piston_e = m_o * o.a_p;
      const V rod_e = m_k * o.aG_e, rod_n = m_k * o.aG_n;
      const V f_e = piston_e + rod_e + crank_factor * o.B_e;
      const V f_n = rod_n + crank_factor * o.B_n;
      const V moment_Z = (o.G_e * rod_n - o.G_n * rod_e) + I_G * o.psi_ddot;  // the piston's p x m a is 0
      const V gs = hn::Set(d, cyl.sin_gamma), gc = hn::Set(d, cyl.cos_gamma);
      const V f_X = f_e * gc - f_n * gs, f_Y = f_e * gs + f_n * gc;
      P_X = P_X + f_X;
      P_Y = P_Y + f_Y;
      H_X = H_X + hn::Set(d, -cyl.z) * f_Y;
      H_Y = H_Y + hn::Set(d, cyl.z) * f_X;
      H_Z = H_Z + moment_Z;
    }
    StoreTail(d, hn::Neg(P_X), out[0] + i, count);
    StoreTail(d, hn::Neg(P_Y), out[1] + i, count);
    StoreTail(d, hn::Neg(H_X), out[2] + i, count);
    StoreTail(d, hn::Neg(H_Y), out[3] + i, count);
    StoreTail(d, hn::Neg(H_Z), out[4] + i, count);
  }
  return source.allFinite(d);
}

// The entry points, one per quantity: the angle source is chosen here.
template <class Kernel>
bool withSource(const Angles& angles, double scale, Kernel kernel) {
  const D d;
  if (angles.phi != nullptr) {
    ArbitraryAngles source(d, angles, scale);
    return kernel(source);
  }
  GridAngles source(d, angles, scale);
  return kernel(source);
}

bool GravityTorque(const Params& p, const Angles& a, double* Q) {
  return withSource(a, 1.0, [&](auto& source) { return gravityTorque(p, source, a.n, Q); });
}
bool PotentialEnergy(const Params& p, const Angles& a, double* U) {
  return withSource(a, 0.5, [&](auto& source) { return potentialEnergy(p, source, a.n, U); });
}
bool PistonKinematicsKernel(const Params& p, const Angles& a, const std::vector<std::array<double*, 3>>& out) {
  return withSource(a, 1.0, [&](auto& source) { return pistonKinematicsBatch(p, source, a.n, out); });
}
bool Reactions(const Params& p, const Angles& a, const ReactionPointers& out) {
  return withSource(a, 1.0, [&](auto& source) { return reactions(p, source, a.n, out); });
}
bool Shaking(const Params& p, const Angles& a, const std::array<double*, 5>& out) {
  return withSource(a, 1.0, [&](auto& source) { return shaking(p, source, a.n, out); });
}

}  // namespace crankcheck::analytic::batch_detail::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace crankcheck::analytic {
namespace batch_detail {

HWY_EXPORT(TargetName);
HWY_EXPORT(GravityTorque);
HWY_EXPORT(PotentialEnergy);
HWY_EXPORT(PistonKinematicsKernel);
HWY_EXPORT(Reactions);
HWY_EXPORT(Shaking);

Params makeParams(const Mechanism& m, RodInertiaForm rod = RodInertiaForm::kTrueInertia) {
  if (hasPinOffsets(m) || !m.balance_shafts.empty())
    throw std::invalid_argument("the batch kernels (batch.h) are written for centric cylinders without balance shafts, "
                                "and this mechanism has pin offsets or shafts: evaluate it angle by angle (calcEvaluation "
                                "and the scalar functions)");
  Params p;
  p.m = &m;
  p.r = m.crank.radius;
  p.l = m.rod.length;
  p.lambda = p.r / p.l;
  p.w = m.machine.speed;
  p.g = m.machine.gravity;
  const GravityCoefficients U = calcGravityCoefficients(m);
  p.U1 = U.U1;
  p.U2 = U.U2;
  p.mu = m.rod.com_from_wrist_pin / m.rod.length;
  p.m_o = m.piston.mass;
  p.m_k = m.rod.mass;
  // calcReactions: the two-mass rod without Delta_I has m_k3 l^2 = m_k z_k l about A.
  p.I_o = rod == RodInertiaForm::kTwoMassWithoutDeltaI ? p.m_k * m.rod.com_from_wrist_pin * m.rod.length
                                                        : m.rod.inertia_about_wrist_pin;
  p.I_G = m.rod.inertia_about_wrist_pin - p.m_k * m.rod.com_from_wrist_pin * m.rod.com_from_wrist_pin;
  p.m_s = m.crank.mass;
  p.m_p = m.crank.counterweight_mass;
  p.throw_first_moment = m.crank.mass * m.crank.com_radius - m.crank.counterweight_mass * m.crank.counterweight_radius;
  p.gas = m.gas.has_value();
  if (m.machine.crank_angles.size() != static_cast<size_t>(m.machine.cylinders))
    throw std::invalid_argument("batch kernels: the mechanism has " + std::to_string(m.machine.crank_angles.size()) +
                                " crank angles for " + std::to_string(m.machine.cylinders) + " cylinders");
  for (int j = 0; j < m.machine.cylinders; ++j) {
    Cylinder c;
    c.j = j;
    const SinCos alpha = calcSinCos(m.machine.crank_angles[static_cast<size_t>(j)]);
    const SinCos gamma = calcSinCos(getBankAngle(m, j));
    c.sin_alpha = alpha.sin;
    c.cos_alpha = alpha.cos;
    c.sin_gamma = gamma.sin;
    c.cos_gamma = gamma.cos;
    c.z = getAxialPosition(m, j);
    c.root_alpha = std::sqrt((1.0 - p.lambda * alpha.sin) * (1.0 + p.lambda * alpha.sin));
    c.U1_sin_gamma = p.U1 * gamma.sin;
    p.cylinders.push_back(c);
  }
  return p;
}

Angles arbitrary(const char* who, std::span<const double> phi, size_t n) {
  if (phi.size() != n)
    throw std::invalid_argument(std::string(who) + ": " + std::to_string(phi.size()) + " angles but outputs of " +
                                std::to_string(n));
  return {phi.data(), 0.0, 0.0, n};
}

Angles grid(const char* who, double phi0, double step, size_t n) {
  const double last = n == 0 ? phi0 : phi0 + static_cast<double>(n - 1) * step;
  if (!std::isfinite(phi0) || !std::isfinite(step) || !std::isfinite(last))
    throw std::invalid_argument(std::string(who) + ": the grid's angles must be finite (phi0 " + std::to_string(phi0) +
                                ", step " + std::to_string(step) + ")");
  return {nullptr, phi0, step, n};
}

void requireSize(const char* who, const char* what, std::span<double> s, size_t n) {
  if (s.size() != n)
    throw std::invalid_argument(std::string(who) + ": " + what + " has " + std::to_string(s.size()) +
                                " entries, expected " + std::to_string(n));
}

void requireFinite(const char* who, bool finite) {
  if (!finite) throw std::invalid_argument(std::string(who) + ": an angle is NaN or infinite");
}

std::vector<std::array<double*, 3>> kinematicsPointers(const char* who, const Mechanism& m,
                                                       std::span<const PistonKinematicsSpans> cylinders, size_t n) {
  if (cylinders.size() != static_cast<size_t>(m.machine.cylinders))
    throw std::invalid_argument(std::string(who) + ": " + std::to_string(cylinders.size()) +
                                " cylinders of outputs for " + std::to_string(m.machine.cylinders) + " cylinders");
  std::vector<std::array<double*, 3>> out;
  for (const PistonKinematicsSpans& c : cylinders) {
    requireSize(who, "x_p", c.x_p, n);
    requireSize(who, "v_p", c.v_p, n);
    requireSize(who, "a_p", c.a_p, n);
    out.push_back({c.x_p.data(), c.v_p.data(), c.a_p.data()});
  }
  return out;
}

ReactionPointers reactionPointers(const char* who, const Mechanism& m, const ReactionsSpans& spans, size_t n) {
  requireSize(who, "drive_torque", spans.drive_torque, n);
  requireSize(who, "bearing_force_X", spans.bearing_force_X, n);
  requireSize(who, "bearing_force_Y", spans.bearing_force_Y, n);
  if (!spans.cylinders.empty() && spans.cylinders.size() != static_cast<size_t>(m.machine.cylinders))
    throw std::invalid_argument(std::string(who) + ": " + std::to_string(spans.cylinders.size()) +
                                " cylinders of outputs for " + std::to_string(m.machine.cylinders) + " cylinders");
  ReactionPointers out{spans.drive_torque.data(), spans.bearing_force_X.data(), spans.bearing_force_Y.data(), {}};
  for (const CylinderReactionsSpans& c : spans.cylinders) {
    requireSize(who, "crank_pin_force_X", c.crank_pin_force_X, n);
    requireSize(who, "crank_pin_force_Y", c.crank_pin_force_Y, n);
    requireSize(who, "wrist_pin_force_X", c.wrist_pin_force_X, n);
    requireSize(who, "wrist_pin_force_Y", c.wrist_pin_force_Y, n);
    requireSize(who, "wall_force", c.wall_force, n);
    out.cylinders.push_back({c.crank_pin_force_X.data(), c.crank_pin_force_Y.data(), c.wrist_pin_force_X.data(),
                             c.wrist_pin_force_Y.data(), c.wall_force.data()});
  }
  return out;
}

std::array<double*, 5> shakingPointers(const char* who, const ShakingSpans& s, size_t n) {
  requireSize(who, "force_X", s.force_X, n);
  requireSize(who, "force_Y", s.force_Y, n);
  requireSize(who, "moment_X", s.moment_X, n);
  requireSize(who, "moment_Y", s.moment_Y, n);
  requireSize(who, "moment_Z", s.moment_Z, n);
  return {s.force_X.data(), s.force_Y.data(), s.moment_X.data(), s.moment_Y.data(), s.moment_Z.data()};
}

}  // namespace batch_detail

using namespace batch_detail;

void calcGravityTorqueBatch(const Mechanism& m, std::span<const double> phi, std::span<double> Q) {
  constexpr const char* kWho = "calcGravityTorqueBatch";
  const Angles a = arbitrary(kWho, phi, Q.size());
  requireFinite(kWho, HWY_DYNAMIC_DISPATCH(GravityTorque)(makeParams(m), a, Q.data()));
}

void calcGravityTorqueOnGrid(const Mechanism& m, double phi0, double step, std::span<double> Q) {
  const Angles a = grid("calcGravityTorqueOnGrid", phi0, step, Q.size());
  HWY_DYNAMIC_DISPATCH(GravityTorque)(makeParams(m), a, Q.data());
}

void calcPotentialEnergyBatch(const Mechanism& m, std::span<const double> phi, std::span<double> U) {
  constexpr const char* kWho = "calcPotentialEnergyBatch";
  const Angles a = arbitrary(kWho, phi, U.size());
  requireFinite(kWho, HWY_DYNAMIC_DISPATCH(PotentialEnergy)(makeParams(m), a, U.data()));
}

void calcPotentialEnergyOnGrid(const Mechanism& m, double phi0, double step, std::span<double> U) {
  const Angles a = grid("calcPotentialEnergyOnGrid", phi0, step, U.size());
  HWY_DYNAMIC_DISPATCH(PotentialEnergy)(makeParams(m), a, U.data());
}

void calcPistonKinematicsBatch(const Mechanism& m, std::span<const double> phi,
                               std::span<const PistonKinematicsSpans> cylinders) {
  constexpr const char* kWho = "calcPistonKinematicsBatch";
  const auto out = kinematicsPointers(kWho, m, cylinders, phi.size());
  const Angles a = arbitrary(kWho, phi, phi.size());
  requireFinite(kWho, HWY_DYNAMIC_DISPATCH(PistonKinematicsKernel)(makeParams(m), a, out));
}

void calcPistonKinematicsOnGrid(const Mechanism& m, double phi0, double step,
                                std::span<const PistonKinematicsSpans> cylinders) {
  constexpr const char* kWho = "calcPistonKinematicsOnGrid";
  const size_t n = cylinders.empty() ? 0 : cylinders[0].x_p.size();
  const auto out = kinematicsPointers(kWho, m, cylinders, n);
  HWY_DYNAMIC_DISPATCH(PistonKinematicsKernel)(makeParams(m), grid(kWho, phi0, step, n), out);
}

void calcReactionsBatch(const Mechanism& m, std::span<const double> phi, const ReactionsSpans& out,
                        RodInertiaForm rod) {
  constexpr const char* kWho = "calcReactionsBatch";
  const ReactionPointers pointers = reactionPointers(kWho, m, out, phi.size());
  const Angles a = arbitrary(kWho, phi, phi.size());
  requireFinite(kWho, HWY_DYNAMIC_DISPATCH(Reactions)(makeParams(m, rod), a, pointers));
}

void calcReactionsOnGrid(const Mechanism& m, double phi0, double step, const ReactionsSpans& out, RodInertiaForm rod) {
  constexpr const char* kWho = "calcReactionsOnGrid";
  const size_t n = out.drive_torque.size();
  const ReactionPointers pointers = reactionPointers(kWho, m, out, n);
  HWY_DYNAMIC_DISPATCH(Reactions)(makeParams(m, rod), grid(kWho, phi0, step, n), pointers);
}

void calcShakingBatch(const Mechanism& m, std::span<const double> phi, const ShakingSpans& out) {
  constexpr const char* kWho = "calcShakingBatch";
  const std::array<double*, 5> pointers = shakingPointers(kWho, out, phi.size());
  const Angles a = arbitrary(kWho, phi, phi.size());
  requireFinite(kWho, HWY_DYNAMIC_DISPATCH(Shaking)(makeParams(m), a, pointers));
}

void calcShakingOnGrid(const Mechanism& m, double phi0, double step, const ShakingSpans& out) {
  constexpr const char* kWho = "calcShakingOnGrid";
  const size_t n = out.force_X.size();
  const std::array<double*, 5> pointers = shakingPointers(kWho, out, n);
  HWY_DYNAMIC_DISPATCH(Shaking)(makeParams(m), grid(kWho, phi0, step, n), pointers);
}

const char* getBatchTargetName() { return HWY_DYNAMIC_DISPATCH(TargetName)(); }

}  // namespace crankcheck::analytic
#endif  // HWY_ONCE
