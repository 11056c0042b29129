// A program graded by `crankcheck grade --free-run` (protocol 2, a time-stepped run), written as a user's simulator
// would be: no crankcheck code, only the request's "scene" object, nlohmann-json and Eigen. It integrates the engine
// in MAXIMAL coordinates with the semi-implicit (symplectic) Euler scheme and velocity-level constraints, the scheme of
// many game and engine simulators:
//
//   build/bin/crankcheck grade --free-run ... -- build/bin/free_run_example_euler
//
// Bodies in the plane (docs/CONVENTIONS.md):
//   the crankshaft: one coordinate phi about O, inertia I_c = I_w + sum_j (m_s r_s^2 + m_p r_p^2), the throws' crank
//     masses and counterweights being points on the crank line at r_s and -r_p;
//   rod j: its centre of mass G (x, y) and its angle psi about +Z (the direction from the wrist pin A to the crank pin
//     B), mass m_k, central inertia I_G = I_o - m_k z_k^2, so A = G - z_k u(psi) and B = G + (l - z_k) u(psi);
//   piston j: a particle P (x, y) of mass m_o.
// Constraints of cylinder j (5 rows): the crank pin (rod's B = r u(gamma_j + theta_j), 2 rows), the wrist pin (rod's
// A = P, 2 rows), the piston on its line (n_j . P = delta_j, 1 row); the "held" drive adds phi_dot = omega0 (1 row).
//
// One step from (q_n, v_n) at t_n:
//   v* = v_n + dt M^-1 f(q_n)                    f: gravity, the gas force -p_j A e_j on piston j, the load torque
//   (J M^-1 J^T) lambda = b - J v*               J = the constraints' Jacobian at q_n; b = 0 (omega0 on the drive's row)
//   v_{n+1} = v* + M^-1 J^T lambda               so that J v_{n+1} = b: lambda are the step's constraint impulses
//   q_{n+1} = q_n + dt v_{n+1}
//   then a post-step position projection (no Baumgarte term): q += -M^-1 J^T (J M^-1 J^T)^-1 C(q), repeated until the
//   constraint violation C is at rounding (at most 8 times); the velocities are left as they are.
//
// Reported (the protocol's names and signs): phi (the crank coordinate, unwrapped) at t = t_{n+1}; omega = v_{n+1}'s
// crank component, a backward difference of phi, standing at t - dt/2 ("omega_t"). The other values belong to the
// configuration q_n the step was computed at, t_n = t - dt ("values_t"): x_p = e_j . P(q_n); v_p = e_j . v_P(n+1), the
// velocity the step's constraints make consistent with q_n; a_p = e_j . (v_P(n+1) - v_P(n)) / dt; rod_angle, rod_omega
// and rod_alpha likewise from psi(q_n), psi_dot(n+1) and its change (with the conventions' sign); drive_torque = the
// drive row's impulse / dt; crank_pin_force (on the rod from the crank) = its rows' impulse / dt; wrist_pin_force (on
// the piston from the rod) = minus its rows' impulse / dt; wall_force = the line row's impulse / dt; bearing_force (on
// the crank from the main bearing) from Newton's law of the crank's point masses, M_c a_c = F_bearing + gravity -
// sum_j crank_pin_force_j, a_c from phi(q_n), omega(n+1) and (omega(n+1) - omega(n)) / dt. The velocity change of a step
// is what turns the velocities from q_{n-1}'s constraints to q_n's, so a_p and the forces are first order in dt at t_n
// (a_p alone stands at t - 3 dt/2 to second order). The first step has no such change (the start velocities fit q_0
// exactly), so its sample carries phi and omega only, as does the sample at t = 0.
//
// Step: the request's dt, or with "own" 1/720 of a revolution at omega0 (shortened so a whole number of steps ends at
// t_end). A sample at t = 0, every round(output_interval / dt) >= 1 steps, and at the last step. The balance shafts
// of a scene are not in the request's "scene" object and are therefore not modelled.
//
// Reads one JSON request per line on stdin, writes one JSON response per line on stdout (flushed). A request it cannot
// read: one line on stderr, exit status 2; a run that diverges: one line, exit status 1.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using Eigen::MatrixXd;
using Eigen::Vector2d;
using Eigen::VectorXd;
using nlohmann::json;

