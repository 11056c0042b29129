// The exact periodic steady state of the crank train (analytic/torsion_steady.h) against what it did not produce: the
// test's own integration of the train's equations in absolute angles and time (Boost's Cash-Karp 5(4), another
// integrator and another form of the equations than the code's Dormand-Prince on deviations in s = omega t), and the
// limit of a stiff shaft, where the flywheel section carries the rigid engine's drive torque (reactions.h).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <boost/numeric/odeint.hpp>

#include "crankcheck/analytic/crank_train.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/analytic/torsion_domain.h"
#include "crankcheck/analytic/torsion_forced.h"
#include "crankcheck/analytic/torsion_steady.h"
#include "crankcheck/scene/scene_file.h"
#include "../support/crankshaft_scene.h"

namespace crankcheck::analytic {
namespace {

Mechanism loadWithCrankshaft(const std::string& scene, const std::string& crankshaft_table) {
  return testing::loadSceneWithCrankshaft(std::filesystem::path(CRANKCHECK_SCENES_DIR) / scene, crankshaft_table);
}

const char* kInline4Train =
    "throw_inertia = 2.0e-3\nfront_inertia = 4.0e-3\nstiffness = [4.0e5, 5.5e5, 5.5e5, 5.5e5, 7.0e5]\n"
    "section_damping = 1.5\nthrow_damping = 0.4\n";

// CONVENTIONS "Torsion", written out in absolute angles psi and time t: body i (front mass, then the throws), the
// flywheel at omega t; section i between body i and body i + 1 (the last: the flywheel).
struct AbsoluteEquations {
  const CrankTrain& t;
  void operator()(const std::vector<double>& y, std::vector<double>& dy, double time) const {
    const int n = t.countBodies();
    auto psi = [&](int i) { return i < n ? y[static_cast<size_t>(i)] : t.omega * time; };
    auto rate = [&](int i) { return i < n ? y[static_cast<size_t>(n + i)] : t.omega; };
    for (int i = 0; i < n; ++i) {
      double torque = 0.0, inertia = t.front_inertia;
      // The sections on either side: K (psi_b - psi_a) + C (rate_b - rate_a) on a, the opposite on b.
      torque += t.stiffness[static_cast<size_t>(i)] * (psi(i + 1) - psi(i)) +
                t.section_damping[static_cast<size_t>(i)] * (rate(i + 1) - rate(i));
      if (i > 0)
        torque -= t.stiffness[static_cast<size_t>(i - 1)] * (psi(i) - psi(i - 1)) +
                  t.section_damping[static_cast<size_t>(i - 1)] * (rate(i) - rate(i - 1));
      const int j = i - (t.has_front ? 1 : 0);
      if (j >= 0) {
        const ThrowLoads l = calcThrowLoads(t.throws[static_cast<size_t>(j)], psi(i));
        inertia = t.throw_inertia + l.J;
        torque += l.gas_torque - l.gravity_torque - 0.5 * l.dJ * rate(i) * rate(i) - t.throw_damping * (rate(i) - t.omega);
      }
      dy[static_cast<size_t>(i)] = rate(i);
      dy[static_cast<size_t>(n + i)] = torque / inertia;
    }
  }
};

// From the code's periodic state, one cycle of the test's own integration returns to it, and the twists it passes
// through give the code's peak-to-peak values. Tolerances: the return within 1e-8 of the twist scale (angles) and
// of omega times it (rates): Cash-Karp at 1e-12 over a cycle of about 1e4 steps errs by about 1e-10 of the scale,
// and the code's orbit is periodic to 1000 x its tolerance 1e-11 = 1e-8 of the scale (torsion_steady.h). The
// peak-to-peak twists within 2e-8 of the scale: what is left of a transient of 1e-8 moves each extreme by up to that,
// the peak-to-peak by up to twice it (largest difference found: 1.2e-10 of the scale; CRANKCHECK_PRINT_RATIOS=1).
// (Issue 30 promises 1e-6 of each value.)
TEST(ExactSteadyState, AnotherIntegratorReturnsToThePeriodicState) {
  for (double rpm : {2000.0, 6000.0}) {
    SCOPED_TRACE(rpm);
    Mechanism m = loadWithCrankshaft("inline4_four_stroke.toml", kInline4Train);
    m.speed_rpm = rpm;
    m.machine.speed = rpm * M_PI / 30.0;
    const CrankTrain train = makeCrankTrain(m);
    // Both entries: at 2000 rpm its own Holzer start (1e-4), at 6000 rpm the caller's converged Holzer response.
    const ExactSteadyState e = rpm < 3000.0 ? calcExactSteadyState(m) : calcExactSteadyState(m, calcHolzerResponse(m));
    const int n = train.countBodies();
    std::vector<double> y(static_cast<size_t>(2 * n));
    for (int i = 0; i < n; ++i) {
      y[static_cast<size_t>(i)] = e.x0(i);
      y[static_cast<size_t>(n + i)] = train.omega + e.x_dot0(i);
    }
    const std::vector<double> y0 = y;
    const double period = train.cycle / train.omega;
    const int samples = 2048;
    std::vector<double> times;
    for (int k = 0; k <= samples; ++k) times.push_back(period * k / samples);
    std::vector<std::vector<double>> twists(static_cast<size_t>(n));
    namespace odeint = boost::numeric::odeint;
    odeint::integrate_times(
        odeint::make_controlled(1e-12 * e.twist_scale, 1e-12, odeint::runge_kutta_cash_karp54<std::vector<double>>()),
        AbsoluteEquations{train}, y, times.begin(), times.end(), period / 4096,
        [&](const std::vector<double>& state, double time) {
          if (time > period * (1 - 0.5 / samples)) return;
          for (int i = 0; i < n; ++i) {
            const double next = i + 1 < n ? state[static_cast<size_t>(i + 1)] : train.omega * time;
            twists[static_cast<size_t>(i)].push_back(next - state[static_cast<size_t>(i)]);
          }
        });
    for (int i = 0; i < n; ++i) {
      EXPECT_NEAR(y[static_cast<size_t>(i)] - train.omega * period, y0[static_cast<size_t>(i)], 1e-8 * e.twist_scale);
      EXPECT_NEAR(y[static_cast<size_t>(n + i)], y0[static_cast<size_t>(n + i)], 1e-8 * e.twist_scale * train.omega);
      const double p2p = findSignalExtremes(calcSignalFromSamples(twists[static_cast<size_t>(i)])).peakToPeak();
      if (std::getenv("CRANKCHECK_PRINT_RATIOS"))
        std::printf("%g rpm section %d: p2p differs by %.2e of the twist scale\n", rpm, i,
                    std::fabs(p2p - e.peak_to_peak[static_cast<size_t>(i)]) / e.twist_scale);
      EXPECT_NEAR(p2p, e.peak_to_peak[static_cast<size_t>(i)], 2e-8 * e.twist_scale)
          << "section " << i;
    }
  }
}

// The error bound of a state at the report's settings (tolerance 1e-8, 2048 samples: the report's torsion part) against what it
// bounds: the distance of its peak-to-peaks from those of a state at 1e-11 (whose own error, about 1e-9 of the twist
// scale, torsion_steady.h, is below a tenth of every bound checked here), on both example scenes at their own speeds
// and the four at 7500 rpm. It must be positive and cover that distance (seen: 0.03 to 0.49 of the bound, the largest
// on the marine six, whose distance is the periodicity Newton stopped at; before the bound saw that periodicity and the
// looser run took its own steps, the marine six at 105 rpm read a bound of 0 where the distance was 2.2e-7 of the
// scale).
TEST(ExactSteadyState, ErrorBoundCoversTheDistanceToATighterState) {
  struct Case {
    const char* scene;
    double rpm;
  };
  for (const Case& c : {Case{"inline6_two_stroke_marine.toml", 105.0}, Case{"inline4_four_stroke.toml", 6000.0},
                        Case{"inline4_four_stroke.toml", 7500.0}}) {
    SCOPED_TRACE(std::string(c.scene) + " at " + std::to_string(c.rpm) + " rpm");
    Mechanism m = loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / c.scene);
    m.speed_rpm = c.rpm;
    m.machine.speed = c.rpm * M_PI / 30.0;
    SteadyStateOptions report;
    report.tolerance = 1e-8;
    report.samples = 2048;
    SteadyStateOptions tight;
    tight.tolerance = 1e-11;
    tight.samples = 2048;
    const ExactSteadyState e = calcExactSteadyState(m, report), reference = calcExactSteadyState(m, tight);
    EXPECT_GT(e.error_bound, 0.0);
    EXPECT_LE(e.residual, 1000.0 * report.tolerance);
    for (size_t i = 0; i < e.peak_to_peak.size(); ++i)
      EXPECT_LE(std::fabs(e.peak_to_peak[i] - reference.peak_to_peak[i]), e.error_bound) << "section " << i;
  }
}

// A stiff shaft: with every K scaled by f the twist falls as 1 / f, and the torque the driven flywheel puts on the
// shaft through its section, K twist + C twist' (on the last throw), tends to the drive torque that keeps the rigid
// engine at omega (reactions.h, the whole engine: Newton-Euler, not the train's equations). Order by order: the orders
// far above the shaft's natural frequencies never reach the flywheel (the throws' inertia takes them), so the
// comparison is of the orders n <= 8 (p <= 16 of the four-stroke cycle), whose difference goes as (n omega / w_1)^2,
// i.e. 1 / f: checked is a fall of at least 5-fold from f = 10 to f = 100 and below 1e-2 of the largest order at
// f = 100. The rigid torque's orders by FFT of 4096 samples (aliasing of its corners about 1e-7 of them).
TEST(ExactSteadyState, StiffShaftCarriesTheRigidEngineTorque) {
  std::vector<double> differences;
  for (double f : {10.0, 100.0}) {
    Mechanism m = loadWithCrankshaft("inline4_four_stroke.toml", kInline4Train);
    for (double& k : m.crankshaft->stiffness) k *= f;
    // The dampers by sqrt(f), so that every mode keeps its damping ratio C / (2 sqrt(K J)).
    for (double& c : m.crankshaft->section_damping) c *= std::sqrt(f);
    m.crankshaft->throw_damping *= std::sqrt(f);
    const CrankTrain train = makeCrankTrain(m);
    const ExactSteadyState e = calcExactSteadyState(m);
    differences.push_back(testing::calcFlywheelTorqueDifference(m, train, e.twists.back()));
  }
  EXPECT_LT(differences[1], differences[0] / 5);
  EXPECT_LT(differences[1], 1e-2);
}

// Holzer's model is the exact train linearized about the rigid motion with each throw's inertia frozen at its mean.
// With a constant inertia (massless rod and piston: only the crank's point masses turn) the two differ only by the
// loads' dependence on the throw's own angle (T(omega t + x) against T(omega t)), a term of order x: with the gas and
// gravity scaled by a, the twist goes as a and the relative difference between the two methods (a frequency-domain
// sum and a time-domain shooting, sharing no code but the loads) as a. Checked: it falls at least 5-fold from a = 1
// to a = 0.1, and is below 1e-2 at a = 0.1.
TEST(ExactSteadyState, ConstantInertiaAndSmallLoadsGiveHolzersResponse) {
  std::vector<double> differences;
  for (double a : {1.0, 0.1}) {
    Mechanism m = loadWithCrankshaft("inline4_four_stroke.toml", kInline4Train);
    m.piston.mass = 0.0;
    m.rod.mass = 0.0;
    m.rod.inertia_about_wrist_pin = 0.0;
    for (double& p : m.gas->pressures) p *= a;
    m.machine.gravity *= a;
    const ExactSteadyState e = calcExactSteadyState(m);
    const HolzerResponse h = calcHolzerResponse(m);
    double worst = 0.0;
    for (size_t i = 0; i < e.peak_to_peak.size(); ++i)
      worst = std::max(worst, std::fabs(e.peak_to_peak[i] / h.peak_to_peak[i] - 1.0));
    differences.push_back(worst);
  }
  if (std::getenv("CRANKCHECK_PRINT_RATIOS")) std::printf("a = 1: %.3e, a = 0.1: %.3e\n", differences[0], differences[1]);
  EXPECT_LT(differences[1], differences[0] / 5);
  EXPECT_LT(differences[1], 1e-2);
}

// The work limit (SteadyStateOptions::max_evaluations): a state that needs more evaluations of the train's equations is
// refused with one line naming the limit. 1000 is less than one cycle of the example four at 6000 rpm (about 5e4 at
// tolerance 1e-11); the default, 2e7, bounds a state to about 10 s. Before, the steady state had no work limit (every
// section at 1e-10 N m/rad ran past 500 s).
TEST(ExactSteadyState, PastMaxEvaluationsIsRefused) {
  const Mechanism m = loadWithCrankshaft("inline4_four_stroke.toml", kInline4Train);
  SteadyStateOptions options;
  options.max_evaluations = 1000;
  try {
    calcExactSteadyState(m, options);
    ADD_FAILURE() << "not refused";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("more than 1000 evaluations of the train's equations "
                                         "(SteadyStateOptions::max_evaluations)"),
              std::string::npos) << e.what();
    // The example's sections are light on damping: its stiffness is the fastest rate, and the advice is the old one.
    EXPECT_NE(std::string(e.what()).find("a shaft this stiff, or a resonance this lightly damped"), std::string::npos)
        << e.what();
  }
  // Every section at 1e18 N m s/rad: the damping's rate (C / (J omega), about 1e17 per crank radian) far past the
  // stiffness's (about 25): told so, with the keys to change ("add damping" was the advice once).
  Mechanism heavy = m;
  heavy.crankshaft->section_damping = {1e18};
  try {
    calcExactSteadyState(heavy, options);
    ADD_FAILURE() << "not refused";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("a damping this heavy against the train's inertias makes its equations too "
                                         "stiff for the analytic route (per crank radian: the stiffness's fastest rate "),
              std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("; reduce [crankshaft].section_damping or throw_damping"), std::string::npos)
        << e.what();
  }
}

