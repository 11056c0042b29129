#include "crankcheck/validation/engine_runs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "crankcheck/analytic/gas_work.h"
#include "crankcheck/analytic/motion.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/variants.h"
#include "crankcheck/solver/engine.h"

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

// The engine of a spec, checked: it runs free (Route::kSimulate: it has the integrator, the accuracy is finite and
// > 0; Route::kStepFree: it has the settings, the step is finite and > 0).
const Engine& checkSpec(const EngineRunSpec& spec) {
  const Engine* engine = nullptr;
  std::vector<std::string> running;  // every engine that runs free, in the registry's order
  for (Route route : {Route::kSimulate, Route::kStepFree})
    for (const Engine& e : listEngines(route)) {
      running.push_back(e.name);
      if (e.name == spec.engine) engine = &e;
    }
  if (!engine) {
    for (const Engine& e : listEngines())
      if (e.name == spec.engine)
        throw std::invalid_argument("free run: the engine " + spec.engine + " does not run free (the engines that do: " +
                                    joinNames(running) + ")");
    throw std::invalid_argument("free run: no engine \"" + spec.engine + "\" (the engines that run free: " +
                                joinNames(running) + ")");
  }
  if (engine->simulate) {
    if (std::find(engine->integrators.begin(), engine->integrators.end(), spec.integrator) == engine->integrators.end())
      throw std::invalid_argument("free run: the engine " + spec.engine + " has no integrator \"" + spec.integrator +
                                  "\" (it has " + joinNames(engine->integrators) + ")");
    if (!(std::isfinite(spec.accuracy) && spec.accuracy > 0.0))
      throw std::invalid_argument("free run: " + spec.engine + " " + spec.integrator + ": the accuracy " +
                                  shortText(spec.accuracy) + " is not finite and > 0");
    return *engine;
  }
  if (std::find(engine->settings.begin(), engine->settings.end(), spec.integrator) == engine->settings.end())
    throw std::invalid_argument("free run: " + engine->name + " has no settings \"" + spec.integrator + "\" (it has " +
                                joinNames(engine->settings) + ")");
  if (!(std::isfinite(spec.accuracy) && spec.accuracy > 0.0))
    throw std::invalid_argument("free run: " + engine->name + ": the step " + shortText(spec.accuracy) +
                                " s is not finite and > 0");
  return *engine;
}

// Engine::accuracy_meaning's first clause: up to its first " (" or ", ", without a leading "the ".
std::string shortMeaning(const std::string& meaning) {
  std::string s = meaning.substr(0, std::min(meaning.find(" ("), meaning.find(", ")));
  if (s.rfind("the ", 0) == 0) s = s.substr(4);
  return s;
}

// A run judged by the time-stepped grade's measures (run_measures.h): its row without the engine's own columns (engine,
// integrator, accuracy, revolutions, steps, cost). exact_horizon [s]: the phase error's horizon, or the run's end if
// it ends sooner.
EngineRunRow measureRun(const Mechanism& m, const Trajectory& run, const RunLoad& load, double exact_horizon) {
  EngineRunRow row;
  row.scene = m.name;
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
  if (!run.omega_time.empty()) {
    const double lag = run.time.back() - run.omega_time.back(), dt = run.time.back() - run.time[run.time.size() - 2];
    row.omega_reading = std::fabs(lag) <= 1e-9 * dt ? "at the step" : shortText(lag / dt) + " of a step behind";
  } else {
    row.omega_reading = run.omega_half_step_behind ? "half a step behind" : "at the step";
  }
  return row;
}

// The checks every free run shares: a release speed, whole revolutions, the scene's gas and flywheel.
void checkFreeRunScene(const Mechanism& m, double omega0, int revolutions, const RunLoad& load) {
  if (!(std::isfinite(omega0) && omega0 > 0.0))
    throw std::invalid_argument("free run: the release speed " + shortText(omega0) + " rad/s is not finite and > 0");
  if (revolutions < 1)
    throw std::invalid_argument("free run: " + std::to_string(revolutions) + " revolutions (at least 1)");
  if (m.gas && !load.gas)
    throw std::invalid_argument("free run: the scene has a [gas] table; the engines' free runs are judged under gravity "
                                "alone (drop it: Mechanism::gas)");
  if (load.gas && !m.gas) throw std::invalid_argument("loaded run: the scene has no [gas] table");
  if (!m.flywheel_inertia) throw std::invalid_argument("free run: the scene needs the flywheel inertia [flywheel].inertia");
}

}  // namespace

