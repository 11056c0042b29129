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

#include "crankcheck/scene/engine.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::python {

/// The quantities of `crankcheck eval --format json`, in its order, with the number of components of each.
struct QuantityInfo {
  const char* name;
  int components;     ///< 1 (a number), 2 ([X, Y]) or 3 ([X, Y, Z])
  bool per_cylinder;  ///< one value (or vector) per cylinder
};
/// U, Q, U_star, Q_star, drive_torque, bearing_force, shaking_force, shaking_moment, x_p, v_p, a_p,
/// crank_pin_force, wrist_pin_force, wall_force, gas_force, rod_angle, rod_omega, rod_alpha.
const std::vector<QuantityInfo>& listQuantities();
/// The entry of listQuantities() called `name`, or nullptr.
const QuantityInfo* findQuantity(const std::string& name);
/// Whether the quantity is defined for m: U_star and Q_star need a flywheel and a speed (eval prints null otherwise),
/// gas_force needs [gas] (eval leaves it out otherwise).
bool isDefined(const Mechanism& m, const std::string& name);

/// Caller-owned output: for each quantity either empty (not computed) or one pointer to
/// n x components x (k if per cylinder) doubles, laid out as [component][cylinder][angle]: component c of cylinder j
/// at angle i is at data[(c k + j) n + i] (k = 1 for whole-mechanism quantities).
struct BatchOutput {
  double* U = nullptr;
  double* Q = nullptr;
  double* U_star = nullptr;
  double* Q_star = nullptr;
  double* drive_torque = nullptr;
  double* bearing_force = nullptr;   ///< 2 components
  double* shaking_force = nullptr;   ///< 2 components
  double* shaking_moment = nullptr;  ///< 3 components; X and Y NaN when the scene has no axial positions (eval: null)
  double* x_p = nullptr;
  double* v_p = nullptr;
  double* a_p = nullptr;
  double* crank_pin_force = nullptr;  ///< 2 components per cylinder
  double* wrist_pin_force = nullptr;  ///< 2 components per cylinder
  double* wall_force = nullptr;
  double* gas_force = nullptr;
  double* rod_angle = nullptr;
  double* rod_omega = nullptr;
  double* rod_alpha = nullptr;
  /// The pointer of quantity `name` (one of listQuantities()).
  double*& at(const std::string& name);
};

/// Checks that every angle is finite. @throws std::invalid_argument "phi[i] = VALUE: must be a finite number of
/// radians" for the first that is not.
void checkAngles(std::span<const double> phi);

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
