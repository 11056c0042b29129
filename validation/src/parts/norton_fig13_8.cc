// Report part `norton_fig13_8`: piston motion over two revolutions, exact and Norton's two-term (his figure 13-8).
#include <string>
#include <vector>

#include "../part_math.h"
#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/campaign_scenes.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/table.h"
#include "crankcheck/validation/task.h"
#include "crankcheck/validation/part.h"

namespace crankcheck::validation {
namespace {

// norton_fig13_8: piston motion over two revolutions, exact and two-term (Norton's figure 13-8), one row per degree.
struct NortonRow {
  double crank_angle_deg = 0.0;  ///< [deg]
  double x_exact = 0.0, x_two_term = 0.0;  ///< [m]
  double v_exact = 0.0, v_two_term = 0.0;  ///< [m/s]
  double a_exact = 0.0, a_two_term = 0.0;  ///< [m/s^2]
};
const Schema<NortonRow> kNortonTable{
    "norton_fig13_8",
    {numberField("crank_angle_deg", "deg", &NortonRow::crank_angle_deg), numberField("x_exact", "m", &NortonRow::x_exact),
     numberField("x_two_term", "m", &NortonRow::x_two_term), numberField("v_exact", "m/s", &NortonRow::v_exact),
     numberField("v_two_term", "m/s", &NortonRow::v_two_term), numberField("a_exact", "m/s^2", &NortonRow::a_exact),
     numberField("a_two_term", "m/s^2", &NortonRow::a_two_term)}};

TableSet calcNortonFigureTables(const Mechanism& base) {
  std::vector<NortonRow> rows;
  for (int d = 0; d <= 720; ++d) {
    const double theta = radiansFromDegrees(d);
    const analytic::PistonKinematics e = analytic::calcPistonKinematics(base, theta);
    const analytic::PistonKinematics n = analytic::calcPistonKinematicsNorton(base, theta);
    rows.push_back({static_cast<double>(d), e.x_p, n.x_p, e.v_p, n.v_p, e.a_p, n.a_p});
  }
  return kNortonTable.tableSet(std::move(rows));
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
  std::vector<const TableSchema*> schemas() const override { return {&kNortonTable}; }
};

}  // namespace

namespace parts {
const Part& nortonFigure() {
  static const NortonFigurePart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
