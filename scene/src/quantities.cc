#include "crankcheck/scene/quantities.h"

#include <stdexcept>
#include <string>

namespace crankcheck {

namespace {

using Id = QuantityId;
using Scale = QuantityScale;
using Cond = QuantityConditioning;
using Presence = QuantityPresence;

// A whole-mechanism quantity.
Quantity whole(Id id, const char* name, const char* unit, int components, Scale scale, Cond cond, Presence presence,
               bool dimensionless, double* (*at)(Evaluation&)) {
  return {id, name, unit, false, components, scale, cond, presence, true, dimensionless, at, nullptr};
}

// A per-cylinder quantity.
Quantity cylinder(Id id, const char* name, const char* unit, int components, Scale scale, Cond cond, Presence presence,
                  bool in_table, double* (*at)(CylinderEvaluation&)) {
  return {id, name, unit, true, components, scale, cond, presence, in_table, false, nullptr, at};
}

}  // namespace

const std::vector<Quantity>& getQuantityCatalogue() {
  // In QuantityId's order (getQuantity indexes by it); eval's JSON order.
  static const std::vector<Quantity> catalogue = {
      whole(Id::kU, "U", "J", 1, Scale::kAbsoluteHeightEnergy, Cond::kClosure, Presence::kAlways, true,
            [](Evaluation& e) { return &e.U; }),
      whole(Id::kQ, "Q", "N m", 1, Scale::kEnergy, Cond::kLoop, Presence::kAlways, true, [](Evaluation& e) { return &e.Q; }),
      whole(Id::kDriveTorque, "drive_torque", "N m", 1, Scale::kTorque, Cond::kAcceleration, Presence::kAlways, false,
            [](Evaluation& e) { return &e.drive_torque; }),
      whole(Id::kBearingForce, "bearing_force", "N", 2, Scale::kForce, Cond::kAcceleration, Presence::kAlways, false,
            [](Evaluation& e) { return e.bearing_force.data(); }),
      whole(Id::kShakingForce, "shaking_force", "N", 2, Scale::kForce, Cond::kAcceleration, Presence::kAlways, false,
            [](Evaluation& e) { return e.shaking_force.data(); }),
      whole(Id::kShakingMoment, "shaking_moment", "N m", 3, Scale::kMoment, Cond::kAcceleration,
            Presence::kXYWithAxialPositions, false, [](Evaluation& e) { return e.shaking_moment.data(); }),
      cylinder(Id::kPistonPosition, "x_p", "m", 1, Scale::kPosition, Cond::kClosure, Presence::kAlways, true,
               [](CylinderEvaluation& c) { return &c.x_p; }),
      cylinder(Id::kPistonVelocity, "v_p", "m/s", 1, Scale::kVelocity, Cond::kVelocity, Presence::kAlways, true,
               [](CylinderEvaluation& c) { return &c.v_p; }),
      cylinder(Id::kPistonAcceleration, "a_p", "m/s^2", 1, Scale::kAcceleration, Cond::kAcceleration, Presence::kAlways,
               true, [](CylinderEvaluation& c) { return &c.a_p; }),
      cylinder(Id::kCrankPinForce, "crank_pin_force", "N", 2, Scale::kForce, Cond::kAcceleration, Presence::kAlways, true,
               [](CylinderEvaluation& c) { return c.crank_pin_force.data(); }),
      cylinder(Id::kWristPinForce, "wrist_pin_force", "N", 2, Scale::kForce, Cond::kAcceleration, Presence::kAlways, true,
               [](CylinderEvaluation& c) { return c.wrist_pin_force.data(); }),
      cylinder(Id::kWallForce, "wall_force", "N", 1, Scale::kForce, Cond::kAcceleration, Presence::kAlways, true,
               [](CylinderEvaluation& c) { return &c.wall_force; }),
      // The gas force is the load itself (p A), not a reaction the loop amplifies: no conditioning.
      cylinder(Id::kGasForce, "gas_force", "N", 1, Scale::kForce, Cond::kNone, Presence::kWithGas, true,
               [](CylinderEvaluation& c) { return &c.gas_force; }),
      // The rod's swing: an angle (as x_p, through the loop closure), and the relative velocity and acceleration of
      // its ends over its length.
      cylinder(Id::kRodAngle, "rod_angle", "rad", 1, Scale::kRadian, Cond::kClosure, Presence::kAlways, false,
               [](CylinderEvaluation& c) { return &c.rod_angle; }),
      cylinder(Id::kRodOmega, "rod_omega", "rad/s", 1, Scale::kRodVelocity, Cond::kVelocity, Presence::kAlways, false,
               [](CylinderEvaluation& c) { return &c.rod_omega; }),
      cylinder(Id::kRodAlpha, "rod_alpha", "rad/s^2", 1, Scale::kRodAcceleration, Cond::kAcceleration, Presence::kAlways,
               false, [](CylinderEvaluation& c) { return &c.rod_alpha; }),
  };
  return catalogue;
}

const Quantity& getQuantity(QuantityId id) { return getQuantityCatalogue()[static_cast<size_t>(id)]; }

const Quantity* findQuantity(std::string_view name) {
  for (const Quantity& q : getQuantityCatalogue())
    if (name == q.name) return &q;
  return nullptr;
}

double* accessQuantity(const Quantity& q, Evaluation& ev, int cylinder) {
  if (!q.per_cylinder) return q.whole(ev);
  if (cylinder < 0 || static_cast<size_t>(cylinder) >= ev.cylinders.size())
    throw std::out_of_range(std::string(q.name) + ": no cylinder " + std::to_string(cylinder) + " in an evaluation of " +
                            std::to_string(ev.cylinders.size()));
  return q.cylinder(ev.cylinders[static_cast<size_t>(cylinder)]);
}

const double* readQuantity(const Quantity& q, const Evaluation& ev, int cylinder) {
  // The accessors only locate a field: nothing is written through them here.
  return accessQuantity(q, const_cast<Evaluation&>(ev), cylinder);
}

bool isQuantityDefined(const Quantity& q, const Mechanism& m) {
  return q.presence != QuantityPresence::kWithGas || m.gas.has_value();
}

bool isComponentDefined(const Quantity& q, int component, const Mechanism& m) {
  if (!isQuantityDefined(q, m)) return false;
  return q.presence != QuantityPresence::kXYWithAxialPositions || component >= 2 || hasAxialPositions(m);
}

std::string nameOf(QuantityId id) { return getQuantity(id).name; }

}  // namespace crankcheck
