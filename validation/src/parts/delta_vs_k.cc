// Report part `delta_vs_k` (6): the free run's speed fluctuation due to gravity against k. Needs the base scene's flywheel:
// without one the part is left out (campaign.cc's notes say so).
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "../campaign_tables.h"
#include "crankcheck/analytic/motion.h"
#include "crankcheck/simbody_models/free_run.h"
#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/variants.h"

namespace crankcheck::validation {
namespace {

// ------------------------------------------------------------------------------------------------------------
// delta_vs_k: the free run's speed fluctuation with and without gravity, k = 1..12, both strokes, a few speeds.

TableSet calcDeltaVsKTables(const Mechanism& base, Cycle cycle, bool quick) {
  Table t("delta_vs_k", {{"cycle", kText}, {"k", "-"}, {"speed_rpm", "rpm"}, {"delta_gravity", "-"},
                         {"delta_no_gravity", "-"}, {"delta_due_to_gravity", "-"}});
  for (int k = 1; k <= 12; ++k)
    for (double rpm : quick ? std::vector<double>{300.0, 6000.0} : std::vector<double>{60.0, 300.0, 1500.0, 6000.0}) {
      const Mechanism m = withSpeed(withGamma(withCylinders(base, k, cycle), 90.0), rpm);
      double with = std::nan(""), without = std::nan("");
      try {
        with = analytic::calcFreeRun(m, m.engine.speed, true).delta;
        without = analytic::calcFreeRun(m, m.engine.speed, false).delta;
      } catch (const std::domain_error&) {  // too slow to turn over against gravity: no free run to report
      }
      t.rows.push_back({toString(cycle), std::to_string(k), formatNumber(rpm), formatNumber(with), formatNumber(without), formatNumber(std::fabs(with - without))});
    }
  return {{"delta_vs_k", t}};
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
  ReportPart describe(const TableSet& tables) const override { return describeFigure(tables, kCaption); }
  std::vector<std::string> tables() const override { return {"delta_vs_k"}; }
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
