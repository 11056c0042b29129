#pragma once
/// @file
/// `crankcheck grade`: anyone's implementation of these formulas, in any language, judged the way the gate judges
/// the analytic engine. crankcheck starts the user's program (never through a shell), sends it one JSON request
/// per case on stdin and reads one JSON response from its stdout; each value the program provides is compared with
/// Simbody's and with the analytic engine's by the gate's rule (scales.h: |a - b| <= 64 eps scale conditioning,
/// compareEvaluations, the same code path as the gate).
///
/// Scales: calcPositiveScales (a positive scale for every quantity, at rest and without gravity too).
///
/// Protocol 1 (docs/grade.md):
///   request   {"protocol": 1, "case": ID, "scene": {...as eval's "scene"...}, "scene_toml": "...a scene file crankcheck
///             accepts...", "phi_deg": [...], "quantities": ["U", "Q", ...]} (the catalogue's names the scene
///             defines, quantities.h)
///   response  {"results": [...one object per angle, in order, as eval's "results" without "engine"...]}
/// A value left out, or null, is "not provided": reported as such, never as wrong, never as right. Anything else
/// that is not the protocol (not JSON, the wrong number of results, a string where a number belongs, a number
/// that is not finite, a result for another angle) ends the grade with exit status 3 and the first offending line,
/// quoted with every control byte escaped (errors.h: quoteText).
/// With `batch`, one program gets every request of its share of the cases, one per line, and answers one response
/// per line in the same order.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "crankcheck/solver/engine.h"

#include "crankcheck/scene/evaluation.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/grade_program.h"
#include "crankcheck/validation/table.h"

