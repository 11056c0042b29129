#include "crankcheck/validation/evaluation_json.h"

#include "crankcheck/validation/engines.h"

#include <cmath>

#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/scene/quantities.h"

namespace crankcheck::validation {
namespace {

nlohmann::ordered_json vec(const Vec2& v) { return nlohmann::ordered_json::array({v[0], v[1]}); }

nlohmann::ordered_json harmonicToJson(const analytic::ShakingHarmonic& h, bool axial) {
  static const char* const kAxes[3] = {"X", "Y", "Z"};
  nlohmann::ordered_json j;
  j[getQuantity(QuantityId::kShakingForce).name] = {{"amplitude", h.calcForceAmplitude()}, {"cos", vec(h.force_cos)}, {"sin", vec(h.force_sin)}};
  nlohmann::ordered_json moment;
  for (int k = 0; k < 3; ++k) {
    if (k < 2 && !axial) {
      moment[kAxes[k]] = nullptr;  // no axial positions: not defined
      continue;
    }
    moment[kAxes[k]] = {{"amplitude", h.calcMomentAmplitude(k)}, {"cos", h.moment_cos[k]}, {"sin", h.moment_sin[k]}};
  }
  j[getQuantity(QuantityId::kShakingMoment).name] = moment;
  return j;
}

}  // namespace

nlohmann::ordered_json sceneToJson(const Mechanism& m) {
  nlohmann::ordered_json j;
  j["name"] = m.name;
  j["engine"] = {
      {"cylinders", m.machine.cylinders},
      {"cycle", toString(m.machine.cycle)},
      {"acting", toString(m.machine.acting)},
      {"crank_angles", m.machine.crank_angles},
      {"explicit_crank_angles", m.machine.explicit_crank_angles},
      {"cylinder_angle", m.machine.cylinder_angle},
      {"bank_angles", m.machine.bank_angles},
      {"axial_positions", m.machine.axial_positions},
      {"pin_offsets", m.machine.pin_offsets},
      {"speed", m.machine.speed},
      {"gravity", m.machine.gravity},
  };
  j["crank"] = {{"radius", m.crank.radius},
                {"mass", m.crank.mass},
                {"com_radius", m.crank.com_radius},
                {"counterweight_mass", m.crank.counterweight_mass},
                {"counterweight_radius", m.crank.counterweight_radius}};
  j["rod"] = {{"length", m.rod.length},
              {"mass", m.rod.mass},
              {"com_from_wrist_pin", m.rod.com_from_wrist_pin},
              {"inertia_about_wrist_pin", m.rod.inertia_about_wrist_pin}};
  j["piston"] = {{"mass", m.piston.mass}};
  if (m.gas) {
    j["gas"] = {{"bore", m.gas->bore}, {"cycle_angles", m.gas->cycle_angles}, {"pressures", m.gas->pressures},
                {"cycle", m.gas->cycle}};
    j["engine"]["firing_angles"] = m.firing_angles;
  }
  if (!m.balance_shafts.empty()) {  // only a scene that has them: every other scene's document is unchanged
    nlohmann::ordered_json shafts = nlohmann::ordered_json::array();
    for (const BalanceShaftParams& b : m.balance_shafts)
      shafts.push_back({{"ratio", b.ratio}, {"mass", b.mass}, {"radius", b.radius}, {"phase", b.phase},
                        {"position", b.position}});
    j["balance_shafts"] = shafts;
  }
  j["flywheel"] = m.flywheel_inertia ? nlohmann::ordered_json{{"inertia", *m.flywheel_inertia}} : nlohmann::ordered_json(nullptr);
  // Each cylinder's dead centres (theta: its own crank angle; phi: cylinder 0's, in [0, 360)) and stroke: with a pin
  // offset they move off theta = 0 and 180 degrees and the stroke exceeds 2 r.
  j["dead_centres"] = nlohmann::ordered_json::array();
  for (int c = 0; c < m.machine.cylinders; ++c) {
    const analytic::DeadCentres d = analytic::calcDeadCentres(m, getPinOffset(m, c));
    const double alpha = m.machine.crank_angles[static_cast<size_t>(c)];
    auto phiDeg = [&](double theta) {
      const double deg = std::fmod(degreesFromRadians(theta - alpha), 360.0);
      return deg < 0.0 ? deg + 360.0 : deg;
    };
    j["dead_centres"].push_back({{"cylinder", c}, {"pin_offset", getPinOffset(m, c)},
                                 {"outer_theta_deg", degreesFromRadians(d.outer)}, {"inner_theta_deg", degreesFromRadians(d.inner)},
                                 {"outer_phi_deg", phiDeg(d.outer)}, {"inner_phi_deg", phiDeg(d.inner)}, {"stroke", d.stroke}});
  }
  j["lambda"] = calcCrankRatio(m);
  j["units"] = "SI: m, kg, s, rad, N, N m, J";
  return j;
}

nlohmann::ordered_json evaluationToJson(const Evaluation& ev, double phi_deg, const Mechanism& m) {
  // A quantity's value: a number, or an array of its components; a component the scene does not define is null,
  // never 0 (shaking_moment X and Y without axial positions).
  auto value = [&](const Quantity& q, int cylinder) {
    const double* v = readQuantity(q, ev, cylinder);
    if (q.components == 1) return nlohmann::ordered_json(v[0]);
    nlohmann::ordered_json array = nlohmann::ordered_json::array();
    for (int c = 0; c < q.components; ++c)
      array.push_back(isComponentDefined(q, c, m) ? nlohmann::ordered_json(v[c]) : nlohmann::ordered_json(nullptr));
    return array;
  };
  nlohmann::ordered_json j;
  j["engine"] = ev.engine;
  j["phi_deg"] = phi_deg;
  // The paper's dimensionless values NAME_star (divided by I_w omega^2): only with a flywheel and a speed, else null.
  // They follow the whole mechanism's numbers, before its vectors.
  const bool dimensionless = m.flywheel_inertia && m.machine.speed > 0.0;
  const double unit = dimensionless ? *m.flywheel_inertia * m.machine.speed * m.machine.speed : 1.0;
  bool stars_written = false;
  auto writeStars = [&] {
    for (const Quantity& q : getQuantityCatalogue())
      if (!q.per_cylinder && q.dimensionless)
        j[std::string(q.name) + "_star"] =
            dimensionless ? nlohmann::ordered_json(readQuantity(q, ev)[0] / unit) : nlohmann::ordered_json(nullptr);
    stars_written = true;
  };
  for (const Quantity& q : getQuantityCatalogue()) {
    if (q.per_cylinder || !isQuantityDefined(q, m)) continue;
    if (q.components > 1 && !stars_written) writeStars();
    j[q.name] = value(q, -1);
  }
  if (!stars_written) writeStars();
  nlohmann::ordered_json cylinders = nlohmann::ordered_json::array();
  for (size_t c = 0; c < ev.cylinders.size(); ++c) {
    nlohmann::ordered_json cylinder = nlohmann::ordered_json::object();
    for (const Quantity& q : getQuantityCatalogue())
      if (q.per_cylinder && isQuantityDefined(q, m)) cylinder[q.name] = value(q, static_cast<int>(c));  // gas_force: absent without [gas]
    cylinders.push_back(cylinder);
  }
  j["cylinders"] = cylinders;
  return j;
}

nlohmann::ordered_json satOutToJson(const std::vector<SatOut>& sat_out) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const SatOut& s : sat_out) list.push_back({{"engine", s.engine}, {"reason", s.reason}});
  return list;
}

