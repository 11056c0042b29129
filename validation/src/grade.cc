#include "crankcheck/validation/grade.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "crankcheck/validation/campaign_scenes.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/scene/quantities.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/scene/scene_writer.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/evaluation_json.h"
#include "crankcheck/validation/process.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/validation/variants.h"
#include "crankcheck/validation/worst_by_quantity.h"
#include "grade_protocol.h"
#include "parts/engine_fields.h"

namespace crankcheck::validation {

namespace {

using Json = nlohmann::json;

double lambdaOf(const Mechanism& m) { return calcCrankRatio(m); }

// The case as the file says it: the scene text, and the mechanism parsed back from it.
GradeCase makeCase(const std::string& family, const std::string& id, const Mechanism& m, const std::vector<double>& angles) {
  GradeCase c;
  c.id = id;
  c.family = family;
  Mechanism rigid = m;
  rigid.crankshaft.reset();  // grade is about the rigid shaft: the programs see no [crankshaft] table
  c.scene_toml = formatSceneToml(rigid);
  c.mechanism = parseScene(c.scene_toml, id);
  c.mechanism.name = id;
  c.phi_deg = angles;
  return c;
}


}  // namespace

std::vector<GradeCase> buildGradeCases(const std::vector<Mechanism>& scenes, bool quick) {
  const std::vector<Mechanism> families = scenes.empty() ? buildDefaultScenes() : scenes;
  const std::vector<double> sweep = quick ? std::vector<double>{0.9} : std::vector<double>{0.1, 0.2, 0.3, 0.4, 0.6, 0.9};
  const std::vector<double> angles = anglesDeg(quick ? 45.0 : 15.0);
  std::vector<GradeCase> cases;
  std::set<std::string> ids;
  auto add = [&](const std::string& family, std::string id, const Mechanism& m, const std::vector<double>& phis) {
    id = safeStem(id);
    std::string unique = id;
    for (int n = 2; ids.count(unique); ++n) unique = id + "_" + std::to_string(n);
    ids.insert(unique);
    cases.push_back(makeCase(family, unique, m, phis));
  };
  for (const Mechanism& base : families) {
    std::vector<double> lambdas = {lambdaOf(base)};
    for (double lambda : sweep)
      if (std::fabs(lambda - lambdaOf(base)) > 1e-3) lambdas.push_back(lambda);
    for (double lambda : lambdas)
      for (double rpm : base.speed_rpm > 0.0 ? std::vector<double>{base.speed_rpm, 0.0} : std::vector<double>{0.0}) {
        const Mechanism m = withSpeed(withLambda(base, lambda), rpm);
        add(base.name, base.name + "_lambda" + numberTag(lambda) + "_" + numberTag(rpm) + "rpm", m, angles);
      }
  }
  if (scenes.empty() && !quick) {
    // The gate's sweep, as validate runs it (campaign.cc): its base is the first built-in scene.
    const Mechanism& base = families.front();
    const std::vector<double> lambdas = {1e-6, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.9, 0.999};
    const std::vector<double> gammas = {0.0, 180.0, 90.0, -90.0, 37.0};
    const std::vector<double> gate_angles = {0.0, 17.0, 45.0, 90.0, 133.0, 180.0, 222.5, 270.0, 300.0, 359.0, -60.0};
    for (int k = 1; k <= 12; ++k)
      for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke}) {
        const bool two = cycle == Cycle::kTwoStroke;
        const std::string family = std::string("gate sweep ") + (two ? "two" : "four") + "-stroke (k = 1..12)";
        const double rpm_run = two ? 3000.0 : 6000.0;
        for (double lambda : lambdas)
          for (double gamma : gammas)
            for (double rpm : {rpm_run, 0.0}) {
              const Mechanism m = withSpeed(withGamma(withLambda(withCylinders(base, k, cycle), lambda), gamma), rpm);
              add(family,
                  "k" + std::to_string(k) + (two ? "_two_" : "_four_") + gammaTag(gamma) + "_lambda" + numberTag(lambda) +
                      "_" + numberTag(rpm) + "rpm",
                  m, gate_angles);
            }
      }
  }
  return cases;
}

