#include "crankcheck/analytic/balance_shafts.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "crankcheck/analytic/exact_trig.h"

namespace crankcheck::analytic {

BalanceShaftLoads calcBalanceShaftLoads(const Mechanism& m, double phi) {
  return calcBalanceShaftLoads(m, phi, m.machine.speed, 0.0);
}

BalanceShaftLoads calcBalanceShaftLoads(const Mechanism& m, double phi, double omega, double alpha) {
  BalanceShaftLoads out;
  const double g = m.machine.gravity, w = omega;
  for (const BalanceShaftParams& b : m.balance_shafts) {
    const SinCos phase = calcSinCos(b.phase);
    const SinCos turn = calcSinCos(b.ratio * phi), half = calcSinCos(0.5 * b.ratio * phi);
    const SinCos psi = addAngles(phase, turn);                 // ratio phi + phase
    const SinCos mid = addAngles(phase, half);                 // phase + ratio phi / 2
    const double mgr = b.mass * g * b.radius;
    out.U += mgr * 2.0 * half.sin * mid.cos;                   // sin(psi) - sin(phase), free of cancellation
    out.Q += mgr * b.ratio * psi.cos;
    out.drive_torque += mgr * b.ratio * psi.cos;
    const double A = b.mass * b.radius * (b.ratio * w) * (b.ratio * w);  // m rho Omega^2
    const auto [x, y, z] = b.position;
    out.shaking_force[0] += A * psi.cos;
    out.shaking_force[1] += A * psi.sin;
    out.shaking_moment[0] += A * (-z * psi.sin);
    out.shaking_moment[1] += A * (z * psi.cos);
    out.shaking_moment[2] += A * (x * psi.sin - y * psi.cos);
    out.inertia += b.mass * b.radius * b.radius * b.ratio * b.ratio;
    if (alpha != 0.0) {
      // -m times the tangential acceleration rho Omega_dot (-sin psi, cos psi), and its moment -p x m a about O.
      const double T = b.mass * b.radius * (b.ratio * alpha);  // m rho Omega_dot
      out.drive_torque += b.mass * b.radius * b.radius * b.ratio * b.ratio * alpha;
      out.shaking_force[0] += T * psi.sin;
      out.shaking_force[1] -= T * psi.cos;
      out.shaking_moment[0] += T * z * psi.cos;
      out.shaking_moment[1] += T * z * psi.sin;
      out.shaking_moment[2] -= T * (x * psi.cos + y * psi.sin + b.radius);
    }
  }
  return out;
}

ShaftHarmonic calcBalanceShaftHarmonic(const Mechanism& m, const BalanceShaftParams& b, int n) {
  if (b.ratio != std::nearbyint(b.ratio))
    throw std::invalid_argument("balance harmonics need whole-number balance shaft ratios (got " + std::to_string(b.ratio) +
                                ": its shaking is not periodic in the crank angle)");
  ShaftHarmonic h;
  if (std::fabs(b.ratio) != n) return h;
  const double w = m.machine.speed, A = b.mass * b.radius * (b.ratio * w) * (b.ratio * w);
  const double sign = b.ratio > 0 ? 1.0 : -1.0;
  const SinCos p = calcSinCos(b.phase);
  const auto [x, y, z] = b.position;
  // cos psi = cos p cos(n phi) - sign sin p sin(n phi), sin psi = sin p cos(n phi) + sign cos p sin(n phi)
  h.force_cos = {A * p.cos, A * p.sin};
  h.force_sin = {-A * sign * p.sin, A * sign * p.cos};
  h.moment_cos = {-A * z * p.sin, A * z * p.cos, A * (x * p.sin - y * p.cos)};
  h.moment_sin = {-A * z * sign * p.cos, -A * z * sign * p.sin, A * sign * (x * p.cos + y * p.sin)};
  return h;
}

}  // namespace crankcheck::analytic
