#pragma once
/// @file
/// What `Scene.evaluate` of the Python module computes, in plain C++ (no Python here, so that the benchmark
/// bench/python_batch_bench.cc times exactly this code): every quantity of `crankcheck eval` at many crank angles,
/// written into caller-owned memory in structure-of-arrays layout (one contiguous run of n doubles per component and
/// cylinder, the layout the batch kernels of analytic/batch.h write).
///
/// The analytic engine goes through the batch kernels (U, Q, piston kinematics, reactions, shaking); the rod's angle
/// and its derivatives and the gas force, which have no kernel, come from the same scalar functions the analytic
/// engine's calcEvaluation calls (calcCylinderMotion's rod, calcGasForce), angle by angle in C++. A mechanism the
/// kernels do not cover (pin offsets, balance shafts) is evaluated by calcEvaluation angle by angle. Any other engine (validation::listEngines()) is evaluated angle by angle through its EngineModel.
/// Names, units and signs: eval's (docs/eval.md, docs/CONVENTIONS.md).

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "crankcheck/solver/engine.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/scene/quantities.h"

namespace crankcheck::python {

/// The quantities of `crankcheck eval --format json`, with the number of components of each.
struct QuantityInfo {
  const char* name;
  int components;     ///< 1 (a number), 2 ([X, Y]) or 3 ([X, Y, Z])
  bool per_cylinder;  ///< one value (or vector) per cylinder
  /// The catalogue's entry (quantities.h); for NAME_star, the entry of NAME.
  const Quantity* quantity;
  bool star;          ///< the paper's dimensionless NAME_star = NAME / (I_w omega^2)
};
/// The catalogue's quantities in its order (quantities.h), with the dimensionless NAME_star of each that has one
/// after the last of those: U, Q, U_star, Q_star, drive_torque, bearing_force, ..., rod_alpha.
const std::vector<QuantityInfo>& listQuantities();
/// The entry of listQuantities() called `name`, or nullptr.
const QuantityInfo* findQuantity(const std::string& name);
/// Whether the quantity is defined for m: U_star and Q_star need a flywheel and a speed (eval prints null otherwise),
/// gas_force needs [gas] (eval leaves it out otherwise).
bool isDefined(const Mechanism& m, const std::string& name);

/// Caller-owned output: for each quantity either null (not computed) or one pointer to
/// n x components x (k if per cylinder) doubles, laid out as [component][cylinder][angle]: component c of cylinder j
/// at angle i is at data[(c k + j) n + i] (k = 1 for whole-mechanism quantities). shaking_moment's X and Y are NaN
/// when the scene has no axial positions (eval: null).
struct BatchOutput {
  BatchOutput();
  /// The pointer of a catalogue quantity.
  double* operator[](QuantityId id) const { return values[static_cast<size_t>(id)]; }
  /// The pointer of its NAME_star (quantities with `dimensionless`).
  double* star(QuantityId id) const { return stars[static_cast<size_t>(id)]; }
  /// The pointer of quantity `name` (one of listQuantities()). @throws std::invalid_argument for another name.
  double*& at(const std::string& name);

  std::vector<double*> values;  ///< indexed by QuantityId
  std::vector<double*> stars;   ///< indexed by QuantityId
};

/// Checks that every angle is finite. @throws std::invalid_argument "phi[i] = VALUE: must be a finite number of
/// radians" for the first that is not.
void checkAngles(std::span<const double> phi, const char* name = "phi");

/// Whether the batch kernels cover m (batch.h: centric cylinders without balance shafts).
bool batchKernelsAccept(const Mechanism& m);

/// The analytic engine at every angle phi[i] [rad] through the batch kernels (for a mechanism they do not cover,
/// batchKernelsAccept, through the analytic engine's calcEvaluation angle by angle); fills what `out` points at (a kernel
/// runs only when one of its quantities is asked for; what it computes besides goes to scratch memory).
/// Thread-safe: a pure function of m and phi. @throws std::invalid_argument if an angle is not finite; a quantity not
/// defined for m (isDefined) must not be asked for.
void evaluateAnalyticBatch(const Mechanism& m, std::span<const double> phi, const BatchOutput& out);

/// Any engine's model, angle by angle, in the order of phi (a model keeps warm starts: the same angles in the same
/// order give the same results as `crankcheck eval --engine NAME --phi-deg ...`). The model is used by this thread
/// only. @throws std::invalid_argument if an angle is not finite; std::runtime_error naming the engine and the angle if
/// the engine fails there.
void evaluateModel(const Mechanism& m, const Engine& engine, EngineModel& model, std::span<const double> phi,
                   const BatchOutput& out);

}  // namespace crankcheck::python
