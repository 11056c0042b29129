// Report part `stepped_engines`: the physics engines people ship (ODE, Bullet, Box2D: validation/engines.h
// listEngines(Route::kStepAtSpeed)), each driven at the scene's speed by its own time-stepping solver, measured at a series of steps
// and at each of its settings against the closed forms (validation/commands/stepped.h, the same computation as
// `crankcheck stepped`); the figure of each engine's error against its step; sentences read from the data.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "crankcheck/scene/quantities.h"
#include "crankcheck/validation/commands/stepped.h"
#include "crankcheck/validation/engine_runs.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/report_document.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/stepped_errors.h"

namespace crankcheck::validation {
namespace {

// stepped_engines (derived, the figure's data): per engine, settings and step the worst error over the position-level
// quantities (x_p, the loops' separation) and over the loads (the joint forces and the drive torque).
struct SteppedSummaryRow {
  int series = 0;             ///< 1..N: one per (engine, settings), the figure's line
  std::string label;          ///< "ode defaults"
  std::string engine, settings;
  double dt = 0.0;            ///< [s]
  double positions = 0.0;     ///< [-] worst over x_p and loop_error; NaN: none reported
  double loads = 0.0;         ///< [-] worst over the forces and the drive torque; NaN: none reported
};
const Schema<SteppedSummaryRow> kSteppedSummaryTable{
    "stepped_engines",
    {countField("series", &SteppedSummaryRow::series), textField("label", &SteppedSummaryRow::label),
     textField("engine", &SteppedSummaryRow::engine), textField("settings", &SteppedSummaryRow::settings),
     numberField("dt", "s", &SteppedSummaryRow::dt), numberField("positions", "-", &SteppedSummaryRow::positions),
     numberField("loads", "-", &SteppedSummaryRow::loads)}};

// The steps the campaign runs: the default series; --quick without 1e-5 s.
std::vector<double> chooseSteps(bool quick) {
  std::vector<double> steps = getDefaultSteppedSteps();
  if (quick) steps.pop_back();
  return steps;
}

bool isPositionQuantity(const std::string& q) { return q == nameOf(QuantityId::kPistonPosition) || q == kLoopErrorName; }

bool isLoadQuantity(const std::string& q) {
  const Quantity* quantity = findQuantity(q);
  if (!quantity) return false;
  return quantity->scale == QuantityScale::kForce || quantity->scale == QuantityScale::kTorque;
}

void deriveSteppedSummary(TableSet& tables) {
  if (!tables.count(kSteppedErrorsTable.name())) return;
  std::map<std::pair<std::string, std::string>, int> series;
  std::map<std::tuple<std::string, std::string, double>, SteppedSummaryRow> rows;
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  auto worse = [](double have, double e) { return std::isnan(have) || e > have ? e : have; };
  for (const SteppedErrorRow& r : getRows(tables, kSteppedErrorsTable)) {
    const auto key = std::make_pair(r.engine, r.settings);
    if (!series.count(key)) series.emplace(key, 0);
    SteppedSummaryRow& row = rows[{r.engine, r.settings, r.dt}];
    if (row.label.empty()) row = {0, r.engine + " " + r.settings, r.engine, r.settings, r.dt, kNaN, kNaN};
    if (isPositionQuantity(r.quantity)) row.positions = worse(row.positions, r.worst_rel_error);
    if (isLoadQuantity(r.quantity)) row.loads = worse(row.loads, r.worst_rel_error);
  }
  // Series in the registry's order of engines, each engine's settings in its own order.
  int n = 0;
  for (const Engine& e : listEngines(Route::kStepAtSpeed))
    for (const std::string& s : e.settings)
      if (series.count({e.name, s})) series[{e.name, s}] = ++n;
  for (auto& [key, v] : series)
    if (v == 0) v = ++n;  // an engine no longer registered (a merged older report): after the others
  std::vector<SteppedSummaryRow> out;
  for (auto& [key, row] : rows) {
    row.series = series[{row.engine, row.settings}];
    out.push_back(row);
  }
  std::sort(out.begin(), out.end(), [](const SteppedSummaryRow& a, const SteppedSummaryRow& b) {
    return a.series != b.series ? a.series < b.series : a.dt > b.dt;
  });
  tables.insert_or_assign(kSteppedSummaryTable.name(), kSteppedSummaryTable.table(std::move(out)));
}

// The revolutions of the part's free runs.
constexpr int kFreeRevolutions = 5;

// The example scene the default campaign measures the stepped engines on.
constexpr const char* kDefaultScene = "inline4_four_stroke";

// The command that reproduces a finding on `scene` (a scene's name: its file's stem; the example scenes are in
// scenes/, installed in PREFIX/share/crankcheck/scenes).
std::string reproduce(const std::string& scene, const std::string& flags) {
  return formatCodeSpan("crankcheck stepped " + quoteShellWord((scene == kDefaultScene ? "scenes/" + scene : scene) + ".toml") +
                        " " + flags);
}

std::string formatStep(double dt) { return std::fabs(dt - 1.0 / 240.0) < 1e-15 ? "1/240 s" : shortNumber(dt, 3) + " s"; }

// The refusals as the report's sentences, each once: a step refused for every engine (engine "all", before any engine
// ran) is a row of each engine's task.
std::vector<std::string> formatRefusals(const std::vector<SteppedRefusalRow>& refusals) {
  std::vector<std::string> lines;
  std::set<std::string> told;
  for (const SteppedRefusalRow& r : refusals) {
    std::string line = "Refused: " + nameRefuser(r) +
                       (r.settings.empty() ? "" : " (" + r.settings + ")") + (r.dt > 0.0 ? " at " + formatStep(r.dt) : "") +
                       ": " + r.reason + ".";
    if (told.insert(line).second) lines.push_back(std::move(line));
  }
  return lines;
}

ReportPart describeSteppedPart(const TableSet& tables, const std::string& heading) {
  ReportPart part;
  if (!tables.count(kSteppedSummaryTable.name())) return part;
  const std::vector<SteppedSummaryRow>& summary = getRows(tables, kSteppedSummaryTable);
  const std::vector<SteppedErrorRow>& errors = getRows(tables, kSteppedErrorsTable);
  const std::vector<SteppedOrderRow>& orders = getRows(tables, kSteppedOrdersTable);
  part.heading = heading;
  if (summary.empty()) {  // every engine refused the scene (a balance shaft, a massless body): no figure, the reasons
    const std::vector<SteppedRefusalRow>& refusals = getRows(tables, kSteppedRefusalsTable);
    part.blocks.push_back({ReportBlock::kParagraph, "No stepped engine measured scene " +
                                                        (refusals.empty() ? std::string("-") : refusals.front().scene) +
                                                        ": each refused it, for the reason below."});
    for (const std::string& line : formatRefusals(refusals)) part.blocks.push_back({ReportBlock::kParagraph, line});
    return part;
  }
  const std::string scene = errors.empty() ? std::string() : errors.front().scene;
  part.caption =
      "Each stepped engine driven at the scene's speed by its own solver from the exact state, at each of its settings "
      "(one line each): the worst error over one turn after settling, relative to the quantity's scale, against the "
      "time step (log-log; the slope is the observed order). Left: positions (x_p, the loops' separation); right: "
      "loads (the joint forces and the drive torque), each read at the instant the engine's value belongs to. Scene: " +
      scene;
  // 1. Which engine, at its defaults, reaches 1e-3 of the scale on every load at which step.
  for (double target : {1e-3}) {
    std::string s = "At its defaults, within " + shortNumber(target) + " of the scale on every load: ";
    std::vector<std::string> parts_of;
    std::set<std::string> seen;
    for (const SteppedSummaryRow& r : summary) {
      if (r.settings != "defaults" || seen.count(r.engine)) continue;
      seen.insert(r.engine);
      // The largest step that meets the target with every smaller step measured.
      double largest = 0.0;
      for (const SteppedSummaryRow& q : summary) {
        if (q.engine != r.engine || q.settings != "defaults" || !(q.loads <= target)) continue;
        bool below = true;
        for (const SteppedSummaryRow& f : summary)
          if (f.engine == r.engine && f.settings == "defaults" && f.dt < q.dt && !(f.loads <= target)) below = false;
        if (below) largest = std::max(largest, q.dt);
      }
      parts_of.push_back(r.engine + (largest > 0.0 ? " from " + formatStep(largest) + " down" : " at none of the steps"));
    }
    if (!parts_of.empty()) {
      for (size_t i = 0; i < parts_of.size(); ++i) s += (i ? "; " : "") + parts_of[i];
      part.paragraphs.push_back(s + ".");
    }
  }
  // 2. Which quantities do not converge: between the two finest steps the error falls by less than the step does
  // to the power 1/2 (observed order below 0.5) while still above 1e-6 of the scale.
  {
    std::map<std::tuple<std::string, std::string, std::string>, const SteppedOrderRow*> finest;
    for (const SteppedOrderRow& o : orders) {
      const SteppedOrderRow*& f = finest[{o.engine, o.settings, o.quantity}];
      if (!f || o.dt_fine < f->dt_fine) f = &o;
    }
    // Grouped by engine and settings, in the registry's order.
    std::map<std::pair<std::string, std::string>, std::string> stuck;
    for (const auto& [key, o] : finest) {
      double error = 0.0;
      for (const SteppedErrorRow& r : errors)
        if (r.engine == o->engine && r.settings == o->settings && r.quantity == o->quantity && r.dt == o->dt_fine) error = r.worst_rel_error;
      if (error > 1e-6 && !(o->order >= 0.5)) {
        std::string& line = stuck[{o->engine, o->settings}];
        line += (line.empty() ? "" : ", ") + o->quantity + " " + shortNumber(error) + " (order " +
                (std::isfinite(o->order) ? shortNumber(o->order) : "-") + ")";
      }
    }
    if (stuck.empty()) {
      part.paragraphs.push_back("Every quantity converges between the two finest steps (order >= 0.5) or is below 1e-6 of its scale.");
    } else {
      std::string s = "Not converging between the two finest steps (order below 0.5 with the error still above 1e-6 "
                      "of the scale; the error at the finer step): ";
      bool first = true;
      for (const Engine& e : listEngines(Route::kStepAtSpeed))
        for (const std::string& settings : e.settings) {
          const auto it = stuck.find({e.name, settings});
          if (it == stuck.end()) continue;
          s += std::string(first ? "" : "; ") + e.name + " (" + settings + "): " + it->second + ", " +
               reproduce(scene, "--engine " + e.name + " --settings " + settings);
          first = false;
        }
      part.paragraphs.push_back(s + ".");
    }
  }
  // 3. What the defaults that change the physics do: each engine with a "neutralised" settings, at every step.
  for (const Engine& e : listEngines(Route::kStepAtSpeed)) {
    if (std::find(e.settings.begin(), e.settings.end(), "neutralised") == e.settings.end()) continue;
    std::string s;
    for (const SteppedSummaryRow& d : summary) {
      if (d.engine != e.name || d.settings != "defaults") continue;
      for (const SteppedSummaryRow& n : summary)
        if (n.engine == e.name && n.settings == "neutralised" && n.dt == d.dt)
          s += (s.empty() ? "" : "; ") + formatStep(d.dt) + ": loads " + shortNumber(d.loads) + " against " +
               shortNumber(n.loads) + ", positions " + shortNumber(d.positions) + " against " + shortNumber(n.positions);
    }
    if (!s.empty())
      part.paragraphs.push_back(e.name + "'s defaults against its defaults neutralised (" +
                                e.settings_meaning[std::find(e.settings.begin(), e.settings.end(), "neutralised") - e.settings.begin()] +
                                "): " + s + " (" + reproduce(scene, "--engine " + e.name) + ").");
  }
  // 4. Cost per step, at the finest step measured.
  if (tables.count(kSteppedCostTable.name())) {
    std::map<std::string, double> ns;
    double finest = std::numeric_limits<double>::infinity();
    for (const SteppedCostRow& r : getRows(tables, kSteppedCostTable)) finest = std::min(finest, r.dt);
    for (const SteppedCostRow& r : getRows(tables, kSteppedCostTable))
      if (r.dt == finest && r.settings == "defaults") ns[r.engine] = r.ns_per_step;
    std::string s;
    for (const Engine& e : listEngines(Route::kStepAtSpeed))
      if (ns.count(e.name)) s += (s.empty() ? "" : ", ") + e.name + " " + shortNumber(ns[e.name], 3) + " ns";
    if (!s.empty()) part.paragraphs.push_back("Cost per step at its defaults (stepping and reads, one run): " + s + ".");
  }
  // 5. The free runs: each engine's energy trend, delta and phase at each settings and step.
  {
    // Each engine at its defaults; where no run at the defaults could be judged (Bullet's speed cap), its next settings.
    std::string s;
    for (const Engine& e : listEngines(Route::kStepAtSpeed))
      for (const std::string& settings : e.settings) {
        bool any = false;
        for (const EngineRunRow& r : getRows(tables, getSteppedFreeRunsSchema()))
          if (r.engine == e.name && r.integrator == settings) {
            any = true;
            s += (s.empty() ? "" : "; ") + e.name + (settings == "defaults" ? "" : " (" + settings + ")") + " at " +
                 formatStep(r.accuracy) + ": energy " + shortNumber(r.energy_trend_per_revolution) +
                 " a revolution, delta " + shortNumber(r.delta_error_rel) + " off, phase " +
                 shortNumber(r.phase_error_at_horizon) + " rad after " + std::to_string(r.revolutions) + " turns";
          }
        if (any) break;
      }
    if (!s.empty())
      part.paragraphs.push_back("Free runs at the defaults, or the first settings that could be judged (no drive, the "
                                "scene's flywheel, gravity alone, released at "
                                "the scene's speed; judged as grade --free-run judges a program's run; every settings in "
                                "data/stepped_free_runs.csv; " + reproduce(scene, "--free") + "): " + s + ".");
  }
  // 6. What the engines' documentation or upstream reports say, beside the measurement (Engine::notes): the
  // quantity's error at every step, at the settings that neutralise the defaults where the engine has them.
  for (const Engine& e : listEngines(Route::kStepAtSpeed))
    for (const EngineNote& n : e.notes) {
      const bool neutral = std::find(e.settings.begin(), e.settings.end(), "neutralised") != e.settings.end();
      const std::string settings = neutral ? "neutralised" : "defaults";
      std::string measured;
      for (const SteppedErrorRow& r : errors)
        if (r.engine == e.name && r.settings == settings && r.quantity == n.quantity)
          measured += (measured.empty() ? "" : ", ") + shortNumber(r.worst_rel_error) + " at " + formatStep(r.dt);
      if (measured.empty()) continue;
      part.paragraphs.push_back(e.name + "'s " + n.quantity + " (" + settings + "): " + measured + " of its scale. " +
                                n.note + " (" + reproduce(scene, "--engine " + e.name + " --settings " + settings) + ").");
    }
  // 7. The engines themselves: method, instants, what each cannot build, and the refusals of this campaign.
  for (const Engine& e : listEngines(Route::kStepAtSpeed))
    part.paragraphs.push_back(e.name + " (" + e.library + ", measured, never gated): " + e.method + ". Instants: " +
                              e.instants + ". Cannot build: " + e.cannot_build + ".");
  for (const std::string& line : formatRefusals(getRows(tables, kSteppedRefusalsTable))) part.paragraphs.push_back(line);
  part.header = {"engine", "settings", "dt", "quantity", "worst error / scale [-]", "where [deg]", "read at [step]"};
  for (const SteppedErrorRow& r : errors)
    part.rows.push_back({r.engine, r.settings, formatStep(r.dt), r.quantity, shortNumber(r.worst_rel_error),
                         shortNumber(r.where_phi_deg, 4), shortNumber(r.step_fraction)});
  return part;
}

class SteppedEnginesPart final : public Part {
 public:
  std::string key() const override { return "stepped_engines"; }
  std::string title() const override { return "The physics engines people ship: error against time step"; }
  // One task per stepped engine on one scene as given (its gas and layout): the user's first scene, or in the
  // default campaign the example inline four (scenes/inline4_four_stroke.toml: gas, four throws, 3000 rpm). Each task
  // times its own steps: on a core of its own (Task::measures_time).
  std::vector<Task> tasks(const PartContext& context) const override {
    std::vector<Task> out;
    const Mechanism* m = chooseScene(context);
    if (!m) return out;
    for (const Engine& e : listEngines(Route::kStepAtSpeed))
      out.push_back({"stepped " + e.name, true, [m = *m, engine = &e, quick = context.quick] {
                       const SteppedSweep sweep = calcSteppedSweep(m, m.name, {engine}, {}, chooseSteps(quick));
                       TableSet tables = kSteppedErrorsTable.tableSet(sweep.errors);
                       tables.merge(kSteppedCostTable.tableSet(sweep.costs));
                       tables.merge(kSteppedOrdersTable.tableSet(sweep.orders));
                       tables.merge(kSteppedRefusalsTable.tableSet(sweep.refusals));
                       // The free run (a scene with a flywheel): gravity alone, released at the scene's speed, each
                       // settings at 1e-3 and 1e-4 s (quick: 1e-4 s), judged as grade --free-run judges a program's.
                       if (engine->step_free && m.flywheel_inertia) {
                         Mechanism free = m;
                         free.gas.reset();
                         std::vector<EngineRunSpec> specs;
                         for (const std::string& s : engine->settings)
                           for (double dt : quick ? std::vector<double>{1e-4} : std::vector<double>{1e-3, 1e-4})
                             specs.push_back({engine->name, s, dt});
                         std::vector<std::string> refused;
                         std::vector<EngineRunRow> runs = calcEngineRuns(free, free.machine.speed, kFreeRevolutions, specs, {}, &refused);
                         tables.merge(getSteppedFreeRunsSchema().tableSet(std::move(runs)));
                         std::vector<SteppedRefusalRow> refusals;
                         for (const std::string& r : refused) refusals.push_back({m.name, engine->name, "free run", 0.0, r});
                         if (!refusals.empty()) addRows(tables, kSteppedRefusalsTable, std::move(refusals));
                       }
                       return tables;
                     }});
    return out;
  }
  // The sweep's steps grow as the speed falls (a turn at 1e-6 rpm is years of steps) and its cost with the scene (an
  // ODE step on 64 cylinders takes 50 ms): estimated as `crankcheck stepped` estimates it, before any work.
  void checkWork(const PartContext& context) const override {
    const Mechanism* m = chooseScene(context);
    if (!m) return;
    std::vector<const Engine*> engines;
    for (const Engine& e : listEngines(Route::kStepAtSpeed)) engines.push_back(&e);
    std::vector<SteppedJob> jobs;
    try {
      jobs = listSteppedJobs(*m, engines, {}, chooseSteps(context.quick));
    } catch (const std::invalid_argument& e) {
      throw UsageError("part " + key() + ": scene " + m->name + ": " + e.what());
    }
    if (m->flywheel_inertia)  // the free runs, kFreeRevolutions each (as tasks() makes them)
      for (const Engine* e : engines)
        if (e->step_free)
          for (const std::string& s : e->settings)
            for (double dt : context.quick ? std::vector<double>{1e-4} : std::vector<double>{1e-3, 1e-4})
              jobs.push_back({e, s, dt, 1.1 * kFreeRevolutions * 2.0 * M_PI / (std::fabs(m->machine.speed) * dt)});
    checkSteppedWork(*m, jobs, context.work_limit, "part " + key() + " on scene " + m->name,
                     "leave the part out (--parts without " + key() + ")");
  }
  void derive(TableSet& tables) const override { deriveSteppedSummary(tables); }
  ReportPart describe(const TableSet& tables) const override { return describeSteppedPart(tables, heading()); }
  std::vector<const TableSchema*> schemas() const override {
    return {&kSteppedErrorsTable, &kSteppedCostTable, &kSteppedOrdersTable, &kSteppedRefusalsTable, &kSteppedSummaryTable,
            &getSteppedFreeRunsSchema()};
  }
  std::string findOmission(const PartContext& context) const override {
    if (chooseScene(context)) return {};
    return "The stepped engines' part needs the first scene at a speed (speed_rpm != 0): they are driven at it.";
  }

 private:
  // The scene the part runs on (see tasks()); null when it has no speed.
  static const Mechanism* chooseScene(const PartContext& context) {
    const Mechanism* m = nullptr;
    if (!context.user_scenes.empty()) {
      m = &context.user_scenes.front();
    } else {
      for (const Mechanism& scene : context.scenes)
        if (scene.name == kDefaultScene) m = &scene;
      if (!m && !context.scenes.empty()) m = &context.scenes.front();
    }
    return m && std::fabs(m->machine.speed) > 0.0 ? m : nullptr;
  }
};

}  // namespace

namespace parts {
const Part& steppedEngines() {
  static const SteppedEnginesPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
