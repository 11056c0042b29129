// Report part `speed_vs_error` (2): cost per evaluation of Q against its error, every method timed in one run on this
// machine (computed in campaign.cc).
#include <string>
#include <vector>

#include "../campaign_tables.h"
#include "crankcheck/validation/part.h"

namespace crankcheck::validation {
namespace {

class SpeedVsErrorPart final : public Part {
 public:
  std::string key() const override { return "speed_vs_error"; }
  int number() const override { return 2; }
  std::string title() const override { return "Speed against error"; }
  // One task that times: it runs alone (Task::measures_time).
  std::vector<Task> tasks(const PartContext& context) const override {
    return {{"speed_vs_error", true, [base = context.base, quick = context.quick] { return calcSpeedVsErrorTables(base, quick); }}};
  }
  ReportPart describe(const TableSet& tables) const override {
    ReportPart part;
    if (!tables.count(key())) return part;
    part.heading = heading();
    part.blocks.push_back({ReportBlock::kFigure,
                           "Cost per evaluation of Q against its error, all measured in one run on this machine: the "
                           "exact closed form, Fourier orders, the printed eq (15), Simbody at several projection "
                           "tolerances; the Pareto front joined",
                           {}, {}, key()});
    part.blocks.push_back({ReportBlock::kTable, "", {"method", "time per evaluation [ns]", "max error / energy scale [-]", "resolved"},
                           formatRows(tables, key(), {"method", "ns_per_eval", "max_rel_error", "resolved"}, {false, true, true, false})});
    part.blocks.push_back({ReportBlock::kParagraph,
                           "Each error is the maximum over the turn (the Fourier series' from the exact harmonics they "
                           "leave out, the others refined from 72 samples by Brent's method). resolved = 0: the error is "
                           "at rounding level (below 100 x 64 eps of the energy scale), the number is a bound, not a "
                           "measured maximum."});
    return part;
  }
  std::vector<std::string> tables() const override { return {"speed_vs_error"}; }
};

}  // namespace

namespace parts {
const Part& speedVsError() {
  static const SpeedVsErrorPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
