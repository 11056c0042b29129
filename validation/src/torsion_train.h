#pragma once
// The elastic crank train as the report computes it: the accuracies of Holzer's sum and of the exact steady state, the
// cycle's order step and major orders, the sections' names, and the natural frequencies with the spread the throws'
// variable inertia gives them. The torsion part (parts/torsion.cc) sweeps them over speed, the scene sections'
// dynamics topic (your_engine/dynamics.cc) shows them at each scene's own speed.

#include <string>
#include <utility>
#include <vector>

#include "crankcheck/analytic/torsion.h"
#include "crankcheck/analytic/torsion_forced.h"
#include "crankcheck/analytic/torsion_steady.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::validation {

/// Holzer's sum converged to 1e-6 of the largest peak-to-peak; the exact steady state integrated at 1e-8 (its error
/// bound, at most 2e-5 of the largest peak-to-peak on the example scenes, is reported beside it) and sampled 2048 times
/// a cycle (the series' aliasing, a few 1e-7 of a small section's value): far below the percent differences between
/// the two, at a third of the cost of `crankcheck torsion`'s 1e-8 / 1e-11.
analytic::HolzerOptions makeTrainHolzerOptions();
analytic::SteadyStateOptions makeTrainSteadyStateOptions();

/// The working cycle's order step: 1/2 (four-stroke), 1 (two-stroke).
double getOrderStep(const Mechanism& m);

/// The major orders: the multiples of the firings per turn (cylinders x getOrderStep), where the gas torques of evenly
/// spaced firings add, up to order `highest`, ascending.
std::vector<double> listMajorOrders(const Mechanism& m, double highest);

/// Section i's name as a bare word: front-throw0, throw0-throw1, ..., throw3-flywheel (`bodies`: the train's).
std::string nameSection(const Mechanism& m, int i, int bodies);

/// J_min and J_max [kg m^2] of throw j over a turn, [crankshaft].throw_inertia included (extremum.h: sampled, refined
/// by Brent).
std::pair<double, double> findThrowInertiaRange(const Mechanism& m, int j);

/// Holzer's modes and the spread of the variable-inertia train's: the chain with every throw at its J_max (the lowest
/// frequencies) and at its J_min (the highest), the front mass as it is.
struct TorsionModeBand {
  analytic::TorsionModes holzer, at_max, at_min;
  std::vector<analytic::ThrowInertia> inertias;         ///< per throw (findThrows)
  std::vector<std::pair<double, double>> ranges;        ///< per throw: J_min, J_max [kg m^2]
};
/// @throws as analytic::calcTorsionModes.
TorsionModeBand calcTorsionModeBand(const Mechanism& m);

}  // namespace crankcheck::validation