// The speed-free domain (torsion_domain.h): the flywheel section carries the mean torque of every throw, its twist that
// over K. The mean here is the test's own: the trapezoidal mean of calcRigidThrowTorque over 2^16 angles of the cycle
// (not the code's quadrature of the load orders; the pressure table's corners leave it about (2 pi / 2^16)^2 = 1e-8
// relative), so a stiffness 1 % either side of K_min = |T_0| / 0.1 rad is accepted or refused, naming the section's key.
// Before, every section at 1e-20 N m/rad printed an "exact" twist of 0 (and 1e-300 a Holzer twist of nan).
TEST(ExactSteadyState, ShaftTwistedBeyondACrankshaftIsRefused) {
  Mechanism m = loadWithCrankshaft("inline4_four_stroke.toml", kInline4Train);
  const CrankTrain train = makeCrankTrain(m);
  const int N = 1 << 16;
  double mean = 0.0;
  for (const Mechanism& tm : train.throws)
    for (int k = 0; k < N; ++k) mean += calcRigidThrowTorque(tm, train.cycle * k / N, train.omega) / N;
  ASSERT_GT(std::fabs(mean), 1.0);  // [N m] the gas's mean torque: the example four delivers power
  const double K_min = std::fabs(mean) / kMaxShaftTwist;
  m.crankshaft->stiffness.back() = 1.01 * K_min;
  EXPECT_NO_THROW(checkTorsionDomain(m));
  m.crankshaft->stiffness.back() = 0.99 * K_min;
  try {
    checkTorsionDomain(m);
    ADD_FAILURE() << "not refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("[crankshaft].stiffness[4]: "), std::string::npos) << e.what();
  }
  for (double k : {1e-20, 1e-300}) {
    for (double& s : m.crankshaft->stiffness) s = k;
    EXPECT_THROW(checkTorsionDomain(m), std::invalid_argument) << k;
  }
  // Soft enough to pass the mean but not the speed: every section at 3e3 N m/rad twists the first throw's section by
  // 0.12 rad in Holzer's response at 6000 rpm (the test reads it off Holzer's twist signals): the steady state refuses
  // it (std::runtime_error: a valid scene the analysis does not compute) before any integration.
  for (double& s : m.crankshaft->stiffness) s = 3e3;
  EXPECT_NO_THROW(checkTorsionDomain(m));
  const HolzerResponse h = calcHolzerResponse(m);
  double largest = 0.0;
  for (const PeriodicSignal& twist : h.twists) {
    const SignalExtremes e = findSignalExtremes(twist);
    largest = std::max({largest, std::fabs(e.min), std::fabs(e.max)});
  }
  ASSERT_GT(largest, kMaxShaftTwist);
  EXPECT_THROW(calcExactSteadyState(m, h), std::runtime_error);
}

}  // namespace
}  // namespace crankcheck::analytic