namespace crankcheck::validation {

/// What a program is judged against, in the order of the grade tables' columns: the first reference engine (the
/// program's `rel_error` is against it), the closed forms, then the other reference engines (engines.h).
std::vector<const Engine*> listGradeJudges();

/// One request: a scene at one speed and its crank angles.
struct GradeCase {
  std::string id;          ///< unique, [A-Za-z0-9_] only: the file stem of its scene in the report
  std::string family;      ///< the scene it comes from
  Mechanism mechanism;     ///< parsed back from scene_toml: the file and the references are the same mechanism
  std::string scene_toml;  ///< formatSceneToml
  std::vector<double> phi_deg;
};

/// The campaign of a grade: every scene (the built-in ones when `scenes` is empty) at its own lambda and at
/// lambda 0.1, 0.2, 0.3, 0.4, 0.6, 0.9 (quick: 0.9), at its speed and at rest, every 15 degrees (quick: 45); the
/// built-in campaign adds the gate's sweep (k = 1..12, both strokes, 11 lambdas up to 0.999, 5 bank angles, the
/// gate's angles) unless quick.
std::vector<GradeCase> buildGradeCases(const std::vector<Mechanism>& scenes, bool quick);

/// The request of one case as one line of JSON (no newline inside; none at the end).
std::string makeGradeRequest(const GradeCase& c);

/// The program's answer for one case: its values as Evaluations (one per angle), NaN where not provided, and
/// shaking_moment X, Y NaN when the scene has no axial positions (not defined, so never graded).
/// @throws EnvironmentError "PROGRAM: case ID: what is wrong: first offending line" when the response is not the
/// protocol; its line numbered from `first_line`, the response's line in the program's stdout (a --batch's nth line).
std::vector<Evaluation> parseGradeResponse(const GradeCase& c, const std::string& response, const std::string& program,
                                           size_t first_line = 1);

/// A part of the cases the summary shows on its own: a simulator's errors at rest and at speed, and at small and
/// large lambda, differ by orders of magnitude.
struct GradeRegime {
  const char* id;     ///< the summary's `regime` column: all, moving_lambda_le_0.4, ..., at_rest_lambda_gt_0.4
  const char* words;  ///< as the terminal and the report say it: "moving, lambda <= 0.4"
};
/// "all" first, then moving (speed > 0) and at rest, each with lambda up to 0.4 and beyond.
const std::vector<GradeRegime>& getGradeRegimes();
/// The words of a regime id ("all cases" for "all"); the id itself when unknown.
std::string describeGradeRegime(const std::string& id);

/// One row of grade_summary: what a grade found for one quantity in one regime (getGradeRegimes; "all" first, a regime
/// without a value asked left out). The numbers are empty when no value was provided. Errors are relative to the
/// quantity's scale; one beyond double's range is its largest number (1.8e308), never inf.
struct GradeSummaryRow {
  std::string quantity;
  std::string regime;  ///< a GradeRegime's id
  int asked = 0;       ///< values asked (every defined component at every angle of every case of the regime)
  int provided = 0;    ///< of them, the values the program provided
  /// The largest |program - reference| / scale over every provided value and every judge.
  std::optional<double> largest_rel_error;
  /// The largest error / scale against each judge, in listGradeJudges()'s order (columns largest_rel_error_NAME).
  std::vector<std::optional<double>> largest_rel_error_by;
  std::string largest_where_case;  ///< where the largest error is ("" when none was provided)
  std::optional<double> largest_where_phi_deg, largest_where_speed_rpm;  ///< [deg], [rpm]
  /// Where error / tolerance is worst: that error / scale, the ratio, and the tolerance / scale there.
  std::optional<double> rel_error_at_worst_ratio, worst_ratio, tolerance_rel;
  std::string where_case;                                 ///< where the worst ratio is ("" when none was provided)
  std::optional<double> where_phi_deg, where_speed_rpm;  ///< [deg], [rpm]
  std::string verdict;  ///< "pass", "FAIL" or "not provided"
};
/// grade_summary's declaration (its columns follow listGradeJudges(): call it after main() starts).
const Schema<GradeSummaryRow>& getGradeSummarySchema();

/// One row of grade_error_vs_lambda: a provided quantity's largest errors / scale at one lambda.
struct GradeLambdaRow {
  std::string quantity;
  double lambda = 0.0;                  ///< r / l [-]
  double program_max_rel_error = 0.0;   ///< the program's, against the first judge
  double analytic_max_rel_error = 0.0;  ///< the closed forms' own, against the first judge
};
/// grade_error_vs_lambda's declaration.
const Schema<GradeLambdaRow>& getGradeErrorVsLambdaSchema();

/// One row of grade_failures: the worst failing value of one (case, quantity, cylinder).
struct GradeFailureRow {
  std::string case_id, family;
  double lambda = 0.0;                ///< r / l [-]
  std::string quantity;
  std::optional<int> cylinder;        ///< none for a quantity of the whole engine
  double phi_deg = 0.0;               ///< [deg]
  double speed_rpm = 0.0;             ///< [rpm]
  double program_value = 0.0;         ///< [SI] the quantity's own unit
  /// [SI] each judge's value, in listGradeJudges()'s order (columns NAME_value: the first two before rel_error, the
  /// others after tolerance_rel).
  std::vector<double> judge_values;
  double rel_error = 0.0;      ///< |program - first judge| / scale
  double tolerance_rel = 0.0;  ///< the tolerance / scale
};
/// grade_failures' declaration (its columns follow listGradeJudges()).
const Schema<GradeFailureRow>& getGradeFailuresSchema();

/// The schema of grade's table `name` (a CSV stem: the three above); nullptr for any other name. The CSV reader
/// (csv.h: findTableSchema) reads a grade report's data/*.csv back into typed rows through it.
const TableSchema* findGradeTableSchema(const std::string& name);

/// Runs the program on `cases` (several programs at once with jobs > 1; batch: one program per job) and grades
/// every answer. `progress(done, total)` is called after each case. Tables (reports/README.md): grade_summary
/// (GradeSummaryRow), grade_error_vs_lambda (GradeLambdaRow, the rows of the quantities provided) and grade_failures
/// (GradeFailureRow).
/// Every provided value is compared with three references: Simbody, the analytic engine and MuJoCo (exact
/// multipliers); it passes when it agrees with all three by the gate's rule.
/// @throws EnvironmentError when the program cannot be started, crashes, exits with a non-zero status, times out,
/// writes more than the output limit or answers something that is not the protocol (exit status 3).
TableSet runGrade(const std::vector<GradeCase>& cases, const GradeProgram& program, int jobs,
                  const std::function<void(size_t, size_t)>& progress = {});

/// What the report says about the run.
struct GradeReportInfo {
  std::vector<std::string> program;  ///< the graded command line
  bool quick = false, batch = false;
  int jobs = 1;
  double seconds = 0.0;              ///< wall time of the grade
  double timeout_seconds = 0.0;
  std::string gnuplot_version;
  /// The crankcheck program the report's "reproduce" commands call: the one that graded (its absolute path: a build
  /// tree's build/bin/crankcheck is not on PATH); "crankcheck" where it is not known.
  std::string crankcheck_program = "crankcheck";
  /// The engines that cannot build one of the scenes (findSatOut, engines.h): the grade ran in a SatOutScope of them,
  /// against the other engines, and the report names each one with its reason.
  std::vector<SatOut> sat_out;
};

/// Renders the grade's report into `dir` (which must exist and be empty): data/*.csv, the figure
/// grade_error_vs_lambda (when a quantity was provided), cases/ID.toml for every failing case (so that the
/// report's one-line `crankcheck eval` commands reproduce them), index.md and index.html.
/// @throws EnvironmentError if gnuplot fails or a file cannot be written.
void renderGradeReport(const TableSet& tables, const std::vector<GradeCase>& cases, const GradeReportInfo& info,
                       const std::filesystem::path& dir);

/// Verdict of a grade (the summary's "all" rows): 0 when every provided value agrees with every reference engine and
/// at least one was provided, 1 otherwise.
int findGradeExitStatus(const TableSet& tables);

}  // namespace crankcheck::validation
