// Report part 14 (`offset`, validation/src/parts/offset.cc): its thrust peaks, largest drive torque and thrust reversal
// come from coarse samples refined on each engine's own evaluations, so that they do not depend on the grid. Held here
// against the analytic offset engine sampled densely by the test itself (calcEvaluation, no refinement): the quick
// campaign's 2-degree samples, the coarsest the part takes, where unrefined samples miss a peak by up to 1e-3.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "crankcheck/analytic/reactions.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/validation/engine_loads.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/parts.h"
#include "crankcheck/validation/variants.h"

namespace crankcheck::validation {
namespace {

// The part's tables over its quick offsets, its tasks run as the campaign runs them.
TableSet runOffsetPart(const Mechanism& base) {
  const auto& parts = listParts();
  const auto it = std::find_if(parts.begin(), parts.end(), [](const Part* p) { return p->key() == "offset"; });
  if (it == parts.end()) throw std::logic_error("no part offset");
  PartContext context;
  context.base = base;
  context.quick = true;
  TableSet all;
  for (const Task& task : (*it)->tasks(context)) appendTables(all, task.run());
  return all;
}

// The part's engine: the base's parts as one standing four-stroke cylinder, the example gas at 6000 rpm, the pin
// offset f r (the part's description, reports/README.md "offset").
Mechanism makeOffsetEngine(const Mechanism& base, double f) {
  Mechanism m = withSpeed(withGasAtDeadCentres(withGamma(withCylinders(base, 1, Cycle::kFourStroke), 90.0),
                                               makeExampleGas(Cycle::kFourStroke, 2.0 * base.crank.radius)),
                          6000.0);
  m.engine.pin_offsets = {f * m.crank.radius};
  return m;
}

// max of g over phi [deg] in [from, to) on a grid of `step` degrees, and where.
template <class G>
std::pair<double, double> findGridMax(G g, double from, double to, double step) {
  std::pair<double, double> best{-INFINITY, from};
  for (double d = from; d < to; d += step) best = std::max(best, std::pair<double, double>{g(d), d});
  return best;
}

// The largest of g over the cycle, densely: a 0.01-degree grid, then a 1e-6-degree grid over +-0.02 degrees of its
// best point. A maximum at a corner of the pressure table (N_w is piecewise smooth) is missed by a grid by at most its
// slope times half the spacing: |g'| < 50 x max |g| per radian on these engines, so 1e-6 degrees leave 4e-7 of it.
template <class G>
double findDenseMax(G g) {
  const double coarse = findGridMax(g, -360.0, 360.0, 0.01).second;
  return findGridMax(g, coarse - 0.02, coarse + 0.02, 1e-6).first;
}

TEST(OffsetPartTest, RefinedThrustPeaksAndReversalAreTheEnginesOwn) {
  const Mechanism base = loadSceneFile(std::string(CRANKCHECK_SCENES_DIR) + "/inline4_four_stroke.toml");
  const TableSet tables = runOffsetPart(base);
  const Table& t = tables.at("offset_thrust");
  const size_t engine = columnOf(t, "engine"), offset = columnOf(t, "offset_over_r"),
               major = columnOf(t, "peak_major_thrust"), minor = columnOf(t, "peak_minor_thrust"),
               reversal = columnOf(t, "thrust_reversal_deg"), drive = columnOf(t, "max_abs_drive_torque");
  ASSERT_EQ(t.rows.size(), 5 * listComparedEngines().size());  // the quick offsets, every engine
  for (const auto& row : t.rows) {
    const double f = std::stod(row[offset]);
    SCOPED_TRACE(row[engine] + " at delta / r = " + row[offset]);
    const Mechanism m = makeOffsetEngine(base, f);
    auto wall = [&](double deg) { return analytic::calcEvaluation(m, radiansFromDegrees(deg)).cylinders[0].wall_force; };
    const double dense_major = findDenseMax(wall);
    const double dense_minor = findDenseMax([&](double d) { return -wall(d); });
    const double dense_drive =
        findDenseMax([&](double d) { return std::fabs(analytic::calcEvaluation(m, radiansFromDegrees(d)).drive_torque); });
    // 1e-6 relative: the dense grid's own bound (4e-7, above) with a margin; the engines agree with the analytic
    // offset engine to rounding (the cross-check), far below it.
    EXPECT_NEAR(std::stod(row[major]), dense_major, 1e-6 * dense_major);
    EXPECT_NEAR(std::stod(row[minor]), dense_minor, 1e-6 * dense_minor);
    EXPECT_NEAR(std::stod(row[drive]), dense_drive, 1e-6 * dense_drive);

    // The reversal: N_w changes sign there to within 1e-6 degrees, and it is the change nearest phi = 0 within 90
    // degrees on the 0.01-degree grid (none there: the cell is empty).
    double nearest = NAN;
    for (double d = -90.0; d < 90.0; d += 0.01)
      if ((wall(d) > 0.0) != (wall(d + 0.01) > 0.0) && (std::isnan(nearest) || std::fabs(d) < std::fabs(nearest)))
        nearest = d;
    if (std::isnan(nearest)) {
      EXPECT_EQ(row[reversal], "");
      continue;
    }
    ASSERT_NE(row[reversal], "");
    const double rho = std::stod(row[reversal]);
    EXPECT_GE(rho, nearest - 0.01);
    EXPECT_LE(rho, nearest + 0.02);
    const double a = wall(rho - 1e-6), b = wall(rho + 1e-6);
    EXPECT_TRUE(a == 0.0 || b == 0.0 || (a > 0.0) != (b > 0.0)) << "N_w " << a << " and " << b << " N about " << rho;
  }
}

}  // namespace
}  // namespace crankcheck::validation
