// Report part `norton_fig13_8` (5): piston motion over two revolutions, exact and Norton's two-term (his figure 13-8).
#include <string>
#include <vector>

#include "../campaign_tables.h"
#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/part.h"

namespace crankcheck::validation {
namespace {

// ------------------------------------------------------------------------------------------------------------
// norton_fig13_8: piston motion over two revolutions, exact and two-term (Norton's figure 13-8).

TableSet calcNortonFigureTables(const Mechanism& base) {
  Table t("norton_fig13_8", {{"crank_angle_deg", "deg"}, {"x_exact", "m"}, {"x_two_term", "m"}, {"v_exact", "m/s"},
                             {"v_two_term", "m/s"}, {"a_exact", "m/s^2"}, {"a_two_term", "m/s^2"}});
  for (int d = 0; d <= 720; ++d) {
    const double theta = radiansFromDegrees(d);
    const analytic::PistonKinematics e = analytic::calcPistonKinematics(base, theta);
    const analytic::PistonKinematics n = analytic::calcPistonKinematicsNorton(base, theta);
    t.rows.push_back({std::to_string(d), formatNumber(e.x_p), formatNumber(n.x_p), formatNumber(e.v_p), formatNumber(n.v_p), formatNumber(e.a_p), formatNumber(n.a_p)});
  }
  return {{"norton_fig13_8", t}};
}

// The figure's caption.
constexpr const char* kCaption =
    "Piston position, velocity and acceleration over two revolutions, exact and Norton's two-term (13.3c-e), for "
    "the base scene";

class NortonFigurePart final : public Part {
 public:
  std::string key() const override { return "norton_fig13_8"; }
  std::string title() const override { return "Piston motion (after Norton fig. 13-8)"; }
  std::vector<Task> tasks(const PartContext& context) const override {
    return {{"norton_fig13_8", false, [base = context.base] { return calcNortonFigureTables(base); }}};
  }
  ReportPart describe(const TableSet& tables) const override { return describeFigure(tables, kCaption); }
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