Trajectory withRelease(const Trajectory& run, double phi0, double omega0) {
  const size_t n = run.time.size();
  if (run.phi.size() != n || run.omega.size() != n || run.omega_time.size() != n)
    throw std::invalid_argument("withRelease: time, phi, omega and omega_time must have as many samples (" +
                                std::to_string(n) + ", " + std::to_string(run.phi.size()) + ", " +
                                std::to_string(run.omega.size()) + ", " + std::to_string(run.omega_time.size()) + ")");
  if (n < 2) throw std::invalid_argument("withRelease: fewer than 2 samples");
  // The release first: the run is judged from the state it was given, so that what the engine does to it in its
  // first step (a speed cap, damping) is measured, not taken as the run's own start.
  Trajectory out;
  out.seconds_per_step = run.seconds_per_step;
  out.time = {0.0};
  out.phi = {phi0};
  if (run.omega_time.front() > 0.0) {
    out.omega = {omega0};
    out.omega_time = {0.0};
    out.time.insert(out.time.end(), run.time.begin(), run.time.end());
    out.phi.insert(out.phi.end(), run.phi.begin(), run.phi.end());
    out.omega.insert(out.omega.end(), run.omega.begin(), run.omega.end());
    out.omega_time.insert(out.omega_time.end(), run.omega_time.begin(), run.omega_time.end());
    return out;
  }
  // A speed that belongs to its step's start (or before it): the first step's speed is the engine's own reading of
  // the release, standing at t <= 0 in its place; the last step's angle has no speed of its own and is left.
  out.time.insert(out.time.end(), run.time.begin(), run.time.end() - 1);
  out.phi.insert(out.phi.end(), run.phi.begin(), run.phi.end() - 1);
  out.omega = run.omega;
  out.omega_time = run.omega_time;
  return out;
}

Trajectory findOmegaInstants(const Trajectory& result) {
  const size_t n = result.time.size();
  if (result.phi.size() != n || result.omega.size() != n)
    throw std::invalid_argument("findOmegaInstants: time, phi and omega must have as many samples (" +
                                std::to_string(n) + ", " + std::to_string(result.phi.size()) + ", " +
                                std::to_string(result.omega.size()) + ")");
  if (n < 2) throw std::invalid_argument("findOmegaInstants: fewer than 2 samples");
  Trajectory run = result;
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
                                         const std::vector<EngineRunSpec>& specs, const RunLoad& load,
                                         std::vector<std::string>* refusals) {
  checkFreeRunScene(m, omega0, revolutions, load);
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
  // An engine that steps starts from the exact state at phi = 0 with the release speed (the run's input, not what is
  // measured); made once, for the first such spec.
  std::optional<StartState> start;

  std::vector<EngineRunRow> rows;
  for (size_t s = 0; s < specs.size(); ++s) {
    const EngineRunSpec& spec = specs[s];
    const Engine& engine = *engines[s];
    if (engine.simulate) {
      FreeRunSettings settings;
      settings.integrator = spec.integrator;
      settings.accuracy = spec.accuracy;
      settings.revolutions = revolutions;
      settings.gravity = true;
      settings.gas = load.gas;
      settings.load_torque = load_torque;
      const std::clock_t begin = std::clock();
      const FreeRunResult result = engine.simulate(m, omega0, settings);
      const double cpu = static_cast<double>(std::clock() - begin) / CLOCKS_PER_SEC;
      const Trajectory run = findOmegaInstants(result.trajectory);

      EngineRunRow row = measureRun(m, run, load, exact_horizon);
      row.engine = spec.engine;
      row.integrator = spec.integrator;
      row.accuracy = spec.accuracy;
      row.accuracy_meaning_short = shortMeaning(engine.accuracy_meaning);
      row.revolutions = revolutions;
      row.steps = result.steps;
      row.cpu_seconds_per_revolution = cpu / revolutions;
      rows.push_back(std::move(row));
      continue;
    }
    if (!start) {
      const Mechanism released = withSpeed(m, omega0 * 30.0 / M_PI);
      start = calcStartState(released, getClosedFormEngine().build(released)->evaluate(0.0));
    }
    SteppedFreeRunOptions options;
    options.dt = spec.accuracy;
    // The exact run's horizon and a tenth of a turn more (a run that loses speed still reaches it), in whole steps.
    options.steps = static_cast<long>(std::ceil(1.1 * exact_horizon / spec.accuracy));
    options.settings = spec.integrator;
    options.start = *start;
    const std::string who = spec.engine + " (" + spec.integrator + ", " + shortText(spec.accuracy) + " s): ";
    Trajectory result;
    try {
      result = engine.step_free(m, options);
    } catch (const std::exception& e) {  // a scene or step the engine refuses (Box2D's largest rotation a step)
      if (refusals) refusals->push_back(who + e.what());
      continue;
    }
    // A run the measures cannot judge (it stops turning, or falls short of one revolution in the steps given: a speed
    // cap, damping) is reported with the reason, not measured.
    EngineRunRow row;
    try {
      row = measureRun(m, withRelease(result, start->phi, omega0), {}, exact_horizon);
    } catch (const std::exception& e) {
      if (refusals) refusals->push_back(who + "not measured: " + e.what());
      continue;
    }
    row.engine = spec.engine;
    row.integrator = spec.integrator;
    row.accuracy = spec.accuracy;
    row.accuracy_meaning_short = "time step [s]";
    row.revolutions = revolutions;
    row.steps = static_cast<int>(options.steps);
    row.cpu_seconds_per_revolution = result.seconds_per_step * static_cast<double>(options.steps) / revolutions;
    rows.push_back(std::move(row));
  }
  return rows;
}

