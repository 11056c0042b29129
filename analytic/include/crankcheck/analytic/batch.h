#pragma once
/// @file
/// Q = dU/dphi (Stanczak eq 13) at many crank angles at once: the same mathematics as calcGravityTorque, with the
/// arithmetic arranged for throughput. What a sweep over millions of (k, lambda, gamma, phi) points calls.
///
/// Accuracy (tests/analytic/batch_test.cc): within 8 eps of the energy scale of calcGravityTorque for arbitrary
/// angles (each throw's angle is phi rotated by the precomputed alpha_j, one rounding more than sin(phi + alpha_j));
/// within 1e-13 of the energy scale times 1/(1 - lambda^2) on a uniform grid (angle-addition recurrence,
/// re-anchored every 32 steps; the factor is Q's slope near lambda = 1, 1.2 at lambda = 0.4).
/// Unlike the scalar function, quarter turns are not snapped to exact zeros.

#include <span>

#include "crankcheck/scene/mechanism.h"

namespace crankcheck::analytic {

/// Q [N m] at each angle phi[i] [rad]. @throws std::invalid_argument if the spans differ in size.
/// @throws std::invalid_argument if the cylinders are not in one bank (isSingleBank) or the spans differ in size.
void calcGravityTorqueBatch(const Mechanism& m, std::span<const double> phi, std::span<double> Q);

/// Q [N m] on the uniform grid phi_i = phi0 + i step, i = 0 .. Q.size() - 1. sin and cos of phi_i come from the
/// rotation by step (4 multiplications), re-anchored with sincos every 32 steps so that rounding cannot grow.
void calcGravityTorqueOnGrid(const Mechanism& m, double phi0, double step, std::span<double> Q);

}  // namespace crankcheck::analytic
