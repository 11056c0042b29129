#pragma once
/// @file
/// The elastic crank train of a scene's `[crankshaft]` in MuJoCo (docs/CONVENTIONS-crankcheck.md, "Torsion"), never using
/// the analytic formulas nor Simbody. Bodies along the shaft, front first: the front mass F (when front_inertia > 0),
/// the throws 0 .. n-1 (findThrows), the flywheel W driven at psi_W = omega t (the scene's speed). Deviations
/// x_i = psi_i - omega t, t = 0 at the rigid reference; section i's twist x_{i+1} - x_i, the last one -x_{n-1}
/// (CrankTrainRun, solver/crank_train_run.h). No MuJoCo header here: MuJoCo stays in src/.
///
/// Exact route (simulateCrankTrainSteadyState, engine "mujoco", gated): each throw j is a KCrankMujocoModel (kExact)
/// of selectThrow(m, j); at the throw's state (psi_j, psi_j') MuJoCo gives its reduced inertia J_j(psi_j) and the rest
/// of the crank torque (velocity terms, gravity, the gas at the throw's own angle) from its own kinematics, mass matrix
/// and inverse dynamics (KCrankMujocoModel::calcCrankTorqueLine). The train's equations (CONVENTIONS' exact ones) in
/// s = omega t, y = (x, dx/ds):
///   (J_t + J_j) omega^2 x_j'' = elastic_j - c_t omega x_j' - rest_j(psi_j, omega (1 + x_j')),  psi_j = s + x_j,
///   J_F omega^2 x_F'' = elastic_F,  elastic = sum over the body's sections of K_s (x_b - x_a) + C_s omega (x_b' - x_a')
///   on a, the opposite on b (x_W = 0), integrated by Boost.Odeint's Dormand-Prince 5(4) (error per step below
/// `accuracy` relative and `accuracy` x the deviation scale absolute: the largest |x| of the cycle before, the first
/// cycle's from the rigid motion's torques over the softest section), every probe and sample an integrated state.
/// Run to periodic by every engine's one policy (crankcheck/solver/periodic_run.h, as Simbody's): from the rigid motion
/// (x = 0, x' = 0 at t = 0), cycle by cycle, at 1000 x `accuracy` until the deviations and their rates (x' = dx/ds) at
/// the start of a cycle change by less than 1000 x `periodicity` of the largest deviation over that cycle (64 probes),
/// then at `accuracy` until they change by less than `periodicity`, the run moved to the extrapolated fixed point of
/// its last cycle starts (x, x') from the 4th cycle at one accuracy on; then one more cycle sampled at `samples` equal
/// steps.
/// Each cycle runs in its own time from 0 (the equations repeat every cycle), so no angle grows with the run.
/// Measured (tests/gate/torsion_test.cc, defaults): the example four at 6000 rpm 9 cycles, 1.6 s (a throw's torque
/// line about 2 us; 16 cycles, 2.5 s without the extrapolation); the marine six at 105 rpm 13 cycles, 1.4 s (66 and
/// 6.8 s: its 2 %-damped first mode); every
/// sample of every twist within 2e-8 of the twist scale of the analytic engine's exact steady state.

#include "crankcheck/mujoco_models/k_crank_mujoco_model.h"
#include "crankcheck/solver/crank_train_run.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::mujoco_models {

/// MuJoCo's defaults of CrankTrainRunOptions' fields left at 0 (Simbody's: the two routes are held to one gate).
inline constexpr double kCrankTrainAccuracy = 1e-10;     ///< the integrator's error per step, relative
inline constexpr double kCrankTrainPeriodicity = 1e-6;   ///< the cycle-to-cycle change, relative to the deviations

/// The exact route's periodic steady state (see the file comment). Options at 0: the defaults above, and
/// CrankTrainRunOptions{}'s samples (1024) and max_cycles (2000).
/// @throws std::invalid_argument if the scene has no [crankshaft] ("[crankshaft]: ..."), a speed <= 0
///         ("[engine].speed_rpm: ..."), is not a valid mechanism or one MuJoCo builds (KCrankMujocoModel, the message
///         names the key), or the options are bad (accuracy or periodicity < 0 or not finite, samples odd or below 16,
///         max_cycles < 0).
/// @throws std::runtime_error if the run has not become periodic in max_cycles cycles, or the integrator's step
///         collapses (a train that runs away).
CrankTrainRun simulateCrankTrainSteadyState(const Mechanism& m, const CrankTrainRunOptions& options = {});

/// The soft route's default time step, as a fraction of a cycle (accuracy in its sense).
inline constexpr double kSoftCrankTrainStep = 1.0 / 4096;

/// The soft route (engines "mujoco-soft" and "mujoco-soft-stiff", reported, not gated): the train as MuJoCo's users build it. One MJCF: the
/// flywheel W a body on a hinge from the world; inside it throw n-1 on a hinge relative to W, inside that throw n-2
/// relative to throw n-1, ..., the front mass innermost: each hinge's MuJoCo joint stiffness and damping are the
/// section's K_s and C_s (hinge angle psi_b - psi_a = minus the twist); each throw body carries its cylinders' crank
/// point masses and pins (calcMjcf's construction) and J_t as its rotor; the pistons and rods on the world, their loops
/// MuJoCo's soft `connect` equalities (kSoftDefault: its default solref/solimp; kSoftStiff: solimp 0.9999 and solref
/// at its floor of two steps); each throw's damping c_t a fixed tendon over the
/// hinges from W to it (its rate psi_j' - omega) with MuJoCo's tendon damping; gravity MuJoCo's; the gas a force on
/// each slide written by MuJoCo's control callback (mjcb_control) at every stage of a step from the throw's angle.
/// W is driven: its inertia 1e9 x the train's (J_F + n J_t), so its speed hardly moves within a step, and its angle and
/// speed are set back to (omega t, omega) after every step. Stepped by mj_step with MuJoCo's RK4 at a fixed step:
/// `accuracy` is that step as a fraction of a cycle (default 1/4096; the cycle a whole number of steps, a multiple of
/// the samples' and the 64 probes' spacing); run to periodic as the exact route, without its loose start (the step is
/// fixed: the cycle-to-cycle change falls to rounding on MuJoCo's own discrete map), its extrapolation over the chain's
/// whole state (every joint's position and speed but the flywheel's: the loops' give is state of its own).
/// Measured against the exact route (the example four at 6000 rpm, the default step 1/4096): kSoftDefault differs by
/// 0.85 of the largest twist (its loops, time constant 0.02 s, a whole cycle, give way; 13 cycles at periodicity 1e-4,
/// 23 without the extrapolation), kSoftStiff by 3.3e-4 (7 cycles, 11 without; 1.3e-3 at 1/2048: it falls as the step
/// squared, its time constant two steps);
/// tests/mujoco/crank_train_test.cc holds both.
/// @throws as simulateCrankTrainSteadyState; also std::invalid_argument for the exact variant, an accuracy above 0.01
///         (100 steps a cycle) or J_t below 1e-15 kg m^2. One run at a time per thread (the gas callback's context).
CrankTrainRun simulateCrankTrainSoft(const Mechanism& m, Variant variant, const CrankTrainRunOptions& options = {});

}  // namespace crankcheck::mujoco_models
