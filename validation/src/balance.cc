#include "crankcheck/validation/balance.h"

#include <algorithm>
#include <array>
#include <complex>
#include <tuple>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>

#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/validation/table.h"
#include "shaking_spectrum.h"

namespace crankcheck::validation {

BalanceResolution calcBalanceResolution(const Mechanism& m) {
  const Scales sc = calcScales(m);
  const double rule = 2 * kAgreementMultiple * kEps * sc.acceleration_conditioning;
  return {rule * sc.force, rule * sc.moment};
}

std::string findBalanceDisagreement(const analytic::ShakingHarmonic& closed, const analytic::ShakingHarmonic& dft,
                                    int n, const BalanceResolution& resolution) {
  auto differs = [](double a, double b, double tol) { return !(std::abs(a - b) <= tol); };  // NaN differs
  auto say = [&](const std::string& part, double a, double b, double tol, const char* unit) {
    return "harmonic " + std::to_string(n) + "'s " + part + " differs from the closed form by " +
           formatNumber(std::abs(a - b)) + " " + unit + ", beyond the resolution " + formatNumber(tol) + " " + unit;
  };
  static const char* const kAxis[] = {"X", "Y", "Z"};
  for (int i = 0; i < 2; ++i) {
    if (differs(closed.force_cos[i], dft.force_cos[i], resolution.force))
      return say(std::string("F_") + kAxis[i] + " cosine", closed.force_cos[i], dft.force_cos[i], resolution.force, "N");
    if (differs(closed.force_sin[i], dft.force_sin[i], resolution.force))
      return say(std::string("F_") + kAxis[i] + " sine", closed.force_sin[i], dft.force_sin[i], resolution.force, "N");
  }
  for (int i = 0; i < 3; ++i) {
    if (differs(closed.moment_cos[i], dft.moment_cos[i], resolution.moment))
      return say(std::string("M_") + kAxis[i] + " cosine", closed.moment_cos[i], dft.moment_cos[i], resolution.moment, "N m");
    if (differs(closed.moment_sin[i], dft.moment_sin[i], resolution.moment))
      return say(std::string("M_") + kAxis[i] + " sine", closed.moment_sin[i], dft.moment_sin[i], resolution.moment, "N m");
  }
  return "";
}

std::vector<BalanceRow> calcBalance(const Mechanism& m, int order, int samples, std::vector<SatOut>* sat_out) {
  if (order < 1) throw std::invalid_argument("calcBalance: order must be >= 1");
  if (samples == 0) samples = std::max(64, 4 * order);
  if (samples < 2 * order + 1) throw std::invalid_argument("calcBalance: samples must be >= 2 order + 1");
  const std::vector<analytic::ShakingHarmonic> closed = analytic::calcShakingHarmonics(m, order);

  // Each reference engine's F_s and M_s over one revolution, at phi_i = 2 pi i / N, and its harmonics by a DFT.
  std::vector<std::pair<std::string, std::vector<analytic::ShakingHarmonic>>> spectra;
  const BalanceResolution resolution = calcBalanceResolution(m);
  bool disagreed = false;
  for (const Engine* engine : listReferenceEngines()) {
    std::unique_ptr<EngineModel> model;
    try {
      model = engine->build(m);
    } catch (const std::invalid_argument& e) {
      if (!sat_out) throw std::invalid_argument("--engine " + engine->name + ": " + e.what());
      sat_out->push_back({engine->name, m.name, e.what()});
      continue;
    }
    std::vector<analytic::ShakingHarmonic> spectrum = calcShakingSpectrum(sampleShakingTurn(*model, samples), order);
    if (sat_out) {  // an engine that does not hold its accuracy on this scene sits out rather than print its rounding
      std::string disagreement;
      for (int n = 1; n <= order && disagreement.empty(); ++n)
        disagreement = findBalanceDisagreement(closed[n - 1], spectrum[n - 1], n, resolution);
      if (!disagreement.empty()) {
        sat_out->push_back({engine->name, m.name, disagreement + ": the engine does not hold its accuracy on this scene"});
        disagreed = true;
        continue;
      }
    }
    spectra.emplace_back(engine->name, std::move(spectrum));
  }
  if (spectra.empty() && sat_out && !sat_out->empty()) {
    const std::string first = "--engine " + sat_out->front().engine + ": " + sat_out->front().reason;
    if (disagreed)
      throw std::runtime_error("no exact engine confirms the closed form's harmonics: " + first);
    throw std::invalid_argument(first);
  }
  std::vector<BalanceRow> rows;
  for (int n = 1; n <= order; ++n) {
    BalanceRow row;
    row.n = n;
    row.analytic = closed[n - 1];
    for (const auto& [name, spectrum] : spectra) row.engines.emplace_back(name, spectrum[n - 1]);
    row.symmetry = analytic::findHarmonicSymmetry(m, n);
    rows.push_back(row);
  }
  return rows;
}

analytic::ShakingHarmonic withExactZeros(analytic::ShakingHarmonic h, const analytic::HarmonicSymmetry& s) {
  if (!s.decided) return h;
  if (s.force_cancels) h.force_cos = h.force_sin = Vec2{0.0, 0.0};
  for (int k = 0; k < 2; ++k)
    if (s.moment_xy_cancels) h.moment_cos[k] = h.moment_sin[k] = 0.0;
  if (s.moment_z_cancels) h.moment_cos[2] = h.moment_sin[2] = 0.0;
  return h;
}

std::vector<BalanceShaftParams> designBalanceShafts(const Mechanism& m, int n) {
  if (n < 1) throw std::invalid_argument("--design: the harmonic must be >= 1");
  Mechanism unit = m;
  if (!(unit.machine.speed > 0.0)) unit.machine.speed = 1.0;
  const double w = unit.machine.speed, r = m.crank.radius;
  const analytic::ShakingHarmonic h = analytic::calcShakingHarmonics(unit, n).back();
  const std::complex<double> c(h.force_cos[0], h.force_cos[1]), s(h.force_sin[0], h.force_sin[1]);
  const std::complex<double> forward = 0.5 * (c - std::complex<double>(0.0, 1.0) * s);
  const std::complex<double> backward = 0.5 * (c + std::complex<double>(0.0, 1.0) * s);
  double z = 0.0;
  for (int j = 0; j < m.machine.cylinders; ++j) z += getAxialPosition(m, j) / m.machine.cylinders;
  const double floor = kAgreementMultiple * kEps * calcForceScale(unit);
  std::vector<BalanceShaftParams> shafts;
  for (const auto& [part, ratio, x] : {std::tuple{forward, static_cast<double>(n), r}, std::tuple{backward, -static_cast<double>(n), -r}}) {
    if (std::abs(part) <= floor) continue;  // this turning part is rounding: no shaft for it
    BalanceShaftParams b;
    b.ratio = ratio;
    b.radius = r;
    b.mass = std::abs(part) / (r * n * n * w * w);
    b.phase = std::arg(-part);
    b.position = {x, -2.0 * r, z};
    shafts.push_back(b);
  }
  return shafts;
}

const analytic::ShakingHarmonic& BalanceRow::of(const std::string& name) const {
  for (const auto& [engine, harmonic] : engines)
    if (engine == name) return harmonic;
  throw std::out_of_range("BalanceRow: no harmonic of engine " + name);
}

}  // namespace crankcheck::validation
