#pragma once
/// @file
/// The working loads of an engine for the report: example pressure tables, the drive torque split into its gas,
/// inertia and gravity parts over a cycle (report part `torque_split`), and the error of the two-mass rod against
/// each reference engine's rigid rod (report part `rod_models`).

#include "crankcheck/scene/gas.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/campaign.h"

namespace crankcheck::validation {

/// An example gauge-pressure table: a spark-ignition four-stroke cycle (peak 5.6 MPa at 20 degrees) or a slow
/// two-stroke crosshead diesel (peak 15 MPa at 10 degrees), with the given bore [m].
GasParams makeExampleGas(Cycle cycle, double bore);

/// `m` with `gas`, each cylinder firing at its own outer dead centre phi = -alpha_j (mod the cycle): with eqs
/// (8)-(11)'s phases an evenly spaced firing.
Mechanism withGasAtDeadCentres(const Mechanism& m, const GasParams& gas);

/// Report tables (campaign.h's TableSet):
///   torque_split   engine,phi_deg,drive_torque,gas_torque,inertia_torque,gravity_torque, then ENGINE_drive_torque
///                  per reference engine (simbody_drive_torque, mujoco_drive_torque)
///                  over one working cycle of an inline four four-stroke on `car`'s parts (bore 2 r, 6000 rpm) and of
///                  the `marine` engine as it is (bore 2 r / 3), analytic parts, each reference engine's whole drive torque beside
///   gravity_share  cycle,k,speed_rpm,mean_abs_drive_torque,mean_abs_gravity_torque,share,resolved
///                  gravity's share of the mean absolute drive torque over the cycle, k = 1..12, both strokes, the
///                  car's parts with the example pressure table of each stroke, 600 to 6000 rpm; resolved = 0 where the
///                  gravity torque is below 64 eps of the energy scale (rounding, not a torque)
TableSet calcTorqueSplitTables(const Mechanism& car, const Mechanism& marine);

///   rod_models     engine,variable,x,two_mass_error,two_mass_delta_I_error,two_mass_delta_I_resolved,reference
///                  the largest |drive torque of the two-mass rod - the `reference` engine's rigid rod| over the turn (refined,
///                  extremum.h; with Delta_I rounding: resolved 0 marks the number as a bound), relative to the
///                  torque scale, without and with the paper's Delta_I, against lambda (variable "lambda") and
///                  against Delta_I / I_G (variable "delta_I_over_I_G", the rod's central inertia changed) for `car`
///                  and `marine` at their speeds
TableSet calcRodModelTables(const Mechanism& car, const Mechanism& marine);

///   pin_load_polar          scene_index,engine,phi_deg,crank_pin_radial,crank_pin_tangential,bearing_x,bearing_y,scene
///                           over one working cycle (step_deg steps) at the scene's speed, with its gas and gravity:
///                           the crank-pin force (crank on rod 0 at its crank pin) in the crank's own frame (radial:
///                           outward along the throw of cylinder 0, tangential: 90 degrees ahead of it, the direction
///                           of rotation), and the main-bearing force (frame on the crankshaft at O, all throws) in the
///                           frame's X, Y: Norton's polar diagrams (Program ENGINE), the closed forms and each reference engine [N]
///   pin_load_polar_summary  scene,engine,force,max_magnitude,phi_deg_at_max,max_difference_rel
///                           the largest |force| over the cycle (refined, extremum.h) of each engine, and the largest
///                           |analytic - engine| over the samples relative to the force scale (the analytic row: the largest
///                           over the reference engines)
/// scene_index counts from first_index (so that scenes computed one per task keep their places); step_deg is the
/// sampling step (the campaign: 2 degrees, 4 with --quick; the maxima are refined, so they do not depend on it).
TableSet calcPinLoadTables(const std::vector<Mechanism>& scenes, int first_index = 0, double step_deg = 2.0);

}  // namespace crankcheck::validation
