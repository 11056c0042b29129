// Report part `delta_vs_k` (6): the free run's speed fluctuation due to gravity against k. Needs the base scene's flywheel:
// without one the part is left out (campaign.cc's notes say so).
#include <string>
#include <vector>

#include "../campaign_tables.h"
#include "crankcheck/validation/part.h"

namespace crankcheck::validation {
namespace {

// The figure's caption.
constexpr const char* kCaption =
    "The free run (released at phi = 0, no drive, no load, standing engines with the base scene's flywheel): "
    "|delta with gravity - delta without| against k at several speeds; dashed: delta of the varying inertia alone. "
    "Where the solid line lies far below the dashed one, gravity can be neglected at that speed";

class DeltaVsKPart final : public Part {
 public:
  std::string key() const override { return "delta_vs_k"; }
  int number() const override { return 6; }
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
  ReportPart describe(const TableSet& tables) const override {
    ReportPart part;
    if (!tables.count("delta_vs_k")) return part;
    part.heading = heading();
    part.caption = kCaption;
    return part;
  }
  std::vector<std::string> tables() const override { return {"delta_vs_k"}; }
};

}  // namespace

namespace parts {
const Part& deltaVsK() {
  static const DeltaVsKPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
