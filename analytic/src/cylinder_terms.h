#pragma once
/// @file
/// One cylinder's terms of the sums over cylinders that calcReducedInertia (motion.h) and calcGravityTorque
/// (gravity_torque.h) make at a crank angle phi, from the cylinder's crank angle theta_j = phi + alpha_j
/// (calcThrowSinCos): the one formula of each, shared by calcThrowLoads (crank_train.h), which computes theta_j once
/// for both (the crank train's integration evaluates them at every step). Internal to analytic/.

#include "crankcheck/analytic/exact_trig.h"
#include "crankcheck/analytic/motion.h"
#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::analytic {

/// What the kinematics at unit crank speed read of m (r, l; omega = 1): time derivatives are then derivatives in
/// theta. A light copy, not of m's tables.
Mechanism makeUnitSpeedCopy(const Mechanism& m);

/// Adds cylinder j's part of J [kg m^2] and dJ/dphi [kg m^2/rad] (its crank's masses included) to `out`; `unit` is
/// makeUnitSpeedCopy(m).
void addCylinderInertia(const Mechanism& m, const Mechanism& unit, int j, const SinCos& theta, RodInertiaForm form,
                        ReducedInertia& out);

/// [N m] Cylinder j's part of Q, Stanczak eq (13) in its own bank; c = calcGravityCoefficients(m, form).
double calcCylinderGravityTorque(const Mechanism& m, int j, const SinCos& theta, const GravityCoefficients& c);
/// The same with the cylinder's bank angle given as gamma = calcSinCos(getBankAngle(m, j)).
double calcCylinderGravityTorque(const Mechanism& m, int j, const SinCos& theta, const SinCos& gamma,
                                 const GravityCoefficients& c);

}  // namespace crankcheck::analytic
