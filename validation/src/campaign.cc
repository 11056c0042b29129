#include "crankcheck/validation/campaign.h"

#include "campaign_tables.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "crankcheck/analytic/batch.h"
#include "crankcheck/analytic/fourier_series.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/analytic/motion.h"
#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/simbody_models/free_run.h"
#include "crankcheck/simbody_models/grid_sweep.h"
#include "crankcheck/simbody_models/k_crank_gravity_model.h"
#include "crankcheck/simbody_models/k_crank_model.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/balance.h"
#include "crankcheck/validation/engine_loads.h"
#include "crankcheck/validation/install_paths.h"
#include "crankcheck/validation/parts.h"
#include "crankcheck/validation/extremum.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/validation/timing.h"
#include "crankcheck/validation/variants.h"


namespace crankcheck::validation {

std::string formatNumber(double x) {
  char buffer[40];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, x + 0.0).ptr;  // shortest round-trip; -0 as 0
  return std::string(buffer, end);
}

std::string shortNumber(double x, int digits) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, x);
  return buffer;
}

Table::Table(const std::string& name, std::vector<Column> columns) : columns_(std::move(columns)) {
  for (const Column& c : columns_)
    if (!c.text && c.unit.empty())
      throw std::logic_error("table " + name + ": column " + c.name + " is a number without a unit (declare its unit, "
                             "or kText for a text column)");
}

std::vector<std::string> Table::names() const {
  std::vector<std::string> out;
  for (const Column& c : columns_) out.push_back(c.name);
  return out;
}

size_t columnOf(const Table& t, const std::string& name) {
  const auto& columns = t.columns();
  const auto it = std::find_if(columns.begin(), columns.end(), [&](const Column& c) { return c.name == name; });
  if (it == columns.end()) throw std::runtime_error("report: table has no column " + name);
  return static_cast<size_t>(it - columns.begin());
}

void appendTables(TableSet& into, const TableSet& from) {
  for (const auto& [name, table] : from) {
    auto [it, inserted] = into.try_emplace(name, table);
    if (inserted) continue;
    if (it->second.columns() != table.columns()) throw std::runtime_error("table " + name + ": columns differ");
    it->second.rows.insert(it->second.rows.end(), table.rows.begin(), table.rows.end());
  }
}

namespace {

bool parseNumber(const std::string& s, double& x) {
  if (s.empty()) return false;
  char* end = nullptr;
  x = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size();
}

bool rowLess(const std::vector<std::string>& a, const std::vector<std::string>& b) {
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    double x, y;
    if (parseNumber(a[i], x) && parseNumber(b[i], y)) {
      if (x != y) return x < y;
    } else if (a[i] != b[i]) {
      return a[i] < b[i];
    }
  }
  return a.size() < b.size();
}

}  // namespace

void sortTables(TableSet& tables) {
  for (auto& [name, table] : tables) std::stable_sort(table.rows.begin(), table.rows.end(), rowLess);
}

namespace {

using analytic::Eq5Form;
using analytic::LambdaSource;

std::string num(double x) { return formatNumber(x); }

// ------------------------------------------------------------------------------------------------------------
// Scenes

Mechanism makeScene(const std::string& name, int k, Cycle cycle, double gamma_deg, double rpm) {
  Mechanism m;
  m.name = name;
  m.engine.cylinders = k;
  m.engine.cycle = cycle;
  m.engine.crank_angles = calcPhaseAngles(k, cycle, Acting::kSingle);
  m.engine.cylinder_angle = radiansFromDegrees(gamma_deg);
  m.speed_rpm = rpm;
  m.engine.speed = rpm * (M_PI / 30.0);
  // A passenger-car cylinder (the example scene scenes/single_cylinder.toml).
  m.crank = {0.043, 1.2, 0.02, 0.8, 0.035};
  m.rod = {0.145, 0.55, 0.105, 0.0072};
  m.piston.mass = 0.35;
  m.flywheel_inertia = 0.15;
  return m;
}

double lambdaOf(const Mechanism& m) { return calcCrankRatio(m); }

// ------------------------------------------------------------------------------------------------------------
// Cross-check of one case: every quantity, at the scene's speed and at rest; one row per quantity with the worst
// comparison (largest error / tolerance).

struct WorstComparison {
  double ratio_to_tolerance = -1.0;
  double rel_error = 0.0, tolerance_rel = 0.0, phi_deg = 0.0, rpm = 0.0;
  bool pass = true;
};

TableSet crossCheckCase(const std::string& family, const Mechanism& m, const std::vector<double>& angles_deg) {
  std::map<std::pair<std::string, std::string>, WorstComparison> worst;  // (engine, quantity)
  auto note = [&](const std::string& engine, const Comparison& c, double phi_deg, double rpm) {
    WorstComparison& w = worst[{engine, c.quantity}];
    const double ratio = c.error() / c.tolerance();
    w.pass = w.pass && c.agrees();
    if (ratio > w.ratio_to_tolerance) {
      w.ratio_to_tolerance = ratio;
      w.rel_error = c.error() / c.scale;
      w.tolerance_rel = c.tolerance() / c.scale;
      w.phi_deg = phi_deg;
      w.rpm = rpm;
    }
  };
  for (double rpm : m.speed_rpm > 0.0 ? std::vector<double>{m.speed_rpm, 0.0} : std::vector<double>{0.0}) {
    const Mechanism case_m = withSpeed(m, rpm);
    simbody_models::KCrankModel model(case_m);  // also Simbody's second route to Q (virtual power)
    // every other registered engine, exact or soft (engines.h), against the analytic engine
    std::vector<std::pair<std::string, std::unique_ptr<EngineModel>>> others;
    for (const Engine& engine : listEngines())
      if (engine.name != "analytic" && engine.name != "simbody") others.emplace_back(engine.name, engine.build(case_m));
    const Scales sc = calcScales(case_m);
    for (double phi_deg : angles_deg) {
      const double phi = radiansFromDegrees(phi_deg);
      const Evaluation a = analytic::calcEvaluation(case_m, phi);
      for (const Comparison& c : compareEvaluations(case_m, a, model.evaluate(phi))) note("simbody", c, phi_deg, rpm);
      if (rpm == 0.0)
        note("simbody", {"Q (virtual power)", -1, a.Q, model.calcVirtualPowerQ(phi), sc.energy, sc.conditioning}, phi_deg, rpm);
      for (auto& [name, other] : others)
        for (const Comparison& c : compareEvaluations(case_m, a, other->evaluate(phi))) note(name, c, phi_deg, rpm);
    }
  }
  Table t("crosscheck", {{"family", kText}, {"engine", kText}, {"case", kText}, {"lambda", "-"}, {"quantity", kText},
                         {"worst_rel_error", "-"}, {"where_phi_deg", "deg"}, {"where_speed_rpm", "rpm"},
                         {"tolerance_rel", "-"}, {"pass", kText}});
  char case_name[160];
  std::snprintf(case_name, sizeof case_name, "%s lambda=%.4g", m.name.c_str(), lambdaOf(m));
  for (const auto& [key, w] : worst)
    t.rows.push_back({family, key.first, case_name, num(lambdaOf(m)), key.second, num(w.rel_error), num(w.phi_deg),
                      num(w.rpm), num(w.tolerance_rel),
                      findEngine(key.first).gated ? (w.pass ? "pass" : "FAIL") : "reported"});
  return {{"crosscheck", t}};
}

// ------------------------------------------------------------------------------------------------------------
// Maxima over a turn that do not depend on the grid (extremum.h), from the exact harmonics where Q is concerned.

// Q's harmonics with exact Lambda_n up to this order: the tail beyond is below q^100 ~ 1e-28 of Q up to lambda = 0.95
// (q = (lambda / (1 + sqrt(1 - lambda^2)))^2, fourier_series.h).
constexpr int kExactOrder = 200;

std::vector<analytic::TorqueHarmonic> exactHarmonics(const Mechanism& m, Eq5Form form = Eq5Form::kDerived) {
  return analytic::calcGravityTorqueHarmonics(m, kExactOrder, LambdaSource::kExact, form);
}

// The harmonics above `order`: minus the error of the series truncated there (no cancellation: each term is its own
// size, so the error is exact to rounding however small).
std::vector<analytic::TorqueHarmonic> harmonicsAbove(const std::vector<analytic::TorqueHarmonic>& h, int order) {
  std::vector<analytic::TorqueHarmonic> out;
  for (const analytic::TorqueHarmonic& x : h)
    if (x.n > order) out.push_back(x);
  return out;
}

// a - b, harmonic by harmonic.
std::vector<analytic::TorqueHarmonic> harmonicsMinus(const std::vector<analytic::TorqueHarmonic>& a,
                                                     const std::vector<analytic::TorqueHarmonic>& b) {
  std::map<int, analytic::TorqueHarmonic> by_n;
  for (const auto& x : a) by_n[x.n] = x;
  for (const auto& x : b) {
    analytic::TorqueHarmonic& y = by_n[x.n];
    y.n = x.n;
    y.cos_coefficient -= x.cos_coefficient;
    y.sin_coefficient -= x.sin_coefficient;
  }
  std::vector<analytic::TorqueHarmonic> out;
  for (const auto& [n, x] : by_n) out.push_back(x);
  return out;
}

// Samples enough for the maximum of a sum of harmonics: 8 per period of the highest harmonic that is at least 1e-3 of
// the largest (a hump of a smaller one cannot move the maximum by more than its own size), at least 72 (5 degrees).
int samplesFor(const std::vector<analytic::TorqueHarmonic>& h) {
  double largest = 0.0;
  for (const auto& x : h) largest = std::max(largest, std::hypot(x.cos_coefficient, x.sin_coefficient));
  int highest = 1;
  for (const auto& x : h)
    if (std::hypot(x.cos_coefficient, x.sin_coefficient) >= 1e-3 * largest) highest = std::max(highest, x.n);
  return std::max(72, 8 * highest);
}

double maxAbsOfHarmonics(std::vector<analytic::TorqueHarmonic> h) {
  // Harmonics below 1e-18 of the largest cannot move the maximum above rounding (at most 100 of them): left out.
  double largest = 0.0;
  for (const auto& x : h) largest = std::max(largest, std::hypot(x.cos_coefficient, x.sin_coefficient));
  std::erase_if(h, [&](const analytic::TorqueHarmonic& x) { return !(std::hypot(x.cos_coefficient, x.sin_coefficient) >= 1e-18 * largest); });
  if (h.empty()) return 0.0;
  return findMaxAbsOverTurn([&h](double phi) { return analytic::evaluateTorqueHarmonics(h, phi); }, samplesFor(h)).value;
}

// A maximum of a difference computed in double carries an error up to the agreement tolerance (64 eps x scale x
// conditioning, the worst rounding either engine shows); it is known to 1 % only above 100 times that. Below, the
// number is a bound (the quantity is at rounding level), not a measured maximum.
bool resolvedToOnePercent(double rel_value, double conditioning = 1.0) {
  return rel_value > 100.0 * kAgreementMultiple * kEps * conditioning;
}

// The samples of a turn for quantities that hold harmonics up to about n: 6 per period (3 per hump of |f|), at least 48.
int samplesForOrder(int n) { return std::max(48, 6 * n); }

}  // namespace