std::vector<EngineRunSpec> listDefaultEngineRuns(bool quick, const RunLoad& load) {
  std::vector<EngineRunSpec> specs;
  for (const Engine& e : listEngines(Route::kSimulate)) {
    if (e.integrators.empty() || (load.gas && !e.simulates_loads)) continue;
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
  // The engines that step free (they take no gas and no load) at their defaults, at 1e-3 and 1e-4 s (quick: 1e-4 s).
  if (!load.gas)
    for (const Engine& e : listEngines(Route::kStepFree))
      for (double dt : quick ? std::vector<double>{1e-4} : std::vector<double>{1e-3, 1e-4}) specs.push_back({e.name, "defaults", dt});
  return specs;
}

namespace {
// The columns of a table of EngineRunRow: its members, in order.
std::vector<Field<EngineRunRow>> listEngineRunFields() {
  using R = EngineRunRow;
  return {textField("scene", &R::scene), textField("engine", &R::engine), textField("integrator", &R::integrator),
       numberField("accuracy", "-", &R::accuracy), textField("accuracy_meaning", &R::accuracy_meaning_short),
       numberField("energy_trend_per_revolution", "-", &R::energy_trend_per_revolution),
       numberField("delta", "-", &R::delta), numberField("delta_exact", "-", &R::delta_exact),
       numberField("delta_error_rel", "-", &R::delta_error_rel), numberField("phi_max_error", "rad", &R::phi_max_error),
       numberField("phi_min_error", "rad", &R::phi_min_error),
       numberField("phase_error_at_horizon", "rad", &R::phase_error_at_horizon),
       numberField("horizon", "s", &R::horizon_s), countField("revolutions", &R::revolutions),
       countField("steps", &R::steps), textField("omega_reading", &R::omega_reading),
       numberField("cpu_per_revolution", "s", &R::cpu_seconds_per_revolution)};
}
}  // namespace

const Schema<EngineRunRow>& getFreeRunEnginesSchema() {
  static const Schema<EngineRunRow> schema("free_run_engines", listEngineRunFields());
  return schema;
}

const Schema<EngineRunRow>& getSteppedFreeRunsSchema() {
  // Without the processor time: a rerun (or a shard) repeats every other column exactly; the stepped engines' cost is
  // report part stepped_engines' table stepped_cost.
  static const Schema<EngineRunRow> schema("stepped_free_runs", [] {
    std::vector<Field<EngineRunRow>> fields;
    for (Field<EngineRunRow>& f : listEngineRunFields())
      if (f.column.name != "cpu_per_revolution") fields.push_back(std::move(f));
    return fields;
  }());
  return schema;
}

}  // namespace crankcheck::validation
