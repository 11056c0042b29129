// Report part `harmonics` (3): the harmonics of Q, Simbody's DFT against the analytic prediction and the paper's table 1.
#include <string>
#include <vector>

#include "../campaign_tables.h"
#include "crankcheck/validation/part.h"

namespace crankcheck::validation {
namespace {

// The figure's caption.
constexpr const char* kCaption =
    "Harmonics of Q by a DFT of Simbody's Q(phi) (64 angles, lambda = 0.4, standing engines), with the analytic "
    "prediction (circles) and the paper's table 1 / eq (18) (crosses)";

class HarmonicsPart final : public Part {
 public:
  std::string key() const override { return "harmonics"; }
  int number() const override { return 3; }
  std::string title() const override { return "Harmonics of Q"; }
  // One task per cycle.
  std::vector<Task> tasks(const PartContext& context) const override {
    std::vector<Task> out;
    for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke})
      out.push_back({"harmonics " + toString(cycle), false,
                     [base = context.base, cycle] { return calcHarmonicsTables(base, cycle); }});
    return out;
  }
  ReportPart describe(const TableSet& tables) const override {
    ReportPart part;
    if (!tables.count("harmonics")) return part;
    part.heading = heading();
    part.caption = kCaption;
    return part;
  }
  std::vector<std::string> tables() const override { return {"harmonics"}; }
};

}  // namespace

namespace parts {
const Part& harmonics() {
  static const HarmonicsPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