/// A request this program cannot run: its message goes to stderr and the program exits with status 2.
struct BadRequest : std::runtime_error {
  using std::runtime_error::runtime_error;
};

Vector2d unit(double angle) { return {std::cos(angle), std::sin(angle)}; }
Vector2d perp(const Vector2d& v) { return {-v.y(), v.x()}; }  // v turned +90 degrees

struct Cylinder {
  double gamma = 0.0;  ///< [rad] bank angle: e = u(gamma)
  double phase = 0.0;  ///< [rad] theta_j = phi + phase
  double offset = 0.0; ///< [m] pin offset delta_j along n
  double firing = 0.0; ///< [rad] the crank angle of its firing outer dead centre (with gas)
  Vector2d e, n;
};

struct Model {
  std::vector<Cylinder> cylinders;
  double g = 0.0;                             ///< [m/s^2] along -Y
  double r = 0.0, m_s = 0.0, r_s = 0.0, m_p = 0.0, r_p = 0.0;
  double l = 0.0, m_k = 0.0, z = 0.0, I_G = 0.0;
  double m_o = 0.0;
  double I_c = 0.0;                           ///< [kg m^2] the crankshaft about O
  bool has_gas = false;
  std::vector<double> gas_angles, gas_pressures;
  double gas_cycle = 0.0, bore_area = 0.0;

  /// p_j A [N] at crank angle phi: the scene's table, periodic, linear between points and from the last to the first.
  double gasForce(const Cylinder& c, double phi) const {
    double a = std::fmod(phi - c.firing, gas_cycle);
    if (a < 0.0) a += gas_cycle;
    const std::size_t k = gas_angles.size();
    for (std::size_t i = 0; i < k; ++i) {
      const bool last = i + 1 == k;
      const double a1 = last ? gas_cycle : gas_angles[i + 1];
      const double p1 = last ? gas_pressures[0] : gas_pressures[i + 1];
      if (a < a1 || last)
        return bore_area * (gas_pressures[i] + (p1 - gas_pressures[i]) * (a - gas_angles[i]) / (a1 - gas_angles[i]));
    }
    return 0.0;
  }
};

