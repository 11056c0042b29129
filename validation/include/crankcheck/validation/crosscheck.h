#pragma once
/// @file
/// The cross-check behind the verdict and the gate: the closed forms (the analytic engine) against every other
/// registered engine on one case (a scene at one lambda), every quantity at every crank angle, at the scene's speed and
/// at rest; one row per engine and quantity with the worst comparison (largest error / tolerance).

#include <string>
#include <vector>

#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/table.h"

namespace crankcheck::validation {

/// One engine's worst comparison of one quantity in one case.
struct CrossCheckRow {
  std::string family;          ///< the family of cases (a user scene's name, or a built-in family)
  std::string engine;          ///< the engine compared with the analytic one
  std::string case_name;       ///< "NAME lambda=0.3"
  double lambda = 0.0;         ///< [-] the case's crank ratio
  std::string quantity;        ///< as compareEvaluations names it
  double worst_rel_error = 0;  ///< [-] the worst comparison's error relative to the quantity's scale
  double where_phi_deg = 0;    ///< [deg] where it is
  double where_speed_rpm = 0;  ///< [rpm] at which speed (0: at rest)
  double tolerance_rel = 0;    ///< [-] its tolerance relative to the scale
  std::string pass;            ///< "pass" or "FAIL" for a gated engine; "reported" for a measured (soft) one
};

/// data/crosscheck.csv.
extern const Schema<CrossCheckRow> kCrossCheckTable;

/// Cross-checks each of `variants` (cases of one family) at `angles_deg`: one row per engine and quantity of each.
/// `measure_soft`: the engines that are measured, not gated (Engine::gated false) take part too. Variants that differ in
/// gamma alone (the gate's sweep) are checked in lockstep, each engine's model of a later variant starting its
/// assembly from the first variant's at the same angle (EngineModel::startAssemblyFrom); the rows are each variant's,
/// as if alone. @throws what an engine's build or evaluate throws.
std::vector<CrossCheckRow> crossCheckCases(const std::string& family, const std::vector<Mechanism>& variants,
                                           const std::vector<double>& angles_deg, bool measure_soft = true);

}  // namespace crankcheck::validation
