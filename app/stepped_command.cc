#include "stepped_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "crankcheck/validation/commands/stepped.h"
#include "crankcheck/validation/engine_runs.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/stepped_errors.h"
#include "crankcheck/validation/work_limit.h"
#include "flag_checks.h"
#include "help_format.h"
#include "json_output.h"
#include "scene_input.h"

namespace crankcheck::app {

using validation::shortNumber;

void addSteppedOptions(CLI::App& command, SteppedOptions& options) {
  std::vector<std::string> engines = {"all"}, settings = {"all"};
  for (const Engine& e : validation::listEngines(Route::kStepAtSpeed)) {
    engines.push_back(e.name);
    for (const std::string& s : e.settings)
      if (std::find(settings.begin(), settings.end(), s) == settings.end()) settings.push_back(s);
  }
  command.add_option("scene", options.scene_path, "Scene file (TOML); needs speed_rpm != 0")->required();
  command.add_option("--engine", options.engine, "The stepped engine, or all")
      ->check(CLI::IsMember(engines))
      ->capture_default_str();
  command.add_option("--settings", options.settings,
                     "The engines' settings to run (each engine's own, listed below), or all")
      ->check(CLI::IsMember(settings))
      ->capture_default_str();
  command.add_option("--dt", options.steps, "Time steps [s], comma-separated; default 1/240, 1e-3, 1e-4, 1e-5")
      ->delimiter(',')
      ->check(FiniteRange(1e-7, 0.1));
  command.add_flag("--free", options.free,
                   "The free runs instead: no drive, the scene's [flywheel] on the crank, gravity alone (the scene's "
                   "[gas] left out), released at phi = 0 with the scene's speed; each judged as grade --free-run judges "
                   "a program's run (energy trend, delta, phase)");
  CLI::Option* free = command.get_option("--free");
  command.add_option("--revolutions", options.revolutions, "Revolutions of a free run (only with --free)")
      ->check(CLI::Range(1, 1000))
      ->needs(free)
      ->capture_default_str();
  command.add_option(validation::kWorkLimitFlag, options.work_limit,
                     "The longest work to start [s]: the runs are estimated before they start (their steps at the "
                     "measured cost of each engine's step) and refused past it")
      ->check(FiniteRange(1.0, 1e7))
      ->capture_default_str();
  command.add_option("--format", options.format, "Output format")
      ->check(CLI::IsMember({"table", "json"}))
      ->capture_default_str();
  std::string footer = "The stepped engines, each measured, never gated (docs/stepped-engines.md):\n";
  for (const Engine& e : validation::listEngines(Route::kStepAtSpeed)) {
    footer += "- " + e.name + " (" + e.library + "): " + e.method + ". Instants: " + e.instants + ". Cannot build: " +
              e.cannot_build + ".\n";
    for (size_t i = 0; i < e.settings.size(); ++i)
      footer += "    settings " + e.settings[i] + ": " + e.settings_meaning[i] + "\n";
  }
  footer +=
      "Each run starts from the exact state at phi = 0, settles max(64 steps, one turn) and is measured over the next "
      "turn: per quantity the worst |engine - exact| / scale (the scales of docs/CONVENTIONS-crankcheck.md), the "
      "exact value taken at the instant the engine's value belongs to (step fraction: 0 the step's start, 1 its end); "
      "loop_error is the largest joint separation / the position scale. order: log(e1 / e2) / log(dt1 / dt2) between "
      "neighbouring steps. A scene or step an engine cannot take is a refusal line, not an error.";
  command.footer(footer);
}

namespace {

std::string formatStep(double dt) {
  if (std::fabs(dt - 1.0 / 240.0) < 1e-15) return "1/240 s";
  return shortNumber(dt, 3) + " s";
}

}  // namespace

namespace {

// --free: each engine's free run at each settings and step, as grade --free-run's engine rows.
std::string runSteppedFree(const SteppedOptions& options, Mechanism m, const std::vector<const Engine*>& engines,
                           const std::vector<std::string>& settings, std::vector<double> steps) {
  if (!m.flywheel_inertia) throw UsageError(options.scene_path + ": [flywheel].inertia: the free run (--free) needs it");
  if (!(m.machine.speed > 0.0))
    throw UsageError(options.scene_path + ": [engine].speed_rpm: the free run (--free) is released at it; it must be > 0");
  m.gas.reset();  // gravity alone
  std::sort(steps.begin(), steps.end(), std::greater<double>());
  std::vector<validation::EngineRunSpec> specs;
  std::vector<validation::SteppedJob> jobs;
  for (const Engine* e : engines) {
    if (!e->step_free) continue;
    for (const std::string& s : settings.empty() ? e->settings : settings)
      if (std::find(e->settings.begin(), e->settings.end(), s) != e->settings.end())
        for (double dt : steps) {
          specs.push_back({e->name, s, dt});
          jobs.push_back({e, s, dt, 1.1 * options.revolutions * 2.0 * M_PI / (m.machine.speed * dt)});
        }
  }
  if (specs.empty())
    throw UsageError("--free: " + options.engine + (options.engine == "all" ? " stepped engines" : "") +
                     ": no free run to make (no engine chosen runs free at the settings asked)");
  validation::checkSteppedWork(m, jobs, options.work_limit, "--free: the free runs on " + options.scene_path,
                               "a larger --dt or fewer --revolutions");
  std::vector<std::string> refusals;
  std::vector<validation::EngineRunRow> rows;
  try {
    rows = validation::calcEngineRuns(m, m.machine.speed, options.revolutions, specs, {}, &refusals);
  } catch (const std::invalid_argument& e) {
    throw UsageError(options.scene_path + ": " + e.what());
  }
  if (options.engine != "all" && rows.empty() && !refusals.empty())
    throw UsageError(options.scene_path + ": --engine " + options.engine + ": " + refusals.front());
  if (rows.empty())
    throw UsageError(options.scene_path + ": nothing measured: every free run was refused (" +
                     (refusals.empty() ? std::string("no reason given") : refusals.front()) + ")");
  if (options.format == "json") {
    nlohmann::ordered_json doc;
    doc["scene"] = options.scene_path;
    doc["speed_rpm"] = m.speed_rpm;
    doc["revolutions"] = options.revolutions;
    doc["runs"] = nlohmann::ordered_json::array();
    auto number = [](double x) { return std::isfinite(x) ? nlohmann::ordered_json(x) : nlohmann::ordered_json(); };
    for (const validation::EngineRunRow& r : rows)
      doc["runs"].push_back({{"engine", r.engine}, {"settings", r.integrator}, {"dt", r.accuracy},
                             {"energy_trend_per_revolution", number(r.energy_trend_per_revolution)},
                             {"delta", number(r.delta)}, {"delta_exact", number(r.delta_exact)},
                             {"delta_error_rel", number(r.delta_error_rel)}, {"phi_max_error", number(r.phi_max_error)},
                             {"phi_min_error", number(r.phi_min_error)},
                             {"phase_error_at_horizon", number(r.phase_error_at_horizon)}, {"horizon_s", r.horizon_s},
                             {"omega_reading", r.omega_reading},
                             {"cpu_seconds_per_revolution", r.cpu_seconds_per_revolution}});
    doc["refusals"] = refusals;
    return dumpJson(doc);
  }
  std::string out = "free runs of the stepped engines on " + showPath(options.scene_path) + ": released at phi = 0 with " +
                    shortNumber(m.speed_rpm, 6) + " rpm, gravity alone, " + std::to_string(options.revolutions) +
                    " revolutions (the exact delta " + (rows.empty() ? std::string("-") : shortNumber(rows.front().delta_exact, 4)) +
                    ")\n";
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, "%-13s %-11s %8s %10s %10s %10s %-21s %8s\n", "engine", "settings", "dt [s]",
                "energy/rev", "delta err", "phase [rad]", "omega read", "s/rev");
  out += buffer;
  for (const validation::EngineRunRow& r : rows) {
    std::snprintf(buffer, sizeof buffer, "%-13s %-11s %8s %10s %10s %10s %-21s %8s\n", r.engine.c_str(),
                  r.integrator.c_str(), formatStep(r.accuracy).c_str(), shortNumber(r.energy_trend_per_revolution, 2).c_str(),
                  shortNumber(r.delta_error_rel, 2).c_str(), shortNumber(r.phase_error_at_horizon, 2).c_str(),
                  r.omega_reading.c_str(), shortNumber(r.cpu_seconds_per_revolution, 2).c_str());
    out += buffer;
  }
  for (const std::string& r : refusals) out += "refused: " + r + "\n";
  out += "(energy/rev: the least-squares trend of the energy at each turn over E_0, per revolution; delta err: the "
         "speed fluctuation over the first revolution against the exact run's from the run's own state, relative; "
         "phase: the crank angle's error at the horizon; omega read: where the engine's speed stands; s/rev: wall time "
         "per simulated revolution; docs/grade.md, Time-stepped runs)\n";
  return wrapText(out, kHelpWidth);
}

}  // namespace

