#include "crankcheck/validation/free_run_grade.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "crankcheck/analytic/flywheel.h"
#include "crankcheck/analytic/gas_work.h"
#include "crankcheck/analytic/motion.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/scene/quantities.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/scene/scene_writer.h"
#include "crankcheck/solver/stepped_run.h"
#include "crankcheck/validation/commands/stepped.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/work_limit.h"
#include "crankcheck/validation/evaluation_json.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/validation/variants.h"
#include "grade_protocol.h"

namespace crankcheck::validation {

namespace {

using Json = nlohmann::json;
constexpr double kTwoPi = 2.0 * M_PI;
constexpr int kHistoryPointsPerRevolution = 8;

// The table names (CSV stems), each spelled once.
constexpr const char* kMeasuresName = "free_run_measures";
constexpr const char* kConvergenceName = "free_run_convergence";
constexpr const char* kHistoryName = "free_run_history";

// The measures of a run, in the tables' order.
struct MeasureInfo {
  const char* name;
  const char* unit;
};
const MeasureInfo kEnergyTrend{"energy_trend", "1/rev"};
const MeasureInfo kEnergyTrendPerCycle{"energy_trend", "1/cycle"};  // a four-stroke's working cycle under gas
const MeasureInfo kDelta{"delta", "-"};
const MeasureInfo kPhiAtOmegaMax{"phi_at_omega_max", "deg"};
const MeasureInfo kPhiAtOmegaMin{"phi_at_omega_min", "deg"};
const MeasureInfo kPhase{"phase", "rad"};

std::string verdictOf(double error, double tolerance) { return error <= tolerance ? "pass" : "FAIL"; }

// The exact values at a state the program reached: the crank at phi turning at omega, its angular acceleration that of
// the equation of motion there (free: no drive, gravity alone: Lagrange's J phi'' + 1/2 J' phi'^2 + Q = 0; loaded: the
// gas torque less the load on the right; held: 0, the drive supplying whatever torque that takes).
Evaluation calcExactValuesAt(const RunCase& c, double phi, double omega) {
  const double net = c.drive == RunDrive::kLoaded ? analytic::calcGasTorque(c.mechanism, phi) - c.load_torque : 0.0;
  const double alpha =
      c.drive == RunDrive::kHeld ? 0.0 : analytic::calcCrankAcceleration(c.mechanism, phi, omega, net);
  return analytic::calcEvaluationAtState(c.mechanism, phi, omega, alpha);
}

}  // namespace

const char* nameOf(RunDrive drive) {
  return drive == RunDrive::kFree ? "free" : drive == RunDrive::kHeld ? "held" : "loaded";
}

double calcRunPeriod(const Mechanism& m, RunDrive drive) {
  if (!(m.machine.speed > 0.0)) throw std::invalid_argument("calcRunPeriod: the scene has no speed");
  if (drive != RunDrive::kFree) return kTwoPi / m.machine.speed;  // loaded: the steady run's mean speed is the scene's
  Mechanism free = m;
  free.gas.reset();
  return kTwoPi / analytic::calcFreeRun(free, m.machine.speed).omega_mean;
}

double getDefaultRunStep(const Mechanism& m, RunDrive drive) { return calcRunPeriod(m, drive) / 720.0; }

std::vector<RunCase> buildRunCases(const Mechanism& scene, const RunSettings& settings) {
  const std::string& name = scene.name;
  if (!(scene.machine.speed > 0.0))
    throw UsageError("[engine].speed_rpm: a time-stepped run starts at the scene's speed; give one > 0");
  // Two at least: the energy is read once a turn of the exact run, and a run that lands a rounding short of its one
  // turn has a single reading and no trend (every program failed at 1).
  if (settings.revolutions < 2) throw UsageError("--revolutions: at least 2 (the energy trend needs two turns)");
  if (settings.dt_sweep < 1) throw UsageError("--dt-sweep: at least 1");
  Mechanism m = scene;
  m.crankshaft.reset();  // the rigid shaft
  if (settings.drive == RunDrive::kFree) m.gas.reset();  // a free run under gravity alone
  if (settings.drive != RunDrive::kHeld && !m.flywheel_inertia)
    throw UsageError(std::string("[flywheel].inertia: a ") + nameOf(settings.drive) + " run needs the flywheel's "
                     "inertia (the measures are per revolution of a crank that keeps turning); add a [flywheel] table");
  if (settings.drive == RunDrive::kLoaded && !m.gas)
    throw UsageError("[gas]: a loaded run is driven by the gas pressure against a constant load; add a [gas] "
                     "table (or run it --drive free)");
  // Loaded: the load is the gas torque's cycle mean and the run starts at the steady run's speed at phi = 0, so that the
  // exact run is periodic over the working cycle at the scene's mean speed (analytic/flywheel.h).
  double load_torque = 0.0, omega0 = m.machine.speed;
  if (settings.drive == RunDrive::kLoaded) {
    try {
      load_torque = analytic::GasWork(m).getMeanTorque();
      omega0 = analytic::calcSteadyRun(m, *m.flywheel_inertia, load_torque).omega0;
    } catch (const std::domain_error&) {
      throw UsageError("[flywheel].inertia: the crank under this gas and its mean load does not keep turning "
                       "at the scene's speed; a loaded run needs a larger flywheel");
    }
  }
  double period = 0.0;
  try {
    period = calcRunPeriod(m, settings.drive);
  } catch (const std::domain_error&) {
    throw UsageError("the crank released at " + formatNumber(scene.speed_rpm) +
                     " rpm does not turn over against gravity; a free run needs a higher [engine].speed_rpm");
  }
  const double first = settings.dt && !settings.own_step ? *settings.dt : period / 720.0;
  if (!(first > 0.0 && std::isfinite(first))) throw UsageError("--dt: a step > 0");
  const double interval = settings.output_interval ? *settings.output_interval : first;
  if (!(interval > 0.0 && std::isfinite(interval))) throw UsageError("--output-interval: a time > 0");
  const double t_end = settings.revolutions * period;
  if (!settings.own_step && first > t_end / kMinRunSamples)
    throw UsageError("--dt: " + formatNumber(first) + " s leaves fewer than " + std::to_string(kMinRunSamples) +
                     " steps in the run's " + formatNumber(t_end) + " s");
  // The sweep's smallest step asks the program for t_end / dt steps: past kMaxRunSteps a run of a real simulator
  // (tens of nanoseconds a step at least) takes longer than any grade waits, and a step below rounding of t (1e-300)
  // is no step at all, so it is refused before the program is started.
  const double smallest = first / std::pow(2.0, settings.own_step ? 0 : settings.dt_sweep - 1);
  if (!settings.own_step && t_end / smallest > kMaxRunSteps)
    throw UsageError("--dt: " + formatNumber(first) + " s" +
                     (settings.dt_sweep > 1 ? " halved " + std::to_string(settings.dt_sweep - 1) + " times (--dt-sweep)"
                                            : std::string()) +
                     " asks for " + formatNumber(t_end / smallest) + " steps in the run's " + formatNumber(t_end) +
                     " s; at most " + formatNumber(kMaxRunSteps) + " (give a larger --dt or fewer --revolutions)");
  if (interval > t_end / kMinRunSamples)
    throw UsageError("--output-interval: " + formatNumber(interval) + " s leaves fewer than " +
                     std::to_string(kMinRunSamples) + " samples in the run's " + formatNumber(t_end) + " s");
  // A sample more than a quarter turn after the last (at the run's mean speed) leaves a turn unsampled: its run would
  // be refused as too coarse (checkRun) after the program ran, so the request is refused before it starts.
  if (const double angle = 2.0 * std::numbers::pi * interval / period; angle > kMaxStepAngle)
    throw UsageError(std::string(settings.output_interval ? "--output-interval: " : "--dt: ") + formatNumber(interval) +
                     " s between samples turns the crank by " + shortNumber(degreesFromRadians(angle), 4) +
                     " deg at the run's mean speed, more than a quarter turn: a turn is not sampled (at most " +
                     formatNumber(kMaxStepAngle / (2.0 * std::numbers::pi) * period) + " s)");
  std::vector<RunCase> cases;
  for (int i = 0; i < (settings.own_step ? 1 : settings.dt_sweep); ++i) {
    RunCase c;
    c.drive = settings.drive;
    c.family = name;
    if (!settings.own_step) c.dt = first / std::pow(2.0, i);
    c.id = safeStem(name) + "_" + nameOf(settings.drive) + (c.dt ? "_dt" + numberTag(*c.dt) : std::string("_own"));
    c.scene_toml = formatSceneToml(m);
    c.mechanism = parseScene(c.scene_toml, c.id);
    c.mechanism.name = name;
    c.phi0 = 0.0;
    c.omega0 = omega0;
    c.load_torque = load_torque;
    c.t_end = t_end;
    c.output_interval = settings.output_interval ? interval : c.dt ? *c.dt : interval;  // default: every step
    c.revolutions = settings.revolutions;
    cases.push_back(std::move(c));
  }
  return cases;
}

std::string makeRunRequest(const RunCase& c) {
  nlohmann::ordered_json request;
  request["protocol"] = 2;
  request["case"] = c.id;
  request["scene"] = sceneToJson(c.mechanism);
  request["scene_toml"] = c.scene_toml;
  request["drive"] = nameOf(c.drive);
  request["gas"] = c.mechanism.gas.has_value();  // free: never (the scene's [gas] is left out); held: the scene's
  request["load_torque"] = c.load_torque;
  request["gravity"] = true;
  request["phi0"] = c.phi0;
  request["omega0"] = c.omega0;
  if (c.dt)
    request["dt"] = *c.dt;
  else
    request["dt"] = "own";
  request["t_end"] = c.t_end;
  request["output_interval"] = c.output_interval;
  nlohmann::ordered_json quantities = nlohmann::ordered_json::array();
  for (const Quantity& q : getQuantityCatalogue())
    if (isQuantityDefined(q, c.mechanism) && q.id != QuantityId::kU && q.id != QuantityId::kQ) quantities.push_back(q.name);
  request["quantities"] = quantities;
  return request.dump();
}

ProgramRun parseRunResponse(const RunCase& c, const std::string& response, const std::string& program) {
  const std::string where = program + ": case " + c.id + ": ";
  auto fail = [&](const std::string& what, size_t at = 0) -> void { throwProtocolError(where, what, response, at); };
  const Json doc = parseResponseObject(response, "samples", where);
  const Json& samples = doc["samples"];
  if (samples.size() < static_cast<size_t>(kMinRunSamples))
    fail("too few samples (" + std::to_string(samples.size()) + "; at least " + std::to_string(kMinRunSamples) + ")");
  ProgramRun out;
  std::vector<double> omega_time;
  for (size_t i = 0; i < samples.size(); ++i) {
    const Json& s = samples[i];
    const std::string at = "samples[" + std::to_string(i) + "]";
    if (!s.is_object()) fail(at + " must be an object");
    auto number = [&](const char* key, bool required) -> std::optional<double> {
      if (!s.contains(key) || s[key].is_null()) {
        if (required) fail(at + "." + key + " is missing (every sample gives t, phi and omega)");
        return std::nullopt;
      }
      if (!s[key].is_number()) fail(at + "." + key + " must be a number");
      const double x = s[key].get<double>();
      if (!std::isfinite(x)) fail(at + "." + key + " is not a finite number");
      return x;
    };
    const double t = *number("t", true), phi = *number("phi", true), omega = *number("omega", true);
    const std::optional<double> omega_t = number("omega_t", false), values_t = number("values_t", false);
    // A sample past the run's end (beyond one output interval and one step, which a program that does not land on
    // t_end may take), or a crank angle more than kMaxTurnsFactor times the run's turns from phi0, is a broken run:
    // measured, either would cost without a bound (a sample at t = 1e9 s ran crankcheck's measures for hours, one at
    // phi = 1e300 rad crashed the turn count).
    const double overshoot = c.output_interval + c.dt.value_or(c.output_interval);
    if (t > c.t_end + overshoot + 1e-9 * c.t_end)
      fail(at + ".t is " + formatNumber(t) + " s, past the run's end t_end = " + formatNumber(c.t_end) +
           " s (by more than an output interval and a step)");
    constexpr double kMaxTurnsFactor = 100.0;
    const double max_angle = kMaxTurnsFactor * 2.0 * M_PI * (c.revolutions + 1);
    if (!(std::fabs(phi - c.phi0) <= max_angle))
      fail(at + ".phi is " + formatNumber(phi) + " rad, more than " + formatNumber(kMaxTurnsFactor) +
           " times the run's " + std::to_string(c.revolutions) + " revolutions from phi0 = " + formatNumber(c.phi0) + " rad");
    if (i > 0 && !(t > out.run.time.back()))
      fail(at + ".t is " + formatNumber(t) + " s, not after the sample before (" + formatNumber(out.run.time.back()) +
           " s): time must increase");
    if (i > 0 && !(phi > out.run.phi.back()))
      fail(at + ".phi is " + formatNumber(phi) + " rad, not past the sample before (" + formatNumber(out.run.phi.back()) +
           " rad): the crank angle must keep increasing (unwrapped, the crank turning forward)");
    // The crank turns forward (phi increasing, above): a speed <= 0 is a broken run, named here, not blamed on the
    // scene's speed by the measures that take the run's first state.
    if (!(omega > 0.0))
      fail(at + ".omega is " + formatNumber(omega) + " rad/s; the run turns forward, released at the request's omega0 = " +
           formatNumber(c.omega0) + " rad/s, so omega must stay > 0");
    const double t_omega = omega_t ? *omega_t : t;
    if (i > 0 && !(t_omega > omega_time.back()))
      fail(at + ": omega stands at " + formatNumber(t_omega) + " s, not after the sample before's (" +
           formatNumber(omega_time.back()) + " s)");
    out.run.time.push_back(t);
    out.run.phi.push_back(phi);
    out.run.omega.push_back(omega);
    omega_time.push_back(t_omega);
    out.values_time.push_back(values_t ? *values_t : t);
    Evaluation e = readProgramValues(s, at, c.mechanism, [&](const std::string& what) { fail(what); },
                                     {"t", "phi", "omega", "omega_t", "values_t"});
    for (const Quantity& q : getQuantityCatalogue())
      for (int j = 0; j < (q.per_cylinder ? c.mechanism.machine.cylinders : 1); ++j)
        for (int n = 0; n < q.components; ++n)
          if (std::isfinite(readQuantity(q, e, q.per_cylinder ? j : -1)[n])) out.any_value = true;
    e.phi = phi;
    out.values.push_back(std::move(e));
  }
  const double tolerance = 1e-9 * c.t_end;
  if (std::fabs(out.run.time.front()) > tolerance)
    fail("the first sample is at t = " + formatNumber(out.run.time.front()) + " s; it must be at t = 0");
  if (out.run.time.back() < c.t_end - tolerance)
    fail("the run stops at t = " + formatNumber(out.run.time.back()) + " s, before t_end = " + formatNumber(c.t_end) + " s");
  // Each value's instant within the run: omega's within the samples either side of its own (the first's and the
  // last's within one interval past the run: a speed kept half a step behind its angle), every other value's
  // within the run. One far outside is a broken run, not a slow one (an omega_t 1e6 s out once gave a phase of 1e41).
  const std::vector<double>& t = out.run.time;
  const size_t n = t.size();
  for (size_t i = 0; i < n; ++i) {
    const double before = i > 0 ? t[i - 1] : t[0] - (t[1] - t[0]);
    const double after = i + 1 < n ? t[i + 1] : t[n - 1] + (t[n - 1] - t[n - 2]);
    if (!(omega_time[i] >= before && omega_time[i] <= after))
      fail("samples[" + std::to_string(i) + "].omega_t is " + formatNumber(omega_time[i]) +
           " s, outside the samples either side of its t = " + formatNumber(t[i]) + " s (" + formatNumber(before) +
           " to " + formatNumber(after) + " s): omega must stand within its step");
    if (!(out.values_time[i] >= t.front() && out.values_time[i] <= t.back()))
      fail("samples[" + std::to_string(i) + "].values_t is " + formatNumber(out.values_time[i]) +
           " s, outside the run (" + formatNumber(t.front()) + " to " + formatNumber(t.back()) + " s)");
  }
  out.run.omega_time = std::move(omega_time);
  return out;
}

const Schema<RunMeasureRow>& getRunMeasuresSchema() {
  using R = RunMeasureRow;
  static const Schema<R> schema(
      kMeasuresName,
      {textField("case", &R::case_id), textField("scene", &R::scene), textField("drive", &R::drive),
       optionalField("dt", "s", &R::dt), textField("measure", &R::measure), textField("unit", &R::unit),
       optionalField("program", "SI", &R::program), optionalField("exact", "SI", &R::exact),
       optionalField("error", "SI", &R::error), numberField("tolerance", "SI", &R::tolerance),
       numberField("resolution", "SI", &R::resolution),
       numberField("horizon", "s", &R::horizon_s), textField("where", &R::where), textField("verdict", &R::verdict)});
  return schema;
}

const Schema<RunConvergenceRow>& getRunConvergenceSchema() {
  using R = RunConvergenceRow;
  static const Schema<R> schema(
      kConvergenceName,
      {textField("scene", &R::scene), textField("drive", &R::drive), textField("measure", &R::measure),
       optionalField("observed_order", "-", &R::observed_order), optionalField("largest_step", "s", &R::largest_step),
       numberField("tolerance", "SI", &R::tolerance)});
  return schema;
}

const Schema<RunHistoryRow>& getRunHistorySchema() {
  using R = RunHistoryRow;
  static const Schema<R> schema(kHistoryName,
                                {textField("case", &R::case_id), optionalField("dt", "s", &R::dt),
                                 numberField("time", "s", &R::time), numberField("phase_error", "rad", &R::phase_error),
                                 optionalField("energy_error", "-", &R::energy_error)});
  return schema;
}

namespace {

// Grades one answer: its measure rows and its history rows.
void gradeRun(const RunCase& c, const ProgramRun& answer, const RunTolerances& tol, const std::string& program,
              std::vector<RunMeasureRow>& measures, std::vector<RunHistoryRow>& history) {
  const Mechanism& m = c.mechanism;
  const Trajectory& run = answer.run;
  // The horizon: t_end, or the run's last sample where that stands within rounding before it (parseRunResponse allows
  // 1e-9 of t_end: a run that adds its steps up reaches t_end to rounding).
  const double horizon = std::min(c.t_end, run.time.back());
  auto row = [&](const MeasureInfo& info, std::optional<double> value, std::optional<double> exact, double error,
                 double tolerance, double resolution, std::string where) {
    RunMeasureRow r;
    r.case_id = c.id;
    r.scene = c.family;
    r.drive = nameOf(c.drive);
    r.dt = c.dt;
    r.measure = info.name;
    r.unit = info.unit;
    r.program = value;
    r.exact = exact;
    r.error = error;
    r.tolerance = tolerance;
    r.resolution = resolution;
    r.horizon_s = horizon;
    r.where = std::move(where);
    r.verdict = verdictOf(error, tolerance);
    measures.push_back(std::move(r));
  };
  const size_t first_history = history.size();
  try {
    const TrajectoryReader reader(run);
    const double revolutions = (run.phi.back() - run.phi.front()) / kTwoPi;
    // The history's instants: kHistoryPointsPerRevolution per revolution of the horizon, and t_end.
    std::vector<double> times;
    const int points = c.revolutions * kHistoryPointsPerRevolution;
    for (int i = 0; i <= points; ++i) times.push_back(horizon * i / points);
    if (c.drive != RunDrive::kHeld) {
      const RunLoad load{c.drive == RunDrive::kLoaded};
      const bool cycles = load.gas && m.machine.cycle == Cycle::kFourStroke;  // the period: a working cycle of 4 pi
      const std::string period = cycles ? "working cycle" : "revolution";
      const std::vector<double> energy = calcEnergyAtTurns(m, run, load);
      const double trend = calcEnergyTrend(m, run, load);
      row(cycles ? kEnergyTrendPerCycle : kEnergyTrend, trend, 0.0, std::fabs(trend), tol.energy_trend, 64.0 * kEps,
          "over " + std::to_string(energy.size() - 1) + " " + period + "s, at phi = phi0 + " +
              (cycles ? "4 pi k" : "2 pi k") + (load.gas ? " (E - W + T_L phi)" : ""));
      const SpeedFluctuationComparison f = calcSpeedFluctuation(m, run, load);
      row(kDelta, f.run.delta, f.exact.delta, std::fabs(f.delta_error) / f.exact.delta, tol.delta,
          64.0 * kEps / f.exact.delta, "first " + period);
      const double to_deg = 180.0 / M_PI, flat = 8.0 * std::sqrt(kEps / f.exact.delta) * to_deg;
      row(kPhiAtOmegaMax, f.run.phi_at_omega_max * to_deg, f.exact.phi_at_omega_max * to_deg,
          std::fabs(f.phi_max_error) * to_deg, tol.extreme_phase, flat, "first " + period);
      row(kPhiAtOmegaMin, f.run.phi_at_omega_min * to_deg, f.exact.phi_at_omega_min * to_deg,
          std::fabs(f.phi_min_error) * to_deg, tol.extreme_phase, flat, "first " + period);
      // The turns' crossings join the history with their energy.
      std::vector<double> turn_times;
      const double turn = cycles ? 2.0 * kTwoPi : kTwoPi;
      for (size_t k = 0; k < energy.size(); ++k) turn_times.push_back(reader.findTimeAtPhase(run.phi.front() + turn * k));
      std::vector<double> all = times;
      all.insert(all.end(), turn_times.begin(), turn_times.end());
      const std::vector<double> errors = calcPhaseErrors(m, run, all, load);
      const double at_end = errors[times.size() - 1];
      row(kPhase, reader.findPhi(horizon), reader.findPhi(horizon) - at_end, std::fabs(at_end), tol.phase,
          64.0 * kEps * reader.findPhi(horizon), "t = " + formatNumber(horizon) + " s (" + formatNumber(std::round(revolutions * 10) / 10) + " revolutions)");
      for (size_t i = 0; i < times.size(); ++i) history.push_back({c.id, c.dt, times[i], errors[i], std::nullopt});
      for (size_t k = 0; k < turn_times.size(); ++k)
        history.push_back({c.id, c.dt, turn_times[k], errors[times.size() + k], energy[k] / energy.front() - 1.0});
    } else {
      auto held = [&](double t) { return reader.findPhi(t) - (c.phi0 + c.omega0 * t); };
      const double at_end = held(horizon);
      row(kPhase, reader.findPhi(horizon), c.phi0 + c.omega0 * horizon, std::fabs(at_end), tol.phase,
          64.0 * kEps * reader.findPhi(horizon), "t = " + formatNumber(horizon) + " s (" + std::to_string(c.revolutions) + " revolutions)");
      for (double t : times) history.push_back({c.id, c.dt, t, held(t), std::nullopt});
    }
    std::stable_sort(history.begin() + static_cast<long>(first_history), history.end(),
                     [](const RunHistoryRow& a, const RunHistoryRow& b) { return a.time < b.time; });

    // The values at the program's own states against the exact values at those states.
    const Scales scales = calcPositiveScales(m);
    struct Worst {
      double error = -1.0, t = 0.0, phi = 0.0;
      int cylinder = -1;
    };
    std::map<std::string, Worst> worst;  // by quantity
    std::vector<std::string> order;
    for (size_t i = 0; i < answer.values.size(); ++i) {
      const Evaluation& given = answer.values[i];
      std::optional<Evaluation> exact;
      const double tv = answer.values_time[i];
      for (const Quantity& q : getQuantityCatalogue()) {
        if (q.id == QuantityId::kU || q.id == QuantityId::kQ) continue;  // functions of phi alone: the state grade's
        for (int j = 0; j < (q.per_cylinder ? m.machine.cylinders : 1); ++j) {
          const double* p = readQuantity(q, given, q.per_cylinder ? j : -1);
          for (int n = 0; n < q.components; ++n) {
            if (!std::isfinite(p[n])) continue;
            if (!(tv >= run.time.front() && tv <= run.time.back()))
              throw std::invalid_argument("samples[" + std::to_string(i) + "].values_t = " + formatNumber(tv) +
                                          " s is outside the run");
            const double phi = reader.findPhi(tv);
            if (!exact) exact = calcExactValuesAt(c, phi, reader.findOmega(tv));
            const double e = readQuantity(q, *exact, q.per_cylinder ? j : -1)[n];
            const double error = std::fabs(p[n] - e) / getQuantityScale(scales, q.scale, m);
            auto [it, inserted] = worst.try_emplace(q.name);
            if (inserted) order.push_back(q.name);
            if (error > it->second.error) it->second = {error, tv, phi, q.per_cylinder ? j : -1};
          }
        }
      }
    }
    for (const std::string& name : order) {
      const Worst& w = worst[name];
      const double phi_deg = std::fmod(w.phi, kTwoPi) * 180.0 / M_PI;
      row({name.c_str(), "-"}, std::nullopt, std::nullopt, w.error, tol.values, 64.0 * kEps,
          "t = " + formatNumber(w.t) + " s, phi = " + formatNumber(std::round(phi_deg * 100) / 100) + " deg" +
              (w.cylinder >= 0 ? ", cylinder " + std::to_string(w.cylinder) : std::string()));
      measures.back().measure = name;
    }
  } catch (const std::invalid_argument& e) {
    throw EnvironmentError(program + ": case " + c.id + ": the run cannot be measured: " + e.what());
  } catch (const std::domain_error& e) {
    throw EnvironmentError(program + ": case " + c.id + ": the run cannot be measured: " + e.what());
  }
}

}  // namespace

TableSet runRunGrade(const std::vector<RunCase>& cases, const GradeProgram& program, const RunTolerances& tolerances,
                     const std::function<void(size_t, size_t)>& progress) {
  if (program.argv.empty()) throw UsageError("grade: no program given (crankcheck grade --free-run SCENE -- PROGRAM)");
  // The limit is per run at its scene's largest step; a run of n times the steps (its step halved log2 n times in a
  // sweep) has n times the limit: the sweep's finest step is no more likely to meet it than the first.
  std::map<std::string, double> largest_step;
  for (const RunCase& c : cases)
    if (c.dt) largest_step[c.family] = std::max(largest_step[c.family], *c.dt);
  return gradeRunAnswers(
      cases,
      [&](const RunCase& c) {
        GradeProgram scaled = program;
        if (c.dt) scaled.timeout_seconds *= largest_step.at(c.family) / *c.dt;
        return runOnce(scaled, makeRunRequest(c) + "\n", 1, "case " + c.id);
      },
      tolerances, program.argv.front(), progress);
}

TableSet gradeRunAnswers(const std::vector<RunCase>& cases, const std::function<std::string(const RunCase&)>& answer,
                         const RunTolerances& tolerances, const std::string& name,
                         const std::function<void(size_t, size_t)>& progress) {
  std::vector<RunMeasureRow> measures;
  std::vector<RunHistoryRow> history;
  for (size_t i = 0; i < cases.size(); ++i) {
    const RunCase& c = cases[i];
    const ProgramRun run = parseRunResponse(c, answer(c), name);
    gradeRun(c, run, tolerances, name, measures, history);
    if (progress) progress(i + 1, cases.size());
  }

  // Convergence over each scene's sweep: per measure, the observed order and the largest step meeting the tolerance.
  std::vector<RunConvergenceRow> convergence;
  std::vector<std::string> scenes;
  for (const RunCase& c : cases)
    if (std::find(scenes.begin(), scenes.end(), c.family) == scenes.end()) scenes.push_back(c.family);
  for (const std::string& scene : scenes) {
    std::vector<std::string> names;
    std::map<std::string, std::vector<const RunMeasureRow*>> by_measure;
    for (const RunMeasureRow& r : measures)
      if (r.scene == scene && r.dt && r.error) {
        if (!by_measure.count(r.measure)) names.push_back(r.measure);
        by_measure[r.measure].push_back(&r);
      }
    for (const std::string& measure : names) {
      std::vector<const RunMeasureRow*> rows = by_measure[measure];
      if (rows.size() < 2) continue;
      std::sort(rows.begin(), rows.end(), [](const RunMeasureRow* a, const RunMeasureRow* b) { return *a->dt > *b->dt; });
      RunConvergenceRow out;
      out.scene = scene;
      out.drive = rows.front()->drive;
      out.measure = measure;
      out.tolerance = rows.front()->tolerance;
      std::vector<double> steps, errors;
      for (const RunMeasureRow* r : rows)
        if (*r->error > 10.0 * r->resolution) steps.push_back(*r->dt), errors.push_back(*r->error);
      if (steps.size() >= 2 && steps.front() != steps.back()) out.observed_order = calcObservedOrder(steps, errors);
      for (size_t i = rows.size(); i-- > 0;) {  // from the smallest step up, while each meets the tolerance
        if (!(*rows[i]->error <= rows[i]->tolerance)) break;
        out.largest_step = *rows[i]->dt;
      }
      convergence.push_back(std::move(out));
    }
  }
  TableSet tables;
  tables.emplace(kMeasuresName, getRunMeasuresSchema().table(std::move(measures)));
  tables.emplace(kHistoryName, getRunHistorySchema().table(std::move(history)));
  if (!convergence.empty()) tables.emplace(kConvergenceName, getRunConvergenceSchema().table(std::move(convergence)));
  return tables;
}

void addEngineRuns(TableSet& tables, const std::vector<RunCase>& cases, bool quick) {
  std::vector<EngineRunRow> rows;
  std::set<std::string> done;
  for (const RunCase& c : cases) {
    if (c.drive == RunDrive::kHeld || !done.insert(c.family).second) continue;
    const RunLoad load{c.drive == RunDrive::kLoaded};
    // Every engine that runs free (the physics engines people ship take no gas and no load: not in a loaded run's).
    for (EngineRunRow& row :
         calcEngineRuns(c.mechanism, c.omega0, c.revolutions, listDefaultEngineRuns(quick, load), load))
      rows.push_back(std::move(row));
  }
  if (!rows.empty()) addRows(tables, getFreeRunEnginesSchema(), std::move(rows));
}

void checkRunGradeWork(const std::vector<RunCase>& cases, bool quick, double limit_seconds) {
  // crankcheck's own work after the program answers, in all: the engines' reference runs of each scene (every
  // horizon: on a k = 64 scene the default 10 revolutions of Simbody's and MuJoCo's runs took over 10 minutes, and
  // were not estimated), timed over one revolution and counted for the horizon (an upper bound: a run's start costs
  // more than its later revolutions; a tenth more work on the default horizon), plus the stepped engines' free runs, their steps at each engine's
  // measured cost of a step (estimateSteppedWork: no probe where a ceiling on that cost keeps the sum in the limit).
  // Each engine's run is probed on its own, and the probing stops once what it measured already passes the limit:
  // the check costs at most about the limit over the revolutions (a minute of the default), not the whole work.
  double reference = 0.0;
  int revolutions = 0;
  std::set<std::string> done;
  for (const RunCase& c : cases) {
    revolutions = std::max(revolutions, c.revolutions);
    if (c.drive == RunDrive::kHeld || !done.insert(c.family).second || reference > limit_seconds) continue;
    const RunLoad load{c.drive == RunDrive::kLoaded};
    // One revolution of each; a loaded run's working cycle, two of a four-stroke (its measures need a whole cycle).
    const int probed = std::min(c.revolutions, load.gas && c.mechanism.machine.cycle == Cycle::kFourStroke ? 2 : 1);
    for (const EngineRunSpec& spec : listDefaultEngineRuns(quick, load)) {
      if (findEngineOffering(spec.engine, Route::kStepFree)) continue;  // estimated by its steps below
      const auto begin = std::chrono::steady_clock::now();
      (void)calcEngineRuns(c.mechanism, c.omega0, probed, {spec}, load);
      reference += std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count() * c.revolutions /
                   probed;
      if (reference > limit_seconds) break;
    }
  }
  double stepped = 0.0;
  std::string stepped_how;
  std::set<std::string> families;
  for (const RunCase& c : cases) {
    if (c.drive != RunDrive::kFree || !families.insert(c.family).second || reference > limit_seconds) continue;
    std::vector<SteppedJob> jobs;
    for (const EngineRunSpec& spec : listDefaultEngineRuns(quick))
      if (const Engine* e = findEngineOffering(spec.engine, Route::kStepFree))
        jobs.push_back({e, spec.integrator, spec.accuracy, 1.1 * c.t_end / spec.accuracy});
    const SteppedWorkEstimate e =
        estimateSteppedWork(c.mechanism, jobs, std::max(limit_seconds - reference - stepped, 0.0),
                            "--revolutions: the stepped engines' free runs of " + c.family + " over " +
                                std::to_string(c.revolutions) + " revolutions",
                            "fewer --revolutions");
    stepped += e.seconds;
    if (stepped_how.empty()) stepped_how = e.how;
  }
  checkWorkLimit("--revolutions: crankcheck's own runs over " + std::to_string(revolutions) + " revolutions",
                 reference + stepped,
                 "the engines' reference runs of each scene timed over one revolution and counted for the horizon, " +
                     std::string(reference > limit_seconds ? "at least " : "") + formatDuration(reference) +
                     (reference > limit_seconds ? " (probing stopped past the limit)" : "") + "; the stepped engines' free runs " +
                     formatDuration(stepped) + (stepped_how.empty() ? std::string() : " (" + stepped_how + ")"),
                 "fewer --revolutions", limit_seconds);
}

int findRunGradeExitStatus(const TableSet& tables) {
  // The largest step of each scene: the one asked (--dt); the sweep's smaller steps are the convergence study.
  std::map<std::string, double> largest;
  for (const RunMeasureRow& r : getRows(tables, getRunMeasuresSchema()))
    largest[r.scene] = std::max(largest[r.scene], r.dt ? *r.dt : 0.0);
  int graded = 0;
  for (const RunMeasureRow& r : getRows(tables, getRunMeasuresSchema())) {
    if ((r.dt ? *r.dt : 0.0) != largest[r.scene] || r.verdict == "not provided") continue;
    ++graded;
    if (r.verdict != "pass") return 1;
  }
  return graded > 0 ? 0 : 1;
}

}  // namespace crankcheck::validation
