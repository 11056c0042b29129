#pragma once
/// @file
/// One part of the validation report, the way an engine is one entry of engines.h: its own file under
/// validation/src/parts/ says what work it needs (tasks), what it computes from finished work (derive) and how the
/// report shows it (describe); the registry (parts.h) lists the parts in report order, one line each. The campaign
/// (campaign.h) collects every part's tasks; the report (report.h) draws and places every part. The whole contract of
/// a part is the abstract class below (after Google Benchmark's reporters: a few virtual methods, one file each).

#include <functional>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/task.h"
#include "crankcheck/validation/report_part.h"

namespace crankcheck::validation {

/// What a part's tasks are built from: the campaign's scenes as buildCampaign resolved them.
struct PartContext {
  /// The base of the figures: the first scene, as a standing centric inline engine of its k and cycle without
  /// balance shafts (campaign.cc says when that differs from the scene as given).
  Mechanism base;
  /// The first scene as given (its own layout, offsets and shafts).
  Mechanism first;
  /// The user's scene files, or the example scenes (scenes/*.toml) in the default campaign.
  std::vector<Mechanism> scenes;
  /// The user's scene files alone; empty in the default campaign.
  std::vector<Mechanism> user_scenes;
  /// (family of cases, scene) of every cross-checked scene: the built-in families, or one per user scene.
  std::vector<std::pair<std::string, Mechanism>> families;
  bool quick = false;  ///< fewer lambdas, angles and methods: a smoke test of the whole report
  double work_limit = 600.0;  ///< [s] the longest estimated work a part may start (CampaignOptions::work_limit)
};

/// A task's estimated cost, relative: the campaign starts the larger first so that parallel jobs end together (the
/// order changes no table: they are sorted). Ties keep the order in which the parts list them.
namespace task_cost {
inline constexpr double kFineCycleRun = 4.0;  ///< an engine's run over a working cycle at fine steps (flywheel)
inline constexpr double kCycleSweep = 3.0;   ///< every engine over a working cycle at 1 degree, refined (offset)
inline constexpr double kCrossCheck = 2.0;   ///< every engine on one case at every angle and speed
inline constexpr double kGateSweep = 1.0;    ///< the gate's sweep of one k and stroke over lambda and gamma
inline constexpr double kShort = 0.0;        ///< the rest (seconds at most)
}  // namespace task_cost

/// A value that several of a part's tasks read, computed once by the first that asks (the others wait for it): the
/// tasks share it through a std::shared_ptr made in Part::tasks. If the computation throws, the exception goes to that
/// caller and the next one tries again (std::call_once).
template <class T>
class SharedResult {
 public:
  explicit SharedResult(std::function<T()> calc) : calc_(std::move(calc)) {}
  const T& get() {
    std::call_once(once_, [this] { value_ = calc_(); });
    return value_;
  }

 private:
  const std::function<T()> calc_;
  std::once_flag once_;
  T value_{};
};

/// Maxima over a turn (or a cycle) that a part's table states: found so that they do not depend on the sampling grid,
/// the quick and the full campaign must give them within 1 % (tests/cli/quick_report_test.cc reads every part's).
struct ReportedMaximum {
  std::string table;                      ///< the CSV stem
  std::vector<std::string> key;           ///< the columns that identify a row in both campaigns
  std::vector<std::string> maxima;        ///< the columns that hold maxima
  std::string bound_column, bound_value;  ///< a row whose bound_column is bound_value states a bound (rounding), not a
                                          ///< maximum; empty: every row states values
};

/// One part of the report.
class Part {
 public:
  virtual ~Part() = default;
  /// The figure's and main table's stem ("flywheel": flywheel.png, data/flywheel.csv, reports/flywheel.gp).
  virtual std::string key() const = 0;
  /// Its heading without the number ("Flywheel sizing: ...").
  virtual std::string title() const = 0;
  /// True for the report's core (the verdict, the summary, the scenes): always run whatever `validate --parts` asks,
  /// placed first, headed by their title alone; false for the numbered parts, which `--parts` chooses from.
  virtual bool always() const { return false; }
  /// The independent units of work whose tables the part reads; each with its Task::cost.
  virtual std::vector<Task> tasks(const PartContext& context) const = 0;
  /// Adds the tables computed from the finished work of every task (the report runs it on the sorted tables before
  /// writing them). Default: nothing.
  virtual void derive(TableSet& tables) const { (void)tables; }
  /// The part as the report shows it (heading "N. title", the figure's caption, sentences, a table); an empty heading
  /// when the tables it needs are missing: the part is left out.
  virtual ReportPart describe(const TableSet& tables) const = 0;
  /// The schemas of the tables it writes (its tasks' and derive's), declared once in its file (table.h).
  virtual std::vector<const TableSchema*> schemas() const { return {}; }
  /// The CSV stems it writes (its tasks' and derive's), for tests and docs: its schemas' names.
  virtual std::vector<std::string> tables() const {
    std::vector<std::string> out;
    for (const TableSchema* schema : schemas()) out.push_back(schema->name());
    return out;
  }
  /// The figures it draws (stems of reports/NAME.gp, data/NAME.csv, NAME.png, NAME.svg); drawn when data/NAME.csv
  /// exists.
  virtual std::vector<std::string> figures() const { return {key()}; }
  /// The maxima its tables state (ReportedMaximum). Default: none.
  virtual std::vector<ReportedMaximum> maxima() const { return {}; }
  /// Why the part has nothing to show for these scenes (a sentence for the report's notes: what is missing and how to
  /// get the part), or empty when it has. A part left out for its scenes is never left out without a word.
  virtual std::string findOmission(const PartContext& context) const {
    (void)context;
    return {};
  }

  /// Checks before any work that the part's work on these scenes is estimated within context.work_limit (work_limit.h),
  /// for a part whose work grows without a bound the scene sets (steps per turn at a low speed). Default: nothing.
  /// @throws UsageError naming the part, the scene, the estimate and how to ask for less.
  virtual void checkWork(const PartContext& context) const { (void)context; }
  /// Its number in the report: its place among the numbered parts of the registry (parts.h), 1..N; 0 for a part that
  /// is always() run. No part states its own number; prose names a part by its title or key, or asks the registry.
  /// @throws std::logic_error for a part that is not registered.
  int number() const;
  /// "N. title" (a numbered part) or the title (always()): the heading describe() gives.
  std::string heading() const { return always() ? title() : std::to_string(number()) + ". " + title(); }

 protected:
  /// describe() of a part that is its figure alone: the heading and `caption` when its table data/KEY.csv is there;
  /// left out (empty heading) when it is not.
  ReportPart describeFigure(const TableSet& tables, const std::string& caption) const {
    ReportPart part;
    if (!tables.count(key())) return part;
    part.heading = heading();
    part.caption = caption;
    return part;
  }
};

}  // namespace crankcheck::validation