Model readScene(const json& scene) {
  Model m;
  const json& engine = scene.at("engine");
  const int k = engine.at("cylinders").get<int>();
  const std::vector<double> phases = engine.at("crank_angles").get<std::vector<double>>();
  std::vector<double> banks = engine.value("bank_angles", std::vector<double>{});
  std::vector<double> offsets = engine.value("pin_offsets", std::vector<double>{});
  if (banks.empty()) banks.assign(k, engine.at("cylinder_angle").get<double>());
  if (offsets.empty()) offsets.assign(k, 0.0);
  if (k < 1 || static_cast<int>(phases.size()) != k || static_cast<int>(banks.size()) != k ||
      static_cast<int>(offsets.size()) != k)
    throw BadRequest("scene.engine: cylinders, crank_angles, bank_angles and pin_offsets disagree");
  m.g = engine.at("gravity").get<double>();
  const json& crank = scene.at("crank");
  m.r = crank.at("radius").get<double>();
  m.m_s = crank.value("mass", 0.0);
  m.r_s = crank.value("com_radius", 0.0);
  m.m_p = crank.value("counterweight_mass", 0.0);
  m.r_p = crank.value("counterweight_radius", 0.0);
  const json& rod = scene.at("rod");
  m.l = rod.at("length").get<double>();
  m.m_k = rod.at("mass").get<double>();
  m.z = rod.at("com_from_wrist_pin").get<double>();
  m.I_G = rod.at("inertia_about_wrist_pin").get<double>() - m.m_k * m.z * m.z;
  m.m_o = scene.at("piston").at("mass").get<double>();
  const double I_w = scene.contains("flywheel") && scene["flywheel"].is_object()
                         ? scene["flywheel"].value("inertia", 0.0) : 0.0;
  m.I_c = I_w + k * (m.m_s * m.r_s * m.r_s + m.m_p * m.r_p * m.r_p);
  if (!(m.I_c > 0.0 && m.m_k > 0.0 && m.I_G > 0.0 && m.m_o > 0.0))
    throw BadRequest("this simulator needs a positive crank inertia, rod mass, rod central inertia and piston mass");
  std::vector<double> firing;
  if (scene.contains("gas") && scene["gas"].is_object()) {
    const json& gas = scene["gas"];
    m.has_gas = true;
    m.gas_angles = gas.at("cycle_angles").get<std::vector<double>>();
    m.gas_pressures = gas.at("pressures").get<std::vector<double>>();
    m.gas_cycle = gas.at("cycle").get<double>();
    const double bore = gas.at("bore").get<double>();
    m.bore_area = std::numbers::pi * bore * bore / 4.0;
    firing = engine.at("firing_angles").get<std::vector<double>>();
    if (m.gas_angles.empty() || m.gas_angles.size() != m.gas_pressures.size() || static_cast<int>(firing.size()) != k)
      throw BadRequest("scene.gas: the pressure table or the firing angles do not fit the cylinders");
  }
  for (int j = 0; j < k; ++j) {
    Cylinder c;
    c.gamma = banks[j];
    c.phase = phases[j];
    c.offset = offsets[j];
    c.firing = m.has_gas ? firing[j] : 0.0;
    c.e = unit(c.gamma);
    c.n = perp(c.e);
    m.cylinders.push_back(c);
  }
  return m;
}

// Generalized coordinates: q[0] = phi; cylinder j at 1 + 5 j: G.x, G.y, psi, P.x, P.y. Constraint rows: cylinder j at
// 5 j: crank pin (x, y), wrist pin (x, y), line; the drive's row last when held.
int dof(int j) { return 1 + 5 * j; }

class Simulator {
 public:
  Simulator(const Model& m, bool held) : m_(m), held_(held) {
    k_ = static_cast<int>(m.cylinders.size());
    n_ = 1 + 5 * k_;
    rows_ = 5 * k_ + (held ? 1 : 0);
    inverse_mass_ = VectorXd::Zero(n_);
    inverse_mass_[0] = 1.0 / m.I_c;
    for (int j = 0; j < k_; ++j) {
      const int b = dof(j);
      inverse_mass_.segment(b, 5) << 1.0 / m.m_k, 1.0 / m.m_k, 1.0 / m.I_G, 1.0 / m.m_o, 1.0 / m.m_o;
    }
    jacobian_ = MatrixXd::Zero(rows_, n_);
  }

  /// Places the bodies at crank angle phi0 with the crank speed omega0 (rods and pistons on the outer branch, their
  /// velocities solved from the velocity constraints).
  void start(double phi0, double omega0) {
    q_ = VectorXd::Zero(n_);
    v_ = VectorXd::Zero(n_);
    q_[0] = phi0;
    for (int j = 0; j < k_; ++j) {
      const Cylinder& c = m_.cylinders[j];
      const double theta = phi0 + c.phase;
      const double across = m_.r * std::sin(theta) - c.offset;
      if (std::abs(across) >= m_.l) throw BadRequest("the rod cannot reach its piston's line (l <= r + |offset|)");
      const Vector2d B = m_.r * unit(c.gamma + theta);
      const Vector2d P = (m_.r * std::cos(theta) + std::sqrt(m_.l * m_.l - across * across)) * c.e + c.offset * c.n;
      const Vector2d ab = (B - P) / m_.l;
      const int b = dof(j);
      q_.segment<2>(b) = P + m_.z * ab;
      q_[b + 2] = std::atan2(ab.y(), ab.x());
      q_.segment<2>(b + 3) = P;
    }
    // J_rest v_rest = -J_phi omega0 over the 5 k velocity constraints of the cylinders.
    fillJacobian(q_);
    const MatrixXd rest = jacobian_.block(0, 1, 5 * k_, n_ - 1);
    const VectorXd rhs = -jacobian_.block(0, 0, 5 * k_, 1) * omega0;
    v_[0] = omega0;
    v_.tail(n_ - 1) = rest.partialPivLu().solve(rhs);
  }