// The computations of parts 1-8 (campaign_tables.h).
// ------------------------------------------------------------------------------------------------------------
// error_vs_lambda: every approximate method against its exact reference at one lambda. Every maximum is found on the
// same grid in the quick and the full campaign: Q's truncation errors from the exact harmonics, the others by
// refining the best samples (extremum.h); the engines' agreement (rounding) is marked unresolved.

TableSet calcErrorVsLambdaTables(const Mechanism& base, double lambda) {
  const Mechanism m = withLambda(base, lambda);
  const double r = m.crank.radius, w = m.engine.speed;
  const double E = calcEnergyScale(m);
  const Scales sc = calcScales(m);
  Table t("error_vs_lambda", {{"quantity", kText}, {"method", kText}, {"lambda", "-"}, {"max_abs_error", "SI"},
                              {"max_rel_error", "-"}, {"resolved", kText}});
  auto add = [&](const std::string& quantity, const std::string& method, double max_abs, double scale, bool resolved) {
    t.rows.push_back({quantity, method, num(lambda), num(max_abs), num(max_abs / scale), resolved ? "1" : "0"});
  };
  auto direct = [&](const std::string& quantity, const std::string& method, double scale,
                    const std::function<double(double)>& error) {
    const double value = findMaxAbsOverTurn(error, 360).value;
    add(quantity, method, value, scale, resolvedToOnePercent(value / scale));
  };
  direct("x_p", "norton_two_term", r, [&](double phi) {
    return analytic::calcPistonKinematicsNorton(m, phi).x_p - analytic::calcPistonKinematics(m, phi).x_p; });
  direct("v_p", "norton_two_term", r * w, [&](double phi) {
    return analytic::calcPistonKinematicsNorton(m, phi).v_p - analytic::calcPistonKinematics(m, phi).v_p; });
  direct("a_p", "norton_two_term", r * w * w, [&](double phi) {
    return analytic::calcPistonKinematicsNorton(m, phi).a_p - analytic::calcPistonKinematics(m, phi).a_p; });
  const auto exact = exactHarmonics(m);
  for (int order : {2, 4, 6, 8, 10, 12}) {
    const double value = maxAbsOfHarmonics(harmonicsAbove(exact, order));  // truncation error, exact to rounding
    add("Q", "fourier_order_" + std::to_string(order), value, E, true);
  }
  {
    const double value = maxAbsOfHarmonics(harmonicsMinus(analytic::calcGravityTorqueHarmonics(m, 12, LambdaSource::kAsPrinted), exact));
    add("Q", "paper_eq15_printed", value, E, resolvedToOnePercent(value / E));
  }
  {
    const double value = maxAbsOfHarmonics(harmonicsMinus(exactHarmonics(m, Eq5Form::kAsPrinted), exact));
    add("Q", "paper_eq5_printed", value, E, resolvedToOnePercent(value / E));
  }
  direct("U", "paper_eq5_printed", E, [&](double phi) {
    return analytic::calcPotentialEnergy(m, phi, Eq5Form::kAsPrinted) - analytic::calcPotentialEnergy(m, phi); });
  // The engines' agreement: rounding, so a bound (the worst seen at 5 degree steps), never a resolved maximum.
  simbody_models::KCrankModel model(m);
  std::map<std::string, double> worst;
  for (double phi_deg : anglesDeg(5.0)) {
    const double phi = radiansFromDegrees(phi_deg);
    const Evaluation s = model.evaluate(phi), a = analytic::calcEvaluation(m, phi);
    auto track = [&](const std::string& key, double error) { worst[key] = std::max(worst[key], std::fabs(error)); };
    track("Q", a.Q - s.Q);
    track("U", a.U - s.U);
    track("x_p", a.cylinders[0].x_p - s.cylinders[0].x_p);
    track("v_p", a.cylinders[0].v_p - s.cylinders[0].v_p);
    track("a_p", a.cylinders[0].a_p - s.cylinders[0].a_p);
  }
  for (const auto& [quantity, error] : worst) {
    const double scale = quantity == "x_p" ? r : quantity == "v_p" ? r * w : quantity == "a_p" ? r * w * w : E;
    add(quantity, "analytic_vs_simbody", error, scale, resolvedToOnePercent(error / scale, sc.conditioning));
  }
  return {{"error_vs_lambda", t}};
}