std::string makeGradeRequest(const GradeCase& c) {
  nlohmann::ordered_json request;
  request["protocol"] = 1;
  request["case"] = c.id;
  request["scene"] = sceneToJson(c.mechanism);
  request["scene_toml"] = c.scene_toml;
  request["phi_deg"] = c.phi_deg;
  nlohmann::ordered_json quantities = nlohmann::ordered_json::array();
  for (const Quantity& q : getQuantityCatalogue())
    if (isQuantityDefined(q, c.mechanism)) quantities.push_back(q.name);
  request["quantities"] = quantities;
  return request.dump();  // one line: strings escape their newlines
}

std::vector<Evaluation> parseGradeResponse(const GradeCase& c, const std::string& response, const std::string& program,
                                           size_t first_line) {
  const std::string where = program + ": case " + c.id + ": ";
  auto fail = [&](const std::string& what, size_t at = 0) -> void {
    throwProtocolError(where, what, response, at, first_line);
  };
  const Json doc = parseResponseObject(response, "results", where, first_line);
  const Json& results = doc["results"];
  if (results.size() != c.phi_deg.size())
    fail("expected " + std::to_string(c.phi_deg.size()) + " results (one per angle of phi_deg), got " +
         std::to_string(results.size()));
  std::vector<Evaluation> out;
  for (size_t i = 0; i < results.size(); ++i) {
    const Json& r = results[i];
    const std::string at = "results[" + std::to_string(i) + "]";
    if (r.is_object() && r.contains("phi_deg") && !r["phi_deg"].is_null()) {
      if (!r["phi_deg"].is_number()) fail(at + ".phi_deg must be a number or null");
      const double phi = r["phi_deg"].get<double>();
      if (!std::isfinite(phi)) fail(at + ".phi_deg is not a finite number");
      if (std::fabs(phi - c.phi_deg[i]) > 1e-9 * std::max(1.0, std::fabs(c.phi_deg[i])))
        fail(at + ".phi_deg is " + formatNumber(phi) + ", the request's angle " + std::to_string(i) + " is " +
             formatNumber(c.phi_deg[i]) + " (results must come in the request's order)");
    }
    Evaluation e = readProgramValues(r, at, c.mechanism, [&](const std::string& what) { fail(what); }, {"phi_deg"});
    e.phi = radiansFromDegrees(c.phi_deg[i]);
    out.push_back(std::move(e));
  }
  return out;
}

const std::vector<GradeRegime>& getGradeRegimes() {
  static const std::vector<GradeRegime> regimes = {{"all", "all cases"},
                                                   {"moving_lambda_le_0.4", "moving, lambda <= 0.4"},
                                                   {"moving_lambda_gt_0.4", "moving, lambda > 0.4"},
                                                   {"at_rest_lambda_le_0.4", "at rest, lambda <= 0.4"},
                                                   {"at_rest_lambda_gt_0.4", "at rest, lambda > 0.4"}};
  return regimes;
}

std::string describeGradeRegime(const std::string& id) {
  for (const GradeRegime& r : getGradeRegimes())
    if (id == r.id) return r.words;
  return id;
}

namespace {

// The regime of a case besides "all" (getGradeRegimes): moving or at rest, lambda up to 0.4 (the gate's fine
// sweep; 1e-9 for the rounding of r / l) or beyond.
std::string regimeOf(const Mechanism& m) {
  return std::string(m.machine.speed > 0.0 ? "moving" : "at_rest") + (lambdaOf(m) <= 0.4 + 1e-9 ? "_lambda_le_0.4" : "_lambda_gt_0.4");
}

// An error / scale or error / tolerance as a number: one beyond double's range (a program's 1e308 against a scale
// below 1) is shown as the largest double, never as inf.
double finiteRatio(double x) { return std::min(x, std::numeric_limits<double>::max()); }

}  // namespace

std::vector<const Engine*> listGradeJudges() {
  const std::vector<const Engine*> references = listReferenceEngines();
  std::vector<const Engine*> judges = {references.front(), &getClosedFormEngine()};
  judges.insert(judges.end(), references.begin() + 1, references.end());
  return judges;
}

