// Newton's method on Simbody's constraint errors, block by block (block_newton.h). Never compiled with NDEBUG.
#include "block_newton.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#ifdef NDEBUG
#error "Simbody code must not be compiled with NDEBUG: Debian's Simbody was built without it (SIMBODY-NOTES.md)"
#endif

namespace crankcheck::simbody_models {
namespace {

// At most this many Newton steps (from a near start: one or two; from 60 degrees off with a Jacobian computed again:
// four or five).
constexpr int kSteps = 8;

double calcMaxAbs(const std::vector<double>& v) {
  double result = 0.0;
  for (double x : v) result = std::max(result, std::abs(x));
  return std::isfinite(result) ? result : std::numeric_limits<double>::infinity();
}

}  // namespace

BlockNewton::BlockNewton(std::vector<Block> blocks, const SimTK::State& state) : blocks_(std::move(blocks)) {
  for (const Block& b : blocks_) {
    const int n = static_cast<int>(b.q.size());
    int mp = 0, mv = 0, ma = 0;
    b.constraint.getNumConstraintEquationsInUse(state, mp, mv, ma);
    if (n < 1 || n > 2 || b.u.size() != b.q.size() || b.step.size() != b.q.size() || mp != n || mv != 0 || ma != 0)
      throw std::logic_error("BlockNewton: a block has 1 or 2 coordinates and as many holonomic equations");
    SimTK::MultiplierIndex px0, vx0, ax0;
    b.constraint.getIndexOfMultipliersInUse(state, px0, vx0, ax0);
    first_row_.push_back(px0);  // the holonomic equations come first, in the multipliers as in QErr and UErr
    colors_ = std::max(colors_, n);
  }
  jacobian_.assign(blocks_.size(), {});
}

void BlockNewton::readErrors(const SimTK::State& state, bool velocity, std::vector<double>& e) const {
  const SimTK::Vector& all = velocity ? state.getUErr() : state.getQErr();
  e.resize(2 * blocks_.size());
  for (size_t b = 0; b < blocks_.size(); ++b) {
    e[2 * b] = all[first_row_[b]];
    e[2 * b + 1] = blocks_[b].q.size() == 2 ? all[first_row_[b] + 1] : 0.0;
  }
}

void BlockNewton::calcJacobian(const SimTK::System& system, SimTK::State& state) {
  system.realize(state, SimTK::Stage::Position);
  readErrors(state, false, errors_);
  q_start_ = state.getQ();
  std::vector<double>& moved = moved_;
  moved.resize(blocks_.size());
  for (int c = 0; c < colors_; ++c) {
    // Coordinate c of every block moved at once (each by its exact floating-point step): the blocks are independent.
    {
      SimTK::Vector& q = state.updQ();
      for (size_t b = 0; b < blocks_.size(); ++b) {
        if (static_cast<int>(blocks_[b].q.size()) <= c) continue;
        const SimTK::QIndex qx = blocks_[b].q[c];
        const double before = q[qx];
        q[qx] = before + blocks_[b].step[c];
        moved[b] = q[qx] - before;
      }
    }
    system.realize(state, SimTK::Stage::Position);
    readErrors(state, false, perturbed_);
    for (size_t b = 0; b < blocks_.size(); ++b) {
      const size_t n = blocks_[b].q.size();
      if (static_cast<int>(n) <= c) continue;
      for (size_t row = 0; row < n; ++row)
        jacobian_[b][row * n + static_cast<size_t>(c)] = (perturbed_[2 * b + row] - errors_[2 * b + row]) / moved[b];
    }
    state.updQ() = q_start_;
  }
  system.realize(state, SimTK::Stage::Position);
  jacobian_valid_ = true;
  jacobian_closure_ = calcMaxAbs(errors_);
}

void BlockNewton::takeStep(SimTK::State& state, const std::vector<double>& e, bool velocity) const {
  SimTK::Vector& x = velocity ? state.updU() : state.updQ();
  for (size_t b = 0; b < blocks_.size(); ++b) {
    const Block& block = blocks_[b];
    const std::array<double, 4>& J = jacobian_[b];
    const double e0 = e[2 * b], e1 = e[2 * b + 1];
    auto at = [&](size_t i) { return velocity ? int(block.u[i]) : int(block.q[i]); };
    if (block.q.size() == 1) {
      x[at(0)] -= e0 / J[0];
      continue;
    }
    const double det = J[0] * J[3] - J[1] * J[2];
    x[at(0)] -= (e0 * J[3] - J[1] * e1) / det;
    x[at(1)] -= (J[0] * e1 - J[2] * e0) / det;
  }
}

bool BlockNewton::closePositions(const SimTK::System& system, SimTK::State& state, double threshold,
                                 double acceptance) {
  system.realize(state, SimTK::Stage::Position);
  readErrors(state, false, errors_);
  double error = calcMaxAbs(errors_);
  if (error <= threshold) return true;
  calcJacobian(system, state);  // errors_ stay those of the start
  bool fresh = true;            // the Jacobian is that of the point the next step starts from
  for (int step = 0; step < kSteps; ++step) {
    takeStep(state, errors_, false);
    system.realize(state, SimTK::Stage::Position);
    readErrors(state, false, errors_);
    const double next = calcMaxAbs(errors_);
    if (next <= threshold) return true;
    if (next > 1e-4 * error) {
      // A step that cut the error less than 1e4-fold. With the Jacobian of its own start and not even halving it, the
      // error is Simbody's rounding (a shaft's gearing in radians, a rod kilometres long): accepted below `acceptance`.
      // With an older Jacobian (a start 10 degrees off or more), computed again where the next step starts.
      if (fresh && !(next <= 0.5 * error)) return next <= acceptance;
      calcJacobian(system, state);
      fresh = true;
    } else {
      fresh = false;
    }
    error = next;
  }
  return false;
}

bool BlockNewton::solveVelocities(const SimTK::System& system, SimTK::State& state, double threshold,
                                  double acceptance, double near) {
  system.realize(state, SimTK::Stage::Velocity);
  readErrors(state, true, errors_);
  double error = calcMaxAbs(errors_);
  if (error <= threshold) return true;
  // The velocity errors are linear in u with the position Jacobian as matrix (the coordinates' qdot are their u's):
  // with the Jacobian of the assembled positions, or of a start within `near` of them, each step cuts the error by its
  // relative error (about 1e-8).
  if (!jacobian_valid_ || jacobian_closure_ > near) {
    calcJacobian(system, state);  // the u's are kept; Velocity is realized again below
    system.realize(state, SimTK::Stage::Velocity);
    readErrors(state, true, errors_);
  }
  for (int step = 0; step < kSteps; ++step) {
    takeStep(state, errors_, true);
    system.realize(state, SimTK::Stage::Velocity);
    readErrors(state, true, errors_);
    const double next = calcMaxAbs(errors_);
    if (next <= threshold) return true;
    if (!(next <= 0.5 * error)) return next <= acceptance;  // rounding, as for the positions
    error = next;
  }
  return false;
}

}  // namespace crankcheck::simbody_models
