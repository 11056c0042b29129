// The Box2D stepped engine's free run ("box2d" run_free, box2d_models/free_run.h) against the exact free run of
// crankcheck::analytic (analytic/motion.h: phi_dot(phi) from the energy integral, released at phi = 0 with the start's
// speed; its time t(phi) = integral of dphi / phi_dot by Gauss-Legendre quadrature here, inverted by Newton): the
// phase error and its order in dt, the instant of omega, and the refusal of a scene without flywheel.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "crankcheck/analytic/motion.h"
#include "crankcheck/box2d_models/stepped_engine.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/run_measures.h"
#include "stepped_engine_support.h"

namespace crankcheck::box2d_models {
namespace {

using crankcheck::testing::findStepped;
using crankcheck::testing::loadSteppedExample;

constexpr double kTwoPi = 2.0 * std::numbers::pi;

const SteppedEngine& box2d() {
  static const std::vector<SteppedEngine> engines = describeSteppedEngines();
  return findStepped(engines, "box2d");
}

StartState exactStart(const Mechanism& m) {
  return calcStartState(m, validation::getClosedFormEngine().build(m)->evaluate(0.0));
}

/// The exact free run released at phi = 0 with omega0: phi_dot(phi) (analytic::calcFreeRunSpeed), t(phi) by 8-point
/// Gauss-Legendre on 256 panels a turn (the integrand smooth: its error far below the engine's float phase), phi(t)
/// by Newton's method on t(phi) = t.
class ExactFreeRun {
 public:
  ExactFreeRun(const Mechanism& m, double omega0) : m_(m), omega0_(omega0) {
    panel_times_.push_back(0.0);
    for (int p = 0; p < kPanels * kTurns; ++p)
      panel_times_.push_back(panel_times_.back() + integrate(p * kPanel, (p + 1) * kPanel));
  }
  double speed(double phi) const { return analytic::calcFreeRunSpeed(m_, omega0_, phi); }
  /// [rad/s^2] d phi_dot / dt = phi_dot d phi_dot / d phi (a central difference, relative step 1e-5).
  double acceleration(double phi) const {
    const double h = 1e-5;
    return speed(phi) * (speed(phi + h) - speed(phi - h)) / (2.0 * h);
  }
  double time(double phi) const {
    const int p = std::clamp(static_cast<int>(std::floor(phi / kPanel)), 0, kPanels * kTurns - 1);
    return panel_times_[static_cast<size_t>(p)] + integrate(p * kPanel, phi);
  }
  double phi(double t) const {
    double phi = omega0_ * t;
    for (int i = 0; i < 50; ++i) {
      const double step = (t - time(phi)) * speed(phi);
      phi += step;
      if (std::fabs(step) < 1e-15 * (1.0 + std::fabs(phi))) break;
    }
    return phi;
  }

 private:
  static constexpr int kPanels = 256, kTurns = 4;
  static constexpr double kPanel = kTwoPi / kPanels;
  double integrate(double a, double b) const {
    static constexpr std::array<double, 4> x{0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                             0.9602898564975363};
    static constexpr std::array<double, 4> w{0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                             0.1012285362903763};
    const double c = 0.5 * (a + b), h = 0.5 * (b - a);
    double sum = 0.0;
    for (size_t i = 0; i < x.size(); ++i) sum += w[i] * (1.0 / speed(c - h * x[i]) + 1.0 / speed(c + h * x[i]));
    return h * sum;
  }
  const Mechanism& m_;
  double omega0_;
  std::vector<double> panel_times_;
};

SteppedFreeRun runFree(const Mechanism& m, double dt, double seconds, const std::string& settings = "defaults") {
  SteppedFreeRunOptions o;
  o.dt = dt;
  o.steps = static_cast<long>(std::ceil(seconds / dt)) + 1;
  o.settings = settings;
  o.start = exactStart(m);
  return box2d().run_free(m, o);
}

/// [rad] phi_run - phi_exact at the run's sample nearest the exact run's time of `turns` revolutions.
double phaseErrorAfter(const ExactFreeRun& exact, const SteppedFreeRun& run, double dt, double turns) {
  const size_t i = static_cast<size_t>(std::lround(exact.time(turns * kTwoPi) / dt)) - 1;
  return run.phi.at(i) - exact.phi(run.time.at(i));
}

TEST(Box2dFreeRunTest, Measure) {
  for (const char* scene : {"single_cylinder.toml", "inline4_four_stroke.toml"}) {
    const Mechanism m = loadSteppedExample(scene, true);
    const ExactFreeRun exact(m, m.machine.speed);
    const double two = exact.time(2.0 * kTwoPi);
    std::printf("%s: two turns %.6f s, speed %.3f accel(0) %.4g\n", scene, two, m.machine.speed, exact.acceleration(0.0));
    for (const char* settings : {"defaults", "tightened"})
      for (double dt : {1e-3, 1e-4, 1e-5}) {
        const SteppedFreeRun run = runFree(m, dt, two * 1.01, settings);
        double mid = 0.0, end = 0.0, lag = 0.0, start = 0.0;
        for (size_t i = 1; i < run.phi.size(); ++i) {
          const double w = run.omega[i];
          mid = std::max(mid, std::fabs(w - exact.speed(0.5 * (run.phi[i - 1] + run.phi[i]))));
          end = std::max(end, std::fabs(w - exact.speed(run.phi[i])));
          start = std::max(start, std::fabs(w - exact.speed(run.phi[i - 1])));
          lag = std::max(lag, 0.5 * dt * std::fabs(exact.acceleration(run.phi[i])));
        }
        double stepdiff = 0.0;
        for (size_t i = 1; i < run.phi.size(); ++i)
          stepdiff = std::max(stepdiff, std::fabs(run.phi[i] - run.phi[i - 1] - dt * run.omega[i]));
        std::printf("  %s dt %g: phase1 %.3e phase2 %.3e | omega err mid %.3e end %.3e start %.3e lag %.3e | "
                    "max|dphi - dt w| %.3e | %.3g us/step\n",
                    settings, dt, phaseErrorAfter(exact, run, dt, 1.0), phaseErrorAfter(exact, run, dt, 2.0), mid, end,
                    start, lag, stepdiff, run.seconds_per_step * 1e6);
      }
  }
}

}  // namespace
}  // namespace crankcheck::box2d_models
