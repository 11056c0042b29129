// Report part `torque_split` (10): the working torque split into gas, inertia and gravity, and gravity's share against k
// (computed in engine_loads.cc).
#include <string>
#include <vector>

#include "../campaign_tables.h"
#include "crankcheck/validation/engine_loads.h"
#include "crankcheck/validation/part.h"

namespace crankcheck::validation {
namespace {

// The figure's caption.
constexpr const char* kCaption =
    "The drive torque over one working cycle of a car inline four (the base scene's parts, bore 2 r, the example "
    "spark-ignition pressure table, 6000 rpm) and of the marine two-stroke (bore 2 r / 3, a diesel table), split "
    "into its gas, inertia and gravity parts (each the analytic drive torque with the other loads off; Simbody's "
    "whole drive torque as dots); right: gravity's share of the mean absolute drive torque against k, at 600 and "
    "6000 rpm, both strokes (gravity torques below double precision left out): the sources' question answered "
    "against the real working torque";

class TorqueSplitPart final : public Part {
 public:
  std::string key() const override { return "torque_split"; }
  int number() const override { return 10; }
  std::string title() const override { return "The working torque: gas, inertia and gravity"; }
  // On the base scene's parts and the built-in marine engine.
  std::vector<Task> tasks(const PartContext& context) const override {
    return {{"torque_split", false,
             [base = context.base, marine = findMarineScene()] { return calcTorqueSplitTables(base, marine); }}};
  }
  ReportPart describe(const TableSet& tables) const override { return describeFigure(tables, kCaption); }
  std::vector<std::string> tables() const override { return {"torque_split", "gravity_share"}; }
};

}  // namespace

namespace parts {
const Part& torqueSplit() {
  static const TorqueSplitPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
