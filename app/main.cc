// crankcheck: the command-line front end. Verbs live in their own files; this one parses flags (CLI11) and
// maps user errors to one message on stderr and exit status 2.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>

#include "eval_command.h"
#include "motion_command.h"
#include "validate_command.h"
#include "usage_error.h"

int main(int argc, char** argv) {
  CLI::App app{"crankcheck: validates slider-crank and k-crank formulas against an independent Simbody model"};
  app.set_version_flag("--version", "crankcheck 0.1.0");
  app.require_subcommand(1);

  crankcheck::app::EvalOptions eval;
  CLI::App* eval_cmd = app.add_subcommand(
      "eval", "Evaluate U, Q, drive torque, reactions and piston kinematics of a scene at given crank angles");
  crankcheck::app::addEvalOptions(*eval_cmd, eval);

  crankcheck::app::MotionOptions motion;
  CLI::App* motion_cmd = app.add_subcommand(
      "motion", "The free run under gravity: speed fluctuation delta with and without gravity, analytic and Simbody");
  crankcheck::app::addMotionOptions(*motion_cmd, motion);

  crankcheck::app::ValidateOptions validate;
  CLI::App* validate_cmd = app.add_subcommand(
      "validate", "The main job: cross-check both engines over a campaign and write the report (figures, CSV, index)");
  crankcheck::app::addValidateOptions(*validate_cmd, validate);

  crankcheck::app::MergeOptions merge;
  CLI::App* report_cmd = app.add_subcommand("report", "Work with reports");
  report_cmd->require_subcommand(1);
  CLI::App* merge_cmd = report_cmd->add_subcommand("merge", "Merge shards of 'validate --shard I/N' into one report");
  crankcheck::app::addMergeOptions(*merge_cmd, merge);

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "crankcheck: " << e.what() << "\n" << "Run 'crankcheck --help' for usage.\n";
    return 2;
  }

  try {
    if (validate_cmd->parsed()) return crankcheck::app::runValidate(validate);
    if (merge_cmd->parsed()) return crankcheck::app::runMerge(merge);
    std::string output;
    if (eval_cmd->parsed()) output = crankcheck::app::runEval(eval);
    if (motion_cmd->parsed()) output = crankcheck::app::runMotion(motion);
    std::fwrite(output.data(), 1, output.size(), stdout);  // only complete results are ever printed
    return 0;
  } catch (const crankcheck::app::UsageError& e) {
    std::cerr << "crankcheck: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {  // not the user's fault: a failure of the harness or its tools
    std::cerr << "crankcheck: error: " << e.what() << "\n";
    return 1;
  }
}
