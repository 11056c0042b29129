#include "crankcheck/validation/balance.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "crankcheck/simbody_models/k_crank_model.h"

namespace crankcheck::validation {

std::vector<BalanceRow> calcBalance(const Mechanism& m, int order, int samples) {
  if (order < 1) throw std::invalid_argument("calcBalance: order must be >= 1");
  if (samples == 0) samples = std::max(64, 4 * order);
  if (samples < 2 * order + 1) throw std::invalid_argument("calcBalance: samples must be >= 2 order + 1");
  const std::vector<analytic::ShakingHarmonic> closed = analytic::calcShakingHarmonics(m, order);

  // Simbody's F_s and M_s over one revolution, at phi_i = 2 pi i / N.
  simbody_models::KCrankModel model(m);
  std::vector<Evaluation> values;
  for (int i = 0; i < samples; ++i) values.push_back(model.evaluate(2.0 * M_PI * i / samples));

  std::vector<BalanceRow> rows;
  for (int n = 1; n <= order; ++n) {
    BalanceRow row;
    row.n = n;
    row.analytic = closed[n - 1];
    row.simbody.n = n;
    for (int i = 0; i < samples; ++i) {
      // The DFT: c_n = (2 / N) sum f(phi_i) cos(n phi_i), s_n likewise (n < N / 2). n i mod N keeps the angle exact.
      const double angle = 2.0 * M_PI * static_cast<double>((static_cast<long long>(n) * i) % samples) / samples;
      const double c = 2.0 * std::cos(angle) / samples, s = 2.0 * std::sin(angle) / samples;
      const Evaluation& v = values[i];
      for (int k = 0; k < 2; ++k) {
        row.simbody.force_cos[k] += v.shaking_force[k] * c;
        row.simbody.force_sin[k] += v.shaking_force[k] * s;
      }
      for (int k = 0; k < 3; ++k) {
        row.simbody.moment_cos[k] += v.shaking_moment[k] * c;
        row.simbody.moment_sin[k] += v.shaking_moment[k] * s;
      }
    }
    row.symmetry = analytic::findHarmonicSymmetry(m, n);
    rows.push_back(row);
  }
  return rows;
}

}  // namespace crankcheck::validation
