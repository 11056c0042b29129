// Report part `offset` (validation/src/parts/offset.cc): its thrust peaks, largest drive torque and thrust reversal
// come from coarse samples refined on each engine's own evaluations, so that they do not depend on the grid. Held here
// against the analytic offset engine sampled densely by the test itself (calcEvaluation, no refinement): the quick
// campaign's 2-degree samples, the coarsest the part takes, where unrefined samples miss a peak by up to 1e-3.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <variant>
#include <vector>

#include "crankcheck/analytic/reactions.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/validation/example_gas.h"
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
  m.machine.pin_offsets = {f * m.crank.radius};
  return m;
}

// The largest of g over phi [deg] in [from, to) on a grid of `step` degrees: where, the value, and the largest change
// between neighbouring points of the grid.
struct GridMax {
  double at = 0.0, value = -INFINITY, change = 0.0;
};
template <class G>
GridMax findGridMax(G g, double from, double to, double step) {
  GridMax best;
  double previous = g(from);
  for (int i = 0; from + i * step < to; ++i) {
    const double d = from + i * step, value = g(d);
    if (value > best.value) best = {d, value, best.change};
    best.change = std::max(best.change, std::fabs(value - previous));
    previous = value;
  }
  return best;
}

// The largest of g over the cycle, by the test's own grids: 0.01 degrees, then 1e-6 degrees over +-0.02 degrees of the
// best point. The true maximum lies within a cell of the fine grid's best point, so it is above that point by less than
// the largest change between neighbours there (`change`), whether the maximum is smooth or at a corner of the pressure
// table.
template <class G>
GridMax findDenseMax(G g) {
  const double coarse = findGridMax(g, -360.0, 360.0, 0.01).at;
  return findGridMax(g, coarse - 0.02, coarse + 0.02, 1e-6);
}

TEST(OffsetPartTest, RefinedThrustPeaksAndReversalAreTheEnginesOwn) {
  const Mechanism base = loadSceneFile(std::string(CRANKCHECK_SCENES_DIR) + "/inline4_four_stroke.toml");
  const TableSet tables = runOffsetPart(base);
  const Table& t = tables.at("offset_thrust");
  const size_t engine = columnOf(t, "engine"), offset = columnOf(t, "offset_over_r"),
               major = columnOf(t, "peak_major_thrust"), minor = columnOf(t, "peak_minor_thrust"),
               reversal = columnOf(t, "thrust_reversal_deg"), drive = columnOf(t, "max_abs_drive_torque");
  ASSERT_EQ(t.size(), 5 * listComparedEngines().size());  // the quick offsets, every engine
  for (size_t i = 0; i < t.size(); ++i) {
    const double f = std::get<double>(t.cell(i, offset));
    SCOPED_TRACE(std::get<std::string>(t.cell(i, engine)) + " at delta / r = " + formatNumber(f));
    const Mechanism m = makeOffsetEngine(base, f);
    auto wall = [&](double deg) { return analytic::calcEvaluation(m, radiansFromDegrees(deg)).cylinders[0].wall_force; };
    // The part's refined value (Brent's method to 1e-10 rad, on the engine's own evaluations) against the test's grid:
    // at most the grid's last change above it, and below it by rounding alone: 64 eps of the value (each engine agrees
    // with the analytic offset engine to 2e-15 of the force scale, offset.csv).
    auto expectRefined = [](const Cell& cell, const GridMax& dense, const char* what) {
      const double refined = std::get<double>(cell), rounding = 64.0 * std::numeric_limits<double>::epsilon() * dense.value;
      EXPECT_GE(refined, dense.value - rounding) << what;
      EXPECT_LE(refined, dense.value + dense.change + rounding) << what << " (grid change " << dense.change << ")";
    };
    expectRefined(t.cell(i, major), findDenseMax(wall), "major thrust");
    expectRefined(t.cell(i, minor), findDenseMax([&](double d) { return -wall(d); }), "minor thrust");
    expectRefined(t.cell(i, drive),
                  findDenseMax([&](double d) { return std::fabs(analytic::calcEvaluation(m, radiansFromDegrees(d)).drive_torque); }),
                  "drive torque");

    // The reversal: N_w changes sign there to within 1e-6 degrees, and it is the change nearest phi = 0 within 90
    // degrees on the 0.01-degree grid (none there: the cell is empty).
    double nearest = NAN;
    for (double d = -90.0; d < 90.0; d += 0.01)
      if ((wall(d) > 0.0) != (wall(d + 0.01) > 0.0) && (std::isnan(nearest) || std::fabs(d) < std::fabs(nearest)))
        nearest = d;
    const Cell rho_cell = t.cell(i, reversal);
    if (std::isnan(nearest)) {
      EXPECT_TRUE(std::holds_alternative<std::monostate>(rho_cell));
      continue;
    }
    ASSERT_TRUE(std::holds_alternative<double>(rho_cell));
    const double rho = std::get<double>(rho_cell);
    EXPECT_GE(rho, nearest - 0.01);
    EXPECT_LE(rho, nearest + 0.02);
    const double a = wall(rho - 1e-6), b = wall(rho + 1e-6);
    EXPECT_TRUE(a == 0.0 || b == 0.0 || (a > 0.0) != (b > 0.0)) << "N_w " << a << " and " << b << " N about " << rho;
  }
}

}  // namespace
}  // namespace crankcheck::validation
