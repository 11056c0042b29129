// The k-crank mechanism in MuJoCo (Debian libmujoco-dev 2.2.2). The only translation unit of the library that
// includes MuJoCo. Never includes the analytic library or Simbody: MuJoCo computes the kinematics (mj_kinematics,
// mj_jacSite, mj_objectAcceleration), the bias forces (mj_rne) and the joint reactions (mj_rnePostConstraint).
// mujoco_models/README.md lists the traps this file avoids.
#include "crankcheck/mujoco_models/k_crank_mujoco_model.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "crankcheck/mujoco_models/crank_train.h"
#include "crankcheck/scene/scene_file.h"
#include "crank_train_run.h"

namespace crankcheck::mujoco_models {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr int kMaxNewtonIterations = 100;
constexpr const char* kFileName = "crankcheck.xml";

// MuJoCo reports errors through a handler that must not return; the default one prints and calls exit(1), and
// writes MUJOCO_LOG.TXT into the working directory. crankcheck checks every input MuJoCo would refuse before it
// builds a model, so an error here is MuJoCo's own failure: one line and exit status 3 (internal failure), no log
// file in the user's folder. Warnings (e.g. a non-finite acceleration, after which MuJoCo resets its data) are not
// printed (they would corrupt --format json on stdout): every result is checked for finiteness instead.
[[noreturn]] void onMujocoError(const char* message) {
  std::fprintf(stderr, "crankcheck: MuJoCo failed: %s\n", message);
  std::fflush(stderr);
  std::_Exit(3);
}
void onMujocoWarning(const char*) {}
void installHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_error = onMujocoError;
    mju_user_warning = onMujocoWarning;
  });
}

/// The shortest text that reads back as the same double (MJCF is parsed with strtod-like rules).
std::string num(double x) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  return std::string(buffer, result.ptr);
}
std::string vec3(double x, double y, double z) { return num(x) + " " + num(y) + " " + num(z); }

struct PointMass {
  double mass;
  std::array<double, 3> p;
};

/// The crankshaft's point masses (per cylinder: m_s at r_s on its throw, m_p at r_p opposite, in the plane z_j), of
/// the cylinders listed (every cylinder when none are).
std::vector<PointMass> crankPointMasses(const Mechanism& m, std::vector<int> cylinders = {}) {
  if (cylinders.empty())
    for (int j = 0; j < m.engine.cylinders; ++j) cylinders.push_back(j);
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

}  // namespace

std::string toString(Variant variant) {
  switch (variant) {
    case Variant::kExact: return "mujoco";
    case Variant::kSoftDefault: return "mujoco-soft";
    case Variant::kSoftStiff: return "mujoco-soft-stiff";
  }
  return "mujoco";
}

std::string getMujocoVersion() {
  const int v = mj_version();  // e.g. 222
  return std::to_string(v / 100) + "." + std::to_string(v / 10 % 10) + "." + std::to_string(v % 10);
}

