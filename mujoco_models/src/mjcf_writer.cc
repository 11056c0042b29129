// The MJCF writer (mjcf_writer.h): calcMjcf and the soft crank train's calcTrainMjcf. Includes MuJoCo for its
// compiler's limits only (mjMINVAL): what MuJoCo would refuse is refused first, by the scene key.
#include "mjcf_writer.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "crankcheck/scene/scene_file.h"

namespace crankcheck::mujoco_models {

std::string num(double x) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  return std::string(buffer, result.ptr);
}

namespace {

std::string vec3(double x, double y, double z) { return num(x) + " " + num(y) + " " + num(z); }

struct PointMass {
  double mass;
  std::array<double, 3> p;
};

/// The crankshaft's point masses (per cylinder: m_s at r_s on its throw, m_p at r_p opposite, in the plane z_j), of
/// the cylinders listed (every cylinder when none are).
std::vector<PointMass> crankPointMasses(const Mechanism& m, std::vector<int> cylinders = {}) {
  if (cylinders.empty())
    for (int j = 0; j < m.machine.cylinders; ++j) cylinders.push_back(j);
  std::vector<PointMass> points;
  for (int j : cylinders) {
    const double beta = getThrowAngle(m, j);
    const double z = getAxialPosition(m, j);
    const double c = std::cos(beta), s = std::sin(beta);
    if (m.crank.mass > 0.0) points.push_back({m.crank.mass, {m.crank.com_radius * c, m.crank.com_radius * s, z}});
    if (m.crank.counterweight_mass > 0.0)
      points.push_back({m.crank.counterweight_mass, {-m.crank.counterweight_radius * c, -m.crank.counterweight_radius * s, z}});
  }
  return points;
}

/// What MuJoCo would refuse, checked first so that the message names the scene key (MuJoCo's compiler rejects a
/// body on a joint whose mass or any principal inertia is below mjMINVAL = 1e-15).
void checkBuildable(const Mechanism& m) {
  try {
    validateMechanism(m, m.name.empty() ? std::string("mechanism") : m.name);
  } catch (const SceneError& error) {
    throw std::invalid_argument(std::string("invalid mechanism: ") + error.what());
  }
  if (!(m.piston.mass >= mjMINVAL))
    throw std::invalid_argument("piston.mass: MuJoCo cannot build a piston lighter than 1e-15 kg (its bodies on "
                                "joints need mass > mjMINVAL); the mujoco engines need m_o > 0");
  if (!(m.rod.mass >= mjMINVAL))
    throw std::invalid_argument("rod.mass: MuJoCo cannot build a rod lighter than 1e-15 kg; the mujoco engines need "
                                "m_k > 0");
  const double rod_inertia_about_com = m.rod.inertia_about_wrist_pin - m.rod.mass * m.rod.com_from_wrist_pin * m.rod.com_from_wrist_pin;
  if (!(rod_inertia_about_com >= mjMINVAL))
    throw std::invalid_argument("rod.inertia_about_wrist_pin: MuJoCo needs the rod's inertia about its centre of mass, "
                                "I_o - m_k z_k^2 = " + num(rod_inertia_about_com) + " kg m^2, above 1e-15 kg m^2 (a "
                                "point-mass rod cannot be built)");
  for (size_t i = 0; i < m.balance_shafts.size(); ++i)
    if (!(m.balance_shafts[i].mass >= mjMINVAL))
      throw std::invalid_argument("balance_shaft[" + std::to_string(i) + "].mass: MuJoCo cannot build a body lighter "
                                  "than 1e-15 kg");
  double crank_mass = 0.0;
  for (const PointMass& p : crankPointMasses(m)) crank_mass += p.mass;
  if (!(crank_mass >= mjMINVAL))
    throw std::invalid_argument("crank.mass: MuJoCo cannot build a crankshaft without mass (crank.mass and "
                                "crank.counterweight_mass are both 0; a body on a joint needs mass > 1e-15 kg)");
  // The crank body's rotor inertia (calcMjcf): the flywheel's, or a nominal m r^2 without one.
  if (m.flywheel_inertia && !(*m.flywheel_inertia >= mjMINVAL))
    throw std::invalid_argument("flywheel.inertia: MuJoCo cannot build a crankshaft whose inertia is below 1e-15 kg m^2 "
                                "(a body on a joint needs every principal inertia > mjMINVAL); got " + num(*m.flywheel_inertia));
  if (!m.flywheel_inertia && !(crank_mass * m.crank.radius * m.crank.radius >= mjMINVAL))
    throw std::invalid_argument("crank.radius: MuJoCo cannot build a crankshaft whose inertia m r^2 is below 1e-15 kg m^2 "
                                "without a [flywheel] (give [flywheel].inertia)");
}

/// The model's head: compiler, options (gravity, contacts off, the constraint solver off for kExact), the constraint
/// rows (`rows`), the soft variants' equality defaults; then <worldbody> opens.
std::string writeMjcfHead(const Mechanism& m, Variant variant, int rows) {
  std::string x;
  x += "<mujoco model=\"crankcheck\">\n";
  // Inertias exactly as written: none from geometry, no lower bounds, no rebalancing.
  x += "  <compiler angle=\"radian\" inertiafromgeom=\"false\" boundmass=\"0\" boundinertia=\"0\" "
       "balanceinertia=\"false\" settotalmass=\"-1\"/>\n";
  x += "  <option gravity=\"" + vec3(0.0, -m.machine.gravity, 0.0) + "\" timestep=\"0.002\">\n";
  // energy: mj_energyPos computes the potential only when enabled
  x += std::string("    <flag contact=\"disable\" energy=\"enable\"") +
       (variant == Variant::kExact ? " constraint=\"disable\"" : "") + "/>\n";
  x += "  </option>\n";
  // MuJoCo's defaults (njmax 500, a stack of 1.25e6 doubles: 10 MB per mjData, zeroed at every build) cost more than
  // the whole evaluation. A full row table is checked after every solve (mjWARN_CNSTRFULL).
  x += "  <size njmax=\"" + std::to_string(rows) + "\" nconmax=\"1\"/>\n";
  if (variant == Variant::kSoftStiff) {
    // The stiffest the solver accepts: impedance at its ceiling mjMAXIMP = 0.9999, time constant at the refsafe
    // floor of twice the time step.
    x += "  <default>\n    <equality solref=\"0.004 1\" solimp=\"0.9999 0.9999 0.001 0.5 2\"/>\n  </default>\n";
  }
  x += "  <worldbody>\n";
  return x;
}

/// A crankshaft body `name` on a hinge about +Z at O (`joint`: the hinge's extra attributes) carrying the point masses
/// and crank-pin sites (crank_pin<j>) of `cylinders` (all when empty) and the isotropic rotor inertia `rotor` [kg m^2];
/// `inner`: its child bodies. Indented by `indent`.
std::string writeCrankBody(const Mechanism& m, const std::string& name, const std::vector<int>& cylinders, double rotor,
                           const std::string& joint, const std::string& inner, const std::string& indent) {
  // The first point mass is the body's own inertial, with the rotor as an isotropic inertia about it (only I_zz ever
  // acts, w x I w = 0 for an isotropic tensor); every other point mass is a jointless child body with zero inertia. No
  // full inertia tensor: MuJoCo would diagonalize it, and its eigen-solver's rounding (1e-12 of the products of
  // inertia) showed in the V8's shaking moment.
  const std::vector<PointMass> points = crankPointMasses(m, cylinders);
  const double r = m.crank.radius;
  std::string x;
  x += indent + "<body name=\"" + name + "\" pos=\"0 0 0\">\n";
  x += indent + "  <joint name=\"" + name + "\" type=\"hinge\" axis=\"0 0 1\" pos=\"0 0 0\"" + joint + "/>\n";
  x += indent + "  <inertial pos=\"" + vec3(points[0].p[0], points[0].p[1], points[0].p[2]) + "\" mass=\"" +
       num(points[0].mass) + "\" diaginertia=\"" + vec3(rotor, rotor, rotor) + "\"/>\n";
  for (size_t i = 1; i < points.size(); ++i)
    x += indent + "  <body name=\"" + name + "_mass" + std::to_string(i) + "\" pos=\"" +
         vec3(points[i].p[0], points[i].p[1], points[i].p[2]) + "\"><inertial pos=\"0 0 0\" mass=\"" +
         num(points[i].mass) + "\" diaginertia=\"0 0 0\"/></body>\n";
  for (int j = 0; j < m.machine.cylinders; ++j) {
    if (!cylinders.empty() && std::find(cylinders.begin(), cylinders.end(), j) == cylinders.end()) continue;
    const double beta = getThrowAngle(m, j);
    x += indent + "  <site name=\"crank_pin" + std::to_string(j) + "\" pos=\"" +
         vec3(r * std::cos(beta), r * std::sin(beta), getAxialPosition(m, j)) + "\"/>\n";
  }
  x += inner;
  x += indent + "</body>\n";
  return x;
}

/// Piston j on a slide along e_j (origin on the crank axis at z_j, moved by the pin offset delta_j along n_j: the slide
/// coordinate is x_p), its rod on a hinge at the wrist pin pointing along -e_j at hinge angle 0.
std::string writeCylinder(const Mechanism& m, int j) {
  const double l = m.rod.length, r = m.crank.radius;
  const double piston_nominal_inertia = m.piston.mass * r * r;
  const double rod_inertia = m.rod.inertia_about_wrist_pin - m.rod.mass * m.rod.com_from_wrist_pin * m.rod.com_from_wrist_pin;
  const std::string J = std::to_string(j);
  const double gamma = getBankAngle(m, j);
  const double ex = std::cos(gamma), ey = std::sin(gamma);
  const double delta = getPinOffset(m, j);  // the wrist pin on x_p e_j + delta n_j
  std::string x;
  x += "    <body name=\"piston" + J + "\" pos=\"" + vec3(-delta * ey, delta * ex, getAxialPosition(m, j)) + "\">\n";
  x += "      <joint name=\"slide" + J + "\" type=\"slide\" axis=\"" + vec3(ex, ey, 0.0) + "\" pos=\"0 0 0\"/>\n";
  x += "      <inertial pos=\"0 0 0\" mass=\"" + num(m.piston.mass) + "\" diaginertia=\"" +
       vec3(piston_nominal_inertia, piston_nominal_inertia, piston_nominal_inertia) + "\"/>\n";
  x += "      <body name=\"rod" + J + "\" pos=\"0 0 0\">\n";
  x += "        <joint name=\"wrist" + J + "\" type=\"hinge\" axis=\"0 0 1\" pos=\"0 0 0\"/>\n";
  x += "        <inertial pos=\"" + vec3(-m.rod.com_from_wrist_pin * ex, -m.rod.com_from_wrist_pin * ey, 0.0) +
       "\" mass=\"" + num(m.rod.mass) + "\" diaginertia=\"" + vec3(rod_inertia, rod_inertia, rod_inertia) + "\"/>\n";
  x += "        <site name=\"big_end" + J + "\" pos=\"" + vec3(-l * ex, -l * ey, 0.0) + "\"/>\n";
  x += "      </body>\n";
  x += "    </body>\n";
  return x;
}

/// The loop of cylinder j: a `connect` between rod j's big end and the crank pin on body `crank` (the anchor on the
/// crank is set after compiling: setCrankPinAnchors).
std::string writeLoop(const Mechanism& m, int j, const std::string& crank) {
  const double l = m.rod.length, gamma = getBankAngle(m, j);
  return "    <connect name=\"loop" + std::to_string(j) + "\" body1=\"rod" + std::to_string(j) + "\" body2=\"" + crank +
         "\" anchor=\"" + vec3(-l * std::cos(gamma), -l * std::sin(gamma), 0.0) + "\"/>\n";
}

}  // namespace