std::string runStepped(const SteppedOptions& options) {
  const Mechanism m = loadScene(options.scene_path);
  std::vector<const Engine*> engines;
  for (const Engine& e : validation::listEngines(Route::kStepAtSpeed))
    if (options.engine == "all" || e.name == options.engine) engines.push_back(&e);
  const std::vector<std::string> settings =
      options.settings == "all" ? std::vector<std::string>{} : std::vector<std::string>{options.settings};
  // Settings that none of the chosen engines has: nothing would run.
  if (!settings.empty() &&
      std::none_of(engines.begin(), engines.end(), [&](const Engine* e) {
        return std::find(e->settings.begin(), e->settings.end(), settings.front()) != e->settings.end();
      })) {
    std::string theirs;
    for (const Engine* e : engines)
      for (const std::string& s : e->settings) theirs += (theirs.empty() ? "" : ", ") + s;
    throw UsageError("--settings: " + options.settings + ": " +
                     (options.engine == "all" ? std::string("no stepped engine has it")
                                              : options.engine + " has no such settings") +
                     " (" + (options.engine == "all" ? "theirs" : "its") + ": " + theirs + ")");
  }
  const std::vector<double> steps = options.steps.empty() ? validation::getDefaultSteppedSteps() : options.steps;
  for (size_t i = 0; i < steps.size(); ++i)  // a step twice: its runs twice, and an order fitted to no change (null)
    for (size_t j = 0; j < i; ++j)
      if (steps[j] == steps[i])
        throw UsageError("--dt: " + validation::formatNumber(steps[i]) + " is given twice");
  if (options.free) return runSteppedFree(options, m, engines, settings, steps);
  validation::SteppedSweep sweep;
  try {
    validation::checkSteppedWork(m, validation::listSteppedJobs(m, engines, settings, steps), options.work_limit,
                                 "--dt: the runs on " + options.scene_path, "a larger step");
    sweep = validation::calcSteppedSweep(m, options.scene_path, engines, settings, steps);
  } catch (const std::invalid_argument& e) {
    throw UsageError(options.scene_path + ": " + e.what());
  }
  // One engine named that cannot build the scene: the user's input (exit status 2), not a table.
  if (options.engine != "all" && sweep.errors.empty())
    for (const validation::SteppedRefusalRow& r : sweep.refusals)
      if (r.dt == 0.0 && r.engine == options.engine)
        throw UsageError(options.scene_path + ": --engine " + options.engine + ": " + r.reason);
  // A request that measures nothing is not a result: every engine refused the scene (or every step).
  if (sweep.errors.empty()) {
    std::string why;
    for (const validation::SteppedRefusalRow& r : sweep.refusals)
      if (const std::string who = validation::nameRefuser(r); why.find(who + ": ") == std::string::npos)
        why += (why.empty() ? "" : "; ") + who + ": " + r.reason;
    throw UsageError(options.scene_path + ": nothing measured: every stepped engine refused it (" +
                     (why.empty() ? std::string("no reason given") : why) + ")");
  }
  if (options.format == "json") {
    nlohmann::ordered_json doc;
    doc["scene"] = options.scene_path;
    doc["speed_rpm"] = m.speed_rpm;
    doc["errors"] = nlohmann::ordered_json::array();
    for (const validation::SteppedErrorRow& r : sweep.errors)
      doc["errors"].push_back({{"engine", r.engine}, {"settings", r.settings}, {"dt", r.dt}, {"quantity", r.quantity},
                               {"worst_rel_error", r.worst_rel_error}, {"where_phi_deg", r.where_phi_deg},
                               {"step_fraction", r.step_fraction}});
    doc["costs"] = nlohmann::ordered_json::array();
    for (const validation::SteppedCostRow& r : sweep.costs)
      doc["costs"].push_back({{"engine", r.engine}, {"settings", r.settings}, {"dt", r.dt}, {"ns_per_step", r.ns_per_step}});
    doc["orders"] = nlohmann::ordered_json::array();
    for (const validation::SteppedOrderRow& r : sweep.orders)
      doc["orders"].push_back({{"engine", r.engine}, {"settings", r.settings}, {"quantity", r.quantity},
                               {"dt_coarse", r.dt_coarse}, {"dt_fine", r.dt_fine},
                               {"order", std::isfinite(r.order) ? nlohmann::ordered_json(r.order) : nlohmann::ordered_json()}});
    doc["refusals"] = nlohmann::ordered_json::array();
    for (const validation::SteppedRefusalRow& r : sweep.refusals)
      doc["refusals"].push_back({{"engine", r.engine}, {"settings", r.settings.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(r.settings)},
                                 {"dt", r.dt > 0.0 ? nlohmann::ordered_json(r.dt) : nlohmann::ordered_json()},
                                 {"reason", r.reason}});
    return dumpJson(doc);
  }
  // The table: per engine and settings, a quantity per line, the worst error / scale at each step, the last order.
  std::string out = "stepped engines on " + showPath(options.scene_path) + " at " + shortNumber(m.speed_rpm, 6) +
                    " rpm: worst |engine - exact| / scale over one turn after settling\n";
  std::vector<double> sorted = steps;
  std::sort(sorted.begin(), sorted.end(), std::greater<double>());
  std::map<std::pair<std::string, std::string>, std::vector<const validation::SteppedErrorRow*>> blocks;
  std::vector<std::pair<std::string, std::string>> order;
  for (const validation::SteppedErrorRow& r : sweep.errors) {
    const auto key = std::make_pair(r.engine, r.settings);
    if (!blocks.count(key)) order.push_back(key);
    blocks[key].push_back(&r);
  }
  char buffer[256];
  for (const auto& key : order) {
    out += "\n" + key.first + ", settings " + key.second + "\n";
    std::snprintf(buffer, sizeof buffer, "  %-16s %5s", "quantity", "read");
    out += buffer;
    for (double dt : sorted) {
      std::snprintf(buffer, sizeof buffer, " %10s", formatStep(dt).c_str());
      out += buffer;
    }
    out += "  order\n";
    std::vector<std::string> quantities;
    std::map<std::string, std::map<double, const validation::SteppedErrorRow*>> cells;
    std::map<double, double> ns;
    for (const validation::SteppedErrorRow* r : blocks[key]) {
      if (!cells.count(r->quantity)) quantities.push_back(r->quantity);
      cells[r->quantity][r->dt] = r;
    }
    for (const validation::SteppedCostRow& c : sweep.costs)
      if (c.engine == key.first && c.settings == key.second) ns[c.dt] = c.ns_per_step;
    for (const std::string& q : quantities) {
      std::snprintf(buffer, sizeof buffer, "  %-16s %5.2g", q.c_str(), cells[q].begin()->second->step_fraction);
      out += buffer;
      for (double dt : sorted) {
        const auto it = cells[q].find(dt);
        std::snprintf(buffer, sizeof buffer, " %10s", it == cells[q].end() ? "refused" : shortNumber(it->second->worst_rel_error, 2).c_str());
        out += buffer;
      }
      std::string last = "-";
      for (const validation::SteppedOrderRow& o : sweep.orders)
        if (o.engine == key.first && o.settings == key.second && o.quantity == q && std::isfinite(o.order))
          last = shortNumber(o.order, 2);  // the finest pair's, the last in the series
      out += "  " + last + "\n";
    }
    std::snprintf(buffer, sizeof buffer, "  %-16s %5s", "ns per step", "");
    out += buffer;
    for (double dt : sorted) {
      std::snprintf(buffer, sizeof buffer, " %10s", ns.count(dt) ? shortNumber(ns[dt], 3).c_str() : "-");
      out += buffer;
    }
    out += "\n";
  }
  for (const validation::SteppedRefusalRow& r : sweep.refusals)
    out += "refused: " + validation::nameRefuser(r) +
           (r.settings.empty() ? "" : ", settings " + r.settings) +
           (r.dt > 0.0 ? " at " + formatStep(r.dt) : "") + ": " + r.reason + "\n";
  out += "(read: the step fraction each value belongs to, 0 the step's start, 1 its end; order: between the two "
         "finest steps measured)\n";
  return wrapText(out, kHelpWidth);
}

}  // namespace crankcheck::app