  /// One step to t_next (the drive's prescribed angle there when held).
  void step(double dt, double omega0, double phi_next, bool gas, bool gravity, double load) {
    q_old_ = q_;
    v_old_ = v_;
    VectorXd force = VectorXd::Zero(n_);
    const double g = gravity ? m_.g : 0.0;
    const double phi = q_[0];
    force[0] = -load;
    for (int j = 0; j < k_; ++j) {
      const Cylinder& c = m_.cylinders[j];
      const int b = dof(j);
      force[0] -= (m_.m_s * m_.r_s - m_.m_p * m_.r_p) * g * std::cos(c.gamma + phi + c.phase);
      force[b + 1] -= m_.m_k * g;
      force[b + 4] -= m_.m_o * g;
      if (gas) force.segment<2>(b + 3) -= m_.gasForce(c, phi) * c.e;
    }
    const VectorXd v_star = v_ + dt * inverse_mass_.cwiseProduct(force);
    fillJacobian(q_);
    VectorXd target = VectorXd::Zero(rows_);
    if (held_) target[rows_ - 1] = omega0;
    const MatrixXd A = jacobian_ * inverse_mass_.asDiagonal() * jacobian_.transpose();
    impulse_ = A.ldlt().solve(target - jacobian_ * v_star);
    v_ = v_star + inverse_mass_.cwiseProduct(jacobian_.transpose() * impulse_);
    q_ += dt * v_;
    project(phi_next);
  }

  double phi() const { return q_[0]; }
  double omega() const { return v_[0]; }
  bool finite() const { return q_.allFinite() && v_.allFinite() && impulse_.allFinite(); }

  /// The step's values (standing at t_n, the configuration q_n it was computed at), in the protocol's names.
  json values(double dt, const std::set<std::string>& wanted, bool gravity) const {
    json out = json::object();
    if (held_ && wanted.count("drive_torque")) out["drive_torque"] = impulse_[rows_ - 1] / dt;
    const double g = gravity ? m_.g : 0.0;
    const double phi_n = q_old_[0];
    const double w = v_[0];
    const double alpha = (v_[0] - v_old_[0]) / dt;
    Vector2d bearing = Vector2d::Zero();
    json cylinders = json::array();
    for (int j = 0; j < k_; ++j) {
      const Cylinder& c = m_.cylinders[j];
      const int b = dof(j);
      const Vector2d crank_pin = impulse_.segment<2>(5 * j) / dt;
      const Vector2d wrist_pin = -impulse_.segment<2>(5 * j + 2) / dt;
      const Vector2d u = unit(c.gamma + phi_n + c.phase);
      const double mr = m_.m_s * m_.r_s - m_.m_p * m_.r_p;
      bearing += mr * (alpha * perp(u) - w * w * u) + (m_.m_s + m_.m_p) * g * Vector2d(0.0, 1.0) + crank_pin;
      json cyl = json::object();
      if (wanted.count("x_p"))
        cyl["x_p"] = c.e.dot(q_old_.segment<2>(b + 3));
      if (wanted.count("v_p")) cyl["v_p"] = c.e.dot(v_.segment<2>(b + 3));
      if (wanted.count("a_p")) cyl["a_p"] = c.e.dot(v_.segment<2>(b + 3) - v_old_.segment<2>(b + 3)) / dt;
      if (wanted.count("crank_pin_force")) cyl["crank_pin_force"] = {crank_pin.x(), crank_pin.y()};
      if (wanted.count("wrist_pin_force")) cyl["wrist_pin_force"] = {wrist_pin.x(), wrist_pin.y()};
      if (wanted.count("wall_force")) cyl["wall_force"] = impulse_[5 * j + 4] / dt;
      // The rod angle beta of the conventions: u(psi) = -cos(beta) e + sin(beta) n, so beta = gamma + pi - psi.
      if (wanted.count("rod_angle"))
        cyl["rod_angle"] = std::remainder(c.gamma + std::numbers::pi - q_old_[b + 2], 2.0 * std::numbers::pi);
      if (wanted.count("rod_omega")) cyl["rod_omega"] = -v_[b + 2];
      if (wanted.count("rod_alpha")) cyl["rod_alpha"] = -(v_[b + 2] - v_old_[b + 2]) / dt;
      cylinders.push_back(cyl);
    }
    if (wanted.count("bearing_force")) out["bearing_force"] = {bearing.x(), bearing.y()};
    if (!cylinders.empty() && !cylinders[0].empty()) out["cylinders"] = cylinders;
    return out;
  }

