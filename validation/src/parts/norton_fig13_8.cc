// Report part `norton_fig13_8` (5): piston motion over two revolutions, exact and Norton's two-term (his figure 13-8).
#include <string>
#include <vector>

#include "../campaign_tables.h"
#include "crankcheck/validation/part.h"

namespace crankcheck::validation {
namespace {

// The figure's caption.
constexpr const char* kCaption =
    "Piston position, velocity and acceleration over two revolutions, exact and Norton's two-term (13.3c-e), for "
    "the base scene";

class NortonFigurePart final : public Part {
 public:
  std::string key() const override { return "norton_fig13_8"; }
  int number() const override { return 5; }
  std::string title() const override { return "Piston motion (after Norton fig. 13-8)"; }
  std::vector<Task> tasks(const PartContext& context) const override {
    return {{"norton_fig13_8", false, [base = context.base] { return calcNortonFigureTables(base); }}};
  }
  ReportPart describe(const TableSet& tables) const override {
    ReportPart part;
    if (!tables.count("norton_fig13_8")) return part;
    part.heading = heading();
    part.caption = kCaption;
    return part;
  }
  std::vector<std::string> tables() const override { return {"norton_fig13_8"}; }
};

}  // namespace

namespace parts {
const Part& nortonFigure() {
  static const NortonFigurePart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
