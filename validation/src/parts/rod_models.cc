// Report part `rod_models` (11): what the two-mass rod costs against the rigid rod (computed in engine_loads.cc).
#include <string>
#include <vector>

#include "../campaign_tables.h"
#include "crankcheck/validation/engine_loads.h"
#include "crankcheck/validation/part.h"

namespace crankcheck::validation {
namespace {

// The figure's caption.
constexpr const char* kCaption =
    "The largest drive-torque error over the turn of the two-mass rod (m_k1 at the wrist pin, m_k3 at the crank "
    "pin) against Simbody's rigid rod, relative to the torque scale, against lambda and against Delta_I / I_G, for "
    "the car and the marine engine; dashed: the paper's two-mass rod with Delta_I, exact to rounding";

class RodModelsPart final : public Part {
 public:
  std::string key() const override { return "rod_models"; }
  int number() const override { return 11; }
  std::string title() const override { return "What the two-mass rod costs"; }
  // On the base scene's parts and the built-in marine engine.
  std::vector<Task> tasks(const PartContext& context) const override {
    return {{"rod_models", false,
             [base = context.base, marine = findMarineScene()] { return calcRodModelTables(base, marine); }}};
  }
  ReportPart describe(const TableSet& tables) const override { return describeFigure(tables, kCaption); }
  std::vector<std::string> tables() const override { return {"rod_models"}; }
};

}  // namespace

namespace parts {
const Part& rodModels() {
  static const RodModelsPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
