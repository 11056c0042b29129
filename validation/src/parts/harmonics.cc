// Report part `harmonics`: the harmonics of Q, each reference engine's DFT against the analytic prediction and the paper's table 1.
#include <cmath>
#include <complex>
#include <cstdlib>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <unsupported/Eigen/FFT>

#include "../part_math.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/balance.h"
#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/campaign_scenes.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/table.h"
#include "crankcheck/validation/task.h"
#include "crankcheck/validation/part.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/validation/variants.h"
#include "engine_fields.h"

namespace crankcheck::validation {
namespace {

// harmonics: per cycle, k and order n, the amplitude of Q's harmonic n relative to the energy scale: the analytic
// prediction, whether the paper's table 1 / eq (18) says it is nonzero (empty where the paper says nothing), and each
// reference engine's DFT, a column per engine in the registry's order.
struct HarmonicsRow {
  std::string cycle;
  int k = 1, n = 1;
  double analytic_amplitude = 0.0;           ///< [N m] / energy scale
  std::optional<bool> paper_nonzero;         ///< written "1", "0" or empty
  std::vector<double> engine_amplitudes;     ///< [N m] / energy scale, per reference engine (listReferenceEngines)
};

// The paper's claim as the text column "paper_nonzero": "1", "0", or empty.
Field<HarmonicsRow> paperClaimField() {
  return {Column("paper_nonzero", kText),
          [](const HarmonicsRow& r) { return Cell(r.paper_nonzero ? std::string(*r.paper_nonzero ? "1" : "0") : ""); },
          [](HarmonicsRow& r, Cell c) {
            const std::string text = std::get<std::string>(std::move(c));
            if (text.empty()) r.paper_nonzero = std::nullopt;
            else r.paper_nonzero = text != "0";
          }};
}

std::vector<Field<HarmonicsRow>> makeHarmonicsFields() {
  std::vector<Field<HarmonicsRow>> fields = {
      textField("cycle", &HarmonicsRow::cycle), countField("k", &HarmonicsRow::k), countField("n", &HarmonicsRow::n),
      numberField("analytic_amplitude", "N m", &HarmonicsRow::analytic_amplitude), paperClaimField()};
  addEngineNumberFields(fields, "_amplitude", "N m", &HarmonicsRow::engine_amplitudes);  // each reference's DFT
  return fields;
}

// The table's schema: its columns depend on the engines in play (engine_fields.h).
const Schema<HarmonicsRow>& getHarmonicsTable() { return getEngineSchema<HarmonicsRow, makeHarmonicsFields>("harmonics"); }

TableSet calcHarmonicsTables(const Mechanism& base, Cycle cycle) {
  const int M = 64, max_order = 24;
  const std::vector<const Engine*> references = listReferenceEngines();
  std::vector<HarmonicsRow> rows;
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
      HarmonicsRow row{toString(cycle), k, n, predicted.count(n) ? predicted[n] / E : 0.0,
                       analytic::getPaperHarmonicClaim(k, cycle, n), {}};
      for (const std::vector<double>& a : amplitude) row.engine_amplitudes.push_back(a[n - 1] / E);
      rows.push_back(std::move(row));
    }
  }
  return getHarmonicsTable().tableSet(std::move(rows));
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
  std::vector<const TableSchema*> schemas() const override { return {&getHarmonicsTable()}; }
};

}  // namespace

namespace parts {
const Part& harmonics() {
  static const HarmonicsPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
