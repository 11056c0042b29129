#pragma once
/// @file
/// `crankcheck grade --free-run`: a program that steps the crank train through time (an engine simulator, a game or
/// robotics physics engine, a student's integrator) judged on its run. crankcheck sends it one request per time step of
/// its sweep (protocol 2, docs/grade.md "Time-stepped runs"), under the process rules of protocol 1 (grade.h: argument
/// vector, time limit, killed process group, output limit), and measures the trajectory it answers against the exact
/// run (run_measures.h) and the engines that simulate (engine_runs.h).
///
/// Protocol 2:
///   request   {"protocol": 2, "case": ID, "scene": {...as eval's...}, "scene_toml": "...", "drive": "free"|"held"|"loaded",
///             "gas": BOOL, "load_torque": N M, "gravity": true, "phi0": RAD, "omega0": RAD/S, "dt": S|"own",
///             "t_end": S, "output_interval": S, "quantities": [...]}
///   response  {"samples": [{"t": S, "phi": RAD, "omega": RAD/S, "omega_t": S?, "values_t": S?,
///               ...values as eval's names, "cylinders": [...]}, ...]}
/// omega_t and values_t say at which instant omega and the other values stand (default: t): a velocity kept as a
/// backward difference stands half a step behind its angle, a constraint force solved over a step at the step's middle;
/// the grade evaluates the exact values at those instants.

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "crankcheck/scene/evaluation.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/engine_runs.h"
#include "crankcheck/validation/grade.h"
#include "crankcheck/validation/run_measures.h"
#include "crankcheck/validation/table.h"