// ------------------------------------------------------------------------------------------------------------
// speed_vs_error: cost per evaluation of Q against its error, every method measured in one Google Benchmark run.

TableSet calcSpeedVsErrorTables(const Mechanism& base, bool quick) {
  const Mechanism m = withSpeed(base, 0.0);
  const double E = calcEnergyScale(m);
  const std::vector<double> angles = [&] {
    std::vector<double> v;
    for (double d : anglesDeg(quick ? 30.0 : 5.0)) v.push_back(radiansFromDegrees(d));
    return v;
  }();

  struct Method {
    std::string name;
    std::function<double(double)> eval;   // Q at phi
    std::shared_ptr<simbody_models::KCrankModel> model;
  };
  std::vector<Method> methods;
  auto reduced = std::make_shared<simbody_models::KCrankGravityModel>(m);
  methods.push_back({"simbody_reduced_tol_1e-12", [reduced](double phi) { return reduced->calcHoldingTorque(phi); }, nullptr});
  methods.push_back({"exact_closed_form", [m](double phi) { return analytic::calcGravityTorque(m, phi); }, nullptr});
  for (int order : {2, 4, 6, 8, 12}) {
    auto harmonics = std::make_shared<std::vector<analytic::TorqueHarmonic>>(analytic::calcGravityTorqueHarmonics(m, order));
    methods.push_back({"fourier_order_" + std::to_string(order),
                       [harmonics](double phi) { return analytic::evaluateTorqueHarmonics(*harmonics, phi); }, nullptr});
  }
  auto printed = std::make_shared<std::vector<analytic::TorqueHarmonic>>(
      analytic::calcGravityTorqueHarmonics(m, 12, LambdaSource::kAsPrinted));
  methods.push_back({"paper_eq15_printed", [printed](double phi) { return analytic::evaluateTorqueHarmonics(*printed, phi); }, nullptr});
  for (double tol : quick ? std::vector<double>{1e-4, 1e-12} : std::vector<double>{1e-4, 1e-6, 1e-8, 1e-10, 1e-12}) {
    auto model = std::make_shared<simbody_models::KCrankModel>(m, simbody_models::ModelOptions{tol});
    char name[48];
    std::snprintf(name, sizeof name, "simbody_tol_%.0e", tol);
    methods.push_back({name, [model](double phi) { return model->calcHoldingTorque(phi); }, model});
  }

  // Errors against the exact closed form (the closed form's own error against Simbody at 1e-12): the maximum over the
  // turn, the same in the quick and the full campaign: the Fourier series' from the exact harmonics they leave out, the
  // others by refining the best of 72 samples (extremum.h). resolved = 0: at rounding level, a bound.
  std::map<std::string, std::pair<double, bool>> errors;
  simbody_models::KCrankModel reference(m);
  const auto exact_harmonics = exactHarmonics(m);
  for (const Method& method : methods) {
    double worst = 0.0;
    bool resolved = true;
    if (method.name.rfind("fourier_order_", 0) == 0) {
      worst = maxAbsOfHarmonics(harmonicsAbove(exact_harmonics, std::stoi(method.name.substr(14))));
    } else if (method.name == "paper_eq15_printed") {
      worst = maxAbsOfHarmonics(harmonicsMinus(*printed, exact_harmonics));
      resolved = resolvedToOnePercent(worst / E);
    } else {
      const bool closed_form = method.name == "exact_closed_form";
      worst = findMaxAbsOverTurn([&](double phi) {
                return method.eval(phi) - (closed_form ? reference.calcHoldingTorque(phi) : analytic::calcGravityTorque(m, phi));
              }, 72).value;
      resolved = resolvedToOnePercent(worst / E, calcScales(m).conditioning);
    }
    errors[method.name] = {worst / E, resolved};
  }
  std::vector<std::pair<std::string, std::function<void()>>> timed;
  for (const Method& method : methods) {
    auto counter = std::make_shared<size_t>(0);
    timed.emplace_back(method.name, [method, counter, angles] {
      const double phi = angles[(*counter)++ % angles.size()];
      benchmark::DoNotOptimize(method.eval(phi));
    });
  }
  // The same methods where they also have a batch form (issue 14): the SIMD kernels on arbitrary angles and on a
  // uniform grid (batch.h), and Simbody over a grid by superposing one-cylinder models (grid_sweep.h). Each call
  // evaluates a whole batch; the table gives ns per angle.
  constexpr size_t kBatch = 4096;
  const size_t simbody_grid = quick ? 72 : 360;
  auto batch_angles = std::make_shared<std::vector<double>>(kBatch);
  for (size_t i = 0; i < kBatch; ++i)  // the same turn, not a grid: each angle nudged off the sample
    (*batch_angles)[i] = angles[i % angles.size()] + 1e-3 * static_cast<double>(i / angles.size());
  auto batch_out = std::make_shared<std::vector<double>>(kBatch);
  const double grid_step = 2.0 * M_PI / static_cast<double>(kBatch);
  struct BatchMethod {
    std::string name;
    size_t angles_per_call;
    std::function<void()> run;  // fills *batch_out (Simbody: its own grid)
  };
  const std::vector<BatchMethod> batch_methods = {
      {"exact_closed_form_batch", kBatch, [m, batch_angles, batch_out] {
         analytic::calcGravityTorqueBatch(m, *batch_angles, *batch_out);
         benchmark::DoNotOptimize(batch_out->data());
       }},
      {"exact_closed_form_grid", kBatch, [m, batch_out, grid_step] {
         analytic::calcGravityTorqueOnGrid(m, 0.0, grid_step, *batch_out);
         benchmark::DoNotOptimize(batch_out->data());
       }},
      {"simbody_grid_superposition", simbody_grid, [m, simbody_grid] {
         benchmark::DoNotOptimize(simbody_models::calcHoldingTorqueOnGrid(m, 0.0, 2.0 * M_PI / static_cast<double>(simbody_grid), simbody_grid));
       }},
  };
  {
    // Their errors: the kernels against the scalar closed form (rounding: a bound), Simbody's sums against it.
    std::vector<double> batch(kBatch), grid(kBatch);
    analytic::calcGravityTorqueBatch(m, *batch_angles, batch);
    analytic::calcGravityTorqueOnGrid(m, 0.0, grid_step, grid);
    double worst_batch = 0.0, worst_grid = 0.0, worst_sweep = 0.0;
    for (size_t i = 0; i < kBatch; ++i) {
      worst_batch = std::max(worst_batch, std::fabs(batch[i] - analytic::calcGravityTorque(m, (*batch_angles)[i])));
      worst_grid = std::max(worst_grid, std::fabs(grid[i] - analytic::calcGravityTorque(m, static_cast<double>(i) * grid_step)));
    }
    const std::vector<double> sweep =
        simbody_models::calcHoldingTorqueOnGrid(m, 0.0, 2.0 * M_PI / static_cast<double>(simbody_grid), simbody_grid);
    for (size_t i = 0; i < simbody_grid; ++i)
      worst_sweep = std::max(worst_sweep, std::fabs(sweep[i] - analytic::calcGravityTorque(m, 2.0 * M_PI * static_cast<double>(i) /
                                                                                               static_cast<double>(simbody_grid))));
    errors["exact_closed_form_batch"] = {worst_batch / E, false};
    errors["exact_closed_form_grid"] = {worst_grid / E, false};
    errors["simbody_grid_superposition"] = {worst_sweep / E, resolvedToOnePercent(worst_sweep / E, calcScales(m).conditioning)};
  }
  for (const BatchMethod& b : batch_methods) timed.emplace_back(b.name, b.run);
  const std::map<std::string, double> ns = measureNanosecondsPerCall(timed, quick ? 0.01 : 0.05);
  Table t("speed_vs_error", {{"method", kText}, {"ns_per_eval", "ns"}, {"max_rel_error", "-"}, {"resolved", kText}});
  for (const Method& method : methods) {
    const auto it = ns.find(method.name);
    if (it != ns.end())
      t.rows.push_back({method.name, num(it->second), num(errors[method.name].first), errors[method.name].second ? "1" : "0"});
  }
  for (const BatchMethod& b : batch_methods) {
    const auto it = ns.find(b.name);
    if (it != ns.end())
      t.rows.push_back({b.name, num(it->second / static_cast<double>(b.angles_per_call)), num(errors[b.name].first),
                        errors[b.name].second ? "1" : "0"});
  }
  return {{"speed_vs_error", t}};
}

