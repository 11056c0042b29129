#include "shaking_spectrum.h"

#include <complex>
#include <stdexcept>

#include <unsupported/Eigen/FFT>

namespace crankcheck::validation {

ShakingTurn sampleShakingTurn(EngineModel& model, int samples) {
  if (samples < 1) throw std::invalid_argument("sampleShakingTurn: samples must be >= 1");
  ShakingTurn turn;
  turn.force.reserve(samples);
  turn.moment.reserve(samples);
  for (int i = 0; i < samples; ++i) {
    const Evaluation e = model.evaluateMotion(2.0 * M_PI * i / samples);  // shaking alone
    turn.force.push_back(e.shaking_force);
    turn.moment.push_back(e.shaking_moment);
  }
  return turn;
}

std::vector<analytic::ShakingHarmonic> calcShakingSpectrum(const ShakingTurn& turn, int order) {
  const int samples = static_cast<int>(turn.force.size());
  if (order < 1) throw std::invalid_argument("calcShakingSpectrum: order must be >= 1");
  if (samples < 2 * order + 1 || turn.moment.size() != turn.force.size())
    throw std::invalid_argument("calcShakingSpectrum: samples must be >= 2 order + 1");
  // The spectrum of the 5 signals (F_s X, Y; M_s X, Y, Z).
  constexpr int kSignals = 5;
  std::array<std::vector<std::complex<double>>, kSignals> spectrum;
  Eigen::FFT<double> fft;
  std::vector<double> signal(samples);
  for (int k = 0; k < kSignals; ++k) {
    for (int i = 0; i < samples; ++i) signal[i] = k < 2 ? turn.force[i][k] : turn.moment[i][k - 2];
    fft.fwd(spectrum[k], signal);
  }
  const double to_coefficient = 2.0 / samples;
  std::vector<analytic::ShakingHarmonic> out;
  for (int n = 1; n <= order; ++n) {
    analytic::ShakingHarmonic h;
    h.n = n;
    for (int k = 0; k < 2; ++k) {
      h.force_cos[k] = to_coefficient * spectrum[k][n].real();
      h.force_sin[k] = -to_coefficient * spectrum[k][n].imag();
    }
    for (int k = 0; k < 3; ++k) {
      h.moment_cos[k] = to_coefficient * spectrum[k + 2][n].real();
      h.moment_sin[k] = -to_coefficient * spectrum[k + 2][n].imag();
    }
    out.push_back(h);
  }
  return out;
}

}  // namespace crankcheck::validation
