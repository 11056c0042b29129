// crankcheck: the command-line front end. Verbs live in their own files; this one parses flags (CLI11) and
// maps every failure to one message on stderr and its exit status (kExitStatus below, docs/safety.md "Exit status").

#include <csignal>
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <new>
#include <string>
#include <string_view>
#include <vector>

#include "balance_command.h"
#include "eval_command.h"
#include "flag_checks.h"
#include "flywheel_command.h"
#include "torsion_command.h"
#include "motion_command.h"
#include "stepped_command.h"
#include "grade_command.h"
#include "help_format.h"
#include "crankcheck/validation/interrupt.h"
#include "crankcheck/validation/process.h"
#include "validate_command.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/output_folder.h"

namespace {

constexpr const char* kExitStatus =
    "Exit status (the same for every command):\n"
    "  0  every comparison agrees (eval, motion: the results were printed)\n"
    "  1  a comparison that should hold failed, or a result cannot be computed to its accuracy (refused)\n"
    "  2  bad input or usage: a bad scene, flag or output folder; nothing was written\n"
    "  3  the environment failed: a tool missing (gnuplot), a disk full, a write refused\n"
    "  128+N  interrupted by signal N (SIGHUP 129, SIGINT 130, SIGTERM 143); the partial output was removed and "
    "every program crankcheck started was ended\n"
    "Output folders (--out): crankcheck creates a folder, or replaces one that is empty or holds a report it wrote "
    "itself (crankcheck-manifest.json); any other folder, a file or a symbolic link is refused with status 2.";

// `COMMAND ... -- WORD...`: every word after `--` is an argument as written, even one that starts with '-' (a scene
// file called -lead.toml), as POSIX has it. CLI11 2.1 does not keep that promise inside a subcommand: with its
// positionals filled it hands the words to the main command, which refuses them ("-lead.toml: unknown flag"), and
// with them empty it refuses `--` itself. So each word after `--` goes to CLI11 behind a mark that makes it no flag,
// `--` itself is dropped, and every positional argument takes the mark off again (unmarkPositionals). `grade`'s `--`
// comes before its program's words, which never reach CLI11 (splitGradeProgram).
constexpr std::string_view kAfterDashDash = "\x01crankcheck: after --:";

std::vector<std::string> markWordsAfterDashDash(std::vector<std::string> args) {
  const auto dashes = std::find(args.begin() + 1, args.end(), "--");
  if (dashes == args.end()) return args;
  std::vector<std::string> marked(args.begin(), dashes);
  for (auto word = dashes + 1; word != args.end(); ++word) marked.push_back(std::string(kAfterDashDash) + *word);
  return marked;
}

/// `text` without the marks of markWordsAfterDashDash (a parse error's line quotes the words as given).
std::string unmark(std::string text) {
  for (size_t at = text.find(kAfterDashDash); at != std::string::npos; at = text.find(kAfterDashDash, at))
    text.erase(at, kAfterDashDash.size());
  return text;
}

void unmarkPositionals(CLI::App& app) {
  for (CLI::App* command : app.get_subcommands({})) {
    for (CLI::Option* option : command->get_options())
      if (option->get_positional())
        option->transform([](std::string word) {
          return word.rfind(kAfterDashDash, 0) == 0 ? word.substr(kAfterDashDash.size()) : word;
        });
    unmarkPositionals(*command);
  }
}

// One line for a CLI11 parse error, in the form "crankcheck: --flag: rule" where CLI11 names the flag.
std::string parseErrorMessage(const CLI::ParseError& e) {
  std::string message = unmark(e.what());
  const std::string extras = "The following argument was not expected: ";
  const std::string extras_plural = "The following arguments were not expected: ";
  for (const std::string& prefix : {extras, extras_plural})
    if (message.rfind(prefix, 0) == 0) return message.substr(prefix.size()) + ": unknown flag or argument";
  for (char& c : message)
    if (c == '\n') c = ' ';
  return message;
}

// The edit distance (insertions, deletions, substitutions) between a and b.
size_t calcEditDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// "--flag: unknown flag or argument (did you mean --flog?)" for the first argument like a flag that CLI11 did not take in `app` or
// a subcommand it parsed; empty when there is none. CLI11 checks the required flags first: a mistyped required flag
// was reported as missing, not as mistyped.
std::string findUnknownFlag(const CLI::App& app) {
  for (const std::string& arg : app.remaining(false)) {
    if (arg.size() < 2 || arg[0] != '-') continue;
    const std::string flag = arg.substr(0, arg.find('='));
    std::string closest;
    size_t best = 3;  // a suggestion within two edits
    for (const CLI::Option* option : app.get_options())
      for (const std::string& name : option->get_lnames())
        if (const size_t d = calcEditDistance(flag, "--" + name); d < best) {
          best = d;
          closest = "--" + name;
        }
    return flag + ": unknown flag or argument" + (closest.empty() ? std::string() : " (did you mean " + closest + "?)");
  }
  for (const CLI::App* sub : app.get_subcommands())
    if (std::string found = findUnknownFlag(*sub); !found.empty()) return found;
  return {};
}

// "valdate: unknown command (did you mean validate?)" when `app` (or the subcommand it parsed: `report`) needs a
// subcommand and was given a word that names none; empty otherwise. CLI11 said only "A subcommand is required".
std::string findUnknownCommand(const CLI::App& app) {
  for (const CLI::App* sub : app.get_subcommands())
    if (std::string found = findUnknownCommand(*sub); !found.empty()) return found;
  if (!app.get_subcommands().empty() || app.get_subcommands({}).empty()) return {};
  for (const std::string& arg : app.remaining(false)) {
    if (arg.empty() || arg[0] == '-') continue;
    std::string closest;
    size_t best = 3;  // a suggestion within two edits
    for (const CLI::App* command : app.get_subcommands({}))
      if (const size_t d = calcEditDistance(arg, command->get_name()); d < best) {
        best = d;
        closest = command->get_name();
      }
    return crankcheck::escapeControls(unmark(arg)) + ": unknown command" +
           (closest.empty() ? std::string() : " (did you mean " + closest + "?)");
  }
  return {};
}

// `status`, once everything written to stdout has reached it; else EnvironmentError. A write that fails while stdio's
// buffer fills (output over 4 KiB to a full disk) is seen only in the stream's error flag: fflush alone then succeeds
// on an empty buffer and the lost results went unnoticed with status 0.
int checkStdout(int status) {
  std::cout.flush();
  errno = 0;
  const bool flushed = std::fflush(stdout) == 0;
  if (!flushed || std::ferror(stdout) || !std::cout.good())
    throw crankcheck::EnvironmentError(std::string("stdout: cannot write the results") +
                                       (errno != 0 ? std::string(": ") + std::strerror(errno) : std::string()));
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  crankcheck::validation::watchInterrupts();  // from here on, a signal ends every child with crankcheck
  // and whatever a program leaves behind (a setsid child, a daemon) comes back to crankcheck to be ended: none outlives it
  (void)crankcheck::validation::reapLeftBehindProcesses();
  // A file-size limit (ulimit -f) is a full disk to crankcheck: the write fails (EFBIG), the output is refused with
  // status 3 and its partial folder removed, instead of SIGXFSZ killing the process with its partial output left.
  std::signal(SIGXFSZ, SIG_IGN);
  using crankcheck::app::describeEngines;
  const std::string engines = describeEngines();
  CLI::App app{"crankcheck checks the closed-form formulas of piston engines and compressors (slider-crank kinematics, "
               "gravity's potential energy and torque, gas and inertia loads, balance, flywheels, torsional vibration) "
               "against independent multibody engines: " + engines + ". It reports how far each formula is from "
               "them and where it breaks, and grades your own program by the same rule. Every command takes a scene "
               "file (TOML: docs/SCENE-FORMAT.md); `crankcheck COMMAND --help` says more. Docs: the repository's "
               "README.md and docs/, or PREFIX/share/crankcheck/docs and `man crankcheck-COMMAND` when installed.",
               "crankcheck"};
  app.formatter(std::make_shared<crankcheck::app::WrappingFormatter>());
  app.set_version_flag("--version", std::string("crankcheck ") + crankcheck::validation::getCrankcheckVersion());
  app.footer(kExitStatus);
  app.require_subcommand(1);

  crankcheck::app::EvalOptions eval;
  CLI::App* eval_cmd = app.add_subcommand(
      "eval", "Evaluate a scene at given crank angles in one engine or all: U, Q, drive torque, joint reactions, "
              "piston and rod kinematics, shaking force and moment (SI units; angles in degrees)");
  crankcheck::app::addEvalOptions(*eval_cmd, eval);

  crankcheck::app::MotionOptions motion;
  CLI::App* motion_cmd = app.add_subcommand(
      "motion", "The free run from the scene's speed without a drive: speed fluctuation delta with and without "
                "gravity, by the exact energy integral and by each engine that simulates: " +
                    describeEngines([](const crankcheck::Engine& e) { return static_cast<bool>(e.simulate); }));
  crankcheck::app::addMotionOptions(*motion_cmd, motion);

  crankcheck::app::FlywheelOptions flywheel;
  CLI::App* flywheel_cmd = app.add_subcommand(
      "flywheel", "Flywheel sizing (Norton 13.9) for a speed fluctuation C over the gas cycle: the exact inertia, "
                  "Norton's method and its error, and Simbody's free run with the exact inertia");
  crankcheck::app::addFlywheelOptions(*flywheel_cmd, flywheel);

  crankcheck::app::BalanceOptions balance;
  CLI::App* balance_cmd = app.add_subcommand(
      "balance", "Shaking force and moment harmonic by harmonic: the closed forms against each exact engine's "
                 "Fourier analysis (" +
                     describeEngines([](const crankcheck::Engine& e) { return e.gated; }) +
                     "), and what vanishes by symmetry; --design N: balance shafts that cancel harmonic N");
  crankcheck::app::addBalanceOptions(*balance_cmd, balance);

  crankcheck::app::TorsionOptions torsion;
  CLI::App* torsion_cmd = app.add_subcommand(
      "torsion", "Torsional vibration of the scene's [crankshaft]: Holzer's natural frequencies, critical speeds and "
                 "twist against the exact steady state of the variable-inertia crank train, and each engine's run of "
                 "it (--engine)");
  crankcheck::app::addTorsionOptions(*torsion_cmd, torsion);

  crankcheck::app::SteppedOptions stepped;
  CLI::App* stepped_cmd = app.add_subcommand(
      "stepped", "The physics engines people ship (" + crankcheck::app::describeEngineNames(crankcheck::Route::kStepAtSpeed) +
                     ", measured, never gated), each driven at the scene's speed by its own time-stepping solver: every "
                     "quantity it reports against the closed forms at a series of time steps and at each of its "
                     "settings, the observed order, the cost per step");
  crankcheck::app::addSteppedOptions(*stepped_cmd, stepped);

  crankcheck::app::ValidateOptions validate;
  CLI::App* validate_cmd = app.add_subcommand(
      "validate", "The main job: cross-check the closed forms against every engine (" + engines +
                      ") over a campaign (the built-in one, or your scenes) and write the report: Markdown, HTML, "
                      "figures, CSV data");
  crankcheck::app::addValidateOptions(*validate_cmd, validate);

  crankcheck::app::GradeOptions grade;
  CLI::App* grade_cmd = app.add_subcommand(
      "grade", "Grade your own program's values against the analytic engine and every exact engine (" +
                   describeEngines([](const crankcheck::Engine& e) { return e.gated; }) +
                   ") by the gate's rule: crankcheck grade [SCENE...] [options] -- PROGRAM [ARG...]");
  crankcheck::app::addGradeOptions(*grade_cmd, grade);

  crankcheck::app::MergeOptions merge;
  CLI::App* report_cmd = app.add_subcommand("report", "Work with reports: merge the shards of 'validate --shard I/N'");
  report_cmd->require_subcommand(1);
  CLI::App* merge_cmd = report_cmd->add_subcommand("merge", "Merge shards of 'validate --shard I/N' into one report");
  crankcheck::app::addMergeOptions(*merge_cmd, merge);

  // `grade ... -- PROGRAM ARG...`: the program's words never reach CLI11 (they are not crankcheck's).
  std::vector<std::string> args = markWordsAfterDashDash(crankcheck::app::splitGradeProgram(argc, argv, grade.program));
  unmarkPositionals(app);
  try {
    std::vector<std::string> reversed(args.rbegin(), args.rend() - 1);  // CLI11 takes them in reverse, without argv[0]
    app.parse(reversed);
  } catch (const CLI::Success& e) {  // --help, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string unknown = findUnknownCommand(app);  // a mistyped command, then a mistyped flag, before what is missing
    if (unknown.empty()) unknown = findUnknownFlag(app);
    std::cerr << "crankcheck: " << (unknown.empty() ? parseErrorMessage(e) : unknown) << " (see crankcheck --help)\n";
    return 2;
  }

  try {
    crankcheck::app::checkNoEmptyValues(app, args);
    // validate, merge and grade print their verdict as they go; the other commands print only complete results.
    if (validate_cmd->parsed()) return checkStdout(crankcheck::app::runValidate(validate));
    if (merge_cmd->parsed()) return checkStdout(crankcheck::app::runMerge(merge));
    if (grade_cmd->parsed()) return checkStdout(crankcheck::app::runGrade(grade));
    std::string output;
    bool checks_hold = true;  // eval --split checks that its parts add up to the whole
    if (eval_cmd->parsed()) {
      const crankcheck::app::EvalOutput result = crankcheck::app::runEval(eval);
      output = result.text;
      checks_hold = result.checks_hold;
    }
    if (motion_cmd->parsed()) output = crankcheck::app::runMotion(motion);
    if (balance_cmd->parsed()) output = crankcheck::app::runBalance(balance);
    if (flywheel_cmd->parsed()) output = crankcheck::app::runFlywheel(flywheel);
    if (torsion_cmd->parsed()) output = crankcheck::app::runTorsion(torsion);
    if (stepped_cmd->parsed()) output = crankcheck::app::runStepped(stepped);
    std::fwrite(output.data(), 1, output.size(), stdout);  // only complete results are ever printed
    return checkStdout(checks_hold ? 0 : 1);
  } catch (const crankcheck::UsageError& e) {
    crankcheck::validation::yieldToInterrupt();  // each error below: unless an interrupt caused it
    std::cerr << "crankcheck: " << crankcheck::formatOneLine(e.what()) << "\n";
    return 2;
  } catch (const crankcheck::UncomputableError& e) {
    crankcheck::validation::yieldToInterrupt();
    std::cerr << "crankcheck: " << crankcheck::formatOneLine(e.what()) << "\n";
    return 1;
  } catch (const crankcheck::EnvironmentError& e) {
    crankcheck::validation::yieldToInterrupt();
    std::cerr << "crankcheck: " << crankcheck::formatOneLine(e.what()) << "\n";
    return 3;
  } catch (const std::filesystem::filesystem_error& e) {
    crankcheck::validation::yieldToInterrupt();
    std::cerr << "crankcheck: " << crankcheck::formatOneLine(e.what()) << "\n";
    return 3;
  } catch (const std::bad_alloc&) {
    std::cerr << "crankcheck: out of memory\n";
    return 3;
  } catch (const std::exception& e) {  // not the user's input: the harness itself could not complete
    crankcheck::validation::yieldToInterrupt();
    std::cerr << "crankcheck: could not complete: " << crankcheck::formatOneLine(e.what()) << "\n";
    return 3;
  }
}