// ------------------------------------------------------------------------------------------------------------
// harmonics: DFT of Simbody's Q over one turn, against the analytic prediction and the paper's claim.

TableSet calcHarmonicsTables(const Mechanism& base, Cycle cycle) {
  const int M = 64, max_order = 24;
  Table t("harmonics", {{"cycle", kText}, {"k", "-"}, {"n", "-"}, {"simbody_amplitude", "N m"},
                        {"analytic_amplitude", "N m"}, {"paper_nonzero", kText}});
  for (int k = 1; k <= 12; ++k) {
    const Mechanism m = withSpeed(withGamma(withCylinders(withLambda(base, 0.4), k, cycle), 90.0), 0.0);
    const double E = calcEnergyScale(m);
    simbody_models::KCrankGravityModel model(m);  // U and Q only: the reduced model suffices
    std::vector<double> q(M);
    for (int i = 0; i < M; ++i) q[i] = model.calcHoldingTorque(2.0 * M_PI * i / M);
    std::map<int, double> predicted;
    for (const analytic::TorqueHarmonic& h : analytic::calcGravityTorqueHarmonics(m, max_order))
      predicted[h.n] = std::hypot(h.cos_coefficient, h.sin_coefficient);
    for (int n = 1; n <= max_order; ++n) {
      std::complex<double> sum = 0.0;
      for (int i = 0; i < M; ++i) sum += q[i] * std::polar(1.0, -2.0 * M_PI * n * i / M);
      const double amplitude = 2.0 * std::abs(sum) / M;
      const std::optional<bool> claim = analytic::getPaperHarmonicClaim(k, cycle, n);
      t.rows.push_back({toString(cycle), std::to_string(k), std::to_string(n), num(amplitude / E),
                        num(predicted.count(n) ? predicted[n] / E : 0.0), claim ? (*claim ? "1" : "0") : ""});
    }
  }
  return {{"harmonics", t}};
}

// ------------------------------------------------------------------------------------------------------------
// gravity_significance: max |Q| against k, relative to k = 1 and to the inertia torque at the scene's speed. The
// analytic maximum is that of Q's exact harmonics (no cancellation: exact however small); Simbody's is found on the
// same grid, refined the same way (extremum.h); below the agreement tolerance Simbody's is a bound, not a value.

TableSet calcGravitySignificanceTables(const Mechanism& base, Cycle cycle) {
  Table t("gravity_significance", {{"cycle", kText}, {"k", "-"}, {"max_abs_Q", "N m"}, {"ratio_to_k1", "-"},
                                   {"max_inertia_torque", "N m"}, {"ratio_to_inertia", "-"},
                                   {"simbody_max_abs_Q", "N m"}, {"resolved", kText}, {"first_order", "-"},
                                   {"simbody_bound", "N m"}, {"simbody_ratio_to_k1", "-"},
                                   {"paper_negligible", kText}});
  double q1 = 0.0, q1_simbody = 0.0;
  for (int k = 1; k <= 12; ++k) {
    const Mechanism m = withGamma(withCylinders(base, k, cycle), 90.0);
    const auto harmonics = exactHarmonics(m);
    const int first = harmonics.empty() ? 0 : harmonics.front().n;
    const int samples = samplesForOrder(first);
    const double max_q = maxAbsOfHarmonics(harmonics);
    const double max_inertia = findMaxAbsOverTurn([&](double phi) {
      return analytic::calcReactions(m, phi).drive_torque - analytic::calcGravityTorque(m, phi); }, samples).value;
    simbody_models::KCrankGravityModel model(withSpeed(m, 0.0));
    // Every hump of |Q| is the same height to rounding (the first surviving harmonic dominates by 1 / lambda^2), so two
    // refinements find the maximum.
    const double max_q_simbody = findMaxAbsOverTurn([&](double phi) { return model.calcHoldingTorque(phi); }, samples, 2).value;
    if (k == 1) q1 = max_q, q1_simbody = max_q_simbody;
    // Below the agreement tolerance an engine's Q(phi) is rounding, not physics (CONVENTIONS.md: tiny values are
    // compared absolutely against the scale): Simbody then shows only that |Q| is below the bound.
    const double bound = kAgreementMultiple * kEps * calcEnergyScale(m);
    const bool resolved = max_q_simbody > bound;
    const bool paper_negligible = k == 7 || k == 9 || k == 11;  // Stanczak section 7
    t.rows.push_back({toString(cycle), std::to_string(k), num(max_q), num(max_q / q1), num(max_inertia),
                      num(max_inertia > 0 ? max_q / max_inertia : 0.0), num(max_q_simbody), resolved ? "yes" : "no",
                      std::to_string(first), num(bound),
                      num(resolved ? max_q_simbody / q1_simbody : bound / q1_simbody), paper_negligible ? "1" : "0"});
  }
  return {{"gravity_significance", t}};
}