nlohmann::ordered_json balanceResolutionToJson(const BalanceResolution& resolution) {
  return {{"force", resolution.force}, {"moment", resolution.moment}};
}

nlohmann::ordered_json balanceToJson(const std::vector<BalanceRow>& rows, bool axial) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const BalanceRow& row : rows) {
    nlohmann::ordered_json h;
    h["n"] = row.n;
    h[getClosedFormEngine().name] = harmonicToJson(withExactZeros(row.analytic, row.symmetry), axial);
    for (const auto& [engine, harmonic] : row.engines) h[engine] = harmonicToJson(harmonic, axial);
    const auto& s = row.symmetry;
    auto decided = [&](bool v) { return s.decided ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr); };
    h["vanishes_by_symmetry"] = {{"force", decided(s.force_cancels)},
                                 {"moment_xy", axial ? decided(s.moment_xy_cancels) : nlohmann::ordered_json(nullptr)},
                                 {"moment_z", decided(s.moment_z_cancels)}};
    // What no centric cylinder carries at this order, whatever the phases (analytic/shaking.h).
    h["absent_by_order"] = {{"force", s.force_order_absent},
                            {"moment_xy", axial ? nlohmann::ordered_json(s.force_order_absent) : nlohmann::ordered_json(nullptr)},
                            {"moment_z", s.moment_z_order_absent}};
    h["absent_by_direction"] = {
        {"moment_x", axial ? nlohmann::ordered_json(s.moment_x_direction_absent) : nlohmann::ordered_json(nullptr)},
        {"moment_y", axial ? nlohmann::ordered_json(s.moment_y_direction_absent) : nlohmann::ordered_json(nullptr)}};
    out.push_back(h);
  }
  return out;
}

nlohmann::ordered_json motionRunToJson(const MotionRun& run) {
  if (!run.not_measured.empty())
    return {{"integrator", run.integrator}, {"step_s", run.accuracy}, {"steps", run.steps}, {"not_measured", run.not_measured}};
  nlohmann::ordered_json j = {{"delta_gravity", run.delta_gravity}, {"delta_no_gravity", run.delta_no_gravity},
                              {"omega_min", run.omega_min}, {"omega_max", run.omega_max}, {"omega_mean", run.omega_mean}};
  if (!run.integrator.empty()) {
    j["integrator"] = run.integrator;
    j["energy_drift_per_revolution"] = run.energy_drift;
    j["steps"] = run.steps;
  }
  return j;
}

}  // namespace crankcheck::validation
