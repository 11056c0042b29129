// Report part `harmonics` (3): the harmonics of Q, each reference engine's DFT against the analytic prediction and the paper's table 1.
#include <cmath>
#include <complex>
#include <cstdlib>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <unsupported/Eigen/FFT>

#include "../campaign_tables.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/balance.h"
#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/validation/variants.h"

namespace crankcheck::validation {
namespace {

// ------------------------------------------------------------------------------------------------------------
// harmonics: DFT of each reference engine's Q over one turn, against the analytic prediction and the paper's claim.

TableSet calcHarmonicsTables(const Mechanism& base, Cycle cycle) {
  const int M = 64, max_order = 24;
  const std::vector<const Engine*> references = listReferenceEngines();
  std::vector<Column> columns = {{"cycle", kText}, {"k", "-"}, {"n", "-"}, {"analytic_amplitude", "N m"}, {"paper_nonzero", kText}};
  for (const Engine* e : references) columns.push_back({e->name + "_amplitude", "N m"});  // each reference's DFT
  Table t("harmonics", columns);
  for (int k = 1; k <= 12; ++k) {
    const Mechanism m = withSpeed(withGamma(withCylinders(withLambda(base, 0.4), k, cycle), 90.0), 0.0);
    const double E = calcEnergyScale(m);
    std::map<int, double> predicted;
    for (const analytic::TorqueHarmonic& h : analytic::calcGravityTorqueHarmonics(m, max_order))
      predicted[h.n] = std::hypot(h.cos_coefficient, h.sin_coefficient);
    // amplitude[engine][n - 1]: the DFT of the engine's Q(phi) at M angles (U and Q only: a gravity model suffices)
    std::vector<std::vector<double>> amplitude;
    for (const Engine* engine : references) {
      const std::unique_ptr<EngineModel> model = buildGravityModel(*engine, m);
      std::vector<double> q(M);
      for (int i = 0; i < M; ++i) q[i] = model->calcQ(2.0 * M_PI * i / M);
      std::vector<std::complex<double>> spectrum;  // X_n = sum_i q_i exp(-2 pi i n i / M): Eigen's FFT (kissfft)
      Eigen::FFT<double>().fwd(spectrum, q);
      std::vector<double>& a = amplitude.emplace_back();
      for (int n = 1; n <= max_order; ++n) a.push_back(2.0 * std::abs(spectrum[n]) / M);
    }
    for (int n = 1; n <= max_order; ++n) {
      const std::optional<bool> claim = analytic::getPaperHarmonicClaim(k, cycle, n);
      std::vector<std::string> row = {toString(cycle), std::to_string(k), std::to_string(n),
                                      formatNumber(predicted.count(n) ? predicted[n] / E : 0.0),
                                      claim ? (*claim ? "1" : "0") : ""};
      for (const std::vector<double>& a : amplitude) row.push_back(formatNumber(a[n - 1] / E));
      t.rows.push_back(row);
    }
  }
  return {{"harmonics", t}};
}

// The figure's caption: it colours the first reference engine's DFT.
std::string caption() {
  return "Harmonics of Q by a DFT of " + listReferenceEngines().front()->name +
         "'s Q(phi) (64 angles, lambda = 0.4, standing engines; every reference engine's DFT in data/harmonics.csv), with "
         "the analytic prediction (circles) and the paper's table 1 / eq (18) (crosses)";
}

class HarmonicsPart final : public Part {
 public:
  std::string key() const override { return "harmonics"; }
  std::string title() const override { return "Harmonics of Q"; }
  // One task per cycle.
  std::vector<Task> tasks(const PartContext& context) const override {
    std::vector<Task> out;
    for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke})
      out.push_back({"harmonics " + toString(cycle), false,
                     [base = context.base, cycle] { return calcHarmonicsTables(base, cycle); }});
    return out;
  }
  ReportPart describe(const TableSet& tables) const override { return describeFigure(tables, caption()); }
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