std::string calcMjcf(const Mechanism& m, Variant variant) {
  checkBuildable(m);
  const int k = m.machine.cylinders;
  const double r = m.crank.radius;
  // The constraint rows this model can have: 3 per connect (the loops), 1 per joint equality (the shafts' gears),
  // a few to spare; no contacts.
  std::string x = writeMjcfHead(m, variant, 3 * k + static_cast<int>(m.balance_shafts.size()) + 8);
  // Crankshaft: the flywheel I_w as its rotor (a nominal m r^2 without a flywheel: it never acts at a prescribed
  // constant speed).
  double mass = 0.0;
  for (const PointMass& p : crankPointMasses(m)) mass += p.mass;
  x += writeCrankBody(m, "crank", {}, m.flywheel_inertia.value_or(mass * r * r), "", "", "    ");
  for (int j = 0; j < k; ++j) x += writeCylinder(m, j);
  // Balance shafts: a body on a hinge about Z through (x, y, z), its eccentric point mass at rho along the body's x
  // axis (at the hinge angle from +X), with a nominal isotropic inertia 1e-9 m rho^2 (MuJoCo needs one; at a constant
  // shaft speed an isotropic inertia never acts). The exact way couples it to the crank itself (hinge angle = ratio
  // phi + phase); the soft ways by a joint equality.
  for (size_t i = 0; i < m.balance_shafts.size(); ++i) {
    const BalanceShaftParams& b = m.balance_shafts[i];
    const std::string I = std::to_string(i);
    const double nominal = std::max(1e-9 * b.mass * b.radius * b.radius, 1e-15);
    x += "    <body name=\"shaft" + I + "\" pos=\"" + vec3(b.position[0], b.position[1], b.position[2]) + "\">\n";
    x += "      <joint name=\"shaft" + I + "\" type=\"hinge\" axis=\"0 0 1\" pos=\"0 0 0\"/>\n";
    x += "      <inertial pos=\"" + vec3(b.radius, 0.0, 0.0) + "\" mass=\"" + num(b.mass) + "\" diaginertia=\"" +
         vec3(nominal, nominal, nominal) + "\"/>\n";
    x += "    </body>\n";
  }
  x += "  </worldbody>\n";
  x += "  <equality>\n";
  for (size_t i = 0; i < m.balance_shafts.size(); ++i)  // shaft = phase + ratio crank
    x += "    <joint name=\"gear" + std::to_string(i) + "\" joint1=\"shaft" + std::to_string(i) + "\" joint2=\"crank\" polycoef=\"" +
         num(m.balance_shafts[i].phase) + " " + num(m.balance_shafts[i].ratio) + " 0 0 0\"/>\n";
  for (int j = 0; j < k; ++j) x += writeLoop(m, j, "crank");
  x += "  </equality>\n";
  x += "</mujoco>\n";
  return x;
}