namespace {

/// The model's head: compiler, options (gravity, contacts off, the constraint solver off for kExact), the constraint
/// rows (`rows`), the soft variants' equality defaults; then <worldbody> opens.
std::string writeMjcfHead(const Mechanism& m, Variant variant, int rows) {
  std::string x;
  x += "<mujoco model=\"crankcheck\">\n";
  // Inertias exactly as written: none from geometry, no lower bounds, no rebalancing.
  x += "  <compiler angle=\"radian\" inertiafromgeom=\"false\" boundmass=\"0\" boundinertia=\"0\" "
       "balanceinertia=\"false\" settotalmass=\"-1\"/>\n";
  x += "  <option gravity=\"" + vec3(0.0, -m.engine.gravity, 0.0) + "\" timestep=\"0.002\">\n";
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
  for (int j = 0; j < m.engine.cylinders; ++j) {
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
  const int k = m.engine.cylinders;
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

namespace {

/// An invariant: the constraint rows calcMjcf sized (njmax) held every row MuJoCo made; it drops rows silently
/// otherwise (a warning, which crankcheck does not print). @throws std::logic_error if they did not.
void checkRowsFit(const mjData* d) {
  if (d->warning[mjWARN_CNSTRFULL].number > 0)
    throw std::logic_error("MuJoCo: the constraint rows outgrew the model's njmax (calcMjcf's <size>)");
}

/// MJCF text -> mjModel through MuJoCo's virtual file system (2.2.2 has no mj_loadXMLString). One file system per
/// thread, kept: mjVFS holds 2000 file names of 1000 bytes, and zeroing a new one (mj_defaultVFS) was a quarter of
/// a one-cylinder model's build (0.41 ms). The file is removed again after each load, whatever happens.
mjModel* compileModel(const std::string& xml) {
  thread_local const std::unique_ptr<mjVFS> vfs = [] {
    auto fresh = std::make_unique<mjVFS>();  // large: on the heap
    mj_defaultVFS(fresh.get());
    return fresh;
  }();
  if (mj_makeEmptyFileVFS(vfs.get(), kFileName, static_cast<int>(xml.size())) != 0)
    throw std::runtime_error("MuJoCo: could not make the in-memory model file");
  struct RemoveFile {
    mjVFS* vfs;
    ~RemoveFile() { mj_deleteFileVFS(vfs, kFileName); }
  } remove_file{vfs.get()};
  const int index = mj_findFileVFS(vfs.get(), kFileName);
  std::memcpy(vfs->filedata[index], xml.data(), xml.size());
  char error[1024] = "";
  mjModel* model = mj_loadXML(kFileName, vfs.get(), error, sizeof error);
  if (!model) {
    std::string text = error;  // MuJoCo's message spans lines: one line here, as every message of crankcheck
    for (char& c : text)
      if (c == '\n' || c == '\r') c = ' ';
    while (!text.empty() && text.back() == ' ') text.pop_back();
    throw std::runtime_error("MuJoCo could not compile the model: " + text);
  }
  return model;
}

/// MJCF text -> a model of its own (the caller may change it): a copy of the same text's compiled model when one of
/// the thread's last few loads had it. The cross-checks build each case's exact model three times (MuJoCo's exact way,
/// and under each soft way's own model), and the compiler is deterministic, so a copy (mj_copyModel) is what a new
/// compile would give, at a small part of its cost.
mjModel* loadModel(const std::string& xml) {
  installHandlers();
  constexpr size_t kKept = 4;
  struct Compiled {
    std::string xml;
    std::unique_ptr<mjModel, void (*)(mjModel*)> model;
  };
  thread_local std::vector<Compiled> kept;
  auto found = std::find_if(kept.begin(), kept.end(), [&](const Compiled& c) { return c.xml == xml; });
  if (found == kept.end()) {
    if (kept.size() == kKept) kept.erase(kept.begin());
    kept.push_back({xml, {compileModel(xml), mj_deleteModel}});
    found = kept.end() - 1;
  }
  mjModel* copy = mj_copyModel(nullptr, found->model.get());
  if (!copy) throw std::runtime_error("MuJoCo: could not copy a compiled model");
  return copy;
}

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

/// The connect's anchor on the crank: MuJoCo's compiler put it where the big end is at qpos0 (an open loop); the crank
/// pin is where it belongs (MUJOCO-NOTES.md). Equality j is "loop<j>".
void setCrankPinAnchors(mjModel* model, const Mechanism& m) {
  for (int j = 0; j < m.engine.cylinders; ++j) {
    const int equality = mj_name2id(model, mjOBJ_EQUALITY, ("loop" + std::to_string(j)).c_str());
    const double beta = getThrowAngle(m, j);
    double* data = model->eq_data + mjNEQDATA * equality;
    data[3] = m.crank.radius * std::cos(beta);
    data[4] = m.crank.radius * std::sin(beta);
    data[5] = getAxialPosition(m, j);
  }
}

/// Solves the 2 x 2 system [a b; c d] x = (p, q).
std::array<double, 2> solve2(double a, double b, double c, double d, double p, double q) {
  const double det = a * d - b * c;
  return {(p * d - b * q) / det, (a * q - c * p) / det};
}

std::array<double, 3> cross(const double* a, const double* b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

}  // namespace

class KCrankMujocoModel::Impl {
 public:
  Impl(const Mechanism& m, Variant variant);

  Evaluation evaluate(double phi);
  void setSpeed(double omega) {
    if (!std::isfinite(omega)) throw std::invalid_argument("KCrankMujocoModel: crank speed omega must be finite");
    m_.engine.speed = omega;
    m_.speed_rpm = omega * (30.0 / M_PI);
  }
  double potentialEnergy(double phi);
  double holdingTorque(double phi);
  CrankTorqueLine crankTorqueLine(double phi, double phi_dot);
  double closureError() const { return closure_error_; }
  /// The exactly closed state at crank angle phi and crank speed omega: MuJoCo's qpos and qvel.
  void calcClosedState(double phi, double omega, std::vector<double>& qpos, std::vector<double>& qvel) {
    close(phi);
    solveVelocities(omega);
    qpos.assign(data_->qpos, data_->qpos + model_->nq);
    qvel.assign(data_->qvel, data_->qvel + model_->nv);
  }
  int crankJoint() const { return crank_q_; }
  const Mechanism& mechanism() const { return m_; }
  Variant variant() const { return variant_; }

 private:
  struct Cylinder {
    int slide_q = 0, slide_v = 0, wrist_q = 0, wrist_v = 0;
    int piston_body = 0, rod_body = 0, crank_pin_site = 0, big_end_site = 0, equality = 0;
    double n[3] = {0, 0, 0};  // e_j turned +90 degrees
    // The loop's Jacobian columns at the closed configuration (rows X, Y): the big end's with respect to the slide
    // and the wrist hinge, the crank pin's with respect to the crank hinge.
    double jb_s[2] = {0, 0}, jb_h[2] = {0, 0}, jc[2] = {0, 0};
  };
  /// Closes every loop at crank angle phi by Newton's method on the big end's gap (MuJoCo's kinematics and site
  /// Jacobians); leaves the kinematics and the Jacobian columns of the closed configuration.
  void close(double phi);
  /// Every joint's velocity [rad/s, m/s] at crank speed omega with the loops closed (J v = 0: the dependent speeds
  /// from the Jacobian columns of the last closure) into qvel (nv values).
  void calcLoopVelocities(double omega, double* qvel) const;
  /// Dependent speeds for crank speed omega (calcLoopVelocities), then MuJoCo's velocity-dependent quantities
  /// (mj_comVel).
  void solveVelocities(double omega);
  /// Dependent accelerations at zero crank acceleration: J qacc = -(Jdot v), Jdot v from MuJoCo's site
  /// accelerations at qacc = 0.
  void solveAccelerations();
  /// Exact multipliers at the current q, v, qacc: J_dep^T f_j = (M qacc + bias - applied)_dep, then the crank
  /// torque. `gas` adds the gas forces as applied forces. Returns tau; f_j in forces_.
  double solveExactForces(double phi, bool gas);
  /// MuJoCo's soft solver: the crank torque that gives the crank zero acceleration, and the solver's qacc (into
  /// data_->qacc) and loop forces (into forces_). State q, v copied from data_.
  double solveSoftForces(double phi, bool gas);
  /// Joint reactions from the loop forces forces_ and data_->qacc, by mj_rnePostConstraint.
  void fillReactions(Evaluation& e);
  /// -dP/dt, -dH_O/dt with gravity off from data_->qacc (MuJoCo's body accelerations).
  void fillShaking(Evaluation& e);
  double potential() {
    mj_energyPos(model_.get(), data_.get());
    return data_->energy[0];
  }
  void checkFinite(const Evaluation& e, double phi) const;

  Mechanism m_;
  Variant variant_;
  ModelPtr model_;  // constraint solver off: closure, exact multipliers, reactions
  DataPtr data_;
  ModelPtr soft_model_;  // soft variants: MuJoCo's own constraint solver
  DataPtr soft_data_;
  int crank_q_ = 0, crank_v_ = 0, crank_body_ = 0;
  std::vector<Cylinder> cylinders_;
  struct Shaft {
    int q = 0, v = 0, body = 0;
    double ratio = 0.0, phase = 0.0;
  };
  std::vector<Shaft> shafts_;
  std::vector<std::array<double, 2>> forces_;  // f_j: the crank on rod j at its crank pin (crank_pin_force)
  std::vector<double> jacobian_;               // 3 x nv scratch
  std::vector<double> rne_;                    // nv scratch
  std::vector<double> unit_, mass_times_unit_; // nv scratch: u at unit crank speed, M u
  double rotor_inertia_ = 0.0;                 // [kg m^2] the rotors' part of u^T M u (crankTorqueLine)
  double reference_potential_ = 0.0;           // V(0)
  double closure_error_ = 0.0;
  double closure_tolerance_ = 0.0;
  bool closed_ = false;
  double closed_phi_ = 0.0;
  // The motion of the last exact kinematics at crank speed != 0, per unit crank angle: each cylinder's slide and hinge
  // rates dq/dphi = qvel / omega and dq^2/dphi^2 = qacc / omega^2 (constant crank speed) at `phi`. The next closure
  // near it starts from q + dq h + dq^2 h^2 / 2 (close).
  struct AngleMotion {
    bool valid = false;
    double phi = 0.0;
    std::vector<std::array<double, 4>> rates;  // per cylinder: slide dq, slide dq^2, hinge dq, hinge dq^2
  };
  AngleMotion motion_;
  /// Keeps the motion of the kinematics just solved (solveVelocities and solveAccelerations at omega != 0).
  void keepMotion(double omega);
};

KCrankMujocoModel::Impl::Impl(const Mechanism& m, Variant variant) : m_(m), variant_(variant) {
  model_.reset(loadModel(calcMjcf(m_, Variant::kExact)));
  data_.reset(mj_makeData(model_.get()));
  if (variant_ != Variant::kExact) {
    soft_model_.reset(loadModel(calcMjcf(m_, variant_)));
    soft_data_.reset(mj_makeData(soft_model_.get()));
    // Deterministic results: each solve starts cold, not from the previous call's accelerations.
    soft_model_->opt.disableflags |= mjDSBL_WARMSTART;
  }
  const mjModel* mm = model_.get();
  const int crank_joint = mj_name2id(mm, mjOBJ_JOINT, "crank");
  crank_q_ = mm->jnt_qposadr[crank_joint];
  crank_v_ = mm->jnt_dofadr[crank_joint];
  crank_body_ = mj_name2id(mm, mjOBJ_BODY, "crank");
  const int k = m_.engine.cylinders;
  cylinders_.resize(k);
  forces_.assign(k, {0.0, 0.0});
  for (int j = 0; j < k; ++j) {
    Cylinder& c = cylinders_[j];
    const std::string J = std::to_string(j);
    const int slide = mj_name2id(mm, mjOBJ_JOINT, ("slide" + J).c_str());
    const int wrist = mj_name2id(mm, mjOBJ_JOINT, ("wrist" + J).c_str());
    c.slide_q = mm->jnt_qposadr[slide];
    c.slide_v = mm->jnt_dofadr[slide];
    c.wrist_q = mm->jnt_qposadr[wrist];
    c.wrist_v = mm->jnt_dofadr[wrist];
    c.piston_body = mj_name2id(mm, mjOBJ_BODY, ("piston" + J).c_str());
    c.rod_body = mj_name2id(mm, mjOBJ_BODY, ("rod" + J).c_str());
    c.crank_pin_site = mj_name2id(mm, mjOBJ_SITE, ("crank_pin" + J).c_str());
    c.big_end_site = mj_name2id(mm, mjOBJ_SITE, ("big_end" + J).c_str());
    c.equality = mj_name2id(mm, mjOBJ_EQUALITY, ("loop" + J).c_str());
    const double gamma = getBankAngle(m_, j);
    c.n[0] = -std::sin(gamma);
    c.n[1] = std::cos(gamma);
  }
  if (soft_model_) setCrankPinAnchors(soft_model_.get(), m_);
  for (size_t i = 0; i < m_.balance_shafts.size(); ++i) {
    const int joint = mj_name2id(mm, mjOBJ_JOINT, ("shaft" + std::to_string(i)).c_str());
    shafts_.push_back({mm->jnt_qposadr[joint], mm->jnt_dofadr[joint], mj_name2id(mm, mjOBJ_BODY, ("shaft" + std::to_string(i)).c_str()),
                       m_.balance_shafts[i].ratio, m_.balance_shafts[i].phase});
  }
  jacobian_.resize(3 * static_cast<size_t>(mm->nv));
  rne_.resize(static_cast<size_t>(mm->nv));
  unit_.resize(static_cast<size_t>(mm->nv));
  mass_times_unit_.resize(static_cast<size_t>(mm->nv));
  // The isotropic rotor inertias calcMjcf gives the crankshaft (I_w or nominal) and the balance shafts (nominal):
  // their Z component, at unit crank speed the shaft turning at its ratio.
  rotor_inertia_ = mm->body_inertia[3 * crank_body_ + 2];
  for (const Shaft& s : shafts_) rotor_inertia_ += s.ratio * s.ratio * mm->body_inertia[3 * s.body + 2];
  closure_tolerance_ = 4.0 * kEps * (m_.rod.length + m_.crank.radius);
  close(0.0);
  reference_potential_ = potential();
}

void KCrankMujocoModel::Impl::close(double phi) {
  if (!std::isfinite(phi)) throw std::invalid_argument("KCrankMujocoModel: crank angle phi must be finite");
  const mjModel* mm = model_.get();
  mjData* d = data_.get();
  const double l = m_.rod.length;
  // Warm start from the previous closure when it is near; otherwise a crude guess that is no solution: the piston at
  // x = l, the rod along -e (its big end at O). Newton's first step from there puts the piston on the outer branch.
  const double step = std::remainder(phi - closed_phi_, 2.0 * M_PI);
  const bool warm = closed_ && std::fabs(step) <= 1.0;
  if (!warm) {
    for (Cylinder& c : cylinders_) {
      d->qpos[c.slide_q] = l;
      d->qpos[c.wrist_q] = 0.0;
    }
  } else if (motion_.valid && motion_.phi == closed_phi_) {
    // Near the last motion: MuJoCo's own motion carried on to phi (its second-order Taylor step), not the last angle's
    // q: Newton then needs about one step fewer. A hinge carried out of (-pi/2, pi/2) keeps the last angle's q.
    for (size_t j = 0; j < cylinders_.size(); ++j) {
      const Cylinder& c = cylinders_[j];
      const std::array<double, 4>& r = motion_.rates[j];
      const double hinge = d->qpos[c.wrist_q] + r[2] * step + 0.5 * r[3] * step * step;
      if (!(std::fabs(hinge) < M_PI_2)) continue;
      d->qpos[c.slide_q] += r[0] * step + 0.5 * r[1] * step * step;
      d->qpos[c.wrist_q] = hinge;
    }
  }
  d->qpos[crank_q_] = phi;
  for (const Shaft& s : shafts_) d->qpos[s.q] = s.ratio * phi + s.phase;  // the gear's (linear) constraint, solved
  const int nv = mm->nv;
  for (int iteration = 0;; ++iteration) {
    mj_kinematics(mm, d);
    mj_comPos(mm, d);
    double worst = 0.0;
    for (Cylinder& c : cylinders_) {
      const double* b = d->site_xpos + 3 * c.big_end_site;
      const double* p = d->site_xpos + 3 * c.crank_pin_site;
      worst = std::max({worst, std::fabs(b[0] - p[0]), std::fabs(b[1] - p[1])});
    }
    // Jacobian columns at this configuration (kept: at the closed configuration they are the loop's Jacobian).
    for (Cylinder& c : cylinders_) {
      mj_jacSite(mm, d, jacobian_.data(), nullptr, c.big_end_site);
      c.jb_s[0] = jacobian_[c.slide_v];
      c.jb_s[1] = jacobian_[nv + c.slide_v];
      c.jb_h[0] = jacobian_[c.wrist_v];
      c.jb_h[1] = jacobian_[nv + c.wrist_v];
      mj_jacSite(mm, d, jacobian_.data(), nullptr, c.crank_pin_site);
      c.jc[0] = jacobian_[crank_v_];
      c.jc[1] = jacobian_[nv + crank_v_];
    }
    if (worst <= closure_tolerance_) {
      closure_error_ = worst;
      break;
    }
    if (iteration == kMaxNewtonIterations) {
      closed_ = false;
      throw std::runtime_error("MuJoCo: the loop does not close at phi = " + num(phi) + " rad (gap " + num(worst) +
                               " m after " + std::to_string(kMaxNewtonIterations) + " Newton steps)");
    }
    for (Cylinder& c : cylinders_) {
      const double* b = d->site_xpos + 3 * c.big_end_site;
      const double* p = d->site_xpos + 3 * c.crank_pin_site;
      const auto step = solve2(c.jb_s[0], c.jb_h[0], c.jb_s[1], c.jb_h[1], p[0] - b[0], p[1] - b[1]);
      d->qpos[c.slide_q] += step[0];
      // The rod hinge stays within (-pi/2, pi/2): the physical branch (piston outside the crank pin). A step that
      // would leave it goes halfway to the limit instead.
      const double psi = d->qpos[c.wrist_q];
      double next = psi + step[1];
      if (!(std::fabs(next) < M_PI_2)) next = 0.5 * (psi + std::copysign(M_PI_2, step[1]));
      d->qpos[c.wrist_q] = next;
    }
  }
  closed_ = true;
  closed_phi_ = phi;
}

void KCrankMujocoModel::Impl::keepMotion(double omega) {
  if (omega == 0.0) return;
  const mjData* d = data_.get();
  motion_.valid = true;
  motion_.phi = closed_phi_;
  motion_.rates.resize(cylinders_.size());
  for (size_t j = 0; j < cylinders_.size(); ++j) {
    const Cylinder& c = cylinders_[j];
    motion_.rates[j] = {d->qvel[c.slide_v] / omega, d->qacc[c.slide_v] / (omega * omega), d->qvel[c.wrist_v] / omega,
                        d->qacc[c.wrist_v] / (omega * omega)};
  }
}

void KCrankMujocoModel::Impl::calcLoopVelocities(double omega, double* qvel) const {
  qvel[crank_v_] = omega;
  for (const Shaft& s : shafts_) qvel[s.v] = s.ratio * omega;
  for (const Cylinder& c : cylinders_) {
    // J_big_end,dep v_dep = J_crank_pin,crank omega
    const auto v = solve2(c.jb_s[0], c.jb_h[0], c.jb_s[1], c.jb_h[1], c.jc[0] * omega, c.jc[1] * omega);
    qvel[c.slide_v] = v[0];
    qvel[c.wrist_v] = v[1];
  }
}

void KCrankMujocoModel::Impl::solveVelocities(double omega) {
  calcLoopVelocities(omega, data_->qvel);
  mj_comVel(model_.get(), data_.get());
}

void KCrankMujocoModel::Impl::solveAccelerations() {
  const mjModel* mm = model_.get();
  mjData* d = data_.get();
  mju_zero(d->qacc, mm->nv);
  mju_zero(d->xfrc_applied, 6 * mm->nbody);
  mj_rnePostConstraint(mm, d);  // body accelerations at qacc = 0: velocity terms (and gravity's offset) only
  for (const Cylinder& c : cylinders_) {
    double ab[6], ac[6];
    mj_objectAcceleration(mm, d, mjOBJ_SITE, c.big_end_site, ab, 0);
    mj_objectAcceleration(mm, d, mjOBJ_SITE, c.crank_pin_site, ac, 0);
    // Jdot v = a_big_end - a_crank_pin at qacc = 0 (the gravity offset MuJoCo adds to every body cancels)
    const auto a = solve2(c.jb_s[0], c.jb_h[0], c.jb_s[1], c.jb_h[1], -(ab[3] - ac[3]), -(ab[4] - ac[4]));
    d->qacc[c.slide_v] = a[0];
    d->qacc[c.wrist_v] = a[1];
  }
  d->qacc[crank_v_] = 0.0;
  for (const Shaft& s : shafts_) d->qacc[s.v] = 0.0;
}

double KCrankMujocoModel::Impl::solveExactForces(double phi, bool gas) {
  const mjModel* mm = model_.get();
  mjData* d = data_.get();
  mj_rne(mm, d, 1, rne_.data());  // M qacc + bias (gravity, centrifugal, Coriolis)
  double tau = rne_[crank_v_];
  for (size_t j = 0; j < cylinders_.size(); ++j) {
    const Cylinder& c = cylinders_[j];
    const double applied_slide = gas ? -calcGasForce(m_, static_cast<int>(j), phi) : 0.0;  // -p A along e_j
    // J_dep^T f = (M qacc + bias - applied)_dep
    forces_[j] = solve2(c.jb_s[0], c.jb_s[1], c.jb_h[0], c.jb_h[1], rne_[c.slide_v] - applied_slide, rne_[c.wrist_v]);
    // crank row: M qacc + bias = tau - J_crank_pin^T f
    tau += c.jc[0] * forces_[j][0] + c.jc[1] * forces_[j][1];
  }
  // Each gear: the shaft's row, M qacc + bias = mu, and the crank's gets -ratio mu: tau = ... + ratio mu.
  for (const Shaft& s : shafts_) tau += s.ratio * rne_[s.v];
  return tau;
}

double KCrankMujocoModel::Impl::solveSoftForces(double phi, bool gas) {
  const mjModel* sm = soft_model_.get();
  mjData* s = soft_data_.get();
  const mjData* d = data_.get();
  mju_copy(s->qpos, d->qpos, sm->nq);
  mju_copy(s->qvel, d->qvel, sm->nv);
  mju_zero(s->qfrc_applied, sm->nv);
  for (size_t j = 0; j < cylinders_.size(); ++j)
    s->qfrc_applied[cylinders_[j].slide_v] = gas ? -calcGasForce(m_, static_cast<int>(j), phi) : 0.0;
  // The solver's crank acceleration is linear in the crank torque (equality constraints only: one quadratic
  // problem); two solves give the line, a third the state at the torque where it crosses zero. The torque is an
  // applied force: only the acceleration stage depends on it, so the second and third solves redo that stage alone
  // (mj_forwardSkip past mjSTAGE_VEL: the positions and velocities are the first solve's).
  bool first_solve = true;
  auto crankAcceleration = [&](double tau) {
    s->qfrc_applied[crank_v_] = tau;
    if (first_solve) mj_forward(sm, s);
    else mj_forwardSkip(sm, s, mjSTAGE_VEL, 1);
    first_solve = false;
    checkRowsFit(s);
    return s->qacc[crank_v_];
  };
  const double a0 = crankAcceleration(0.0);
  const double a1 = crankAcceleration(1.0);
  const double tau = -a0 / (a1 - a0);
  crankAcceleration(tau);
  mju_copy(data_->qacc, s->qacc, sm->nv);
  for (size_t j = 0; j < cylinders_.size(); ++j) forces_[j] = {0.0, 0.0};
  for (int i = 0; i < s->nefc; ++i) {
    if (s->efc_type[i] != mjCNSTR_EQUALITY) continue;
    for (size_t j = 0; j < cylinders_.size(); ++j) {
      // connect rows: X, Y, Z of (big end - crank pin); the force acts on body1, the rod
      if (s->efc_id[i] != cylinders_[j].equality) continue;
      forces_[j] = {s->efc_force[i], s->efc_force[i + 1]};
      i += 2;
      break;
    }
  }
  return tau;
}

void KCrankMujocoModel::Impl::fillReactions(Evaluation& e) {
  const mjModel* mm = model_.get();
  mjData* d = data_.get();
  mju_zero(d->xfrc_applied, 6 * mm->nbody);
  // The loop forces as body forces (force, torque about the body's centre of mass): f on the rod at its big end,
  // -f on the crankshaft at the crank pin. Gravity, gas and the crank torque are MuJoCo's own (gravity in cacc, gas
  // and torque as joint forces: they arrive in the joint reactions).
  for (size_t j = 0; j < cylinders_.size(); ++j) {
    const Cylinder& c = cylinders_[j];
    const double f[3] = {forces_[j][0], forces_[j][1], 0.0};
    const double minus_f[3] = {-f[0], -f[1], 0.0};
    const double* b = d->site_xpos + 3 * c.big_end_site;
    const double* p = d->site_xpos + 3 * c.crank_pin_site;
    const double* rod_com = d->xipos + 3 * c.rod_body;
    const double* crank_com = d->xipos + 3 * crank_body_;
    const double arm_b[3] = {b[0] - rod_com[0], b[1] - rod_com[1], b[2] - rod_com[2]};
    const double arm_p[3] = {p[0] - crank_com[0], p[1] - crank_com[1], p[2] - crank_com[2]};
    const auto torque_b = cross(arm_b, f);
    const auto torque_p = cross(arm_p, minus_f);
    double* rod = d->xfrc_applied + 6 * c.rod_body;
    double* crank = d->xfrc_applied + 6 * crank_body_;
    for (int i = 0; i < 3; ++i) {
      rod[i] += f[i];
      rod[3 + i] += torque_b[i];
      crank[i] += minus_f[i];
      crank[3 + i] += torque_p[i];
    }
  }
  mj_rnePostConstraint(mm, d);
  // cfrc_int[b] = (torque, force) on body b's subtree from its parent; the force part is independent of the point.
  const double* bearing = d->cfrc_int + 6 * crank_body_ + 3;
  e.bearing_force = {bearing[0], bearing[1]};
  for (size_t j = 0; j < cylinders_.size(); ++j) {
    const Cylinder& c = cylinders_[j];
    CylinderEvaluation& out = e.cylinders[j];
    out.crank_pin_force = forces_[j];
    const double* on_rod = d->cfrc_int + 6 * c.rod_body + 3;  // the piston on the rod through the wrist pin
    out.wrist_pin_force = {-on_rod[0], -on_rod[1]};
    const double* on_piston = d->cfrc_int + 6 * c.piston_body + 3;  // the frame on the piston through the slide
    out.wall_force = on_piston[0] * c.n[0] + on_piston[1] * c.n[1];
  }
  mju_zero(d->xfrc_applied, 6 * mm->nbody);
}

void KCrankMujocoModel::Impl::fillShaking(Evaluation& e) {
  mjModel* mm = model_.get();
  mjData* d = data_.get();
  const std::array<double, 3> gravity{mm->opt.gravity[0], mm->opt.gravity[1], mm->opt.gravity[2]};
  mju_zero(mm->opt.gravity, 3);
  mju_zero(d->xfrc_applied, 6 * mm->nbody);
  mj_rnePostConstraint(mm, d);
  for (int i = 0; i < 3; ++i) mm->opt.gravity[i] = gravity[i];
  // Each tree's root (the crankshaft, each piston) receives from the frame the rate of change of its tree's momentum
  // (no external loads now): cfrc_int at the tree's centre of mass c; about O, torque + c x force.
  double dP[3] = {0, 0, 0}, dH[3] = {0, 0, 0};
  std::vector<int> roots{crank_body_};
  for (const Cylinder& c : cylinders_) roots.push_back(c.piston_body);
  for (const Shaft& s : shafts_) roots.push_back(s.body);
  for (int b : roots) {
    const double* frc = d->cfrc_int + 6 * b;
    const double* c = d->subtree_com + 3 * mm->body_rootid[b];
    const auto arm = cross(c, frc + 3);
    for (int i = 0; i < 3; ++i) {
      dP[i] += frc[3 + i];
      dH[i] += frc[i] + arm[i];
    }
  }
  e.shaking_force = {-dP[0], -dP[1]};
  e.shaking_moment = {-dH[0], -dH[1], -dH[2]};
}

void KCrankMujocoModel::Impl::checkFinite(const Evaluation& e, double phi) const {
  bool ok = std::isfinite(e.U) && std::isfinite(e.Q) && std::isfinite(e.drive_torque) &&
            std::isfinite(e.bearing_force[0]) && std::isfinite(e.bearing_force[1]);
  for (const CylinderEvaluation& c : e.cylinders)
    ok = ok && std::isfinite(c.x_p) && std::isfinite(c.v_p) && std::isfinite(c.a_p) && std::isfinite(c.wall_force) &&
         std::isfinite(c.crank_pin_force[0]) && std::isfinite(c.wrist_pin_force[0]);
  if (!ok) throw std::runtime_error("MuJoCo returned non-finite values at phi = " + num(phi) + " rad");
}

double KCrankMujocoModel::Impl::potentialEnergy(double phi) {
  close(phi);
  return potential() - reference_potential_;
}

double KCrankMujocoModel::Impl::holdingTorque(double phi) {
  close(phi);
  solveVelocities(0.0);
  mju_zero(data_->qacc, model_->nv);
  return variant_ == Variant::kExact ? solveExactForces(phi, false) : solveSoftForces(phi, false);
}

CrankTorqueLine KCrankMujocoModel::Impl::crankTorqueLine(double phi, double phi_dot) {
  if (variant_ != Variant::kExact)
    throw std::invalid_argument("KCrankMujocoModel: the crank torque line is the exact variant's (hard multipliers)");
  if (!std::isfinite(phi_dot)) throw std::invalid_argument("KCrankMujocoModel: crank speed phi_dot must be finite");
  const mjModel* mm = model_.get();
  mjData* d = data_.get();
  close(phi);
  // J = u^T M u: the kinetic energy's form at unit crank speed (the loop forces do no work along u).
  calcLoopVelocities(1.0, unit_.data());
  mj_crb(mm, d);
  mj_mulM(mm, d, mass_times_unit_.data(), unit_.data());
  CrankTorqueLine line;
  line.inertia = mju_dot(unit_.data(), mass_times_unit_.data(), mm->nv) - rotor_inertia_;
  solveVelocities(phi_dot);
  solveAccelerations();
  keepMotion(phi_dot);
  line.rest = solveExactForces(phi, true);
  if (!(std::isfinite(line.inertia) && std::isfinite(line.rest)))
    throw std::runtime_error("MuJoCo returned non-finite values at phi = " + num(phi) + " rad");
  return line;
}

Evaluation KCrankMujocoModel::Impl::evaluate(double phi) {
  Evaluation e;
  e.engine = toString(variant_);
  e.phi = phi;
  e.cylinders.resize(cylinders_.size());
  const bool exact = variant_ == Variant::kExact;
  const double omega = m_.engine.speed;

  close(phi);
  e.U = potential() - reference_potential_;
  // Q: at rest, gravity alone (no gas)
  e.Q = holdingTorque(phi);

  // At speed: the exact kinematics, then forces by the variant's rule.
  solveVelocities(omega);
  solveAccelerations();
  keepMotion(omega);
  e.drive_torque = exact ? solveExactForces(phi, true) : solveSoftForces(phi, true);
  const mjData* d = data_.get();
  for (size_t j = 0; j < cylinders_.size(); ++j) {
    const Cylinder& c = cylinders_[j];
    CylinderEvaluation& out = e.cylinders[j];
    out.x_p = d->qpos[c.slide_q];
    out.v_p = d->qvel[c.slide_v];
    out.a_p = d->qacc[c.slide_v];
    out.gas_force = calcGasForce(m_, static_cast<int>(j), phi);
    // the hinge turns the rod from -e toward -n: the rod angle of CONVENTIONS.md is minus the hinge angle
    out.rod_angle = -d->qpos[c.wrist_q];
    out.rod_omega = -d->qvel[c.wrist_v];
    out.rod_alpha = -d->qacc[c.wrist_v];
  }
  fillReactions(e);

  // Shaking: gravity and gas off, the same motion.
  if (exact) {
    solveAccelerations();
  } else {
    mjModel* sm = soft_model_.get();
    const std::array<double, 3> gravity{sm->opt.gravity[0], sm->opt.gravity[1], sm->opt.gravity[2]};
    mju_zero(sm->opt.gravity, 3);
    solveSoftForces(phi, false);
    for (int i = 0; i < 3; ++i) sm->opt.gravity[i] = gravity[i];
  }
  fillShaking(e);
  checkFinite(e, phi);
  return e;
}

KCrankMujocoModel::KCrankMujocoModel(const Mechanism& m, Variant variant) : impl_(std::make_unique<Impl>(m, variant)) {}
KCrankMujocoModel::~KCrankMujocoModel() = default;
KCrankMujocoModel::KCrankMujocoModel(KCrankMujocoModel&&) noexcept = default;
KCrankMujocoModel& KCrankMujocoModel::operator=(KCrankMujocoModel&&) noexcept = default;

Evaluation KCrankMujocoModel::evaluate(double phi) { return impl_->evaluate(phi); }
void KCrankMujocoModel::setSpeed(double omega) { impl_->setSpeed(omega); }
double KCrankMujocoModel::calcPotentialEnergy(double phi) { return impl_->potentialEnergy(phi); }
double KCrankMujocoModel::calcHoldingTorque(double phi) { return impl_->holdingTorque(phi); }
CrankTorqueLine KCrankMujocoModel::calcCrankTorqueLine(double phi, double phi_dot) {
  return impl_->crankTorqueLine(phi, phi_dot);
}
double KCrankMujocoModel::getLoopClosureError() const { return impl_->closureError(); }
const Mechanism& KCrankMujocoModel::mechanism() const { return impl_->mechanism(); }
Variant KCrankMujocoModel::variant() const { return impl_->variant(); }


FreeRunResult simulateFreeRun(const Mechanism& m, double omega0, Variant variant, const FreeRunSettings& settings) {
  if (variant == Variant::kExact)
    throw std::invalid_argument("mujoco: no free run in the exact way (MuJoCo's integrators step its soft constraints: "
                                "use mujoco-soft or mujoco-soft-stiff)");
  if (!m.flywheel_inertia)
    throw std::invalid_argument("[flywheel].inertia: missing key (the free run needs the flywheel inertia)");
  if (!(std::isfinite(omega0) && omega0 > 0.0)) throw std::invalid_argument("the release speed omega0 must be > 0");
  int integrator = mjINT_RK4;
  if (settings.integrator == "Euler") integrator = mjINT_EULER;
  else if (settings.integrator == "implicit") integrator = mjINT_IMPLICIT;
  else if (settings.integrator != "RK4" && !settings.integrator.empty())
    throw std::invalid_argument("MuJoCo has no integrator \"" + settings.integrator + "\" (Euler, RK4, implicit)");
  if (!(settings.accuracy > 0.0 && settings.accuracy <= 0.1))
    throw std::invalid_argument("MuJoCo's time step must be a fraction of a revolution in (0, 0.1]");
  if (settings.revolutions < 1) throw std::invalid_argument("the free run needs at least one revolution");
  if (settings.gas || settings.load_torque != 0.0)
    throw std::invalid_argument("MuJoCo's free run takes neither gas forces nor a load torque (Engine::simulates_loads)");

  // The release state, closed exactly (Newton on MuJoCo's kinematics), at phi = 0 with omega0.
  std::vector<double> qpos, qvel;
  int crank_q = 0;
  {
    KCrankMujocoModel::Impl exact(m, Variant::kExact);
    exact.calcClosedState(0.0, omega0, qpos, qvel);
    crank_q = exact.crankJoint();
  }
  ModelPtr model(loadModel(calcMjcf(m, variant)));
  setCrankPinAnchors(model.get(), m);
  model->opt.integrator = integrator;
  model->opt.timestep = settings.accuracy * 2.0 * M_PI / omega0;
  if (!settings.gravity) mju_zero(model->opt.gravity, 3);
  DataPtr data(mj_makeData(model.get()));
  mjData* d = data.get();
  mju_copy(d->qpos, qpos.data(), model->nq);
  mju_copy(d->qvel, qvel.data(), model->nv);
  const int crank_v = model->jnt_dofadr[mj_name2id(model.get(), mjOBJ_JOINT, "crank")];

  FreeRunResult r;
  const double target = 2.0 * M_PI * settings.revolutions;
  const long long max_steps = static_cast<long long>(20.0 * settings.revolutions / settings.accuracy) + 1000;
  for (long long step = 0;; ++step) {
    mj_forward(model.get(), d);  // everything at this state, its energies (mjENBL_ENERGY) among them
    checkRowsFit(d);
    const double phi = d->qpos[crank_q], w = d->qvel[crank_v], e = d->energy[0] + d->energy[1];
    if (!(std::isfinite(phi) && std::isfinite(w) && std::isfinite(e)))
      throw std::runtime_error("MuJoCo's free run became non-finite at t = " + num(d->time) + " s");
    r.time.push_back(d->time);
    r.phi.push_back(phi);
    r.phi_dot.push_back(w);
    r.energy.push_back(e);
    if (phi >= target) break;
    if (step == max_steps)
      throw std::runtime_error("MuJoCo's free run did not complete " + std::to_string(settings.revolutions) +
                               " revolutions in " + std::to_string(max_steps) + " steps (phi = " + num(phi) + " rad)");
    if (integrator == mjINT_EULER) mj_Euler(model.get(), d);
    else if (integrator == mjINT_RK4) mj_RungeKutta(model.get(), d, 4);
    else mj_step(model.get(), d);  // the implicit integrator has no function of its own in 2.2.2
    ++r.steps;
  }
  // The first revolution: the time the crank passes 2 pi (linear between the two steps around it: the steps are a
  // small fraction of a revolution), the extreme speeds at the steps before it.
  size_t i = 1;
  while (r.phi[i] < 2.0 * M_PI) ++i;
  const double t1 = r.time[i - 1] + (2.0 * M_PI - r.phi[i - 1]) / (r.phi[i] - r.phi[i - 1]) * (r.time[i] - r.time[i - 1]);
  r.omega_min = r.omega_max = r.phi_dot[0];
  for (size_t s = 0; s <= i; ++s) {
    r.omega_min = std::min(r.omega_min, r.phi_dot[s]);
    r.omega_max = std::max(r.omega_max, r.phi_dot[s]);
  }
  r.omega_mean = 2.0 * M_PI / t1;
  r.delta = (r.omega_max - r.omega_min) / r.omega_mean;
  double drift = 0.0;
  for (double e : r.energy) drift = std::max(drift, std::fabs(e - r.energy[0]));
  r.energy_drift_per_revolution = drift / std::fabs(r.energy[0]) / settings.revolutions;
  return r;
}

namespace {

/// The elastic crank train as MuJoCo's users build it (crank_train.h, simulateCrankTrainSoft): one MJCF, the bodies
/// nested from the flywheel inward, each on a hinge relative to its neighbour toward W with that section's stiffness
/// and damping, the throws' cylinders and loops as calcMjcf's, each throw's damping a fixed tendon over the hinges
/// from W to it. `flywheel_inertia` [kg m^2]: W's.
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
  std::string x = writeMjcfHead(m, variant, 3 * m.engine.cylinders + 8);
  x += "    <body name=\"flywheel\" pos=\"0 0 0\">\n      <joint name=\"flywheel\" type=\"hinge\" axis=\"0 0 1\" "
       "pos=\"0 0 0\"/>\n      <inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"" +
       vec3(flywheel_inertia, flywheel_inertia, flywheel_inertia) + "\"/>\n" + inner + "    </body>\n";
  for (int j = 0; j < m.engine.cylinders; ++j) x += writeCylinder(m, j);
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

/// MuJoCo's soft train stepped by mj_step (RK4) at a whole number of steps per cycle: the soft route's CycleRun.
class SoftTrainRun final : public CycleRun {
 public:
  SoftTrainRun(const Mechanism& m, Variant variant, int steps_per_cycle);
  ~SoftTrainRun() override;
  void startCycle(double, double) override;
  std::vector<double> readCycleState() const override;
  bool moveTo(const std::vector<double>& cycle_state) override;
  void stepTo(double target) override;
  void readState(std::vector<double>& x, std::vector<double>& x_s) const override;
  long long countSteps() const override { return steps_; }
  /// The gas forces at the current state (MuJoCo's control callback, at every stage of RK4).
  void applyGas(const mjModel* model, mjData* d) const;
  const mjModel* model() const { return model_.get(); }

 private:
  Mechanism m_;
  ModelPtr model_;
  DataPtr data_;
  double omega_ = 0.0, cycle_ = 0.0;
  int steps_per_cycle_ = 0, step_in_cycle_ = 0;
  long long steps_ = 0;
  int flywheel_q_ = 0, flywheel_v_ = 0;
  std::vector<int> body_q_, body_v_;  // the bodies' relative hinges, front first
  struct Gas {
    int cylinder = 0, slide_v = 0, body = 0;  // body: the throw's index along the shaft
  };
  std::vector<Gas> gas_;
};

thread_local const SoftTrainRun* active_train = nullptr;
void applyTrainGas(const mjModel* model, mjData* d) {
  if (active_train && active_train->model() == model) active_train->applyGas(model, d);
}

SoftTrainRun::SoftTrainRun(const Mechanism& m, Variant variant, int steps_per_cycle)
    : m_(m), steps_per_cycle_(steps_per_cycle) {
  const CrankshaftParams& c = *m.crankshaft;
  omega_ = m.engine.speed;
  cycle_ = m.engine.cycle == Cycle::kFourStroke ? 4.0 * M_PI : 2.0 * M_PI;
  const std::vector<std::vector<int>> throws = findThrows(m);
  const int front = c.front_inertia > 0.0 ? 1 : 0;
  // W: 1e9 x the train's own inertias, so that within a step its speed moves by 1e-9 of what a throw's does; it is
  // put back on omega t after every step (the bench's drive).
  const double flywheel_inertia = 1e9 * (c.front_inertia + c.throw_inertia * static_cast<double>(throws.size()));
  model_.reset(loadModel(calcTrainMjcf(m, variant, flywheel_inertia)));
  setCrankPinAnchors(model_.get(), m);
  model_->opt.integrator = mjINT_RK4;
  model_->opt.timestep = cycle_ / omega_ / steps_per_cycle_;
  if (variant == Variant::kSoftStiff)  // the refsafe floor at this step: a time constant of two steps
    for (int e = 0; e < model_->neq; ++e) model_->eq_solref[2 * e] = 2.0 * model_->opt.timestep;
  data_.reset(mj_makeData(model_.get()));
  const mjModel* mm = model_.get();
  auto joint = [&](const std::string& name) { return mj_name2id(mm, mjOBJ_JOINT, name.c_str()); };
  flywheel_q_ = mm->jnt_qposadr[joint("flywheel")];
  flywheel_v_ = mm->jnt_dofadr[joint("flywheel")];
  std::vector<std::string> bodies;
  if (front) bodies.push_back("front");
  for (size_t j = 0; j < throws.size(); ++j) bodies.push_back("throw" + std::to_string(j));
  for (const std::string& b : bodies) {
    body_q_.push_back(mm->jnt_qposadr[joint(b)]);
    body_v_.push_back(mm->jnt_dofadr[joint(b)]);
  }
  // The rigid motion at t = 0: every body at 0 turning at omega (relative hinges at rest), each throw's pistons and
  // rods closed exactly on it (its exact model: slide = x_p, wrist hinge = -rod angle).
  mjData* d = data_.get();
  mju_zero(d->qpos, mm->nq);
  mju_zero(d->qvel, mm->nv);
  d->qvel[flywheel_v_] = omega_;
  for (size_t j = 0; j < throws.size(); ++j) {
    KCrankMujocoModel exact(selectThrow(m, static_cast<int>(j)));
    const Evaluation e = exact.evaluate(0.0);
    for (size_t k = 0; k < throws[j].size(); ++k) {
      const std::string C = std::to_string(throws[j][k]);
      const CylinderEvaluation& cylinder = e.cylinders[k];
      d->qpos[mm->jnt_qposadr[joint("slide" + C)]] = cylinder.x_p;
      d->qvel[mm->jnt_dofadr[joint("slide" + C)]] = cylinder.v_p;
      d->qpos[mm->jnt_qposadr[joint("wrist" + C)]] = -cylinder.rod_angle;
      d->qvel[mm->jnt_dofadr[joint("wrist" + C)]] = -cylinder.rod_omega;
      if (m.gas) gas_.push_back({throws[j][k], mm->jnt_dofadr[joint("slide" + C)], static_cast<int>(j) + front});
    }
  }
  static std::once_flag once;
  std::call_once(once, [] { mjcb_control = applyTrainGas; });
  active_train = this;
}

SoftTrainRun::~SoftTrainRun() {
  if (active_train == this) active_train = nullptr;
}

void SoftTrainRun::applyGas(const mjModel*, mjData* d) const {
  for (const Gas& g : gas_) {
    double psi = d->qpos[flywheel_q_];  // the throw's absolute angle: W's plus the hinges from W to it
    for (size_t b = static_cast<size_t>(g.body); b < body_q_.size(); ++b) psi += d->qpos[body_q_[b]];
    d->qfrc_applied[g.slide_v] = -calcGasForce(m_, g.cylinder, psi);
  }
}

void SoftTrainRun::startCycle(double, double) {
  // A new cycle: W back by one cycle (the same configuration: the gas repeats every cycle), time from 0.
  mjData* d = data_.get();
  step_in_cycle_ = 0;
  d->time = 0.0;
  d->qpos[flywheel_q_] = 0.0;
  d->qvel[flywheel_v_] = omega_;
}

void SoftTrainRun::stepTo(double target) {
  const mjModel* mm = model_.get();
  mjData* d = data_.get();
  const int last = static_cast<int>(std::lround(target / cycle_ * steps_per_cycle_));
  while (step_in_cycle_ < last) {
    mj_step(mm, d);
    checkRowsFit(d);
    ++step_in_cycle_;
    ++steps_;
    d->time = mm->opt.timestep * step_in_cycle_;
    d->qpos[flywheel_q_] = omega_ * d->time;  // the drive
    d->qvel[flywheel_v_] = omega_;
  }
}

// The soft chain's own state: every joint's position and speed but the flywheel's (driven: reset each cycle), the
// loops' give included (soft constraints hold no state of their own; MuJoCo's solver warm start only speeds it).
std::vector<double> SoftTrainRun::readCycleState() const {
  const mjModel* mm = model_.get();
  const mjData* d = data_.get();
  std::vector<double> y;
  for (int i = 0; i < mm->nq; ++i)
    if (i != flywheel_q_) y.push_back(d->qpos[i]);
  for (int i = 0; i < mm->nv; ++i)
    if (i != flywheel_v_) y.push_back(d->qvel[i]);
  return y;
}

bool SoftTrainRun::moveTo(const std::vector<double>& y) {
  const mjModel* mm = model_.get();
  mjData* d = data_.get();
  if (static_cast<int>(y.size()) != mm->nq + mm->nv - 2) return false;
  size_t k = 0;
  for (int i = 0; i < mm->nq; ++i)
    if (i != flywheel_q_) d->qpos[i] = y[k++];
  for (int i = 0; i < mm->nv; ++i)
    if (i != flywheel_v_) d->qvel[i] = y[k++];
  startCycle(0.0, 0.0);  // at a cycle's start: time 0, W at 0 turning at omega
  return true;
}

void SoftTrainRun::readState(std::vector<double>& x, std::vector<double>& x_s) const {
  // x_b = psi_b - omega t: the hinges from W to body b (W on omega t); dx/ds = their rates / omega.
  const mjData* d = data_.get();
  const size_t n = body_q_.size();
  x.assign(n, 0.0);
  x_s.assign(n, 0.0);
  double angle = d->qpos[flywheel_q_] - omega_ * d->time, rate = d->qvel[flywheel_v_] - omega_;
  for (size_t b = n; b-- > 0;) {
    angle += d->qpos[body_q_[b]];
    rate += d->qvel[body_v_[b]];
    x[b] = angle;
    x_s[b] = rate / omega_;
  }
}

}  // namespace

CrankTrainRun simulateCrankTrainSoft(const Mechanism& m, Variant variant, const CrankTrainRunOptions& asked) {
  if (variant == Variant::kExact)
    refuseCrankTrain("variant", "the soft route is MuJoCo's soft constraints' (mujoco-soft, mujoco-soft-stiff)");
  const CrankTrainRunOptions options = resolveCrankTrainOptions(m, asked, kSoftCrankTrainStep, kCrankTrainPeriodicity);
  if (!(options.accuracy <= 0.01))
    refuseCrankTrain("CrankTrainRunOptions", "the soft route's accuracy is its time step as a fraction of a cycle: "
                     "at most 0.01");
  const CrankshaftParams& c = *m.crankshaft;
  if (!(c.throw_inertia >= mjMINVAL))
    refuseCrankTrain("[crankshaft].throw_inertia", "MuJoCo's soft train needs J_t > 1e-15 kg m^2 (the throws' bodies "
                     "on hinges need an inertia)");
  if (c.front_inertia > 0.0 && !(c.front_inertia >= mjMINVAL))
    refuseCrankTrain("[crankshaft].front_inertia", "MuJoCo needs 0 or > 1e-15 kg m^2");
  // Whole steps per cycle, a multiple of the probes' (64) and the samples' spacing, at most `accuracy` of a cycle.
  const long long grain = std::lcm(64LL, static_cast<long long>(options.samples));
  const long long steps = std::max(1LL, static_cast<long long>(std::ceil(1.0 / options.accuracy / grain))) * grain;
  if (steps > (1LL << 24)) refuseCrankTrain("CrankTrainRunOptions", "the soft route's step is too small (over 2^24 a cycle)");
  SoftTrainRun run(m, variant, static_cast<int>(steps));
  const double cycle = m.engine.cycle == Cycle::kFourStroke ? 4.0 * M_PI : 2.0 * M_PI;
  // One stage (a fixed step), moved to the extrapolation of its cycle starts' whole states as the exact routes.
  return runToPeriodic(run, cycle, options, PeriodicPolicy{options.accuracy, kExtrapolationWindow}, "mujoco");
}

}  // namespace crankcheck::mujoco_models