// The tables' names (their CSV stems), each spelled once.
constexpr const char* kSummaryName = "grade_summary";
constexpr const char* kErrorVsLambdaName = "grade_error_vs_lambda";
constexpr const char* kFailuresName = "grade_failures";

std::vector<Field<GradeSummaryRow>> makeGradeSummaryFields() {
  using R = GradeSummaryRow;
  std::vector<Field<R>> fields = {textField("quantity", &R::quantity), textField("regime", &R::regime),
                                  countField("asked", &R::asked), countField("provided", &R::provided),
                                  optionalField("largest_rel_error", "-", &R::largest_rel_error)};
  const std::vector<const Engine*> judges = listGradeJudges();
  for (size_t j = 0; j < judges.size(); ++j)
    fields.push_back(elementField("largest_rel_error_" + judges[j]->name, "-", &R::largest_rel_error_by, j));
  for (Field<R>& f : std::vector<Field<R>>{
           textField("largest_where_case", &R::largest_where_case),
           optionalField("largest_where_phi_deg", "deg", &R::largest_where_phi_deg),
           optionalField("largest_where_speed_rpm", "rpm", &R::largest_where_speed_rpm),
           optionalField("rel_error_at_worst_ratio", "-", &R::rel_error_at_worst_ratio),
           optionalField("worst_ratio", "-", &R::worst_ratio), optionalField("tolerance_rel", "-", &R::tolerance_rel),
           textField("where_case", &R::where_case), optionalField("where_phi_deg", "deg", &R::where_phi_deg),
           optionalField("where_speed_rpm", "rpm", &R::where_speed_rpm), textField("verdict", &R::verdict)})
    fields.push_back(std::move(f));
  return fields;
}

// The schemas with a column per judge follow the engines in play (engine_fields.h).
const Schema<GradeSummaryRow>& getGradeSummarySchema() {
  return getEngineSchema<GradeSummaryRow, makeGradeSummaryFields>(kSummaryName);
}

const Schema<GradeLambdaRow>& getGradeErrorVsLambdaSchema() {
  using R = GradeLambdaRow;
  static const Schema<R> schema(kErrorVsLambdaName,
                                {textField("quantity", &R::quantity), numberField("lambda", "-", &R::lambda),
                                 numberField("program_max_rel_error", "-", &R::program_max_rel_error),
                                 numberField("analytic_max_rel_error", "-", &R::analytic_max_rel_error)});
  return schema;
}

std::vector<Field<GradeFailureRow>> makeGradeFailuresFields() {
  using R = GradeFailureRow;
  const std::vector<const Engine*> judges = listGradeJudges();
  // The program's value, the first two judges' values, the error against the first and its tolerance, the other
  // judges' values.
  std::vector<Field<R>> fields = {
      textField("case", &R::case_id), textField("family", &R::family), numberField("lambda", "-", &R::lambda),
      textField("quantity", &R::quantity), optionalCountField("cylinder", &R::cylinder),
      numberField("phi_deg", "deg", &R::phi_deg), numberField("speed_rpm", "rpm", &R::speed_rpm),
      numberField("program_value", "SI", &R::program_value),
      elementField(judges[0]->name + "_value", "SI", &R::judge_values, 0),
      elementField(judges[1]->name + "_value", "SI", &R::judge_values, 1),
      numberField("rel_error", "-", &R::rel_error), numberField("tolerance_rel", "-", &R::tolerance_rel)};
  for (size_t j = 2; j < judges.size(); ++j)
    fields.push_back(elementField(judges[j]->name + "_value", "SI", &R::judge_values, j));
  return fields;
}

const Schema<GradeFailureRow>& getGradeFailuresSchema() {
  return getEngineSchema<GradeFailureRow, makeGradeFailuresFields>(kFailuresName);
}

const TableSchema* findGradeTableSchema(const std::string& name) {
  // Compared by name first: the schemas follow the engine registry, which a name of another table must not fix.
  if (name == kSummaryName) return &getGradeSummarySchema();
  if (name == kErrorVsLambdaName) return &getGradeErrorVsLambdaSchema();
  if (name == kFailuresName) return &getGradeFailuresSchema();
  return nullptr;
}

