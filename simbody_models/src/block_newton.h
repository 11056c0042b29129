#pragma once
// Newton's method on Simbody's own constraint errors for a mechanism whose constraints fall into independent blocks:
// with the crank prescribed, each cylinder's loop closure involves that cylinder's joints alone (its piston's slide and
// its rod's pin; in the reduced gravity model the slide alone), and a balance shaft's gearing its own pin alone. The
// constraint Jacobian is then block diagonal, each block at most 2 x 2, and all blocks' columns come from as many
// realizations of Stage::Position as the largest block has coordinates (every block's first coordinate moved at once,
// then every block's second). System::projectQ instead forms the whole m x m matrix G M^-1 G^T by m operator passes
// over every constraint (O(k^2) for k cylinders). Private to the library; the models keep Simbody's projections for
// the crude start and as the fallback (simbody_models/README.md, "Evaluating at phi").

#include <Simbody.h>

#include <array>
#include <vector>

namespace crankcheck::simbody_models {

class BlockNewton {
 public:
  /// The finite-difference step of the Jacobian, relative to a length for a slide and in radians for a pin: about
  /// sqrt(eps), so that a column carries about 1e-8 of relative error and each Newton step, position or velocity, cuts
  /// the error by about that much.
  static constexpr double kStep = 1.5e-8;

  /// One block: its coordinates (1 or 2), their u's, the finite-difference step of each [m or rad], and its constraint
  /// (whose holonomic equations, as many as coordinates, are the block's rows).
  struct Block {
    std::vector<SimTK::QIndex> q;
    std::vector<SimTK::UIndex> u;
    std::vector<double> step;
    SimTK::Constraint constraint;
  };

  /// @throws std::logic_error for a block of 0 or more than 2 coordinates or whose constraint has another number of
  /// holonomic equations. `state` realized through Stage::Instance (the error slots are read from it).
  BlockNewton(std::vector<Block> blocks, const SimTK::State& state);

  /// Forget the Jacobian (the positions moved: a new assembly).
  void invalidate() { jacobian_valid_ = false; }

  /// Newton on the positions from the state's q (the prescribed ones set); realized through Stage::Position on return.
  /// true: every position error <= `threshold`, or a step with a fresh Jacobian stalled (rounding) at <= `acceptance`;
  /// false: not converged in 8 steps (q then undefined: the caller restarts).
  bool closePositions(const SimTK::System& system, SimTK::State& state, double threshold, double acceptance);

  /// Newton on the free velocities at the state's positions (the prescribed u's set by the caller), with the Jacobian
  /// of the assembly when it was computed within `near` [m] of closure, else computed here; realized through
  /// Stage::Velocity on return. true and false as closePositions (u then undefined).
  bool solveVelocities(const SimTK::System& system, SimTK::State& state, double threshold, double acceptance,
                       double near);

 private:
  /// Every error of the blocks' rows (position errors at Stage::Position or velocity errors at Stage::Velocity).
  void readErrors(const SimTK::State& state, bool velocity, std::vector<double>& e) const;
  /// The blocks' Jacobian at the state's positions (realized through Position on return, q unchanged).
  void calcJacobian(const SimTK::System& system, SimTK::State& state);
  /// One Newton step from `e` on q (positions) or u (velocities).
  void takeStep(SimTK::State& state, const std::vector<double>& e, bool velocity) const;

  std::vector<Block> blocks_;
  std::vector<int> first_row_;                  // block b's rows in the state's QErr / UErr
  std::vector<std::array<double, 4>> jacobian_;  // block b's d(error rows)/d(coordinates), row by row (2 x 2 or 1 x 1)
  bool jacobian_valid_ = false;
  double jacobian_closure_ = 0.0;  // the largest position error where the Jacobian was computed
  int colors_ = 0;                 // the largest block's coordinates
  std::vector<double> errors_, perturbed_, moved_;  // scratch, kept: an assembly's hot path allocates nothing
  SimTK::Vector q_start_;
};

}  // namespace crankcheck::simbody_models