namespace crankcheck::analytic {
namespace {

// Between the explicit route's reach and the stiff limit's accuracy (3e4 x the example four's stiffness), the stiff
// limit's result was returned with a bound it exceeded: its flywheel twist 13 % above the explicit route's (its bound,
// from the correction's first-order estimate, 11 %). Now it is returned only where its bound is within 1e-2 of the
// largest twist; else the explicit route computes (about 25 s here, outside this test) or, past its work limit (made
// small here), the state is refused naming both routes.
TEST(ExactSteadyState, AStiffLimitWithoutItsAccuracyIsNotReturned) {
  Mechanism m = loadWithCrankshaft("inline4_four_stroke.toml", kInline4Train);
  for (double& k : m.crankshaft->stiffness) k *= 3e4;
  const HolzerResponse h = calcHolzerResponse(m);
  ASSERT_TRUE(h.stiff_limit);
  SteadyStateOptions options;
  options.max_evaluations = 100'000;
  try {
    calcExactSteadyState(m, h, options);
    ADD_FAILURE() << "the stiff limit's inaccurate state was returned";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("the stiff limit's bound is"), std::string::npos) << e.what();
  }
}

// Shafts 1e6, 1e9 and 1e12 times as stiff as the example four's (1e12: 7e17 N m/rad, within the scene format's 1e18):
// both routes take the stiff limit (torsion_forced.h, torsion_steady.h) and compute, where before Holzer's sum was
// refused ("did not converge"). Against what they did not produce: the flywheel section's torque K twist + i w C twist
// tends to the rigid engine's drive torque (reactions.h, Newton-Euler on the whole engine), order by order for
// n <= 8 (p <= 16); the difference is the throws' inertia and damping on the twist, (n omega)^2 J / K <= 4e-7 of it at
// 1e6 (n omega = 5e3 rad/s, J about 1e-2 kg m^2, K 7e11), and the rigid torque's FFT of 4096 samples carries about
// 1e-6 of its orders (its corners' aliasing; found 1.0e-6 at 1e6, 9e-7 at 1e9 and 1e12: that floor): checked below
// 1e-5 of the largest order. And the exact
// steady state's peak-to-peaks lie within its error bound plus Holzer's stiff_bound of Holzer's (the two differ by the
// throws' varying inertia, a (n omega)^2 J / K effect, and the ringing both bound), the twist falling as 1 / K.
TEST(ExactSteadyState, VeryStiffShaftsComputeAndTendToTheRigidDriveTorque) {
  double last_p2p = 0.0;
  for (double f : {1e6, 1e9, 1e12}) {
    SCOPED_TRACE(f);
    Mechanism m = loadWithCrankshaft("inline4_four_stroke.toml", kInline4Train);
    for (double& k : m.crankshaft->stiffness) k *= f;
    const CrankTrain train = makeCrankTrain(m);
    const HolzerResponse h = calcHolzerResponse(m);
    ASSERT_TRUE(h.stiff_limit);
    const ExactSteadyState e = calcExactSteadyState(m, h);
    for (const std::vector<PeriodicSignal>* twists : {&h.twists, &e.twists}) {
      const double difference = testing::calcFlywheelTorqueDifference(m, train, twists->back());
      if (std::getenv("CRANKCHECK_PRINT_RATIOS")) std::printf("f %g: %.3e\n", f, difference);
      EXPECT_LT(difference, 1e-5);
    }
    for (size_t i = 0; i < e.peak_to_peak.size(); ++i)
      EXPECT_LE(std::fabs(e.peak_to_peak[i] - h.peak_to_peak[i]), e.error_bound + h.stiff_bound) << "section " << i;
    const double p2p = *std::max_element(e.peak_to_peak.begin(), e.peak_to_peak.end());
    // The twist falls as 1 / K: from one stiffness to the next (x 1e3) the largest peak-to-peak x 1e3 is the last one
    // to within what the last state promises, its error bound (the ringing after the pressure table's corners: 1.4e-3
    // of its twist at 1e6 x, 1.5e-6 at 1e12 x), not more: 1e-3 of it, below that bound; the next order of the stiff
    // limit, (n w)^2 J / K, is 2e-6 at 1e6 x.
    if (last_p2p > 0.0) EXPECT_NEAR(p2p * 1e3, last_p2p, 1e-3 * last_p2p);
    last_p2p = p2p;
  }
}

// estimateExactSteadyStateWork against the work it estimates, in evaluations of the train's equations (counted, not
// timed): never below it, so that the work limit errs towards refusing early rather than running past it, and within
// 6 x of it. kShootingCycles (8) takes the probe's evaluations per cycle eight times; the computations measured here
// took 2.2 to 5.2 of the probe's cycles (the example four, its throw damping at 1e3 and 1e4 N m s/rad, the marine six).
// The stiff limit, where it answers, is the route estimated, its count its own. A damping of 1e18 N m s/rad is
// estimated past the 1e8 evaluations at which calcExactSteadyState refuses (after about a minute): an estimate that
// sees the refusal coming, from a probe of at most 2e5 evaluations.

TEST(SteadyStateWork, TheProbesEstimateIsAboveTheWorkAndWithinSixTimesIt) {
  std::vector<std::pair<std::string, Mechanism>> cases;
  cases.emplace_back("four", loadWithCrankshaft("inline4_four_stroke.toml", kInline4Train));
  for (double c : {1e3, 1e4}) {
    Mechanism m = cases.front().second;
    m.crankshaft->throw_damping = c;
    cases.emplace_back("four, throw damping " + std::to_string(c), m);
  }
  cases.emplace_back("marine six", loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) /
                                                 "inline6_two_stroke_marine.toml"));
  for (const auto& [name, m] : cases) {
    SCOPED_TRACE(name);
    const HolzerResponse h = calcHolzerResponse(m);
    const SteadyStateWork work = estimateExactSteadyStateWork(m, h);
    const ExactSteadyState e = calcExactSteadyState(m, h);
    EXPECT_FALSE(work.stiff_limit);
    const double ratio = work.evaluations / static_cast<double>(e.evaluations);
    if (std::getenv("CRANKCHECK_PRINT_RATIOS")) std::printf("%s: estimate / work %.2f\n", name.c_str(), ratio);
    EXPECT_GE(ratio, 1.0);
    EXPECT_LE(ratio, 6.0);
  }
  Mechanism stiff = cases.front().second;
  for (double& k : stiff.crankshaft->stiffness) k *= 1e6;
  const HolzerResponse hs = calcHolzerResponse(stiff);
  const SteadyStateWork stiff_work = estimateExactSteadyStateWork(stiff, hs);
  EXPECT_TRUE(stiff_work.stiff_limit);
  EXPECT_EQ(stiff_work.evaluations, static_cast<double>(calcExactSteadyState(stiff, hs).evaluations));

  Mechanism heavy = cases.front().second;
  heavy.crankshaft->throw_damping = 1e18;
  const SteadyStateWork heavy_work = estimateExactSteadyStateWork(heavy, calcHolzerResponse(heavy));
  EXPECT_GT(heavy_work.evaluations, static_cast<double>(SteadyStateOptions{}.max_evaluations));
}

}  // namespace
}  // namespace crankcheck::analytic