// ------------------------------------------------------------------------------------------------------------
// norton_fig13_8: piston motion over two revolutions, exact and two-term (Norton's figure 13-8).

TableSet calcNortonFigureTables(const Mechanism& base) {
  Table t("norton_fig13_8", {{"crank_angle_deg", "deg"}, {"x_exact", "m"}, {"x_two_term", "m"}, {"v_exact", "m/s"},
                             {"v_two_term", "m/s"}, {"a_exact", "m/s^2"}, {"a_two_term", "m/s^2"}});
  for (int d = 0; d <= 720; ++d) {
    const double theta = radiansFromDegrees(d);
    const analytic::PistonKinematics e = analytic::calcPistonKinematics(base, theta);
    const analytic::PistonKinematics n = analytic::calcPistonKinematicsNorton(base, theta);
    t.rows.push_back({std::to_string(d), num(e.x_p), num(n.x_p), num(e.v_p), num(n.v_p), num(e.a_p), num(n.a_p)});
  }
  return {{"norton_fig13_8", t}};
}

// ------------------------------------------------------------------------------------------------------------
// errata: each printed formula against what the engines agree on, at its real size: per layout and engine where
// it is largest, every maximum over a turn from the exact harmonics (or refined, extremum.h). Tables:
//   errata             item,printed,holds,measure,value,verdict
//   eq5_layouts        cycle,k,gamma_deg,max_abs_Q,max_abs_Q_printed,ratio_of_maxima,max_error_rel
//   eq15_coefficients  n,lambda,printed,exact,relative_error
//   eq15_engines       cycle,k,lambda,first_order,max_abs_Q,max_abs_Q_printed,ratio_of_maxima,max_error_rel