namespace {

// What a grade found for one quantity in one regime.
struct QuantityGrade {
  long long asked = 0, provided = 0;
  // The largest error / scale against each judge (listGradeJudges), and where the largest of them is.
  std::vector<double> largest_by;
  double largest = -1.0;
  std::string largest_case;
  double largest_phi_deg = 0.0, largest_rpm = 0.0;
  // Where error / tolerance (the largest over the judges) is worst: that error / scale, tolerance / scale, where
  // (its pass is every value's against every judge), and in which case.
  WorstComparison worst;
  std::string where_case;

  void merge(const QuantityGrade& q) {
    asked += q.asked;
    provided += q.provided;
    largest_by.resize(std::max(largest_by.size(), q.largest_by.size()), 0.0);
    for (size_t j = 0; j < q.largest_by.size(); ++j) largest_by[j] = std::max(largest_by[j], q.largest_by[j]);
    if (q.largest > largest) {
      largest = q.largest;
      largest_case = q.largest_case;
      largest_phi_deg = q.largest_phi_deg;
      largest_rpm = q.largest_rpm;
    }
    if (worst.merge(q.worst)) where_case = q.where_case;
  }
};

struct LambdaError {
  double program = 0.0, analytic = 0.0;
  bool provided = false;
};

struct Failure {
  GradeFailureRow row;
  double ratio = 0.0;
};

// Everything one thread found; merged at the end.
struct GradeState {
  std::map<std::pair<std::string, std::string>, QuantityGrade> quantities;  // (quantity, regime id)
  std::map<std::pair<std::string, double>, LambdaError> by_lambda;  // (quantity, lambda)
  std::map<std::string, Failure> failures;                          // the worst failure per case, quantity, cylinder
};

void gradeCase(const GradeCase& c, const std::vector<Evaluation>& program, GradeState& state) {
  const Mechanism& m = c.mechanism;
  const Scales scales = calcPositiveScales(m);  // positive at rest and without gravity too
  const std::string regime = regimeOf(m);
  // Every judge built from the case's scene: the first reference engine, the closed forms, the other references.
  const std::vector<const Engine*> judges = listGradeJudges();
  std::vector<std::unique_ptr<EngineModel>> models;
  for (const Engine* judge : judges) models.push_back(judge->build(m));
  const double lambda = lambdaOf(m);
  for (size_t i = 0; i < c.phi_deg.size(); ++i) {
    const double phi = radiansFromDegrees(c.phi_deg[i]);
    std::vector<Evaluation> e;
    for (const auto& model : models) e.push_back(model->evaluate(phi));
    std::vector<std::vector<Comparison>> vs;  // the program against each judge
    for (const Evaluation& judge : e) vs.push_back(compareEvaluations(m, scales, program[i], judge));
    const std::vector<Comparison> own = compareEvaluations(m, scales, e[1], e[0]);  // the closed forms' own error
    for (size_t n = 0; n < vs[0].size(); ++n) {
      const Comparison& cs = vs[0][n];
      // A component the scene does not define (shaking_moment X and Y without axial positions): not asked, never
      // graded.
      const bool defined = isComponentDefined(*findQuantity(cs.quantity), cs.component, m);
      LambdaError& le = state.by_lambda[{cs.quantity, lambda}];
      le.analytic = std::max(le.analytic, finiteRatio(own[n].error() / own[n].scale));
      if (!defined) continue;
      QuantityGrade value;  // this one value, merged into the quantity's "all" and its regime
      value.asked = 1;
      if (!std::isnan(cs.a)) {  // provided
        value.provided = 1;
        le.provided = true;
        double worst_error = 0.0;
        bool pass = true;
        for (const std::vector<Comparison>& v : vs) {
          value.largest_by.push_back(finiteRatio(v[n].error() / v[n].scale));
          worst_error = std::max(worst_error, v[n].error());
          pass = pass && v[n].agrees();
        }
        value.largest = *std::max_element(value.largest_by.begin(), value.largest_by.end());
        value.largest_case = value.where_case = c.id;
        value.largest_phi_deg = c.phi_deg[i];
        value.largest_rpm = m.speed_rpm;
        // The judges' tolerances are one (the scale and conditioning are the case's): the worst ratio is the largest
        // error's, its error / scale the largest.
        WorstComparison judged;
        judged.ratio_to_tolerance = finiteRatio(worst_error / cs.tolerance());
        judged.rel_error = value.largest;
        judged.tolerance_rel = cs.tolerance() / cs.scale;
        judged.phi_deg = c.phi_deg[i];
        judged.rpm = m.speed_rpm;
        judged.pass = pass;
        value.worst.merge(judged);
        le.program = std::max(le.program, value.largest_by[0]);
      }
      state.quantities[{cs.quantity, "all"}].merge(value);
      state.quantities[{cs.quantity, regime}].merge(value);
      if (value.provided == 0) continue;
      const double rel_s = value.largest_by[0], ratio = value.worst.ratio_to_tolerance;
      if (!value.worst.pass) {
        const std::string key = c.id + "\n" + cs.quantity + "\n" + std::to_string(cs.cylinder);
        Failure& f = state.failures[key];
        if (ratio > f.ratio) {
          f.ratio = ratio;
          f.row = {c.id, c.family, lambda, cs.quantity, cs.cylinder < 0 ? std::nullopt : std::optional<int>(cs.cylinder),
                   c.phi_deg[i], m.speed_rpm, cs.a, {}, rel_s, cs.tolerance() / cs.scale};
          for (const std::vector<Comparison>& v : vs) f.row.judge_values.push_back(v[n].b);
        }
      }
    }
  }
}

void mergeInto(GradeState& into, const GradeState& from) {
  for (const auto& [key, q] : from.quantities) into.quantities[key].merge(q);
  for (const auto& [key, e] : from.by_lambda) {
    LambdaError& t = into.by_lambda[key];
    t.program = std::max(t.program, e.program);
    t.analytic = std::max(t.analytic, e.analytic);
    t.provided = t.provided || e.provided;
  }
  for (const auto& [key, f] : from.failures)
    if (f.ratio > into.failures[key].ratio) into.failures[key] = f;
}

}  // namespace