namespace crankcheck::validation {

/// What drives the crank in a run.
enum class RunDrive {
  kFree,  ///< nothing: the crank turns freely under gravity alone (no gas, no load), released at phi0 with omega0
  kHeld,  ///< the crank is held at the constant speed omega0 (phi = phi0 + omega0 t); the program reports the torque
  /// the crank turns freely under the scene's gas and gravity against a constant load torque, the gas torque's cycle
  /// mean, from the steady run's speed at phi = 0: the exact run is periodic over the working cycle at the scene's speed
  kLoaded,
};
/// "free", "held", "loaded".
const char* nameOf(RunDrive drive);

/// What is asked of a run and what it is held to. Every tolerance states its horizon: the run's t_end.
struct RunTolerances {
  double energy_trend = 1e-6;     ///< |energy trend| [1 / revolution], relative to E_0
  double delta = 1e-3;            ///< |delta_run - delta_exact| / delta_exact [-]
  double extreme_phase = 1.0;     ///< [deg] the phases of omega_max and omega_min against the exact run's
  double phase = 1e-3;            ///< [rad] |phi_run - phi_exact| at the horizon
  double values = 1e-3;           ///< |program - exact| / the quantity's scale, at the program's own states
};

/// How the grade's requests are built (RunCase).
struct RunSettings {
  RunDrive drive = RunDrive::kFree;
  int revolutions = 10;              ///< the horizon, in revolutions of the exact run at the scene's speed
  std::optional<double> dt;          ///< [s] the step asked; none: 1/720 of a revolution (getDefaultRunStep)
  bool own_step = false;             ///< the program's own step ("dt": "own"; dt and dt_sweep are then not used)
  int dt_sweep = 1;                  ///< the number of steps: dt, dt / 2, dt / 4, ... (1: dt alone)
  std::optional<double> output_interval;  ///< [s] none: every step of each run (own: 1/720 of a revolution)
  RunTolerances tolerances;
};

/// The exact run's time per revolution at the scene's speed: one revolution of the free run released at phi = 0 with
/// the scene's speed (free), 2 pi / omega (held, and loaded: the steady run's mean speed is the scene's) [s].
double calcRunPeriod(const Mechanism& m, RunDrive drive);

/// The step the grade asks when none is given: 1/720 of a revolution (half a degree) [s].
double getDefaultRunStep(const Mechanism& m, RunDrive drive);

/// One request: a scene, a drive, a step.
struct RunCase {
  std::string id;            ///< unique, [A-Za-z0-9_] only
  std::string family;        ///< the scene it comes from
  RunDrive drive = RunDrive::kFree;
  Mechanism mechanism;       ///< parsed back from scene_toml (free: the scene without [gas])
  std::string scene_toml;
  double phi0 = 0.0;         ///< [rad] the crank angle at t = 0 (0: where the engines release their own runs)
  double omega0 = 0.0;       ///< [rad/s] the scene's speed (loaded: the steady run's speed at phi = 0)
  double load_torque = 0.0;  ///< [N m] loaded: the gas torque's cycle mean (GasWork::getMeanTorque); else 0
  std::optional<double> dt;  ///< [s] none: the program's own
  double t_end = 0.0;        ///< [s] revolutions x calcRunPeriod
  double output_interval = 0.0;  ///< [s]
  int revolutions = 0;
};

/// The requests of one scene: one per step of the sweep (dt, dt / 2, ...).
/// @throws UsageError naming the scene when it cannot be run: no speed; free or loaded without [flywheel].inertia;
///         loaded without [gas]; free when the exact run does not turn over (too slow against gravity); loaded when the
///         steady run would stop.
std::vector<RunCase> buildRunCases(const Mechanism& scene, const RunSettings& settings);

/// The request as one line of JSON (no newline inside; none at the end).
std::string makeRunRequest(const RunCase& c);

/// A program's answer to one request.
struct ProgramRun {
  Trajectory run;                    ///< t, phi, omega (with omega's own instants)
  std::vector<double> values_time;   ///< [s] the instant each sample's other values stand at
  std::vector<Evaluation> values;    ///< NaN where not provided (readProgramValues)
  bool any_value = false;            ///< some sample provided some value beyond phi and omega
};

/// Reads a response. @throws EnvironmentError "PROGRAM: case ID: what is wrong; line N: "..."" when it is not the
/// protocol: not JSON, no "samples", a value not a finite number, t not strictly increasing, the first sample not at
/// t = 0 or the last not at t_end (within 1e-9 of t_end), fewer than kMinRunSamples samples, phi not increasing.
ProgramRun parseRunResponse(const RunCase& c, const std::string& response, const std::string& program);

/// One row of free_run_measures: one measure of one run.
struct RunMeasureRow {
  std::string case_id, scene, drive;
  std::optional<double> dt;          ///< [s] none: the program's own step
  std::string measure;               ///< energy_trend, delta, phi_at_omega_max, phi_at_omega_min, phase, or a quantity
  std::string unit;                  ///< the unit of program, exact and error
  std::optional<double> program;     ///< the program's (none for a quantity: see error)
  std::optional<double> exact;       ///< the exact run's
  std::optional<double> error;       ///< as the tolerance measures it; none: not provided
  double tolerance = 0.0;
  /// The smallest error the measure resolves (errors below are rounding; the observed order leaves them out): 64 eps
  /// for the energy trend and a value / scale, 64 eps / delta for delta, 8 sqrt(eps / delta) rad for the phase of an
  /// extreme of speed (a flat extreme's phase is known to the square root of its speed's rounding), 64 eps phi(t_end)
  /// for the phase
  double resolution = 0.0;
  double horizon_s = 0.0;            ///< [s] the run's t_end
  std::string where;                 ///< where the error is (the revolutions, the time, the sample)
  std::string verdict;               ///< "pass", "FAIL", "not provided"
};
const Schema<RunMeasureRow>& getRunMeasuresSchema();

/// One row of free_run_convergence: one measure over a sweep of steps.
struct RunConvergenceRow {
  std::string scene, drive, measure;
  std::optional<double> observed_order;      ///< the slope of log error against log dt over the steps whose error is
                                             ///< above 10 times its resolution (none: fewer than 2)
  std::optional<double> largest_step;        ///< [s] the largest step that meets the tolerance with every smaller one
  double tolerance = 0.0;
};
const Schema<RunConvergenceRow>& getRunConvergenceSchema();

/// One row of free_run_history: the run's errors against time (the report's figure).
struct RunHistoryRow {
  std::string case_id;
  std::optional<double> dt;      ///< [s]
  double time = 0.0;             ///< [s]
  double phase_error = 0.0;      ///< [rad] phi_run - phi_exact at `time` (held: phi0 + omega0 t)
  std::optional<double> energy_error;  ///< (E - E_0) / E_0 at a crossing of phi0 + 2 pi k (free runs)
};
const Schema<RunHistoryRow>& getRunHistorySchema();

/// Runs the program on every case (one program per case, one at a time) and grades each answer. Tables:
/// free_run_measures, free_run_convergence (with more than one step per scene), free_run_history.
/// @throws EnvironmentError (exit status 3) when the program cannot be run, crashes, times out, breaks the protocol, or
///         answers a run the measures cannot read (not covering one revolution, phi not increasing).
TableSet runRunGrade(const std::vector<RunCase>& cases, const GradeProgram& program, const RunTolerances& tolerances,
                     const std::function<void(size_t, size_t)>& progress = {});

/// The engines' own runs of each scene of `cases` that runs free or loaded (engine_runs.h: listDefaultEngineRuns(quick),
/// over the cases' revolutions from the cases' speed; loaded: the engines that take the gas and a load), added to
/// `tables` as free_run_engines: what the program's measures stand beside. Costs a few seconds of one core per scene (quick: under one).
/// @throws std::runtime_error if an engine's run fails.
void addEngineRuns(TableSet& tables, const std::vector<RunCase>& cases, bool quick);

/// Checks before any run that crankcheck's own work on `cases`, in all, is estimated within `limit_seconds`
/// (work_limit.h): the engines' reference runs of addEngineRuns over the horizon, each scene's timed over one revolution
/// and counted for its revolutions (an upper bound: a run's start costs more than its later revolutions), at every
/// horizon; plus the stepped engines' free runs, from each engine's measured cost of a step
/// (commands/stepped.h estimateSteppedWork).
/// @throws UsageError "--revolutions: ... would take about ..., more than --work-limit ..."
void checkRunGradeWork(const std::vector<RunCase>& cases, bool quick, double limit_seconds);

/// The terminal's summary: per scene, each step's measures (program, exact, error, tolerance, verdict), then with a
/// sweep each measure's observed order and largest step meeting its tolerance; within 100 columns.
std::string formatRunGradeSummary(const TableSet& tables, const std::vector<RunCase>& cases);

/// What the report says about the run.
struct RunGradeReportInfo {
  std::vector<std::string> program;  ///< the graded command line
  double seconds = 0.0;              ///< wall time of the grade
  double timeout_seconds = 0.0;
  RunTolerances tolerances;
  std::string gnuplot_version;
};

/// Renders the report into `dir` (which must exist and be empty): data/*.csv, the figures free_run_error_vs_time and
/// (with a sweep) free_run_error_vs_step, index.md and index.html.
/// @throws EnvironmentError if gnuplot fails or a file cannot be written.
void renderRunGradeReport(const TableSet& tables, const std::vector<RunCase>& cases, const RunGradeReportInfo& info,
                          const std::filesystem::path& dir);

/// The grade of runGrade with the answers from `answer(case)` (the response line of each case, in order) instead of a
/// program: the Python module's grade of a function. `name` names the answerer in messages.
/// @throws EnvironmentError as runRunGrade for an answer that is not the protocol or cannot be measured; what `answer`
///         throws.
TableSet gradeRunAnswers(const std::vector<RunCase>& cases, const std::function<std::string(const RunCase&)>& answer,
                         const RunTolerances& tolerances, const std::string& name,
                         const std::function<void(size_t, size_t)>& progress = {});

/// 0 when every measure of the largest step of every scene passes (a measure not provided does not count) and at least
/// one was graded, 1 otherwise.
int findRunGradeExitStatus(const TableSet& tables);

}  // namespace crankcheck::validation
