// Report part `integrator_pareto` (7): Simbody's integrators, cost against error in the free run. Needs the base
// scene's flywheel: without one the part is left out (campaign.cc's notes say so).
#include <string>
#include <vector>

#include "../campaign_tables.h"
#include "crankcheck/validation/part.h"

namespace crankcheck::validation {
namespace {

class IntegratorParetoPart final : public Part {
 public:
  std::string key() const override { return "integrator_pareto"; }
  int number() const override { return 7; }
  std::string title() const override { return "Simbody's integrators"; }
  // One task that times: it runs alone (Task::measures_time); none without the base scene's flywheel.
  std::vector<Task> tasks(const PartContext& context) const override {
    if (!context.base.flywheel_inertia) return {};
    return {{"integrator_pareto", true,
             [base = context.base, quick = context.quick] { return calcIntegratorParetoTables(base, quick); }}};
  }
  ReportPart describe(const TableSet& tables) const override {
    ReportPart part;
    if (!tables.count(key())) return part;
    part.heading = heading();
    part.caption =
        "Simbody's free run by RungeKuttaMerson, CPodes and SemiExplicitEuler2 at accuracies 1e-3 to 1e-10: cost per "
        "simulated revolution (one Google Benchmark run) against the relative error of delta and the energy drift per "
        "revolution, the analytic energy integral as reference";
    part.header = {"integrator", "accuracy [-]", "time per revolution [ns]", "delta error [-]", "energy drift [-]", "status"};
    part.rows = formatRows(tables, key(), {"integrator", "accuracy", "ns_per_revolution", "delta_error", "energy_drift", "status"},
                           {false, true, true, true, true, false});
    return part;
  }
  std::vector<std::string> tables() const override { return {"integrator_pareto"}; }
};

}  // namespace

namespace parts {
const Part& integratorPareto() {
  static const IntegratorParetoPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
