// Report part `pin_load_polar` (12): pin loads over a working cycle as polar diagrams, of the user's scenes or the
// example scenes (computed in engine_loads.cc).
#include <string>
#include <vector>

#include "crankcheck/validation/engine_loads.h"
#include "crankcheck/validation/part.h"

namespace crankcheck::validation {
namespace {

class PinLoadPolarPart final : public Part {
 public:
  std::string key() const override { return "pin_load_polar"; }
  int number() const override { return 12; }
  std::string title() const override { return "Pin loads over a working cycle (polar diagrams)"; }
  // One task per scene, at 2 degree steps (4 with quick).
  std::vector<Task> tasks(const PartContext& context) const override {
    std::vector<Task> out;
    for (size_t i = 0; i < context.scenes.size(); ++i)
      out.push_back({"pin_load_polar " + context.scenes[i].name, false,
                     [m = context.scenes[i], i, quick = context.quick] {
                       return calcPinLoadTables({m}, static_cast<int>(i), quick ? 4.0 : 2.0);
                     }});
    return out;
  }
  ReportPart describe(const TableSet& tables) const override {
    ReportPart part;
    if (!tables.count(key())) return part;
    part.heading = heading();
    part.caption =
        "The crank-pin force of cylinder 0 (crank on rod, in the crank's own frame: x radial outward along the throw, y "
        "tangential in the direction of rotation) and the main-bearing force (frame on the crankshaft at O, all throws, "
        "frame X, Y) over one working cycle at each scene's speed with its gas and gravity, as the tip of the force "
        "vector (after Norton's Program ENGINE); analytic lines, Simbody dots";
    part.paragraphs.push_back(
        "The largest force over the cycle, each engine (the samples, the best two refined by Brent's method), and the "
        "largest difference of the two engines over the samples relative to the force scale:");
    part.header = {"scene", "engine", "force", "max |F| [N]", "max |analytic - Simbody| / force scale [-]"};
    part.rows = formatRows(tables, "pin_load_polar_summary", {"scene", "engine", "force", "max_magnitude", "max_difference_rel"},
                           {false, false, false, true, true});
    return part;
  }
  std::vector<std::string> tables() const override { return {"pin_load_polar", "pin_load_polar_summary"}; }
};

}  // namespace

namespace parts {
const Part& pinLoadPolar() {
  static const PinLoadPolarPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