std::string calcTrainMjcf(const Mechanism& m, Variant variant, double flywheel_inertia) {
  const CrankshaftParams& c = *m.crankshaft;
  const std::vector<std::vector<int>> throws = findThrows(m);
  const int front = c.front_inertia > 0.0 ? 1 : 0;
  auto section = [&](int b) {  // body b's hinge to body b + 1: section b
    return " stiffness=\"" + num(c.stiffness[static_cast<size_t>(b)]) + "\" damping=\"" + num(getSectionDamping(c, b)) + "\"";
  };
  std::string inner;
  if (front)  // a disk of J_F with a unit mass on the axis (MuJoCo needs a mass; on the axis it has no torque)
    inner = "    <body name=\"front\" pos=\"0 0 0\">\n      <joint name=\"front\" type=\"hinge\" axis=\"0 0 1\" "
            "pos=\"0 0 0\"" + section(0) + "/>\n      <inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"" +
            vec3(c.front_inertia, c.front_inertia, c.front_inertia) + "\"/>\n" + inner + "    </body>\n";
  for (size_t j = 0; j < throws.size(); ++j)
    inner = writeCrankBody(m, "throw" + std::to_string(j), throws[j], c.throw_inertia,
                           section(static_cast<int>(j) + front), inner, "    ");
  std::string x = writeMjcfHead(m, variant, 3 * m.machine.cylinders + 8);
  x += "    <body name=\"flywheel\" pos=\"0 0 0\">\n      <joint name=\"flywheel\" type=\"hinge\" axis=\"0 0 1\" "
       "pos=\"0 0 0\"/>\n      <inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"" +
       vec3(flywheel_inertia, flywheel_inertia, flywheel_inertia) + "\"/>\n" + inner + "    </body>\n";
  for (int j = 0; j < m.machine.cylinders; ++j) x += writeCylinder(m, j);
  x += "  </worldbody>\n  <equality>\n";
  for (size_t j = 0; j < throws.size(); ++j)
    for (int cylinder : throws[j]) x += writeLoop(m, cylinder, "throw" + std::to_string(j));
  x += "  </equality>\n";
  if (c.throw_damping > 0.0) {
    x += "  <tendon>\n";
    for (size_t j = 0; j < throws.size(); ++j) {
      x += "    <fixed name=\"bearing" + std::to_string(j) + "\" damping=\"" + num(c.throw_damping) + "\">";
      for (size_t i = j; i < throws.size(); ++i) x += "<joint joint=\"throw" + std::to_string(i) + "\" coef=\"1\"/>";
      x += "</fixed>\n";
    }
    x += "  </tendon>\n";
  }
  x += "</mujoco>\n";
  return x;
}

}  // namespace crankcheck::mujoco_models