TableSet calcErrataTables(const Mechanism& base) {
  Table t("errata", {{"item", kText}, {"printed", kText}, {"holds", kText}, {"measure", kText},
                     {"value", "see measure"}, {"verdict", kText}});
  auto add = [&](const std::string& item, const std::string& printed, const std::string& holds, const std::string& measure,
                 double value, const std::string& verdict) {
    t.rows.push_back({item, printed, holds, measure, num(value), verdict});
  };
  const Mechanism rest = withSpeed(base, 0.0);
  char text[256];
  {  // eq (5): the coefficients, then Q of every layout
    const analytic::GravityCoefficients c = analytic::calcGravityCoefficients(rest);
    const analytic::GravityCoefficients p = analytic::calcGravityCoefficients(rest, Eq5Form::kAsPrinted);
    std::snprintf(text, sizeof text, "Stanczak eq (5): U1 for the base rod (z_k / l = %.3f)",
                  rest.rod.com_from_wrist_pin / rest.rod.length);
    add(text, "U1 = M_t + l_z M_z, l_z = z_k / l", "U1 with (l - z_k) / l (z_k from the wrist pin, eq 2)",
        "printed / true", p.U1 / c.U1, "error");
    std::snprintf(text, sizeof text, "Stanczak eq (5): U2 for the base rod (z_k / l = %.3f)",
                  rest.rod.com_from_wrist_pin / rest.rod.length);
    add(text, "U2 = M_s - M_sp + l_z* M_z, l_z* = (l - z_k) / l", "U2 with z_k / l", "printed / true", p.U2 / c.U2, "error");
  }
  Table layouts("eq5_layouts", {{"cycle", kText}, {"k", "-"}, {"gamma_deg", "deg"}, {"max_abs_Q", "N m"},
                                {"max_abs_Q_printed", "N m"}, {"ratio_of_maxima", "-"}, {"max_error_rel", "-"}});
  struct Worst {
    double error = -1.0, ratio = 0.0;
    std::string where;
  };
  std::map<double, Worst> worst_single, worst_multi;  // by gamma
  for (double gamma : {90.0, 0.0, -90.0, 37.0})
    for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke})
      for (int k = 1; k <= 12; ++k) {
        if (k == 1 && cycle == Cycle::kFourStroke) continue;  // the same single cylinder
        const Mechanism m = withGamma(withCylinders(rest, k, cycle), gamma);
        const auto exact = exactHarmonics(m), printed = exactHarmonics(m, Eq5Form::kAsPrinted);
        const double q = maxAbsOfHarmonics(exact), q_printed = maxAbsOfHarmonics(printed);
        if (q <= kAgreementMultiple * kEps * calcEnergyScale(m)) continue;  // Q vanishes (or is rounding): nothing to err
        const double error = maxAbsOfHarmonics(harmonicsMinus(printed, exact)) / q;
        layouts.rows.push_back({toString(cycle), std::to_string(k), num(gamma), num(q), num(q_printed), num(q_printed / q), num(error)});
        Worst& w = (k == 1 ? worst_single : worst_multi)[gamma];
        if (error > w.error + 1e-12) {
          std::snprintf(text, sizeof text, "k = %d %s", k, toString(cycle).c_str());
          w = {error, q_printed / q, text};
        }
      }
  for (const auto& [which, map] : {std::pair<std::string, const std::map<double, Worst>&>{"single cylinder", worst_single},
                                   std::pair<std::string, const std::map<double, Worst>&>{"multi-cylinder", worst_multi}})
    for (const auto& [gamma, w] : map) {
      const std::string layout = gamma == 90.0 ? "standing" : gamma == 0.0 ? "lying" : gamma == -90.0 ? "hanging" : "inclined 37 deg";
      std::snprintf(text, sizeof text, "Stanczak eq (5): Q of a %s %s, worst: %s", layout.c_str(), which.c_str(),
                    which == "single cylinder" ? "k = 1" : w.where.c_str());
      add(text, "U1, U2 as printed", "U1, U2 from eq (2)", "max |Q_printed - Q| / max |Q|", w.error, "error");
      add(text, "U1, U2 as printed", "U1, U2 from eq (2)", "max |Q_printed| / max |Q|", w.ratio, "error");
    }
  // eq (15): each printed Lambda_n against the exact one, at lambda = 0.4 (the paper's largest) and the base's.
  Table coefficients("eq15_coefficients", {{"n", "-"}, {"lambda", "-"}, {"printed", "-"}, {"exact", "-"},
                                           {"relative_error", "-"}});
  const double base_lambda = lambdaOf(base);
  for (double lambda : {0.4, base_lambda}) {
    const std::vector<double> exact = analytic::calcLambdaCoefficients(lambda, 12);
    const std::vector<double> printed = analytic::calcLambdaCoefficientsAsPrinted(lambda, 12);
    for (int n = 2; n <= 12; n += 2) {
      coefficients.rows.push_back({std::to_string(n), num(lambda), num(printed[n]), num(exact[n]), num(printed[n] / exact[n] - 1.0)});
      if (n >= 8) {
        std::snprintf(text, sizeof text, "Stanczak eq (15): Lambda_%d at lambda = %.3g", n, lambda);
        add(text, "power series to lambda^11", "exact Lambda_n (fourier_series.h)", "printed / exact - 1", printed[n] / exact[n] - 1.0,
            "truncation");
      }
    }
  }
  {  // the printed coefficients: how many, and how many are the exact rationals rounded to six decimals
    int count = 0, rounded = 0;
    for (int n = 2; n <= 12; n += 2)
      for (int power = 1; power <= 11; power += 2) {
        const double printed = analytic::getLambdaSeriesCoefficientAsPrinted(n, power);
        if (printed == 0.0) continue;
        ++count;
        const double exact = analytic::calcLambdaSeriesCoefficient(n, power).toDouble();
        if (std::fabs(std::round(exact * 1e6) / 1e6 - printed) < 1e-12) ++rounded;
      }
    add("Stanczak eq (15): printed coefficients", "Lambda_2..Lambda_12, lambda^1..lambda^11", "exact rationals",
        "count printed", count, "count");
    add("Stanczak eq (15): printed coefficients", "six decimals", "exact rational rounded to six decimals",
        "count equal to the rounded exact value", rounded, "count");
    const double printed = analytic::getLambdaSeriesCoefficientAsPrinted(2, 9);
    const double exact = analytic::calcLambdaSeriesCoefficient(2, 9).toDouble();
    add("Stanczak eq (15): Lambda_2 coefficient of lambda^9", "0.022432", "735/32768 = 0.02243041992",
        "printed / exact - 1", printed / exact - 1.0, "misprint");
  }
  // eq (15) in the engines where only high harmonics survive: standing engines, every k, both strokes.
  Table engines("eq15_engines", {{"cycle", kText}, {"k", "-"}, {"lambda", "-"}, {"first_order", "-"},
                                 {"max_abs_Q", "N m"}, {"max_abs_Q_printed", "N m"}, {"ratio_of_maxima", "-"},
                                 {"max_error_rel", "-"}});
  for (double lambda : {0.4, base_lambda})
    for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke})
      for (int k = 1; k <= 12; ++k) {
        const Mechanism m = withGamma(withCylinders(withLambda(rest, lambda), k, cycle), 90.0);
        const auto exact = exactHarmonics(m);
        const auto printed = analytic::calcGravityTorqueHarmonics(m, 12, LambdaSource::kAsPrinted);
        const double q = maxAbsOfHarmonics(exact), q_printed = maxAbsOfHarmonics(printed);
        const double error = maxAbsOfHarmonics(harmonicsMinus(printed, exact)) / q;
        engines.rows.push_back({toString(cycle), std::to_string(k), num(lambda), std::to_string(exact.front().n), num(q),
                                num(q_printed), num(q_printed / q), num(error)});
        // Engines whose first harmonic the table holds and where the truncation costs more than 1 % (the others:
        // data/eq15_engines.csv; for k = 7, 9, 11 the table has no harmonic at all and gives Q = 0).
        if (exact.front().n <= 12 && error > 0.01) {
          std::snprintf(text, sizeof text, "Stanczak eq (15): Q of a standing k = %d %s at lambda = %.3g", k, toString(cycle).c_str(), lambda);
          add(text, "Lambda_2..Lambda_12 to lambda^11", "exact Lambda_n", "max |Q_printed - Q| / max |Q|", error, "truncation");
        }
      }
  // Section 7: "for example k = 7 first gives a non-zero value at Lambda_14": the first surviving order of k = 7, 9, 11.
  for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke})
    for (int k : {7, 9, 11}) {
      const std::vector<int> survivors = analytic::findSurvivingHarmonics(k, cycle, Acting::kSingle, 4 * k);
      std::snprintf(text, sizeof text, "Stanczak section 7: first surviving order, k = %d %s", k, toString(cycle).c_str());
      add(text, k == 7 ? "for example k = 7: first non-zero at Lambda_14" : "(not stated)", "exact integer analysis",
          "harmonic order", survivors.empty() ? 0 : survivors.front(), "confirmed");
    }
  {  // eq (12): each cylinder referred to its own outer dead centre: a zero level, not an error
    const Mechanism m3 = withCylinders(rest, 3, Cycle::kTwoStroke);
    Mechanism single = withCylinders(rest, 1, Cycle::kTwoStroke);
    double offset = 0.0;
    for (double alpha : m3.engine.crank_angles) offset += analytic::calcPotentialEnergy(single, alpha);
    add("Stanczak eq (12): U_w(0) of a standing three-cylinder two-stroke [J]", "sum of eq (3) per cylinder (U_w(0) != 0)",
        "a choice of zero level; crankcheck uses U = V(phi) - V(0); Q is the same", "U_w(0) [J]", offset, "not an error");
  }
  {  // eq (13): correct; the naming
    simbody_models::KCrankGravityModel model(rest);
    const double value = findMaxAbsOverTurn([&](double phi) {
      return analytic::calcGravityTorque(rest, phi) - model.calcHoldingTorque(phi); }, 72).value;
    add("Stanczak eq (13): Q* = dU*/dphi, called the Lagrange force", "Q* = dU*/dphi",
        "correct as dU/dphi (the torque that holds the shaft); the force in Lagrange's equation is -dU/dphi",
        "max |Q - Simbody's holding torque| / energy scale", value / calcEnergyScale(rest), "correct (naming)");
  }
  {  // Norton 13.3e, against Simbody's piston acceleration
    simbody_models::KCrankModel model(base);
    const double r = base.crank.radius, w = base.engine.speed;
    const double worst = findMaxAbsOverTurn([&](double phi) {
      return analytic::calcPistonKinematicsNorton(base, phi).a_p - model.evaluate(phi).cylinders[0].a_p; }, 72).value;
    std::snprintf(text, sizeof text, "Norton 13.3e: piston acceleration at lambda = %.3g", lambdaOf(base));
    add(text, "-r w^2 (cos + lambda cos 2theta)", "exact (Simbody)", "max |a_two_term - a| / (r w^2)", worst / (r * w * w),
        "approximation");
  }
  return {{"errata", t}, {"eq5_layouts", layouts}, {"eq15_coefficients", coefficients}, {"eq15_engines", engines}};
}

// ------------------------------------------------------------------------------------------------------------
// delta_vs_k: the free run's speed fluctuation with and without gravity, k = 1..12, both strokes, a few speeds.

TableSet calcDeltaVsKTables(const Mechanism& base, Cycle cycle, bool quick) {
  Table t("delta_vs_k", {{"cycle", kText}, {"k", "-"}, {"speed_rpm", "rpm"}, {"delta_gravity", "-"},
                         {"delta_no_gravity", "-"}, {"delta_due_to_gravity", "-"}});
  for (int k = 1; k <= 12; ++k)
    for (double rpm : quick ? std::vector<double>{300.0, 6000.0} : std::vector<double>{60.0, 300.0, 1500.0, 6000.0}) {
      const Mechanism m = withSpeed(withGamma(withCylinders(base, k, cycle), 90.0), rpm);
      double with = std::nan(""), without = std::nan("");
      try {
        with = analytic::calcFreeRun(m, m.engine.speed, true).delta;
        without = analytic::calcFreeRun(m, m.engine.speed, false).delta;
      } catch (const std::domain_error&) {  // too slow to turn over against gravity: no free run to report
      }
      t.rows.push_back({toString(cycle), std::to_string(k), num(rpm), num(with), num(without), num(std::fabs(with - without))});
    }
  return {{"delta_vs_k", t}};
}

// ------------------------------------------------------------------------------------------------------------
// integrator_pareto: Simbody's free run by each integrator and accuracy: cost per simulated revolution (one Google
// Benchmark run) against the error of delta and the energy drift, the analytic energy integral as reference.

