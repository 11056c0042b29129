#pragma once
/// @file
/// One independent unit of a campaign's work: what a report part hands the campaign (Part::tasks, part.h) and the
/// runner runs (runner.h), on any thread or shard; and the notes table any task may add to.

#include <functional>
#include <string>

#include "crankcheck/validation/table.h"

namespace crankcheck::validation {

/// One independent unit of work.
struct Task {
  std::string id;                   ///< e.g. "crosscheck inline4_four_gamma90 lambda=0.3"
  /// Times itself (Google Benchmark): run on a core of its own, never beside another such task (runner.h runTasks:
  /// on one worker while the others compute, when every worker has a core; else after the others).
  bool measures_time = false;
  std::function<TableSet()> run;
  double cost = 0.0;                ///< estimated, relative (part.h's task_cost): buildCampaign lists the largest first
};

/// One note of the campaign: what it left out, and why (only when there is something to say).
struct NoteRow {
  std::string note;
};

/// data/notes.csv.
extern const Schema<NoteRow> kNotesTable;

}  // namespace crankcheck::validation
