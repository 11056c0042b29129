#pragma once
// One engine's shaking force and moment over a crank turn and their harmonics by a DFT: what the balance report part
// (balance.h calcBalance) and the scene sections' balance topic (your_engine/balance.cc) read from every engine.

#include <array>
#include <vector>

#include "crankcheck/analytic/shaking.h"
#include "crankcheck/solver/engine.h"
#include "crankcheck/scene/evaluation.h"

namespace crankcheck::validation {

/// An engine's shaking force F_s [N] (X, Y) and moment M_s [N m] (about O: X, Y, Z) at the crank angles
/// phi_i = 2 pi i / N, i = 0..N-1, at the scene's constant speed (Evaluation::shaking_force, shaking_moment).
struct ShakingTurn {
  std::vector<Vec2> force;
  std::vector<std::array<double, 3>> moment;
};

/// `model`'s F_s and M_s at `samples` equally spaced angles over a turn (EngineModel::evaluateMotion: no U or Q).
/// @throws std::invalid_argument if samples < 1; what the model's evaluation throws.
ShakingTurn sampleShakingTurn(EngineModel& model, int samples);

/// Harmonics 1..order of the sampled F_s and M_s by Eigen's FFT, X_n = sum_i f(phi_i) exp(-i n phi_i):
/// cos_n = (2 / N) Re X_n, sin_n = -(2 / N) Im X_n. Harmonic N - n folds onto n (the DFT's aliasing): the caller
/// samples enough angles for the harmonics beyond N - order to be below what it reads.
/// @throws std::invalid_argument if order < 1 or N < 2 order + 1.
std::vector<analytic::ShakingHarmonic> calcShakingSpectrum(const ShakingTurn& turn, int order);

}  // namespace crankcheck::validation
