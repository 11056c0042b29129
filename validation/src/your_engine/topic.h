#pragma once
// The report's scene sections ("NAME: your engine", part your_engine: parts/your_engine.cc): for each scene the user
// gives (the example scenes in the default campaign), what the textbook formulas, the closed forms and every engine say
// about that scene exactly as given: its layout, speed, gas table, pin offsets, balance shafts, flywheel and
// crankshaft. A section is made of topics (formula fitness, loads, balance, gravity, flywheel and torsion), each one
// file of this folder, listed once in topics.cc. A topic computes its tables on one scene (every row names the scene by
// its file's stem, Mechanism::name, in a column "scene") and describes them for one scene, from the tables alone (the
// report is rendered again from CSV by `report merge`).

#include <optional>
#include <string>
#include <vector>

#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/campaign_scenes.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/table.h"
#include "crankcheck/validation/task.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/report_part.h"

namespace crankcheck::validation::your_engine {

/// One scene of the sections as given, with what it has (data/your_engine.csv): the facts a topic's describe reads to
/// say what a scene lacks, since the report is rendered from the tables alone.
struct SceneFactsRow {
  int scene_index = 0;        ///< its place among the scenes given (the sections' order)
  std::string scene;          ///< the scene file's stem (Mechanism::name)
  std::string given;          ///< "user": a scene the user gave; "example": an example scene of the default campaign
  std::string layout;         ///< one line: cylinders, banks, cycle, acting
  int cylinders = 1;
  std::string cycle, acting;
  double speed_rpm = 0.0;     ///< [rpm]
  double lambda = 0.0;        ///< [-] r / l
  int gas = 0;                ///< 1: the scene has a [gas] table
  int flywheel = 0;           ///< 1: the scene has a [flywheel] inertia
  int crankshaft = 0;         ///< 1: the scene has a [crankshaft] table (the elastic crank train)
  int balance_shafts = 0;     ///< the number of its [[balance_shaft]] tables
  int pin_offsets = 0;        ///< 1: some cylinder's pin is offset
  double max_pin_offset = 0.0;  ///< [m] max_j |delta_j|
};
extern const Schema<SceneFactsRow> kSceneFactsTable;

/// The facts of m: its place `index` among the scenes, `user` true for a scene the user gave (false: an example scene).
SceneFactsRow calcSceneFacts(const Mechanism& m, int index, bool user);

/// The facts of `scene`, or none when the table lacks it (the section was not run).
std::optional<SceneFactsRow> findSceneFacts(const TableSet& tables, const std::string& scene);

/// One formula judged on one scene (data/your_engine_fitness.csv): its largest error over the working cycle (or its
/// one value: a flywheel inertia, a critical speed) against one exact reference, relative to the quantity's scale. Rows
/// come from several topics (the kinematic and torque formulas, Norton's flywheel method, Holzer's constant inertia);
/// the fitness topic describes them all, in the order of `order`.
struct FitnessRow {
  std::string scene;
  int order = 0;                ///< the row's place in the scene's table (formulas in a fixed order, then quantities)
  std::string formula;          ///< "Norton's two-term series (eq 13.3)", "Fourier series of Q to order 4", ...
  std::string quantity;         ///< "x_p", "a_p", "Q", "I_w", "omega_1", ...
  std::string reference;        ///< the exact engine the formula is measured against: "analytic" (its exact closed
                                ///< forms), "simbody", "mujoco", ...
  double max_error_rel = 0.0;   ///< [-] the largest |formula - exact| / scale
  std::string scale;            ///< the scale's name as the report prints it: "r omega^2", "max |Q|", "I_w", ...
  double scale_value = 0.0;     ///< [SI] the scale in the quantity's unit (never zero)
  std::string scale_unit;       ///< its unit: "m/s^2", "N m", "kg m^2", "rad/s", ...
  std::optional<double> phi_deg_at_max;  ///< [deg] where the largest error is; empty for a quantity of no angle
  int resolved = 1;             ///< 0: the error is at rounding level (a bound, part_math.h resolvedToOnePercent)
};
extern const Schema<FitnessRow> kFitnessTable;

/// The gravity of one scene in one engine (data/your_engine_gravity.csv): the paper's question, does gravity matter
/// for this engine, answered at its speed.
struct GravityRow {
  std::string scene, engine;
  double max_abs_Q = 0.0;               ///< [N m] max |Q| over a turn (Q = dU/dphi, the gravity torque on the crank)
  double phi_deg_at_max = 0.0;          ///< [deg] where
  double max_abs_inertia_torque = 0.0;  ///< [N m] max |drive torque| over a turn at the scene's speed, gas and gravity off
  double ratio = 0.0;                   ///< [-] max_abs_Q / max_abs_inertia_torque (NaN at speed 0: not defined)
  int gated = 1;                        ///< 0: a soft way, measured beside the exact engines
  int resolved = 1;                     ///< 0: max |Q| is at rounding level (gravity's torque cancels: a bound)
  /// [N m] the closed forms' max |drive torque| over the working cycle with the scene's [gas] and gravity: what
  /// gravity is judged against where the scene has gas (empty without gas or speed, and for the other engines)
  std::optional<double> max_abs_working_torque;
};
extern const Schema<GravityRow> kGravityTable;

/// "within 1 %", "off by 3.1 %", "off by 44.3 times the scale" (an error beyond the scale itself), "exact to
/// rounding": a formula's verdict from its error relative to the scale.
std::string formatFitness(double max_error_rel, bool resolved);

/// One topic of every scene's section.
class SceneTopic {
 public:
  virtual ~SceneTopic() = default;
  /// Its sub-heading in each scene's section ("Formula fitness").
  virtual std::string title() const = 0;
  /// The tasks computing its rows on `scene` exactly as given, each row naming the scene (its `scene` column =
  /// scene.name); `quick`: the smoke-test campaign (coarser grids, the same maxima found by refinement).
  virtual std::vector<Task> tasks(const Mechanism& scene, bool quick) const = 0;
  /// Tables computed from every finished task (all scenes at once). Default: none.
  virtual void derive(TableSet& tables) const { (void)tables; }
  /// Its blocks in the section of `scene` (a stem), read from the tables alone: sentences, tables, figures. Where the
  /// scene lacks what the topic needs, one paragraph says what and how to add it (never a silent gap). Nothing when its
  /// tables are missing (the section was not run).
  virtual std::vector<ReportBlock> describe(const TableSet& tables, const std::string& scene) const = 0;
  /// The schemas of the tables its tasks and derive write.
  virtual std::vector<const TableSchema*> schemas() const = 0;
  /// The figures it draws (reports/NAME.gp over data/NAME.csv, one figure for every scene). Default: none.
  virtual std::vector<std::string> figures() const { return {}; }
  /// The maxima its tables state (part.h ReportedMaximum). Default: none.
  virtual std::vector<ReportedMaximum> maxima() const { return {}; }
};

/// Every topic, in the order of a section (topics.cc).
const std::vector<const SceneTopic*>& listTopics();

}  // namespace crankcheck::validation::your_engine
