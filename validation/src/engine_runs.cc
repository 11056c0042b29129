#include "crankcheck/validation/engine_runs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>
#include <stdexcept>
#include <string>

#include "crankcheck/analytic/gas_work.h"
#include "crankcheck/analytic/motion.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/scene/engine.h"

namespace crankcheck::validation {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// x as %g, for messages.
std::string shortText(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// The engine of a spec, checked: it simulates, it has the integrator, the accuracy is finite and > 0.
const Engine& checkSpec(const EngineRunSpec& spec) {
  const Engine* engine = nullptr;
  for (const Engine& e : listEngines())
    if (e.name == spec.engine) engine = &e;
  std::vector<std::string> simulating;
  for (const Engine& e : listEngines())
    if (e.simulate) simulating.push_back(e.name);
  if (!engine)
    throw std::invalid_argument("free run: no engine \"" + spec.engine + "\" (the engines that simulate: " +
                                joinNames(simulating) + ")");
  if (!engine->simulate)
    throw std::invalid_argument("free run: the engine " + spec.engine + " does not simulate (the engines that do: " +
                                joinNames(simulating) + ")");
  if (std::find(engine->integrators.begin(), engine->integrators.end(), spec.integrator) == engine->integrators.end())
    throw std::invalid_argument("free run: the engine " + spec.engine + " has no integrator \"" + spec.integrator +
                                "\" (it has " + joinNames(engine->integrators) + ")");
  if (!(std::isfinite(spec.accuracy) && spec.accuracy > 0.0))
    throw std::invalid_argument("free run: " + spec.engine + " " + spec.integrator + ": the accuracy " +
                                shortText(spec.accuracy) + " is not finite and > 0");
  return *engine;
}

// Engine::accuracy_meaning's first clause: up to its first " (" or ", ", without a leading "the ".
std::string shortMeaning(const std::string& meaning) {
  std::string s = meaning.substr(0, std::min(meaning.find(" ("), meaning.find(", ")));
  if (s.rfind("the ", 0) == 0) s = s.substr(4);
  return s;
}

}  // namespace

SteppedRun toSteppedRun(const FreeRunResult& result) {
  const size_t n = result.time.size();
  if (result.phi.size() != n || result.phi_dot.size() != n)
    throw std::invalid_argument("toSteppedRun: time, phi and phi_dot must have as many samples (" + std::to_string(n) +
                                ", " + std::to_string(result.phi.size()) + ", " + std::to_string(result.phi_dot.size()) +
                                ")");
  if (n < 2) throw std::invalid_argument("toSteppedRun: fewer than 2 samples");
  // A sample at the time of the one before it is dropped (an integrator that reports its start twice: Simbody's
  // first return of every internal step is the initial state again).
  SteppedRun run;
  for (size_t i = 0; i < n; ++i) {
    if (i > 0 && result.time[i] == run.time.back()) continue;
    run.time.push_back(result.time[i]);
    run.phi.push_back(result.phi[i]);
    run.omega.push_back(result.phi_dot[i]);
  }
  // A backward difference: phi_i = phi_{i-1} + h_i phi_dot_i, to the rounding of phi's sum (eps |phi_i|) and of the
  // clock's (eps t_i, times the speed), with a margin of 16 for the step's own product and the subtraction.
  bool backward = true;
  for (size_t i = 1; i < run.time.size() && backward; ++i) {
    const double h = run.time[i] - run.time[i - 1];
    const double defect = (run.phi[i] - run.phi[i - 1]) - h * run.omega[i];
    const double rounding = 16.0 * kEps * (std::fabs(run.phi[i]) + std::fabs(run.omega[i]) * std::fabs(run.time[i]));
    backward = std::fabs(defect) <= rounding;
  }
  run.omega_half_step_behind = backward;
  return run;
}

std::vector<EngineRunRow> calcEngineRuns(const Mechanism& m, double omega0, int revolutions,
                                         const std::vector<EngineRunSpec>& specs, const RunLoad& load) {
  if (!(std::isfinite(omega0) && omega0 > 0.0))
    throw std::invalid_argument("free run: the release speed " + shortText(omega0) + " rad/s is not finite and > 0");
  if (revolutions < 1)
    throw std::invalid_argument("free run: " + std::to_string(revolutions) + " revolutions (at least 1)");
  if (m.gas && !load.gas)
    throw std::invalid_argument("free run: the scene has a [gas] table; the engines' free runs are judged under gravity "
                                "alone (drop it: Mechanism::gas)");
  if (load.gas && !m.gas) throw std::invalid_argument("loaded run: the scene has no [gas] table");
  if (!m.flywheel_inertia) throw std::invalid_argument("free run: the scene needs the flywheel inertia [flywheel].inertia");
  std::vector<const Engine*> engines;
  for (const EngineRunSpec& spec : specs) {
    engines.push_back(&checkSpec(spec));
    if (load.gas && !engines.back()->simulates_loads)
      throw std::invalid_argument("loaded run: the engine " + spec.engine + " does not run the gas and a load");
  }

  // The horizon of the phase error: `revolutions` turns of the exact free run released with omega0 at phi = 0 (loaded:
  // the run's own end, `revolutions` turns of the engine's run).
  const double exact_horizon = load.gas ? std::numeric_limits<double>::infinity()
                                        : revolutions * 2.0 * M_PI / analytic::calcFreeRun(m, omega0).omega_mean;
  const double load_torque = load.gas ? analytic::GasWork(m).getMeanTorque() : 0.0;

  std::vector<EngineRunRow> rows;
  for (size_t s = 0; s < specs.size(); ++s) {
    const EngineRunSpec& spec = specs[s];
    const Engine& engine = *engines[s];
    FreeRunSettings settings;
    settings.integrator = spec.integrator;
    settings.accuracy = spec.accuracy;
    settings.revolutions = revolutions;
    settings.gravity = true;
    settings.gas = load.gas;
    settings.load_torque = load_torque;
    const std::clock_t start = std::clock();
    const FreeRunResult result = engine.simulate(m, omega0, settings);
    const double cpu = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
    const SteppedRun run = toSteppedRun(result);

    EngineRunRow row;
    row.scene = m.name;
    row.engine = spec.engine;
    row.integrator = spec.integrator;
    row.accuracy = spec.accuracy;
    row.accuracy_meaning_short = shortMeaning(engine.accuracy_meaning);
    row.energy_trend_per_revolution = calcEnergyTrend(m, run, load);
    const SpeedFluctuationComparison fluctuation = calcSpeedFluctuation(m, run, load);
    row.delta = fluctuation.run.delta;
    row.delta_exact = fluctuation.exact.delta;
    row.delta_error_rel = fluctuation.exact.delta > 0.0 ? fluctuation.delta_error / fluctuation.exact.delta
                                                        : std::numeric_limits<double>::quiet_NaN();
    row.phi_max_error = fluctuation.phi_max_error;
    row.phi_min_error = fluctuation.phi_min_error;
    row.horizon_s = std::min(exact_horizon, run.time.back());
    row.phase_error_at_horizon = calcPhaseError(m, run, row.horizon_s, load);
    row.revolutions = revolutions;
    row.steps = result.steps;
    row.omega_reading = run.omega_half_step_behind ? "half a step behind" : "at the step";
    row.cpu_seconds_per_revolution = cpu / revolutions;
    rows.push_back(std::move(row));
  }
  return rows;
}

std::vector<EngineRunSpec> listDefaultEngineRuns(bool quick, const RunLoad& load) {
  std::vector<EngineRunSpec> specs;
  for (const Engine& e : listEngines()) {
    if (!e.simulate || e.integrators.empty() || (load.gas && !e.simulates_loads)) continue;
    const double a = e.default_accuracy;
    if (e.gated) {
      // A tolerance: the default integrator over four decades, the others each at one accuracy by their order.
      for (double factor : quick ? std::vector<double>{1.0} : std::vector<double>{1e4, 1e2, 1.0})
        specs.push_back({e.name, e.integrators[0], factor * a});
      if (quick) continue;
      for (size_t i = 1; i < e.integrators.size(); ++i) {
        const bool first_order = i < e.integrator_orders.size() && e.integrator_orders[i] == 1;
        specs.push_back({e.name, e.integrators[i], (first_order ? 1e4 : 1e2) * a});
      }
    } else {
      // A fixed step: the default integrator at the default step (at a tenth of it a fourth-order run agrees with it
      // far below the soft constraints' own loss, at ten times the cost), the next one (first order) at the default
      // step and a tenth of it, where its own error shows.
      specs.push_back({e.name, e.integrators[0], a});
      if (e.integrators.size() > 1)
        for (double factor : quick ? std::vector<double>{1.0} : std::vector<double>{1.0, 0.1})
          specs.push_back({e.name, e.integrators[1], factor * a});
    }
  }
  return specs;
}

const Schema<EngineRunRow>& getFreeRunEnginesSchema() {
  using R = EngineRunRow;
  static const Schema<R> schema(
      "free_run_engines",
      {textField("scene", &R::scene), textField("engine", &R::engine), textField("integrator", &R::integrator),
       numberField("accuracy", "-", &R::accuracy), textField("accuracy_meaning", &R::accuracy_meaning_short),
       numberField("energy_trend_per_revolution", "-", &R::energy_trend_per_revolution),
       numberField("delta", "-", &R::delta), numberField("delta_exact", "-", &R::delta_exact),
       numberField("delta_error_rel", "-", &R::delta_error_rel), numberField("phi_max_error", "rad", &R::phi_max_error),
       numberField("phi_min_error", "rad", &R::phi_min_error),
       numberField("phase_error_at_horizon", "rad", &R::phase_error_at_horizon),
       numberField("horizon", "s", &R::horizon_s), countField("revolutions", &R::revolutions),
       countField("steps", &R::steps), textField("omega_reading", &R::omega_reading),
       numberField("cpu_per_revolution", "s", &R::cpu_seconds_per_revolution)});
  return schema;
}

}  // namespace crankcheck::validation
