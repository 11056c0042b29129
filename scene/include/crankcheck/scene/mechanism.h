#pragma once
/// @file
/// The plain description of a k-crank mechanism that every engine is built from: an inline
/// engine (one bank, the paper's and Norton's subject) or any layout of cylinders around one crankshaft (V, W,
/// opposed, radial; cylinders spaced along the shaft), docs/CONVENTIONS.md "Layouts".
/// Symbols, frames and signs follow docs/CONVENTIONS.md and docs/CONVENTIONS-crankcheck.md.
/// Everything here is in SI units (m, kg, s, rad); degrees exist only in scene files and CLI flags.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "crankcheck/scene/gas.h"

namespace crankcheck {

/// Working cycle: sets the cycle period T of eq (8): 2 pi (two-stroke) or 4 pi (four-stroke).
enum class Cycle { kTwoStroke, kFourStroke };

/// Single- or double-acting cylinders: double-acting halves the phase angle (eqs 9, 10).
enum class Acting { kSingle, kDouble };

/// The machine as a whole: its cylinders, their layout, its speed and gravity (an engine or a compressor: the scene
/// file's [engine] table; in code "engine" means a solver of engine.h).
struct MachineParams {
  int cylinders = 1;                         ///< k, number of cylinders (= crank throws), >= 1
  Cycle cycle = Cycle::kFourStroke;
  Acting acting = Acting::kSingle;
  /// alpha_j [rad], j = 0..k-1: crank angle of cylinder j measured from its own outer dead centre when
  /// cylinder 0 is at phi = 0, so theta_j = phi + alpha_j. Inline: the phase angles of eqs (8)-(11) (see
  /// calcPhaseAngles) or the scene's explicit crank_angles_deg. Layout ([[cylinder]]): alpha_j = beta_j - gamma_j,
  /// the throw angle minus the bank angle.
  std::vector<double> crank_angles;
  bool explicit_crank_angles = false;        ///< true when crank_angles came from the scene, not eqs (8)-(11)
  double cylinder_angle = 0.0;               ///< gamma [rad], cylinder axis above the horizontal (layout: gamma_0)
  /// gamma_j [rad] per cylinder, the direction of its axis from +X (CCW). Empty: one bank, every cylinder at
  /// cylinder_angle. Read it through getBankAngle.
  std::vector<double> bank_angles;
  /// z_j [m] per cylinder along the crankshaft (+Z). Empty: every cylinder in the plane z = 0 (the planar model:
  /// the shaking moment's X and Y parts are then not defined). Read it through getAxialPosition.
  std::vector<double> axial_positions;
  /// delta_j [m] per cylinder: the piston-pin (desaxe) offset, signed along n_j (e_j turned +90 degrees): the wrist
  /// pin moves on the line A_j = x_p e_j + delta_j n_j, x_p its coordinate along e_j (docs/CONVENTIONS-crankcheck.md,
  /// "Pin offset"). |delta_j| < l - r. Empty: every cylinder centric. Read it through getPinOffset.
  std::vector<double> pin_offsets;
  double speed = 0.0;                        ///< omega [rad/s], constant crank speed (0 = static)
  double gravity = 9.80665;                  ///< g [m/s^2], acting along -Y
};

/// One crank throw (identical for every cylinder).
struct CrankParams {
  double radius = 0.0;                       ///< r [m]
  double mass = 0.0;                         ///< m_s [kg], a point on the crank line at com_radius
  double com_radius = 0.0;                   ///< r_s [m]
  double counterweight_mass = 0.0;           ///< m_p [kg], a point opposite the crank pin
  double counterweight_radius = 0.0;         ///< r_p [m]
};

/// Connecting rod, a rigid body with its true inertia.
struct RodParams {
  double length = 0.0;                       ///< l [m], wrist pin to crank pin
  double mass = 0.0;                         ///< m_k [kg]
  double com_from_wrist_pin = 0.0;           ///< z_k [m], on the rod axis, measured from the wrist pin
  double inertia_about_wrist_pin = 0.0;      ///< I_o [kg m^2], about the wrist pin axis (>= m_k z_k^2)
};

/// Piston: a particle at the wrist pin.
struct PistonParams {
  double mass = 0.0;                         ///< m_o [kg]
};

/// A balance shaft: an eccentric point mass on a shaft parallel to Z, geared to the crankshaft (an ideal coupling:
/// a torque between the two shafts, no force on the crank's main bearing). Gravity acts on it; the crankshaft drives
/// it, so the drive torque includes it.
struct BalanceShaftParams {
  double ratio = 0.0;     ///< shaft turns per crank turn, signed (2 and -2: a Lanchester pair; -1: a primary balancer)
  double mass = 0.0;      ///< [kg] the eccentric point mass, > 0
  double radius = 0.0;    ///< [m] its distance from the shaft's axis, > 0
  double phase = 0.0;     ///< [rad] its angle from +X at phi = 0: at crank angle phi it is at ratio phi + phase
  std::array<double, 3> position{};  ///< [m] (x, y): the shaft's axis (parallel to Z); z: the mass's plane
};

/// The elastic crank train of a `[crankshaft]` table (docs/CONVENTIONS.md, "The elastic crank train"): bodies along the shaft
/// front mass F (when front_inertia > 0), throws 0..n-1 (findThrows), flywheel W (driven at omega t). Only the torsion
/// analysis reads it; every other command treats the shaft as rigid.
struct CrankshaftParams {
  double throw_inertia = 0.0;   ///< J_t [kg m^2] >= 0, each throw's own inertia beyond [crank]'s point masses
  double front_inertia = 0.0;   ///< [kg m^2] >= 0, the pulley / damper hub; 0: no front mass
  /// K_s [N m/rad] > 0 per section, front to flywheel: n + 1 values with a front mass, n without (n throws).
  std::vector<double> stiffness;
  /// C_s [N m s/rad] >= 0, relative damping of the sections: one value for all, or one per section (as given).
  std::vector<double> section_damping{0.0};
  double throw_damping = 0.0;   ///< c_t [N m s/rad] >= 0, each throw's absolute damping about omega t
};

/// A complete scene: the mechanism plus what a scene file may add (a name, the flywheel inertia).
struct Mechanism {
  std::string name;                          ///< for reports; the scene file's stem
  MachineParams machine;                     ///< the machine as a whole (the TOML table [engine])
  CrankParams crank;
  RodParams rod;
  PistonParams piston;
  std::optional<double> flywheel_inertia;    ///< I_w [kg m^2], only for dimensionless output
  std::optional<GasParams> gas;              ///< the scene's [gas] table; none: no gas force
  /// firing_j [rad] per cylinder (with gas): the crank angle phi at which cylinder j is at its firing outer dead
  /// centre, in [0, cycle). The pressure on piston j is calcGasPressure(gas, phi - firing_j).
  std::vector<double> firing_angles;
  std::vector<BalanceShaftParams> balance_shafts;  ///< the scene's [[balance_shaft]] tables; none: no shafts
  std::optional<CrankshaftParams> crankshaft;  ///< the scene's [crankshaft] table; none: the shaft is rigid
  double speed_rpm = 0.0;                    ///< the scene's speed as given, for display
};

/// lambda = r / l, the crank ratio.
double calcCrankRatio(const Mechanism& m);

/// gamma_j [rad], the bank angle of cylinder j: bank_angles[j], or cylinder_angle for one bank.
double getBankAngle(const Mechanism& m, int j);
/// beta_j = gamma_j + alpha_j [rad], the angle of cylinder j's crank pin on the shaft (at phi = 0, from +X).
double getThrowAngle(const Mechanism& m, int j);
/// z_j [m], the axial position of cylinder j: axial_positions[j], or 0 when the scene gives none.
double getAxialPosition(const Mechanism& m, int j);
/// True when every cylinder lies in one bank (gamma_j = cylinder_angle for all j): the inline engine the
/// paper's series (eqs 14-18) and the reduced and free-run Simbody models are written for.
bool isSingleBank(const Mechanism& m);
/// delta_j [m], the pin offset of cylinder j: pin_offsets[j], or 0 when the scene gives none.
double getPinOffset(const Mechanism& m, int j);
/// The crank throws (crank pins) along the shaft, front first, each listing the cylinders on that pin. The cylinders
/// are taken in the order of their axial positions z_j (the scene's order where equal or not given: a stable sort);
/// a cylinder shares the pin of the throw before it when its throw angle beta equals that throw's (within 1e-9 rad,
/// modulo a turn) and its bank angle differs from those of every cylinder already on it (a V pair, a 180-degree V, a
/// radial star); otherwise it starts the next throw. So every cylinder of one bank has its own throw (an inline four:
/// four), and a V8 has four whether its scene lists the cylinders bank by bank (with axial positions) or pin by pin.
/// The front is at the smallest z (next to the front mass), the flywheel beyond the largest.
std::vector<std::vector<int>> findThrows(const Mechanism& m);
/// The cylinders of throw `throw_index` (findThrows) as a mechanism of their own: their crank angles (explicit), banks,
/// axial positions, pin offsets and firing angles, the same parts and speed; without flywheel, balance shafts or
/// [crankshaft]. Each engine builds a throw of the elastic crank train from it (CONVENTIONS "Torsion").
/// @throws std::out_of_range if there is no such throw.
Mechanism selectThrow(const Mechanism& m, int throw_index);
/// The number of sections of the crank train: throws + 1 with a front mass, throws without.
int countShaftSections(const Mechanism& m);
/// C_s [N m s/rad] of section i (0 = the front one): the one value given for all, or the i-th.
double getSectionDamping(const CrankshaftParams& c, int i);
/// True when some cylinder's pin is offset (delta_j != 0).
bool hasPinOffsets(const Mechanism& m);
/// True when the scene placed the cylinders along the shaft (axial_position or cylinder_spacing).
bool hasAxialPositions(const Mechanism& m);
/// The same mechanism with only some of its loads (for the split of the drive torque into its parts): without gas
/// the [gas] table is dropped, without inertia the speed is 0, without gravity g is 0.
Mechanism withLoads(const Mechanism& m, bool gas, bool inertia, bool gravity);

/// [N] the gas force p A on piston j at crank angle phi [rad], positive toward the crank; 0 without gas.
double calcGasForce(const Mechanism& m, int j, double phi);

/// Phase angles alpha_j = (T / k) j of eqs (8)-(11), j = 0..k-1, in radians, each reduced to [0, 2 pi).
/// T = 2 pi (two-stroke) or 4 pi (four-stroke); double-acting halves T / k. Angles that are exact multiples
/// of 90 degrees come out as the same doubles radiansFromDegrees gives them (exact quarter turns).
/// @throws std::invalid_argument if cylinders < 1.
std::vector<double> calcPhaseAngles(int cylinders, Cycle cycle, Acting acting);

/// Phase angles as fractions of a turn: alpha_j / (2 pi) = numerators[j] / denominator, exactly.
/// Used where an exact (integer) answer is needed, e.g. which harmonics survive the sum over throws.
struct PhaseTurns {
  std::vector<long long> numerators;
  long long denominator = 1;
};
/// @throws std::invalid_argument if cylinders < 1.
PhaseTurns calcPhaseTurns(int cylinders, Cycle cycle, Acting acting);

/// Degrees to radians at the user's edge. Exact multiples of 90 degrees map to n * (pi/2) computed as
/// n * M_PI_2, so that downstream trigonometry can recognise quarter turns exactly.
double radiansFromDegrees(double degrees);
double degreesFromRadians(double radians);

/// [rad] The crank angle phi [rad] brought into [-4 pi, 4 pi], to rounding, for any finite phi: every quantity
/// repeats after 4 pi (a four-stroke cycle; a two-stroke's 2 pi divides it), and the engines keep their promised
/// accuracy only for angles of that size (phi + gamma_j and Simbody's q lose ulp(phi): at 1e17 deg the fourth digit).
/// |phi| <= 4 pi is returned as it is, bit for bit. Beyond, phi / 2 is exact and glibc's sin and cos reduce any
/// double exactly (Payne-Hanek), so 2 atan2(sin(phi / 2), cos(phi / 2)), in (-2 pi, 2 pi], is within about 1e-15 rad
/// of phi modulo 4 pi: the rounding of an angle of a turn or two. NaN and infinities are returned as they are.
double reduceCrankAngle(double phi);
/// [rad] A crank angle typed in degrees, reduced exactly: beyond 720 degrees in magnitude, fmod(degrees, 720) (exact
/// for every finite double) first, then radiansFromDegrees. So `--phi-deg 1e18` is the angle 640 degrees, as it is.
double crankAngleFromDegrees(double degrees);

std::string toString(Cycle cycle);   ///< "two-stroke" | "four-stroke"
std::string toString(Acting acting); ///< "single" | "double"

}  // namespace crankcheck