 private:
  void fillJacobian(const VectorXd& q) {
    jacobian_.setZero();
    for (int j = 0; j < k_; ++j) {
      const Cylinder& c = m_.cylinders[j];
      const int b = dof(j), row = 5 * j;
      const Vector2d up = perp(unit(q[b + 2]));
      // crank pin: G + (l - z) u(psi) - r u(gamma + phi + phase) = 0
      jacobian_.block<2, 2>(row, b).setIdentity();
      jacobian_.block<2, 1>(row, b + 2) = (m_.l - m_.z) * up;
      jacobian_.block<2, 1>(row, 0) = -m_.r * perp(unit(c.gamma + q[0] + c.phase));
      // wrist pin: G - z u(psi) - P = 0
      jacobian_.block<2, 2>(row + 2, b).setIdentity();
      jacobian_.block<2, 1>(row + 2, b + 2) = -m_.z * up;
      jacobian_.block<2, 2>(row + 2, b + 3) = -Eigen::Matrix2d::Identity();
      // the piston on its line: n . P - delta = 0
      jacobian_.block<1, 2>(row + 4, b + 3) = c.n.transpose();
    }
    if (held_) jacobian_(rows_ - 1, 0) = 1.0;
  }

  VectorXd violation(const VectorXd& q, double phi_held) const {
    VectorXd C(rows_);
    for (int j = 0; j < k_; ++j) {
      const Cylinder& c = m_.cylinders[j];
      const int b = dof(j), row = 5 * j;
      const Vector2d G = q.segment<2>(b), P = q.segment<2>(b + 3), u = unit(q[b + 2]);
      C.segment<2>(row) = G + (m_.l - m_.z) * u - m_.r * unit(c.gamma + q[0] + c.phase);
      C.segment<2>(row + 2) = G - m_.z * u - P;
      C[row + 4] = c.n.dot(P) - c.offset;
    }
    if (held_) C[rows_ - 1] = q[0] - phi_held;
    return C;
  }

  void project(double phi_held) {
    const double tolerance = 1e-14 * (m_.l + m_.r);
    for (int iteration = 0; iteration < 8; ++iteration) {
      const VectorXd C = violation(q_, phi_held);
      if (C.lpNorm<Eigen::Infinity>() <= tolerance) return;
      fillJacobian(q_);
      const MatrixXd A = jacobian_ * inverse_mass_.asDiagonal() * jacobian_.transpose();
      q_ -= inverse_mass_.cwiseProduct(jacobian_.transpose() * A.ldlt().solve(C));
    }
  }

  const Model& m_;
  bool held_;
  int k_ = 0, n_ = 0, rows_ = 0;
  VectorXd inverse_mass_, q_, v_, q_old_, v_old_, impulse_;
  MatrixXd jacobian_;
};