TableSet calcIntegratorParetoTables(const Mechanism& base, bool quick) {
  const Mechanism m = withSpeed(base, 300.0);
  const analytic::FreeRun exact = analytic::calcFreeRun(m, m.engine.speed, true);
  struct Run {
    simbody_models::FreeRunOptions options;
    std::string name;
  };
  std::vector<Run> runs;
  const std::vector<double> accuracies = quick ? std::vector<double>{1e-4, 1e-8} : std::vector<double>{1e-3, 1e-4, 1e-6, 1e-8, 1e-10};
  for (simbody_models::IntegratorKind kind : {simbody_models::IntegratorKind::kRungeKuttaMerson, simbody_models::IntegratorKind::kCPodes,
                                              simbody_models::IntegratorKind::kSemiExplicitEuler2})
    for (double accuracy : accuracies) {
      // SemiExplicitEuler2 is first order: below 1e-6 it needs millions of steps per revolution.
      if (kind == simbody_models::IntegratorKind::kSemiExplicitEuler2 && accuracy < 1e-6) continue;
      simbody_models::FreeRunOptions options;
      options.integrator = kind;
      options.accuracy = accuracy;
          char name[64];
      std::snprintf(name, sizeof name, "%s %.0e", simbody_models::toString(kind).c_str(), accuracy);
      runs.push_back({options, name});
    }
  Table t("integrator_pareto", {{"integrator", kText}, {"accuracy", "-"}, {"ns_per_revolution", "ns"},
                                {"delta_error", "-"}, {"energy_drift", "-"}, {"status", kText}});
  // Each run is timed by Google Benchmark and keeps its last result, so that no run is integrated twice just for
  // its error (a run that fails is reported as failed).
  std::vector<std::pair<std::string, std::function<void()>>> timed;
  std::map<std::string, std::shared_ptr<simbody_models::FreeRunResult>> results;
  std::map<std::string, std::shared_ptr<std::string>> failures;
  for (const Run& run : runs) {
    auto result = results[run.name] = std::make_shared<simbody_models::FreeRunResult>();
    auto failure = failures[run.name] = std::make_shared<std::string>();
    timed.emplace_back(run.name, [m, options = run.options, result, failure] {
      if (!failure->empty()) return;
      try {
        *result = simbody_models::simulateFreeRun(m, m.engine.speed, options);
      } catch (const std::exception& e) {
        *failure = e.what();
      }
      benchmark::DoNotOptimize(result->delta);
    });
  }
  const std::map<std::string, double> ns = measureNanosecondsPerCall(timed, 0.01);
  for (const Run& run : runs) {
    const std::string integrator = simbody_models::toString(run.options.integrator);
    const simbody_models::FreeRunResult& result = *results[run.name];
    const auto time = ns.find(run.name);
    if (!failures[run.name]->empty() || time == ns.end()) {
      t.rows.push_back({integrator, num(run.options.accuracy), "nan", "nan", "nan", "failed"});
      continue;
    }
    t.rows.push_back({integrator, num(run.options.accuracy), num(time->second / run.options.revolutions),
                      num(std::fabs(result.delta - exact.delta) / exact.delta), num(result.energy_drift_per_revolution), "ok"});
  }
  return {{"integrator_pareto", t}};
}

namespace {

TableSet scenesTable(const std::vector<std::pair<std::string, Mechanism>>& families) {
  Table t("scenes", {{"family", kText}, {"scene", kText}, {"cylinders", "-"}, {"cycle", kText}, {"acting", kText},
                     {"gamma_deg", "deg"}, {"speed_rpm", "rpm"}, {"r", "m"}, {"l", "m"}, {"lambda", "-"}, {"m_o", "kg"},
                     {"m_k", "kg"}, {"z_k", "m"}, {"I_o", "kg m^2"}, {"m_s", "kg"}, {"r_s", "m"}, {"m_p", "kg"},
                     {"r_p", "m"}, {"g", "m/s^2"}, {"I_w", "kg m^2"}});
  for (const auto& [family, m] : families)
    t.rows.push_back({family, m.name, std::to_string(m.engine.cylinders), toString(m.engine.cycle), toString(m.engine.acting),
                      num(degreesFromRadians(m.engine.cylinder_angle)), num(m.speed_rpm), num(m.crank.radius),
                      num(m.rod.length), num(lambdaOf(m)), num(m.piston.mass), num(m.rod.mass),
                      num(m.rod.com_from_wrist_pin), num(m.rod.inertia_about_wrist_pin), num(m.crank.mass),
                      num(m.crank.com_radius), num(m.crank.counterweight_mass), num(m.crank.counterweight_radius),
                      num(m.engine.gravity), m.flywheel_inertia ? num(*m.flywheel_inertia) : std::string()});
  return {{"scenes", t}};
}

}  // namespace

std::vector<Mechanism> buildDefaultScenes() {
  std::vector<Mechanism> scenes;
  for (double gamma : {90.0, 0.0, 180.0, -90.0})
    scenes.push_back(makeScene("single_cylinder_four_" + gammaTag(gamma), 1, Cycle::kFourStroke, gamma, 3000.0));
  for (int k : {2, 3, 4, 6, 8, 12})
    for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke}) {
      const bool two = cycle == Cycle::kTwoStroke;
      scenes.push_back(makeScene("inline" + std::to_string(k) + (two ? "_two_" : "_four_") + gammaTag(90.0), k, cycle,
                                 90.0, two ? 3000.0 : 6000.0));
    }
  for (double gamma : {0.0, 180.0, -90.0})
    scenes.push_back(makeScene("inline4_four_" + gammaTag(gamma), 4, Cycle::kFourStroke, gamma, 6000.0));
  // Marine scale: a slow two-stroke crosshead diesel (scenes/inline6_two_stroke_marine.toml).
  Mechanism marine = makeScene("marine_inline6_two_gamma90", 6, Cycle::kTwoStroke, 90.0, 105.0);
  marine.crank = {1.2, 9000.0, 0.6, 6000.0, 0.9};
  marine.rod = {3.0, 12000.0, 1.9, 55000.0};
  marine.piston.mass = 14000.0;
  marine.flywheel_inertia = 9.0e5;
  scenes.push_back(marine);
  // Small-engine scale: a 50 cm^3 single-cylinder two-stroke.
  Mechanism small = makeScene("small_engine_single_two_gamma90", 1, Cycle::kTwoStroke, 90.0, 9000.0);
  small.crank = {0.02, 0.15, 0.008, 0.1, 0.014};
  small.rod = {0.075, 0.035, 0.05, 1.2e-4};
  small.piston.mass = 0.06;
  small.flywheel_inertia = 0.004;
  scenes.push_back(small);
  return scenes;
}

Mechanism findMarineScene() {
  for (const Mechanism& m : buildDefaultScenes())
    if (m.name.rfind("marine", 0) == 0) return m;
  throw std::logic_error("campaign: no built-in marine scene");
}

