// The engines' own free runs through the measures of a time-stepped run (engine_runs.h): Simbody's Runge-Kutta-Merson
// at a tight accuracy against the exact free run (bounds from its accuracy), MuJoCo's soft ways losing energy, where
// MuJoCo's velocities stand (against its own Runge-Kutta run at a tenth of the step), the reading of a run's samples,
// the default runs and the refusals. Scenes: the inline four (the report's scene) and hand-made runs, without [gas].

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "crankcheck/scene/scene_file.h"
#include "crankcheck/validation/engine_runs.h"
#include "crankcheck/validation/engines.h"
#include "../support/test_numbers.h"

namespace crankcheck::validation {
namespace {

using testing::kEps;

Mechanism loadWithoutGas(const char* stem) {
  Mechanism m = loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / (std::string(stem) + ".toml"));
  m.gas.reset();  // the free run under gravity alone
  return m;
}

// Simbody's RKM at 1e-10 and MuJoCo's soft ways at their default step (RK4), five revolutions of the inline four at
// its speed (6000 rpm).
TEST(EngineRunsTest, SimbodyFollowsTheExactRunAndMujocoSoftLosesEnergy) {
  const Mechanism m = loadWithoutGas("inline4_four_stroke");
  constexpr int kRevolutions = 5;
  constexpr double kAccuracy = 1e-10;
  const std::vector<EngineRunRow> rows =
      calcEngineRuns(m, m.machine.speed, kRevolutions,
                     {{"simbody", "RungeKuttaMerson", kAccuracy}, {"mujoco-soft", "RK4", 1e-3}, {"mujoco-soft-stiff", "RK4", 1e-3}});
  ASSERT_EQ(rows.size(), 3u);
  const EngineRunRow& simbody = rows[0];
  EXPECT_EQ(simbody.scene, m.name);
  EXPECT_EQ(simbody.engine, "simbody");
  EXPECT_EQ(simbody.integrator, "RungeKuttaMerson");
  EXPECT_EQ(simbody.accuracy, kAccuracy);
  EXPECT_EQ(simbody.accuracy_meaning_short, "integrator's relative accuracy");
  EXPECT_EQ(simbody.revolutions, kRevolutions);
  EXPECT_EQ(simbody.omega_reading, "at the step");
  ASSERT_GT(simbody.steps, 0);
  // The integrator holds each step's local error to `accuracy` relative to the state, the crank speed among it; the
  // energy goes as omega^2, so a step moves it by at most 2 accuracy relative, and a revolution's steps by at most their
  // number times that (no cancellation assumed).
  const double steps_per_revolution = static_cast<double>(simbody.steps) / kRevolutions;
  const double trend_bound = 2.0 * kAccuracy * steps_per_revolution;
  EXPECT_LT(std::fabs(simbody.energy_trend_per_revolution), trend_bound);
  // The acceptance for the reference runs: delta to 1e-6 relative.
  EXPECT_GT(simbody.delta_exact, 0.0);
  EXPECT_LT(std::fabs(simbody.delta_error_rel), 1e-6);
  EXPECT_NEAR(simbody.delta, simbody.delta_exact * (1.0 + simbody.delta_error_rel), 4.0 * kEps * simbody.delta_exact);
  // The phase: every step's speed error at most `accuracy` relative, summed over all the steps, times the angle run.
  const double phase_bound = kAccuracy * simbody.steps * 2.0 * M_PI * kRevolutions;
  EXPECT_LT(std::fabs(simbody.phase_error_at_horizon), phase_bound);
  // The horizon: five turns at the mean speed, which lies between the extremes (omega0 -+ delta omega0).
  const double five_turns = kRevolutions * 2.0 * M_PI / m.machine.speed;
  EXPECT_NEAR(simbody.horizon_s, five_turns, simbody.delta_exact * five_turns);
  EXPECT_GT(simbody.cpu_seconds_per_revolution, 0.0);
  // Where the speed peaks and dips: the inline four's speed repeats every half turn, so its two maxima (and minima) are
  // equal and the run may settle on either; each is judged against the nearest (calcSpeedFluctuation). A flat
  // extreme's phase is known to about sqrt(2 e / (delta / 2)) for a relative speed error e (the speed's curvature at the
  // extreme is about delta / 2 per rad^2): 1e-4 rad at e = 1e-10; 1e-3 rad holds it with a tenfold margin.
  EXPECT_LT(std::fabs(simbody.phi_max_error), 1e-3);
  EXPECT_LT(std::fabs(simbody.phi_min_error), 1e-3);

  // MuJoCo's soft constraints dissipate: each revolution loses energy, orders of magnitude beyond the most Simbody's
  // accuracy allows it (the bound above, not its measured trend, which may come out near 0).
  for (size_t i = 1; i < rows.size(); ++i) {
    SCOPED_TRACE(rows[i].engine);
    EXPECT_EQ(rows[i].accuracy_meaning_short, "fixed time step as a fraction of one revolution at the release speed");
    EXPECT_EQ(rows[i].omega_reading, "at the step");  // RK4: the speed is the state at the step
    EXPECT_LT(rows[i].energy_trend_per_revolution, 0.0);
    EXPECT_GT(std::fabs(rows[i].energy_trend_per_revolution), 1e3 * trend_bound);
  }
}

// Where MuJoCo's velocities stand: its semi-implicit Euler (and implicit) integrator advances qvel first and moves
// qpos by the new qvel, so its recorded speed is a backward difference, half a step behind the recorded angle; RK4
// records both at the same instant. The judge is MuJoCo's own RK4 at a tenth of the step (the same soft dynamics,
// integrated far more closely): the angle at which the speed is largest. Read at the wrong instant, a run's speed
// curve moves by half a step in time, omega0 h / 2 = pi x accuracy in angle.
TEST(EngineRunsTest, MujocoEulerSpeedStandsHalfAStepBehind) {
  const Mechanism m = loadWithoutGas("inline4_four_stroke");
  const Engine& engine = findEngine("mujoco-soft");
  auto run = [&](const char* integrator, double accuracy) {
    FreeRunSettings settings;
    settings.integrator = integrator;
    settings.accuracy = accuracy;
    settings.revolutions = 3;
    return findOmegaInstants(engine.simulate(m, m.machine.speed, settings).trajectory);
  };
  auto phiAtMax = [&](const Trajectory& r) { return calcSpeedFluctuation(m, r).run.phi_at_omega_max; };
  constexpr double kAccuracy = 1e-3;
  const double shift = M_PI * kAccuracy;  // half a step in angle [rad]
  const Trajectory reference = run("RK4", kAccuracy / 10.0);
  ASSERT_FALSE(reference.omega_half_step_behind);
  const double phi_ref = phiAtMax(reference);

  for (const char* integrator : {"Euler", "implicit"}) {
    SCOPED_TRACE(integrator);
    Trajectory r = run(integrator, kAccuracy);
    ASSERT_TRUE(r.omega_half_step_behind);  // recognised by phi_i - phi_{i-1} = h phi_dot_i
    EXPECT_LT(std::fabs(phiAtMax(r) - phi_ref), 0.1 * shift);
    r.omega_half_step_behind = false;  // read at the step instead: off by the half step
    // Within a tenth of the half step: what is left is the Euler run's own first-order error in the extreme's phase
    // and the reference's (RK4 at a tenth of the step), measured 1.0e-4 rad against the shift's 3.1e-3 (0.03 of it).
    EXPECT_NEAR(phiAtMax(r) - phi_ref, shift, 0.1 * shift);
  }
  Trajectory rk4 = run("RK4", kAccuracy);
  ASSERT_FALSE(rk4.omega_half_step_behind);
  EXPECT_LT(std::fabs(phiAtMax(rk4) - phi_ref), 0.1 * shift);
  rk4.omega_half_step_behind = true;  // read half a step behind instead: off by the half step the other way
  EXPECT_NEAR(phiAtMax(rk4) - phi_ref, -shift, 0.1 * shift);
}

// findOmegaInstants on runs made here: the pendulum phi'' = -sin(phi) + 1 stepped by semi-implicit Euler (its velocity a
// backward difference of its angle) and sampled exactly at its own instants by classical Runge-Kutta (its velocity the
// state at the step).
TEST(EngineRunsTest, FindOmegaInstantsRecognisesABackwardDifference) {
  auto accel = [](double phi) { return 1.0 - std::sin(phi); };
  const double h = 1e-3;
  Trajectory euler, rk4;
  double phi = 0.0, omega = 2.0;
  for (int i = 0; i <= 2000; ++i) {
    euler.time.push_back(i * h);
    euler.phi.push_back(phi);
    euler.omega.push_back(omega);
    omega += h * accel(phi);
    phi += h * omega;
  }
  phi = 0.0, omega = 2.0;
  for (int i = 0; i <= 2000; ++i) {
    rk4.time.push_back(i * h);
    rk4.phi.push_back(phi);
    rk4.omega.push_back(omega);
    const double k1p = omega, k1w = accel(phi);
    const double k2p = omega + 0.5 * h * k1w, k2w = accel(phi + 0.5 * h * k1p);
    const double k3p = omega + 0.5 * h * k2w, k3w = accel(phi + 0.5 * h * k2p);
    const double k4p = omega + h * k3w, k4w = accel(phi + h * k3p);
    phi += h / 6.0 * (k1p + 2.0 * k2p + 2.0 * k3p + k4p);
    omega += h / 6.0 * (k1w + 2.0 * k2w + 2.0 * k3w + k4w);
  }
  const Trajectory a = findOmegaInstants(euler);
  EXPECT_TRUE(a.omega_half_step_behind);
  EXPECT_EQ(a.time, euler.time);
  const Trajectory b = findOmegaInstants(rk4);
  EXPECT_FALSE(b.omega_half_step_behind);
  EXPECT_EQ(b.omega, rk4.omega);

  Trajectory short_run;
  short_run.time = short_run.phi = short_run.omega = {0.0};
  EXPECT_THROW(findOmegaInstants(short_run), std::invalid_argument);
  short_run.time = {0.0, 1.0};
  EXPECT_THROW(findOmegaInstants(short_run), std::invalid_argument);
}

TEST(EngineRunsTest, DefaultRuns) {
  auto names = [](const std::vector<EngineRunSpec>& specs) {
    std::vector<std::string> out;
    for (const EngineRunSpec& s : specs) {
      char accuracy[16];
      std::snprintf(accuracy, sizeof accuracy, "%g", s.accuracy);
      out.push_back(s.engine + " " + s.integrator + " " + accuracy);
    }
    return out;
  };
  EXPECT_EQ(names(listDefaultEngineRuns(false)),
            (std::vector<std::string>{"simbody RungeKuttaMerson 1e-06", "simbody RungeKuttaMerson 1e-08",
                                      "simbody RungeKuttaMerson 1e-10", "simbody CPodes 1e-08",
                                      "simbody SemiExplicitEuler2 1e-06", "mujoco-soft RK4 0.001",
                                      "mujoco-soft Euler 0.001", "mujoco-soft Euler 0.0001",
                                      "mujoco-soft-stiff RK4 0.001", "mujoco-soft-stiff Euler 0.001",
                                      "mujoco-soft-stiff Euler 0.0001", "ode defaults 0.001",
                                      "ode defaults 0.0001", "ode-quickstep defaults 0.001",
                                      "ode-quickstep defaults 0.0001", "bullet defaults 0.001",
                                      "bullet defaults 0.0001", "box2d defaults 0.001", "box2d defaults 0.0001"}));
  EXPECT_EQ(names(listDefaultEngineRuns(true)),
            (std::vector<std::string>{"simbody RungeKuttaMerson 1e-10", "mujoco-soft RK4 0.001",
                                      "mujoco-soft Euler 0.001", "mujoco-soft-stiff RK4 0.001",
                                      "mujoco-soft-stiff Euler 0.001", "ode defaults 0.0001",
                                      "ode-quickstep defaults 0.0001", "bullet defaults 0.0001",
                                      "box2d defaults 0.0001"}));
  // A loaded run's: the engines that take the gas and a load, none that steps.
  for (const EngineRunSpec& s : listDefaultEngineRuns(true, {true})) EXPECT_EQ(s.engine, "simbody");
}

TEST(EngineRunsTest, Schema) {
  const Schema<EngineRunRow>& schema = getFreeRunEnginesSchema();
  EXPECT_EQ(schema.name(), "free_run_engines");
  std::vector<std::string> headers;
  for (const Column& c : schema.columns()) headers.push_back(c.text ? c.name : c.name + " [" + c.unit + "]");
  EXPECT_EQ(headers, (std::vector<std::string>{
                         "scene", "engine", "integrator", "accuracy [-]", "accuracy_meaning", "energy_trend_per_revolution [-]",
                         "delta [-]", "delta_exact [-]", "delta_error_rel [-]", "phi_max_error [rad]",
                         "phi_min_error [rad]", "phase_error_at_horizon [rad]", "horizon [s]", "revolutions [-]",
                         "steps [-]", "omega_reading", "cpu_per_revolution [s]"}));
  EngineRunRow row;
  row.engine = "simbody";
  row.steps = 12;
  row.horizon_s = 0.25;
  const Table t = schema.table({row});
  EXPECT_EQ(std::get<std::string>(t.cell(0, 1)), "simbody");
  EXPECT_EQ(std::get<double>(t.cell(0, 12)), 0.25);
  EXPECT_EQ(std::get<double>(t.cell(0, 14)), 12.0);
}

// The refusals, each one clear line naming what is wrong (checked before any run).
TEST(EngineRunsTest, Refusals) {
  const Mechanism m = loadWithoutGas("inline4_four_stroke");
  const double w = m.machine.speed;
  auto message = [&](const Mechanism& mech, double omega0, int revolutions, const std::vector<EngineRunSpec>& specs) {
    try {
      calcEngineRuns(mech, omega0, revolutions, specs);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no std::invalid_argument");
  };
  const EngineRunSpec good{"simbody", "RungeKuttaMerson", 1e-6};
  const std::string running = "simbody, mujoco-soft, mujoco-soft-stiff, ode, ode-quickstep, bullet, box2d";
  EXPECT_EQ(message(m, w, 2, {good, {"dart", "RK4", 1e-3}}),
            "free run: no engine \"dart\" (the engines that run free: " + running + ")");
  EXPECT_EQ(message(m, w, 2, {{"mujoco", "RK4", 1e-3}}),
            "free run: the engine mujoco does not run free (the engines that do: " + running + ")");
  EXPECT_EQ(message(m, w, 2, {{"bullet", "RK4", 1e-3}}),
            "free run: bullet has no settings \"RK4\" (it has defaults, neutralised, tightened)");
  EXPECT_EQ(message(m, w, 2, {{"box2d", "defaults", -1.0}}), "free run: box2d: the step -1 s is not finite and > 0");
  EXPECT_EQ(message(m, w, 2, {{"mujoco-soft", "RungeKuttaMerson", 1e-3}}),
            "free run: the engine mujoco-soft has no integrator \"RungeKuttaMerson\" (it has RK4, Euler, implicit)");
  EXPECT_EQ(message(m, w, 2, {{"simbody", "", 1e-6}}),
            "free run: the engine simbody has no integrator \"\" (it has RungeKuttaMerson, CPodes, SemiExplicitEuler2)");
  EXPECT_EQ(message(m, w, 2, {{"simbody", "CPodes", 0.0}}),
            "free run: simbody CPodes: the accuracy 0 is not finite and > 0");
  EXPECT_EQ(message(m, 0.0, 2, {good}), "free run: the release speed 0 rad/s is not finite and > 0");
  EXPECT_EQ(message(m, w, 0, {good}), "free run: 0 revolutions (at least 1)");
  const Mechanism with_gas = loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / "inline4_four_stroke.toml");
  EXPECT_NE(message(with_gas, w, 2, {good}).find("[gas]"), std::string::npos);
  Mechanism no_flywheel = m;
  no_flywheel.flywheel_inertia.reset();
  EXPECT_NE(message(no_flywheel, w, 2, {good}).find("[flywheel].inertia"), std::string::npos);
  EXPECT_TRUE(calcEngineRuns(m, w, 2, {}).empty());
}

}  // namespace
}  // namespace crankcheck::validation