TableSet runGrade(const std::vector<GradeCase>& cases, const GradeProgram& program, int jobs,
                  const std::function<void(size_t, size_t)>& progress) {
  if (program.argv.empty()) throw UsageError("grade: no program given (crankcheck grade [SCENE...] -- PROGRAM [ARG...])");
  jobs = std::max(1, std::min<int>(jobs, static_cast<int>(std::max<size_t>(cases.size(), 1))));
  const std::string name = program.argv.front();
  std::vector<GradeState> states(static_cast<size_t>(jobs));
  std::atomic<size_t> next{0}, done{0};
  std::atomic<bool> stop{false};
  std::mutex error_mutex, progress_mutex;
  std::exception_ptr error;
  auto report = [&] {
    const size_t d = ++done;
    if (progress) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      progress(d, cases.size());
    }
  };
  auto worker = [&](int job) {
    try {
      GradeState& state = states[static_cast<size_t>(job)];
      if (program.batch) {
        // One program for this job's share: cases job, job + jobs, ...; one request per line, one response per line.
        std::vector<size_t> mine;
        for (size_t i = static_cast<size_t>(job); i < cases.size(); i += static_cast<size_t>(jobs)) mine.push_back(i);
        if (mine.empty()) return;
        std::string input;
        for (size_t i : mine) input += makeGradeRequest(cases[i]) + "\n";
        const std::string out = runOnce(program, input, mine.size(), "batch of " + std::to_string(mine.size()) + " requests");
        std::vector<std::string> lines;
        std::vector<size_t> line_numbers;  // each response's line in the program's stdout, for its messages
        size_t begin = 0;
        for (size_t number = 1; begin < out.size(); ++number) {
          size_t end = out.find('\n', begin);
          if (end == std::string::npos) end = out.size();
          if (out.find_first_not_of(" \t\r", begin) < end) {
            lines.push_back(out.substr(begin, end - begin));
            line_numbers.push_back(number);
          }
          begin = end + 1;
        }
        if (lines.size() != mine.size())
          throw EnvironmentError(name + ": --batch: expected " + std::to_string(mine.size()) + " response lines (one per request), got " +
                                 std::to_string(lines.size()) + (lines.empty() ? std::string() : "; " + quoteLine(out)));
        for (size_t n = 0; n < mine.size() && !stop; ++n) {
          gradeCase(cases[mine[n]], parseGradeResponse(cases[mine[n]], lines[n], name, line_numbers[n]), state);
          report();
        }
        return;
      }
      for (size_t i = next++; i < cases.size() && !stop; i = next++) {
        const GradeCase& c = cases[i];
        const std::string out = runOnce(program, makeGradeRequest(c) + "\n", 1, "case " + c.id);
        gradeCase(c, parseGradeResponse(c, out, name), state);
        report();
      }
    } catch (...) {
      stop = true;
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
    }
  };
  std::vector<std::thread> threads;
  for (int j = 1; j < jobs; ++j) threads.emplace_back(worker, j);
  worker(0);
  for (std::thread& t : threads) t.join();
  if (error) std::rethrow_exception(error);

  GradeState all;
  for (const GradeState& s : states) mergeInto(all, s);
  const size_t judges = listGradeJudges().size();
  std::vector<GradeSummaryRow> summary;
  for (const Quantity& quantity : getQuantityCatalogue())
    for (const GradeRegime& regime : getGradeRegimes()) {
      const auto it = all.quantities.find({quantity.name, regime.id});
      if (it == all.quantities.end() || it->second.asked == 0) continue;
      const QuantityGrade& q = it->second;
      const bool any = q.provided > 0;
      auto number = [any](double x) { return any ? std::optional<double>(x) : std::nullopt; };
      GradeSummaryRow row;
      row.quantity = quantity.name;
      row.regime = regime.id;
      row.asked = static_cast<int>(q.asked);
      row.provided = static_cast<int>(q.provided);
      row.largest_rel_error = number(q.largest);
      for (size_t j = 0; j < judges; ++j) row.largest_rel_error_by.push_back(number(j < q.largest_by.size() ? q.largest_by[j] : 0.0));
      row.largest_where_case = any ? q.largest_case : "";
      row.largest_where_phi_deg = number(q.largest_phi_deg);
      row.largest_where_speed_rpm = number(q.largest_rpm);
      row.rel_error_at_worst_ratio = number(q.worst.rel_error);
      row.worst_ratio = number(q.worst.ratio_to_tolerance);
      row.tolerance_rel = number(q.worst.tolerance_rel);
      row.where_case = any ? q.where_case : "";
      row.where_phi_deg = number(q.worst.phi_deg);
      row.where_speed_rpm = number(q.worst.rpm);
      row.verdict = !any ? "not provided" : q.worst.pass ? "pass" : "FAIL";
      summary.push_back(std::move(row));
    }
  std::vector<GradeLambdaRow> by_lambda;
  for (const auto& [key, e] : all.by_lambda)
    if (e.provided) by_lambda.push_back({key.first, key.second, e.program, e.analytic});
  std::vector<GradeFailureRow> failures;
  for (const auto& [key, f] : all.failures) failures.push_back(f.row);
  TableSet tables;
  tables.emplace(getGradeSummarySchema().name(), getGradeSummarySchema().table(std::move(summary)));
  tables.emplace(getGradeErrorVsLambdaSchema().name(), getGradeErrorVsLambdaSchema().table(std::move(by_lambda)));
  tables.emplace(getGradeFailuresSchema().name(), getGradeFailuresSchema().table(std::move(failures)));
  return tables;
}

int findGradeExitStatus(const TableSet& tables) {
  if (!tables.count(getGradeSummarySchema().name())) return 1;
  bool any = false;
  for (const GradeSummaryRow& row : getRows(tables, getGradeSummarySchema())) {
    if (row.regime != "all") continue;
    if (row.verdict == "FAIL") return 1;
    any = any || row.verdict == "pass";
  }
  return any ? 0 : 1;
}

}  // namespace crankcheck::validation