std::string familyOf(const Mechanism& m) {
  const std::string& n = m.name;
  if (n.rfind("single_cylinder", 0) == 0) return "single cylinder (gamma 90/0/180/-90)";
  if (n.rfind("inline4_four_gamma", 0) == 0 && n != "inline4_four_gamma90") return "inline 4 four-stroke (gamma 0/180/-90)";
  if (n.rfind("inline", 0) == 0) return n.find("_two_") != std::string::npos ? "inline two-stroke (k = 2..12)" : "inline four-stroke (k = 2..12)";
  if (n.rfind("marine", 0) == 0) return "marine scale (inline 6 two-stroke)";
  if (n.rfind("small_engine", 0) == 0) return "small-engine scale (50 cm^3)";
  return n;
}

std::vector<Mechanism> loadExampleScenes() {
  const std::filesystem::path dir = findScenesDir();
  std::vector<std::filesystem::path> files;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
    if (entry.path().extension() == ".toml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  std::vector<Mechanism> scenes;
  for (const auto& file : files) scenes.push_back(loadSceneFile(file));
  return scenes;
}

std::vector<Task> buildCampaign(const CampaignOptions& options) {
  const bool quick = options.quick;
  const std::vector<Mechanism> scenes = options.scenes.empty() ? buildDefaultScenes() : options.scenes;
  // (family of cases, scene): the built-in scenes are grouped into families, user scenes are their own family.
  std::vector<std::pair<std::string, Mechanism>> families;
  for (const Mechanism& m : scenes) families.emplace_back(options.scenes.empty() ? familyOf(m) : m.name, m);
  // The paper's figures (parts 1-7) are about one bank of cylinders: a layout's base scene gives them its parts as
  // a standing inline engine of the same k and cycle, and the report says so.
  const Mechanism& first = scenes.front();
  Mechanism base = isSingleBank(first) ? first : withGamma(withCylinders(first, first.engine.cylinders, first.engine.cycle), 90.0);
  // The paper's figures are about centric cylinders: an offset base scene gives them its parts centric (part 14 and the
  // cross-checks show the offset engine itself).
  const bool offset_base = hasPinOffsets(base) || !base.balance_shafts.empty();
  base.engine.pin_offsets.clear();
  base.balance_shafts.clear();

  std::vector<Task> tasks;
  Table notes("notes", {{"note", kText}});
  if (!isSingleBank(first))
    notes.rows.push_back({"The first scene, " + first.name + ", has cylinders in more than one bank; the figures of parts "
                          "1-7, written for the paper's inline engine, use its parts as a standing inline engine of "
                          "the same cylinder count and cycle. Its own layout is cross-checked in the summary."});
  if (offset_base)
    notes.rows.push_back({"The first scene, " + first.name + ", has pin offsets or balance shafts; the figures of parts 1-7, "
                          "written for the paper's centric engine without shafts, use its parts without them. Its own "
                          "engine is cross-checked in the summary, and part 14 shows what an offset changes."});
  tasks.push_back({"scenes", false, [families] { return scenesTable(families); }});
  // The user's scenes, or the example scenes (scenes/*.toml) in the default campaign: parts 12, 15 and 16.
  std::vector<Mechanism> pin_scenes = options.scenes;
  if (pin_scenes.empty()) pin_scenes = loadExampleScenes();
  const std::vector<double> sweep = quick ? std::vector<double>{} : std::vector<double>{0.1, 0.2, 0.3, 0.4, 0.6, 0.9};
  for (const auto& [family, m] : families) {
    std::vector<double> lambdas = {lambdaOf(m)};
    // A pin offset needs |delta| < l - r: the rod changed to lambda must still reach the crank pin at every angle.
    const double offset = calcLoopRatio(m) * m.rod.length - m.crank.radius;  // max |delta_j|
    for (double lambda : sweep)
      if (std::fabs(lambda - lambdaOf(m)) > 1e-3 && offset < m.crank.radius / lambda - m.crank.radius) lambdas.push_back(lambda);
    for (double lambda : lambdas) {
      const Mechanism variant = withLambda(m, lambda);
      char id[128];
      std::snprintf(id, sizeof id, "crosscheck %s lambda=%.3g", m.name.c_str(), lambda);
      const std::vector<double> angles = anglesDeg(quick ? 45.0 : 15.0);
      tasks.push_back({id, false, [family = family, variant, angles] { return crossCheckCase(family, variant, angles); },
                       task_cost::kCrossCheck});
    }
  }
  // The gate's sweep (tests/gate): every k and stroke over lambda and gamma, at the gate's crank angles (both dead
  // centres and quarter turns), at speed and at rest. Only with the built-in campaign.
  if (options.scenes.empty()) {
    const std::vector<double> sweep_lambdas =
        quick ? std::vector<double>{0.3, 0.999}
              : std::vector<double>{1e-6, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.9, 0.999};
    const std::vector<double> sweep_gammas = quick ? std::vector<double>{90.0, 37.0} : std::vector<double>{0.0, 180.0, 90.0, -90.0, 37.0};
    const std::vector<double> gate_angles = {0.0, 17.0, 45.0, 90.0, 133.0, 180.0, 222.5, 270.0, 300.0, 359.0, -60.0};
    for (int k = 12; k >= 1; --k)
      for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke}) {
        const bool two = cycle == Cycle::kTwoStroke;
        const std::string family = std::string("gate sweep ") + (two ? "two" : "four") + "-stroke (k = 1..12)";
        const Mechanism kbase = withSpeed(withCylinders(base, k, cycle), two ? 3000.0 : 6000.0);
        tasks.push_back({"sweep k=" + std::to_string(k) + " " + toString(cycle), false,
                         [family, kbase, k, two, sweep_lambdas, sweep_gammas, gate_angles] {
                           TableSet out;
                           for (double lambda : sweep_lambdas)
                             for (double gamma : sweep_gammas) {
                               Mechanism variant = withGamma(withLambda(kbase, lambda), gamma);
                               char name[96];
                               std::snprintf(name, sizeof name, "k%d_%s_%s", k, two ? "two" : "four", gammaTag(gamma).c_str());
                               variant.name = name;
                               appendTables(out, crossCheckCase(family, variant, gate_angles));
                             }
                           return out;
                         },
                         task_cost::kGateSweep});
      }
  }
  // The free run (parts 6 and 7) needs the base scene's flywheel; without one those parts are left out, and the
  // report says so: crankcheck invents no inertia on the user's behalf.
  if (!base.flywheel_inertia)
    notes.rows.push_back({"Parts 6 and 7 (the free run) are left out: the base scene " + base.name +
                          " has no [flywheel] inertia and crankcheck does not assume one. Give the first scene a "
                          "[flywheel] table to get them."});
  if (!notes.rows.empty()) tasks.push_back({"notes", false, [notes] { return TableSet{{"notes", notes}}; }});
  // Every registered part's tasks (parts.h), in report order.
  const PartContext context{base, first, pin_scenes, options.scenes, families, quick};
  for (const Part* part : listParts())
    for (Task& task : part->tasks(context)) tasks.push_back(std::move(task));
  // The longest tasks first, so that the jobs finish together (the order changes no table: they are sorted): the
  // flywheel sizings (one task per Simbody run), the offset sweep, then the cross-checks and the gate's sweep, largest
  // k first, then the rest in the order listed (Task::cost).
  std::stable_sort(tasks.begin(), tasks.end(), [](const Task& a, const Task& b) { return a.cost > b.cost; });
  return tasks;
}

}  // namespace crankcheck::validation
