// Report part `delta_vs_k`: the free run's speed fluctuation due to gravity against k. Needs the base scene's flywheel:
// without one the part is left out (campaign.cc's notes say so).
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "../part_math.h"
#include "crankcheck/analytic/motion.h"
#include "crankcheck/simbody_models/free_run.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/campaign_scenes.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/table.h"
#include "crankcheck/validation/task.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/variants.h"
#include "survey.h"

namespace crankcheck::validation {
namespace {

// delta_vs_k: the free run's speed fluctuation with and without gravity, k = 1..12, both strokes, a few speeds; NaN
// where the engine is too slow to turn over against gravity.
struct DeltaRow {
  std::string cycle;
  int k = 1;
  double speed_rpm = 0.0;                                  ///< [rpm]
  double delta_gravity = 0.0, delta_no_gravity = 0.0;      ///< [-]
  double delta_due_to_gravity = 0.0;                       ///< |delta_gravity - delta_no_gravity| [-]
};
const Schema<DeltaRow> kDeltaVsKTable{
    "delta_vs_k",
    {textField("cycle", &DeltaRow::cycle), countField("k", &DeltaRow::k),
     numberField("speed_rpm", "rpm", &DeltaRow::speed_rpm), numberField("delta_gravity", "-", &DeltaRow::delta_gravity),
     numberField("delta_no_gravity", "-", &DeltaRow::delta_no_gravity),
     numberField("delta_due_to_gravity", "-", &DeltaRow::delta_due_to_gravity)}};

TableSet calcDeltaVsKTables(const Mechanism& base, Cycle cycle, bool quick) {
  std::vector<DeltaRow> rows;
  for (int k = 1; k <= 12; ++k)
    for (double rpm : quick ? std::vector<double>{300.0, 6000.0} : std::vector<double>{60.0, 300.0, 1500.0, 6000.0}) {
      const Mechanism m = withSpeed(withGamma(withCylinders(base, k, cycle), 90.0), rpm);
      double with = std::nan(""), without = std::nan("");
      try {
        with = analytic::calcFreeRun(m, m.machine.speed, true).delta;
        without = analytic::calcFreeRun(m, m.machine.speed, false).delta;
      } catch (const std::domain_error&) {  // too slow to turn over against gravity: no free run to report
      }
      rows.push_back({toString(cycle), k, rpm, with, without, std::fabs(with - without)});
    }
  return kDeltaVsKTable.tableSet(std::move(rows));
}

// The figure's caption.
constexpr const char* kCaption =
    "The free run (released at phi = 0, no drive, no load, standing engines with the base scene's flywheel): "
    "|delta with gravity - delta without| against k at several speeds; dashed: delta of the varying inertia alone. "
    "Where the solid line lies far below the dashed one, gravity can be neglected at that speed";

class DeltaVsKPart final : public Part {
 public:
  std::string key() const override { return "delta_vs_k"; }
  std::string title() const override { return "Speed fluctuation due to gravity in the free run"; }
  // One task per cycle; none without the base scene's flywheel (crankcheck invents no inertia).
  std::vector<Task> tasks(const PartContext& context) const override {
    std::vector<Task> out;
    if (!context.base.flywheel_inertia) return out;
    for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke})
      out.push_back({"delta_vs_k " + toString(cycle), false,
                     [base = context.base, cycle, quick = context.quick] { return calcDeltaVsKTables(base, cycle, quick); }});
    return out;
  }
  // The caption with the speeds read from the table.
  ReportPart describe(const TableSet& tables) const override {
    std::vector<double> speeds;
    for (const DeltaRow& row : getRows(tables, kDeltaVsKTable)) speeds.push_back(row.speed_rpm);
    return describeFigure(tables, std::string(kCaption) + (speeds.empty() ? "" : "; " + survey::atSurveySpeeds(speeds)));
  }
  std::vector<const TableSchema*> schemas() const override { return {&kDeltaVsKTable}; }
  std::vector<ReportedMaximum> maxima() const override {
    return {{"delta_vs_k", {"cycle", "k", "speed_rpm"}, {"delta_gravity", "delta_no_gravity"}, "", ""}};
  }
};

}  // namespace

namespace parts {
const Part& deltaVsK() {
  static const DeltaVsKPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
