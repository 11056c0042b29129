// `crankcheck grade` as a user runs it: the two example programs (one must pass, one must fail where the report
// says), and programs that misbehave (exit status 3, one clear line, never a hang).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/types.h>

#include <cerrno>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <utility>
#include <optional>
#include <sstream>
#include <string>

#include "run_cli.h"
#include "crankcheck/validation/grade.h"
#include "crankcheck/validation/report.h"
#include "../support/read_file.h"

#if !defined(CRANKCHECK_FAKE_PROGRAM) || !defined(CRANKCHECK_GRADE_EXAMPLES_DIR) || !defined(CRANKCHECK_ANALYTIC_PROGRAM)
#error "the build defines CRANKCHECK_FAKE_PROGRAM, CRANKCHECK_GRADE_EXAMPLES_DIR and CRANKCHECK_ANALYTIC_PROGRAM"
#endif

namespace crankcheck {
namespace {
namespace fs = std::filesystem;
using testing::FreshFolder;
using testing::runCrankcheck;

using testing::readFile;

using validation::GradeFailureRow;
using validation::GradeLambdaRow;
using validation::GradeSummaryRow;

// The summary's rows, as the report's data/grade_summary.csv holds them (read back through the schema).
const std::vector<GradeSummaryRow>& summaryOf(const validation::TableSet& tables) {
  return validation::getRows(tables, validation::getGradeSummarySchema());
}

// The summary's row for (quantity, regime); a row with an empty quantity and verdict when there is none.
GradeSummaryRow summaryRow(const validation::TableSet& tables, const std::string& quantity, const std::string& regime = "all") {
  for (const GradeSummaryRow& row : summaryOf(tables))
    if (row.quantity == quantity && row.regime == regime) return row;
  ADD_FAILURE() << "no summary row for " << quantity << " in regime " << regime;
  return {};
}

// The verdict of `quantity` over all cases, "" when absent.
std::string verdictOf(const validation::TableSet& tables, const std::string& quantity) {
  return summaryRow(tables, quantity).verdict;
}

// A number of the summary that must be there (a provided quantity's); NaN, and a failure, when it is empty.
double valueOf(const std::optional<double>& x) {
  EXPECT_TRUE(x.has_value());
  return x.value_or(std::nan(""));
}

// True when `text` holds "nan" or "inf" as a word (a number that is none).
bool holdsNanOrInf(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const char* word : {"nan", "inf"})
    for (size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) {
      const bool before = at > 0 && std::isalpha(static_cast<unsigned char>(text[at - 1]));
      const bool after = at + 3 < text.size() && std::isalpha(static_cast<unsigned char>(text[at + 3]));
      if (!before && !after) return true;
    }
  return false;
}

// Every number grade printed (terminal, tables, report) is one.
void expectNoNanOrInf(const validation::ProgramResult& r, const fs::path& out) {
  EXPECT_FALSE(holdsNanOrInf(r.out)) << r.out;
  for (const auto& entry : fs::recursive_directory_iterator(out)) {
    if (entry.path().extension() != ".csv" && entry.path().extension() != ".md") continue;
    EXPECT_FALSE(holdsNanOrInf(readFile(entry.path()))) << entry.path() << ":\n" << readFile(entry.path());
  }
}

TEST(GradeTest, NortonsTwoTermFailsOnPistonMotionAndTheReportShowsWhere) {
  FreshFolder dir;
  const fs::path out = dir.path() / "report";
  // --batch: one Python process per job (the per-request mode is the C++ example's test).
  const auto r = runCrankcheck({"grade", "--quick", "--batch", "--out", out.string(), "--", "/usr/bin/python3",
                                CRANKCHECK_GRADE_EXAMPLES_DIR "/norton_two_term.py"});
  ASSERT_EQ(r.exit_status, 1) << r.out << r.err;
  const validation::TableSet tables = validation::readTables(out);
  for (const char* q : {"x_p", "v_p", "a_p"}) EXPECT_EQ(verdictOf(tables, q), "FAIL") << q;
  for (const char* q : {"U", "Q", "drive_torque", "crank_pin_force", "rod_angle"}) EXPECT_EQ(verdictOf(tables, q), "not provided") << q;
  // Where: the two-term form drops the lambda^3 terms, so its a_p error is largest at the largest lambda of the
  // campaign (0.9 in --quick), and grows with lambda.
  double error_low = 0.0, error_high = 0.0;
  const auto& by_lambda = validation::getRows(tables, validation::getGradeErrorVsLambdaSchema());
  for (const GradeLambdaRow& row : by_lambda)
    if (row.quantity == "a_p") {
      if (row.lambda < 0.35) error_low = std::max(error_low, row.program_max_rel_error);
      if (row.lambda > 0.85) error_high = std::max(error_high, row.program_max_rel_error);
    }
  EXPECT_GT(error_high, 10.0 * error_low);
  const GradeSummaryRow a_p = summaryRow(tables, "a_p");
  EXPECT_NE(a_p.where_case.find("lambda0p9"), std::string::npos);
  EXPECT_NE(a_p.largest_where_case.find("lambda0p9"), std::string::npos);
  // The summary says what it shows: the largest error (the figure's largest point), and the error where error /
  // tolerance is worst, which is no larger; split by regime, since at rest the two-term form is exact in v_p and a_p
  // (both are multiples of omega) while at speed it is off by 1e-3 of the scale and more.
  double largest_in_figure = 0.0;
  for (const GradeLambdaRow& row : by_lambda)
    if (row.quantity == "a_p") largest_in_figure = std::max(largest_in_figure, row.program_max_rel_error);
  // The figure's error is against the first judge (listGradeJudges): the summary's first column of errors by judge.
  ASSERT_FALSE(a_p.largest_rel_error_by.empty());
  const double largest = valueOf(a_p.largest_rel_error_by.front());
  EXPECT_EQ(largest, largest_in_figure);
  EXPECT_GE(valueOf(a_p.largest_rel_error), largest);
  EXPECT_LE(valueOf(a_p.rel_error_at_worst_ratio), valueOf(a_p.largest_rel_error));
  const GradeSummaryRow a_p_moving = summaryRow(tables, "a_p", "moving_lambda_gt_0.4");
  EXPECT_GT(valueOf(a_p_moving.largest_rel_error), 1e-3);
  EXPECT_EQ(a_p_moving.verdict, "FAIL");
  for (const char* regime : {"at_rest_lambda_le_0.4", "at_rest_lambda_gt_0.4"}) {
    const GradeSummaryRow at_rest = summaryRow(tables, "a_p", regime);
    EXPECT_LT(valueOf(at_rest.largest_rel_error), 1e-12) << regime;
    EXPECT_EQ(at_rest.verdict, "pass") << regime;
  }
  for (const char* words : {"largest error / scale", "error at worst ratio", "at rest, lambda <= 0.4", "moving, lambda > 0.4"}) {
    EXPECT_NE(r.out.find(words), std::string::npos) << words << " in the terminal summary:\n" << r.out;
    EXPECT_NE(readFile(out / "index.md").find(words), std::string::npos) << words << " in the report";
  }
  expectNoNanOrInf(r, out);
  // The report's failing cases reproduce: the scene file is there and crankcheck eval accepts it; the command names
  // the program that graded by its path (issue 47: "crankcheck" is not on PATH in a build tree).
  const std::string index = readFile(out / "index.md");
  EXPECT_NE(index.find("`" + fs::canonical(CRANKCHECK_BINARY).string() + " eval cases/"), std::string::npos) << index;
  const auto& failures = validation::getRows(tables, validation::getGradeFailuresSchema());
  ASSERT_FALSE(failures.empty());
  const GradeFailureRow& failure = failures.front();
  const auto eval = runCrankcheck({"eval", (out / "cases" / (failure.case_id + ".toml")).string(), "--phi-deg",
                                   validation::formatNumber(failure.phi_deg), "--engine", "both", "--format", "json"});
  EXPECT_EQ(eval.exit_status, 0) << eval.err;
  EXPECT_TRUE(fs::exists(out / "grade_error_vs_lambda.png"));
  EXPECT_NE(readFile(out / "index.html").find("<html lang=\"en\">"), std::string::npos);
}

// Issue 58: a scene Simbody cannot resolve (the inline four's rod at 1e-9 kg, I_o scaled with it) is graded against
// the other exact engines; Simbody sits out, named on the terminal and in the report, and no table holds a column of
// it. The analytic library's program agrees with MuJoCo there, as the gate's hard cases show.
TEST(GradeTest, AnEngineThatCannotBuildTheSceneSitsOutAndTheOthersJudge) {
  FreshFolder dir;
  std::string scene = readFile(fs::path(CRANKCHECK_SCENES_DIR) / "inline4_four_stroke.toml");
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"mass = 0.52\n", "mass = 1e-9\n"},
                                 {"inertia_about_wrist_pin = 0.0064\n", "inertia_about_wrist_pin = 1.2307692307692308e-11\n"}}) {
    const size_t at = scene.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    scene.replace(at, from.size(), to);
  }
  const fs::path path = dir.path() / "light.toml";
  std::ofstream(path) << scene;
  const fs::path out = dir.path() / "report";
  const auto r = runCrankcheck({"grade", path.string(), "--quick", "--batch", "--out", out.string(), "--",
                                CRANKCHECK_ANALYTIC_PROGRAM});
  ASSERT_EQ(r.exit_status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("\nsimbody sat out: it cannot build scene light (cannot hold its accuracy"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Every provided value agrees with the analytic engine and mujoco."), std::string::npos) << r.out;
  EXPECT_NE(readFile(out / "index.md").find("Engine simbody sat out of this grade: it cannot build scene light"),
            std::string::npos);
  for (const auto& entry : fs::directory_iterator(out / "data"))
    EXPECT_EQ(readFile(entry.path()).find("simbody"), std::string::npos) << entry.path();
}

TEST(GradeTest, TheAnalyticLibraryPassesWithEveryQuantityProvided) {
  FreshFolder dir;
  const fs::path out = dir.path() / "report";
  const auto r = runCrankcheck({"grade", "--quick", "--batch", "--jobs", "2", "--out", out.string(), "--", CRANKCHECK_ANALYTIC_PROGRAM});
  ASSERT_EQ(r.exit_status, 0) << r.out << r.err;
  const validation::TableSet tables = validation::readTables(out);
  ASSERT_FALSE(summaryOf(tables).empty());
  for (const GradeSummaryRow& row : summaryOf(tables)) {
    EXPECT_EQ(row.verdict, "pass") << row.quantity;
    EXPECT_EQ(row.asked, row.provided) << row.quantity << ": every value asked was provided";
  }
  EXPECT_TRUE(validation::getRows(tables, validation::getGradeFailuresSchema()).empty());
}

struct Misbehaviour {
  std::string mode;
  std::string expected;      // a part of the one-line message
  std::string timeout = "5";  // --timeout [s] per request
};
void PrintTo(const Misbehaviour& m, std::ostream* os) { *os << m.mode; }

class GradeMisbehaviourTest : public ::testing::TestWithParam<Misbehaviour> {};

TEST_P(GradeMisbehaviourTest, ExitStatus3WithOneClearLine) {
  FreshFolder dir;
  const fs::path out = dir.path() / "report";
  // 5 s per request: enough for 64 MiB through a pipe on a loaded machine; the two that hang wait out 1 s (their one
  // request is a few hundred bytes each way).
  const auto r = runCrankcheck({"grade", "--quick", "--timeout", GetParam().timeout, "--out", out.string(), "--",
                                CRANKCHECK_FAKE_PROGRAM, GetParam().mode});
  EXPECT_EQ(r.exit_status, 3) << r.out << r.err;
  EXPECT_NE(r.err.find(GetParam().expected), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
  // Nothing of the program's output reaches the terminal raw: no control byte but the final newline.
  for (size_t i = 0; i + 1 < r.err.size(); ++i)
    EXPECT_FALSE(static_cast<unsigned char>(r.err[i]) < 0x20 || r.err[i] == 0x7f) << "byte " << i << " of: " << r.err;
  EXPECT_FALSE(fs::exists(out)) << "no partial report";
}

INSTANTIATE_TEST_SUITE_P(
    Grade, GradeMisbehaviourTest,
    ::testing::Values(Misbehaviour{"silent", "no response on stdout"},
                      Misbehaviour{"garbage", "is not JSON"},
                      Misbehaviour{"no-results", "must be an object {\"results\""},
                      Misbehaviour{"wrong-count", "expected 8 results"},
                      Misbehaviour{"nan", "is not JSON"},
                      // A round of attacks: "U": 12345, "U": <right value> passed (nlohmann keeps the last).
                      Misbehaviour{"duplicate-key", "the key \"U\" is given twice in one object"},
                      Misbehaviour{"misspelled-key", "results[1]: \"Uu\" is not a quantity of eval (one of U, Q"},
                      // A hostile round: a key beside "results" was passed over.
                      Misbehaviour{"extra-top-key", "the key \"extra\\x1b\" is not the protocol (a response is {\"results\""},
                      Misbehaviour{"string", "must be a number or null"},
                      Misbehaviour{"crash", "ended by signal 6"},
                      Misbehaviour{"exit7", "exited with status 7; its stderr: \"something went wrong"},
                      // The end of a long stderr, where a traceback says what failed (issue 59).
                      Misbehaviour{"traceback", "exited with status 1; the end of its stderr: \"...\\n  File \\\"sim.py\\\", "
                                                "line 9, in main\\n    x = 1 / 0\\nZeroDivisionError: division by zero\""},
                      Misbehaviour{"hang", "no complete answer within 1 s", "1"},
                      Misbehaviour{"answer-then-hang", "answered completely but did not exit within 1 s", "1"},
                      // The quote is closed, and ESC, NUL and tab are shown as escapes.
                      Misbehaviour{"control-bytes", "line 1: \"\\x1b[2J\\x1b[31mred\\x1b[0m\\x00\\tafter NUL\""},
                      Misbehaviour{"control-bytes-stderr", "its stderr: \"\\x1b]0;title\\x07\\x00hidden\""},
                      Misbehaviour{"huge", "bytes to stdout (killed)"}),
    [](const ::testing::TestParamInfo<Misbehaviour>& info) {
      std::string name = info.param.mode;
      for (char& c : name)
        if (c == '-') c = '_';
      return name;
    });

// --batch: every response line arrived, then the program did not exit; told so, not "no complete answer". The batch's
// limit is --timeout per request: 0.025 s x the quick campaign's 42 requests = 1.05 s waited out, as the other two
// hanging programs wait (at 0.1 s it was 4.2 s); the stand-in answers every request at once.
TEST(GradeTest, ABatchThatAnsweredCompletelyButDoesNotExitIsToldSo) {
  FreshFolder dir;
  const fs::path out = dir.path() / "report";
  const auto r = runCrankcheck({"grade", "--quick", "--batch", "--jobs", "2", "--timeout", "0.025", "--out", out.string(), "--",
                                CRANKCHECK_FAKE_PROGRAM, "answer-then-hang"});
  EXPECT_EQ(r.exit_status, 3) << r.out << r.err;
  EXPECT_NE(r.err.find(": batch of "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("requests: answered completely but did not exit within"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

// --batch: a broken response is quoted at its own line of the program's stdout (here the fourth: a blank line, then
// responses 1 and 2), where "line 1" of its own text sent the reader to the first response.
TEST(GradeTest, ABatchsBrokenResponseIsQuotedAtItsLine) {
  FreshFolder dir;
  const fs::path out = dir.path() / "report";
  const auto r = runCrankcheck({"grade", "--quick", "--batch", "--out", out.string(), "--", CRANKCHECK_FAKE_PROGRAM,
                                "batch-bad-third"});
  EXPECT_EQ(r.exit_status, 3) << r.out << r.err;
  EXPECT_NE(r.err.find(".U must be a number or null; line 4: \"{\\\"results\\\": [{\\\"U\\\": \\\"12 J\\\"}"),
            std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

// Whether process `pid` still exists (kill with signal 0 reaches it). A zombie would count: crankcheck reaps what it
// ends, and the test process is not the left-behind one's parent.
bool processExists(pid_t pid) { return ::kill(pid, 0) == 0 || errno == EPERM; }

pid_t readPid(const fs::path& file) {
  std::ifstream in(file);
  long pid = 0;
  in >> pid;
  return static_cast<pid_t>(pid);
}

// A program that exits but leaves a process behind in a session of its own (setsid), out of its process group: told
// as it is (not as "did not exit": it had exited), and that process does not outlive crankcheck, which is its reaper
// (it would sleep 60 s). Holding the program's stdout, it is found at the timeout; as a daemon, with its output on
// /dev/null, when the program ends.
TEST(GradeTest, AProcessAProgramLeavesBehindIsEndedAndTheProgramToldSo) {
  FreshFolder dir;
  for (const char* mode : {"setsid-child", "daemon-child"}) {
    const fs::path out = dir.path() / (std::string("report-") + mode), pid_file = dir.path() / (std::string(mode) + ".pid");
    const auto r = runCrankcheck({"grade", "--quick", "--jobs", "1", "--timeout", "0.3", "--out", out.string(), "--",
                                  CRANKCHECK_FAKE_PROGRAM, mode, pid_file.string()});
    EXPECT_EQ(r.exit_status, 3) << r.out << r.err;
    if (std::string(mode) == "setsid-child")
      EXPECT_NE(r.err.find(": exited with status 0, but its output was still open 0.3 s after it started: held by a "
                           "process it left running outside its process group (a setsid child), which crankcheck ended"),
                std::string::npos) << r.err;
    else
      EXPECT_NE(r.err.find(": exited with status 0 but left 1 process running outside its process group (a setsid "
                           "child or a daemon; crankcheck ended it)"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
    const pid_t left = readPid(pid_file);
    ASSERT_GT(left, 0) << mode;
    EXPECT_FALSE(processExists(left)) << mode << ": pid " << left << " outlived crankcheck";
    if (processExists(left)) ::kill(left, SIGKILL);
  }
}

// A program whose child in its own process group (a pipeline's `| cat`) writes past the output limit is told that, not
// that it left processes behind: what crankcheck kills in the program's group is not counted against it.
TEST(GradeTest, OutputPastTheLimitFromAChildInItsGroupIsToldAsSuch) {
  FreshFolder dir;
  const auto r = runCrankcheck({"grade", "--quick", "--jobs", "1", "--out", (dir.path() / "report").string(), "--",
                                CRANKCHECK_FAKE_PROGRAM, "pipeline-flood"});
  EXPECT_EQ(r.exit_status, 3) << r.err;
  EXPECT_NE(r.err.find("wrote more than 67108864 bytes to stdout (killed)"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("left"), std::string::npos) << r.err;
}

TEST(GradeTest, NothingProvidedIsNeitherRightNorWrong) {
  FreshFolder dir;
  const fs::path out = dir.path() / "report";
  const auto r = runCrankcheck({"grade", "--quick", "--out", out.string(), "--", CRANKCHECK_FAKE_PROGRAM, "nothing-provided"});
  EXPECT_EQ(r.exit_status, 1) << "nothing provided is not a pass: " << r.out << r.err;
  const validation::TableSet tables = validation::readTables(out);
  ASSERT_FALSE(summaryOf(tables).empty());
  for (const GradeSummaryRow& row : summaryOf(tables)) {
    EXPECT_EQ(row.verdict, "not provided") << row.quantity;
    EXPECT_EQ(row.provided, 0) << row.quantity;
    EXPECT_FALSE(row.largest_rel_error.has_value()) << row.quantity << ": no error without a value";
  }
}

// At rest v_p and rod_omega are 0 exactly, and r omega = 0: a value of rounding size (1e-18 m/s) is judged against a
// positive velocity scale (the speed the static loads give the mechanism), never against 0 (an error of "inf").
TEST(GradeTest, RoundingOfAVelocityAtRestPassesAgainstAPositiveScale) {
  FreshFolder dir;
  const fs::path out = dir.path() / "report";
  const auto r = runCrankcheck({"grade", "--quick", "--out", out.string(), "--", CRANKCHECK_FAKE_PROGRAM, "tiny-at-rest",
                                "v_p,rod_omega"});
  EXPECT_EQ(r.exit_status, 0) << r.out << r.err;
  const validation::TableSet tables = validation::readTables(out);
  for (const char* q : {"v_p", "rod_omega"}) {
    EXPECT_EQ(verdictOf(tables, q), "pass") << q;
    const double tolerance = valueOf(summaryRow(tables, q).tolerance_rel);
    EXPECT_GT(tolerance, 0.0) << q;
    EXPECT_LT(tolerance, 1e-11) << q << ": 64 eps x conditioning";
  }
  expectNoNanOrInf(r, out);
}

// No gravity, no gas, at rest: nothing moves and nothing loads the mechanism, so every quantity but x_p and the rod
// angle is 0 exactly; every scale is still positive (standard gravity stands in for the missing load), so rounding
// passes and no number printed is nan or inf.
TEST(GradeTest, AtRestWithoutGravityEveryScaleIsPositive) {
  FreshFolder dir;
  const fs::path out = dir.path() / "report", scene = dir.path() / "weightless.toml";
  std::string text = readFile(CRANKCHECK_GRADE_EXAMPLES_DIR "/../../scenes/single_cylinder.toml");
  const size_t g = text.find("gravity = 9.80665");
  ASSERT_NE(g, std::string::npos);
  text.replace(g, 17, "gravity = 0");
  std::ofstream(scene) << text;
  const auto r = runCrankcheck({"grade", scene.string(), "--quick", "--out", out.string(), "--", CRANKCHECK_FAKE_PROGRAM,
                                "tiny-at-rest",
                                "U,Q,drive_torque,bearing_force,shaking_force,shaking_moment,v_p,a_p,wall_force,rod_omega,"
                                "rod_alpha,crank_pin_force,wrist_pin_force"});
  EXPECT_EQ(r.exit_status, 0) << r.out << r.err;
  const validation::TableSet tables = validation::readTables(out);
  for (const char* q : {"U", "Q", "drive_torque", "bearing_force", "shaking_force", "shaking_moment", "v_p", "a_p",
                        "wall_force", "rod_omega", "rod_alpha", "crank_pin_force", "wrist_pin_force"})
    EXPECT_EQ(verdictOf(tables, q), "pass") << q;
  expectNoNanOrInf(r, out);
}

TEST(GradeTest, UsageErrorsAndMissingProgramsAreRefusedBeforeAnyWork) {
  FreshFolder dir;
  const fs::path out = dir.path() / "report";
  const auto none = runCrankcheck({"grade", "--quick", "--out", out.string()});
  EXPECT_EQ(none.exit_status, 2) << none.err;
  EXPECT_NE(none.err.find("no program given"), std::string::npos) << none.err;
  const auto missing = runCrankcheck({"grade", "--quick", "--out", out.string(), "--", "/nonexistent/program"});
  EXPECT_EQ(missing.exit_status, 3) << missing.err;
  EXPECT_NE(missing.err.find("/nonexistent/program: cannot be run"), std::string::npos) << missing.err;
  const auto bad_timeout = runCrankcheck({"grade", "--timeout", "0", "--", CRANKCHECK_FAKE_PROGRAM, "silent"});
  EXPECT_EQ(bad_timeout.exit_status, 2) << bad_timeout.err;
  EXPECT_NE(bad_timeout.err.find("--timeout"), std::string::npos) << bad_timeout.err;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace crankcheck
