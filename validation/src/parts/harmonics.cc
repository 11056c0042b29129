// Report part `harmonics` (3): the harmonics of Q, Simbody's DFT against the analytic prediction and the paper's table 1.
#include <cmath>
#include <complex>
#include <cstdlib>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "../campaign_tables.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/simbody_models/free_run.h"
#include "crankcheck/simbody_models/k_crank_gravity_model.h"
#include "crankcheck/simbody_models/k_crank_model.h"
#include "crankcheck/validation/balance.h"
#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/validation/variants.h"

namespace crankcheck::validation {
namespace {

// ------------------------------------------------------------------------------------------------------------
// harmonics: DFT of Simbody's Q over one turn, against the analytic prediction and the paper's claim.

TableSet calcHarmonicsTables(const Mechanism& base, Cycle cycle) {
  const int M = 64, max_order = 24;
  Table t("harmonics", {{"cycle", kText}, {"k", "-"}, {"n", "-"}, {"simbody_amplitude", "N m"},
                        {"analytic_amplitude", "N m"}, {"paper_nonzero", kText}});
  for (int k = 1; k <= 12; ++k) {
    const Mechanism m = withSpeed(withGamma(withCylinders(withLambda(base, 0.4), k, cycle), 90.0), 0.0);
    const double E = calcEnergyScale(m);
    simbody_models::KCrankGravityModel model(m);  // U and Q only: the reduced model suffices
    std::vector<double> q(M);
    for (int i = 0; i < M; ++i) q[i] = model.calcHoldingTorque(2.0 * M_PI * i / M);
    std::map<int, double> predicted;
    for (const analytic::TorqueHarmonic& h : analytic::calcGravityTorqueHarmonics(m, max_order))
      predicted[h.n] = std::hypot(h.cos_coefficient, h.sin_coefficient);
    for (int n = 1; n <= max_order; ++n) {
      std::complex<double> sum = 0.0;
      for (int i = 0; i < M; ++i) sum += q[i] * std::polar(1.0, -2.0 * M_PI * n * i / M);
      const double amplitude = 2.0 * std::abs(sum) / M;
      const std::optional<bool> claim = analytic::getPaperHarmonicClaim(k, cycle, n);
      t.rows.push_back({toString(cycle), std::to_string(k), std::to_string(n), formatNumber(amplitude / E),
                        formatNumber(predicted.count(n) ? predicted[n] / E : 0.0), claim ? (*claim ? "1" : "0") : ""});
    }
  }
  return {{"harmonics", t}};
}

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
  ReportPart describe(const TableSet& tables) const override { return describeFigure(tables, kCaption); }
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