json answer(const json& request) {
  Model model;
  std::string drive;
  bool gas = false, gravity = true;
  double load = 0.0, phi0 = 0.0, omega0 = 0.0, t_end = 0.0, interval = 0.0, dt = 0.0;
  std::optional<double> given_dt;
  std::set<std::string> wanted;
  try {
    model = readScene(request.at("scene"));
    drive = request.at("drive").get<std::string>();
    gas = request.value("gas", false);
    gravity = request.value("gravity", true);
    if (drive == "loaded") load = request.value("load_torque", 0.0);
    phi0 = request.at("phi0").get<double>();
    omega0 = request.at("omega0").get<double>();
    t_end = request.at("t_end").get<double>();
    interval = request.at("output_interval").get<double>();
    if (!request.at("dt").is_string()) given_dt = request.at("dt").get<double>();
    else if (request.at("dt").get<std::string>() != "own") throw BadRequest("dt must be a number or \"own\"");
    if (request.contains("quantities")) wanted = request["quantities"].get<std::set<std::string>>();
  } catch (const json::exception& error) {
    throw BadRequest(std::string("a request without a usable field: ") + error.what());
  }
  if (drive != "free" && drive != "held" && drive != "loaded")
    throw BadRequest("unknown drive \"" + drive + "\" (free, held or loaded)");
  if (gas && !model.has_gas) throw BadRequest("the request asks for gas but the scene has no gas table");
  if (!(t_end > 0.0) || !(interval > 0.0)) throw BadRequest("t_end and output_interval must be > 0");
  long steps = 0;
  if (given_dt) {
    dt = *given_dt;
    if (!(dt > 0.0)) throw BadRequest("dt must be > 0 or \"own\"");
    steps = std::max(1L, static_cast<long>(std::ceil(t_end / dt - 1e-9)));
  } else {
    if (omega0 == 0.0) throw BadRequest("dt \"own\" needs omega0 != 0 (a step of 1/720 revolution)");
    const double nominal = 2.0 * std::numbers::pi / (720.0 * std::abs(omega0));
    steps = std::max(1L, static_cast<long>(std::ceil(t_end / nominal - 1e-9)));
    dt = t_end / static_cast<double>(steps);
  }
  const long every = std::max(1L, std::lround(interval / dt));
  const bool held = drive == "held";

  Simulator sim(model, held);
  sim.start(phi0, omega0);
  json samples = json::array();
  const json first = {{"t", 0.0}, {"phi", sim.phi()}, {"omega", sim.omega()}};
  samples.push_back(first);
  for (long n = 1; n <= steps; ++n) {
    const double t = static_cast<double>(n) * dt;
    sim.step(dt, omega0, phi0 + omega0 * t, gas, gravity, load);
    if (!sim.finite()) throw std::runtime_error("the run diverged at t = " + std::to_string(t) + " s");
    if (n % every == 0 || n == steps) {
      json sample = {{"t", t}, {"phi", sim.phi()}, {"omega", sim.omega()}, {"omega_t", t - 0.5 * dt}};
      const json values = n > 1 ? sim.values(dt, wanted, gravity) : json::object();
      if (!values.empty()) {
        sample["values_t"] = t - dt;
        sample.update(values);
      }
      samples.push_back(std::move(sample));
    }
  }
  return {{"samples", samples}};
}

}  // namespace

int main() {
  std::string line;
  while (std::getline(std::cin, line)) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    try {
      const json request = json::parse(line);
      if (!request.is_object()) throw BadRequest("a request line that is not a JSON object");
      std::cout << answer(request).dump() << '\n' << std::flush;
    } catch (const json::parse_error& error) {
      std::cerr << "free_run_example_euler: a request line that is not JSON: " << error.what() << '\n';
      return 2;
    } catch (const BadRequest& error) {
      std::cerr << "free_run_example_euler: " << error.what() << '\n';
      return 2;
    } catch (const std::exception& error) {
      std::cerr << "free_run_example_euler: " << error.what() << '\n';
      return 1;
    }
  }
  return 0;
}
