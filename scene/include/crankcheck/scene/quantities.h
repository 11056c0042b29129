#pragma once
/// @file
/// The catalogue of an Evaluation's quantities (evaluation.h): for each its name, unit and shape, the scale it is
/// judged against and how to read it from an Evaluation. Every place that lists quantities walks this list: eval's
/// JSON and its table, the comparison of two engines (validation/scales.h: compareEvaluations), `crankcheck grade`'s
/// request, its parser of a program's answer and its tables, the validate verdict's order, the Python module's
/// `Scene.evaluate`. A new quantity is its Evaluation field, one line of the catalogue (quantities.cc) and each
/// engine's computation (docs/contributing.md, "Adding a quantity").

#include <string_view>
#include <string>
#include <vector>

#include "crankcheck/scene/evaluation.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck {

/// Every quantity, in the catalogue's order (getQuantityCatalogue).
enum class QuantityId {
  kU, kQ, kDriveTorque, kBearingForce, kShakingForce, kShakingMoment,                      // the whole mechanism
  kPistonPosition, kPistonVelocity, kPistonAcceleration, kCrankPinForce, kWristPinForce,  // per cylinder
  kWallForce, kGasForce, kRodAngle, kRodOmega, kRodAlpha,
};

/// The physical scale a quantity is measured against: a member of validation::Scales, or one built from it
/// (validation/scales.h: getQuantityScale).
enum class QuantityScale {
  kAbsoluteHeightEnergy,  ///< Scales::absolute_height_energy (U: an engine's U may subtract absolute heights)
  kEnergy,            ///< Scales::energy
  kTorque,            ///< Scales::torque
  kForce,             ///< Scales::force
  kMoment,            ///< Scales::moment
  kPosition,          ///< Scales::position
  kVelocity,          ///< Scales::velocity
  kAcceleration,      ///< Scales::acceleration
  kRadian,            ///< 1 rad: an angle
  kRodVelocity,       ///< Scales::velocity / l: the relative velocity of the rod's ends over its length [rad/s]
  kRodAcceleration,   ///< Scales::acceleration / l [rad/s^2]
};

/// Which conditioning of validation::Scales multiplies the quantity's tolerance (scales.h explains each).
enum class QuantityConditioning {
  kNone,          ///< 1
  kClosure,       ///< Scales::closure: position-level quantities (U, x_p, the rod angle)
  kLoop,          ///< Scales::conditioning (Q)
  kVelocity,      ///< Scales::velocity_conditioning
  kAcceleration,  ///< Scales::acceleration_conditioning: accelerations, forces, torques, moments
};

/// When a quantity, or some of its components, is defined.
enum class QuantityPresence {
  kAlways,
  kWithGas,                ///< only for a scene with [gas] (eval leaves it out otherwise)
  kXYWithAxialPositions,   ///< components X and Y only when the scene places its cylinders along the shaft
                           ///< (hasAxialPositions; eval prints null otherwise); Z always
};

/// One quantity of an Evaluation.
struct Quantity {
  QuantityId id;
  const char* name;       ///< eval's JSON key, grade's protocol and tables, the validate report (docs/CONVENTIONS.md)
  const char* unit;       ///< SI, as eval's table prints it: "J", "N m", "m/s^2", ...
  bool per_cylinder;      ///< one value (or vector) per cylinder (CylinderEvaluation), else one per Evaluation
  int components;         ///< 1 (a number), 2 ([X, Y], global) or 3 ([X, Y, Z], global)
  QuantityScale scale;
  QuantityConditioning conditioning;
  QuantityPresence presence;
  /// eval's text table shows it (the rod's angle and its derivatives are in the JSON only).
  bool in_table;
  /// The paper's dimensionless form NAME_star = value / (I_w omega^2) exists (eval's JSON and the Python module
  /// give it with a flywheel and a speed).
  bool dimensionless;
  /// The first of the quantity's `components` contiguous values in the Evaluation (whole-mechanism quantities;
  /// null for per-cylinder ones).
  double* (*whole)(Evaluation&);
  /// The same in one cylinder's CylinderEvaluation (per-cylinder quantities; null otherwise).
  double* (*cylinder)(CylinderEvaluation&);
};

/// Every quantity of an Evaluation, in eval's JSON order (the whole mechanism's, then each cylinder's).
const std::vector<Quantity>& getQuantityCatalogue();
/// The name of quantity `id` (getQuantity(id).name), for code that speaks of one quantity by its id.
std::string nameOf(QuantityId id);
/// The catalogue's entry of `id`.
const Quantity& getQuantity(QuantityId id);
/// The catalogue's entry called `name`, or nullptr.
const Quantity* findQuantity(std::string_view name);

/// The first of the q.components contiguous values of quantity q in `ev` (of cylinder `cylinder` when q is per
/// cylinder; `cylinder` is ignored otherwise).
/// @throws std::out_of_range if q is per cylinder and `ev` has no cylinder `cylinder`.
double* accessQuantity(const Quantity& q, Evaluation& ev, int cylinder = -1);
/// The same, read only.
const double* readQuantity(const Quantity& q, const Evaluation& ev, int cylinder = -1);

/// Whether q is defined for m at all (gas_force needs [gas]).
bool isQuantityDefined(const Quantity& q, const Mechanism& m);
/// Whether component `component` of q is defined for m (isQuantityDefined, and shaking_moment's X and Y need axial
/// positions).
bool isComponentDefined(const Quantity& q, int component, const Mechanism& m);

}  // namespace crankcheck
