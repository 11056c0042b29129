// `crankcheck grade` as a user runs it: the two example programs (one must pass, one must fail where the report
// says), and programs that misbehave (exit status 3, one clear line, never a hang).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "run_cli.h"
#include "crankcheck/validation/report.h"

#if !defined(CRANKCHECK_FAKE_PROGRAM) || !defined(CRANKCHECK_GRADE_EXAMPLES_DIR) || !defined(CRANKCHECK_ANALYTIC_PROGRAM)
#error "the build defines CRANKCHECK_FAKE_PROGRAM, CRANKCHECK_GRADE_EXAMPLES_DIR and CRANKCHECK_ANALYTIC_PROGRAM"
#endif

namespace crankcheck {
namespace {
namespace fs = std::filesystem;
using testing::FreshFolder;
using testing::runCrankcheck;

std::string readFile(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The verdict column of the summary for `quantity`, "" when absent.
std::string verdictOf(const validation::TableSet& tables, const std::string& quantity) {
  for (const auto& row : tables.at("grade_summary").rows)
    if (row[0] == quantity) return row.back();
  return "";
}

// A cell of the summary's row for (quantity, regime); "" when there is no such row.
std::string summaryCell(const validation::TableSet& tables, const std::string& quantity, const std::string& regime,
                        const std::string& column) {
  const validation::Table& t = tables.at("grade_summary");
  for (const auto& row : t.rows)
    if (row[0] == quantity && row[validation::columnOf(t, "regime")] == regime) return row[validation::columnOf(t, column)];
  return "";
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
  for (const auto& row : tables.at("grade_error_vs_lambda").rows)
    if (row[0] == "a_p") {
      const double lambda = std::stod(row[1]), error = std::stod(row[2]);
      if (lambda < 0.35) error_low = std::max(error_low, error);
      if (lambda > 0.85) error_high = std::max(error_high, error);
    }
  EXPECT_GT(error_high, 10.0 * error_low);
  EXPECT_NE(summaryCell(tables, "a_p", "all", "where_case").find("lambda0p9"), std::string::npos);
  EXPECT_NE(summaryCell(tables, "a_p", "all", "largest_where_case").find("lambda0p9"), std::string::npos);
  // The summary says what it shows: the largest error (the figure's largest point), and the error where error /
  // tolerance is worst, which is no larger; split by regime, since at rest the two-term form is exact in v_p and a_p
  // (both are multiples of omega) while at speed it is off by 1e-3 of the scale and more.
  double largest_in_figure = 0.0;
  for (const auto& row : tables.at("grade_error_vs_lambda").rows)
    if (row[0] == "a_p") largest_in_figure = std::max(largest_in_figure, std::stod(row[2]));
  const double largest = std::stod(summaryCell(tables, "a_p", "all", "largest_rel_error_simbody"));
  EXPECT_EQ(largest, largest_in_figure);
  EXPECT_GE(std::stod(summaryCell(tables, "a_p", "all", "largest_rel_error")), largest);
  EXPECT_LE(std::stod(summaryCell(tables, "a_p", "all", "rel_error_at_worst_ratio")),
            std::stod(summaryCell(tables, "a_p", "all", "largest_rel_error")));
  EXPECT_GT(std::stod(summaryCell(tables, "a_p", "moving_lambda_gt_0.4", "largest_rel_error")), 1e-3);
  EXPECT_EQ(summaryCell(tables, "a_p", "moving_lambda_gt_0.4", "verdict"), "FAIL");
  for (const char* regime : {"at_rest_lambda_le_0.4", "at_rest_lambda_gt_0.4"}) {
    EXPECT_LT(std::stod(summaryCell(tables, "a_p", regime, "largest_rel_error")), 1e-12) << regime;
    EXPECT_EQ(summaryCell(tables, "a_p", regime, "verdict"), "pass") << regime;
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
  const auto& failure = tables.at("grade_failures").rows.front();
  const auto eval = runCrankcheck({"eval", (out / "cases" / (failure[0] + ".toml")).string(), "--phi-deg", failure[5],
                                   "--engine", "both", "--format", "json"});
  EXPECT_EQ(eval.exit_status, 0) << eval.err;
  EXPECT_TRUE(fs::exists(out / "grade_error_vs_lambda.png"));
  EXPECT_NE(readFile(out / "index.html").find("<html lang=\"en\">"), std::string::npos);
}

TEST(GradeTest, TheAnalyticLibraryPassesWithEveryQuantityProvided) {
  FreshFolder dir;
  const fs::path out = dir.path() / "report";
  const auto r = runCrankcheck({"grade", "--quick", "--batch", "--jobs", "2", "--out", out.string(), "--", CRANKCHECK_ANALYTIC_PROGRAM});
  ASSERT_EQ(r.exit_status, 0) << r.out << r.err;
  const validation::TableSet tables = validation::readTables(out);
  const validation::Table& summary = tables.at("grade_summary");
  for (const auto& row : summary.rows) {
    EXPECT_EQ(row.back(), "pass") << row[0];
    EXPECT_EQ(row[validation::columnOf(summary, "asked")], row[validation::columnOf(summary, "provided")])
        << row[0] << ": every value asked was provided";
  }
  EXPECT_TRUE(tables.at("grade_failures").rows.empty());
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
                      Misbehaviour{"string", "must be a number or null"},
                      Misbehaviour{"crash", "ended by signal 6"},
                      Misbehaviour{"exit7", "exited with status 7; its stderr: \"something went wrong"},
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

TEST(GradeTest, NothingProvidedIsNeitherRightNorWrong) {
  FreshFolder dir;
  const fs::path out = dir.path() / "report";
  const auto r = runCrankcheck({"grade", "--quick", "--out", out.string(), "--", CRANKCHECK_FAKE_PROGRAM, "nothing-provided"});
  EXPECT_EQ(r.exit_status, 1) << "nothing provided is not a pass: " << r.out << r.err;
  const validation::TableSet tables = validation::readTables(out);
  const validation::Table& summary = tables.at("grade_summary");
  for (const auto& row : summary.rows) {
    EXPECT_EQ(row.back(), "not provided") << row[0];
    EXPECT_EQ(row[validation::columnOf(summary, "provided")], "0") << row[0];
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
    const double tolerance = std::stod(summaryCell(tables, q, "all", "tolerance_rel"));
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
