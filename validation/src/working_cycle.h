#pragma once
// Loads over one working cycle (720 degrees four-stroke, 360 two-stroke): the cycle's angle, the crank-pin force in the
// crank's own frame (Norton's polar diagram), and a maximum over the cycle found so that it does not depend on the grid
// (the cycle mapped onto a turn for extremum.h). Shared by the pin_load_polar part and the scene sections' loads topic.

#include <functional>
#include <utility>
#include <vector>

#include "crankcheck/scene/evaluation.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/extremum.h"

namespace crankcheck::validation {

/// [rad] m's working cycle: 4 pi four-stroke, 2 pi two-stroke.
double calcCycleAngle(const Mechanism& m);

/// [N] The crank-pin force of cylinder j of e (crank on rod j at its crank pin) in the crank's own frame: first radial
/// (outward along cylinder j's throw, at angle phi + beta_j from +X), then tangential (90 degrees ahead of it, the
/// direction of rotation). @throws std::out_of_range if e has no cylinder j.
std::pair<double, double> calcCrankPinForceInCrankFrame(const Mechanism& m, const Evaluation& e, int j);

/// max |f| over one working cycle [0, cycle) [rad], f periodic over it, from samples already taken:
/// values[i] = f(cycle i / values.size()); the best `refinements` sampled maxima refined by Brent's method to
/// `tolerance` [rad of the turn the cycle is mapped onto] (extremum.h findMaxAbsOverTurn). The result's phi is the
/// crank angle [rad] in [0, cycle). @throws as findMaxAbsOverTurn.
TurnMaximum findMaxAbsOverCycle(const std::function<double(double)>& f, double cycle, const std::vector<double>& values,
                                int refinements, double tolerance);

}  // namespace crankcheck::validation
