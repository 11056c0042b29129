// Cost per crank angle of each method, measured side by side in one run (Google Benchmark). Ratios between the
// rows are what the reports use: absolute times drift on shared machines.
//   build/bin/crankcheck_bench [--benchmark_format=json]

#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "crankcheck/analytic/batch.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/simbody_models/k_crank_gravity_model.h"
#include "crankcheck/simbody_models/k_crank_model.h"
#include "crankcheck/validation/campaign.h"

namespace crankcheck {
namespace {

// The same mechanism family as the tests: r = 0.05 m, lambda = 0.3, rod centre of mass off the middle.
Mechanism benchMechanism(int k) {
  Mechanism m;
  m.engine.cylinders = k;
  m.engine.cycle = Cycle::kFourStroke;
  m.engine.crank_angles = calcPhaseAngles(k, m.engine.cycle, m.engine.acting);
  m.engine.cylinder_angle = radiansFromDegrees(90.0);
  m.engine.speed = 4500.0 * M_PI / 30.0;
  m.crank = {0.05, 1.7, 0.02, 1.3, 0.04};
  m.rod = {0.05 / 0.3, 0.61, 0.05, 0.61 * (0.05 * 0.05 + 0.045 * 0.045)};
  m.piston.mass = 0.43;
  return m;
}

// A stream of crank angles that the compiler cannot fold: one turn in 1024 steps, then again.
double nextAngle(int& i) { return 2.0 * M_PI * ((i++) & 1023) / 1024.0; }

void BM_BareSinCosSqrt(benchmark::State& state) {  // the floor of any closed form: one sin, one cos, one sqrt
  int i = 0;
  for (auto _ : state) {
    const double phi = nextAngle(i);
    benchmark::DoNotOptimize(std::sin(phi) + std::cos(phi) + std::sqrt(1.0 - 0.09 * std::sin(phi) * std::sin(phi)));
  }
}
BENCHMARK(BM_BareSinCosSqrt);

// Batches of 1e6 angles: items_per_second counts angles (ns per angle = 1e9 / items_per_second).
constexpr size_t kBatch = 1'000'000;

std::vector<double> randomAngles() {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> angle(-10.0, 10.0);
  std::vector<double> phi(kBatch);
  for (double& p : phi) p = angle(rng);
  return phi;
}

void setPerAngle(benchmark::State& state) {
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(kBatch));
}

// The floor of any closed form for arbitrary angles: one sin, one cos and one sqrt per angle.
void BM_BatchBareSinCosSqrt(benchmark::State& state) {
  const std::vector<double> phi = randomAngles();
  std::vector<double> out(kBatch);
  for (auto _ : state) {
    for (size_t i = 0; i < kBatch; ++i) {
      const double s = std::sin(phi[i]), c = std::cos(phi[i]);
      out[i] = c + std::sqrt(1.0 - 0.09 * s * s);
    }
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  setPerAngle(state);
}
BENCHMARK(BM_BatchBareSinCosSqrt)->Unit(benchmark::kMillisecond);

void BM_BatchQArbitraryAngles(benchmark::State& state) {
  const Mechanism m = benchMechanism(static_cast<int>(state.range(0)));
  const std::vector<double> phi = randomAngles();
  std::vector<double> Q(kBatch);
  for (auto _ : state) {
    analytic::calcGravityTorqueBatch(m, phi, Q);
    benchmark::DoNotOptimize(Q.data());
  }
  setPerAngle(state);
}
BENCHMARK(BM_BatchQArbitraryAngles)->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);

void BM_BatchQUniformGrid(benchmark::State& state) {
  const Mechanism m = benchMechanism(static_cast<int>(state.range(0)));
  std::vector<double> Q(kBatch);
  for (auto _ : state) {
    analytic::calcGravityTorqueOnGrid(m, 0.0, 2.0 * M_PI / 3600.0, Q);
    benchmark::DoNotOptimize(Q.data());
  }
  setPerAngle(state);
}
BENCHMARK(BM_BatchQUniformGrid)->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);

// U, kinematics and reactions over the same batch: no dedicated kernel, the scalar functions in a loop.
void BM_BatchUScalarLoop(benchmark::State& state) {
  const Mechanism m = benchMechanism(static_cast<int>(state.range(0)));
  const std::vector<double> phi = randomAngles();
  std::vector<double> U(kBatch);
  for (auto _ : state) {
    for (size_t i = 0; i < kBatch; ++i) U[i] = analytic::calcPotentialEnergy(m, phi[i]);
    benchmark::DoNotOptimize(U.data());
  }
  setPerAngle(state);
}
BENCHMARK(BM_BatchUScalarLoop)->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);

void BM_BatchKinematicsScalarLoop(benchmark::State& state) {
  const Mechanism m = benchMechanism(1);
  const std::vector<double> phi = randomAngles();
  std::vector<double> a(kBatch);
  for (auto _ : state) {
    for (size_t i = 0; i < kBatch; ++i) a[i] = analytic::calcPistonKinematics(m, phi[i]).a_p;
    benchmark::DoNotOptimize(a.data());
  }
  setPerAngle(state);
}
BENCHMARK(BM_BatchKinematicsScalarLoop)->Unit(benchmark::kMillisecond);

void BM_BatchReactionsScalarLoop(benchmark::State& state) {
  const Mechanism m = benchMechanism(static_cast<int>(state.range(0)));
  const std::vector<double> phi = randomAngles();
  std::vector<double> tau(kBatch);
  for (auto _ : state) {
    for (size_t i = 0; i < kBatch; ++i) tau[i] = analytic::calcReactions(m, phi[i]).drive_torque;
    benchmark::DoNotOptimize(tau.data());
  }
  setPerAngle(state);
}
BENCHMARK(BM_BatchReactionsScalarLoop)->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);

void BM_AnalyticQ(benchmark::State& state) {
  const Mechanism m = benchMechanism(static_cast<int>(state.range(0)));
  int i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(analytic::calcGravityTorque(m, nextAngle(i)));
}
BENCHMARK(BM_AnalyticQ)->Arg(1)->Arg(4)->Arg(12);

void BM_AnalyticU(benchmark::State& state) {
  const Mechanism m = benchMechanism(static_cast<int>(state.range(0)));
  int i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(analytic::calcPotentialEnergy(m, nextAngle(i)));
}
BENCHMARK(BM_AnalyticU)->Arg(1)->Arg(4)->Arg(12);

void BM_AnalyticKinematics(benchmark::State& state) {
  const Mechanism m = benchMechanism(1);
  int i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(analytic::calcPistonKinematics(m, nextAngle(i)));
}
BENCHMARK(BM_AnalyticKinematics);

void BM_AnalyticReactions(benchmark::State& state) {
  const Mechanism m = benchMechanism(static_cast<int>(state.range(0)));
  int i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(analytic::calcReactions(m, nextAngle(i)));
}
BENCHMARK(BM_AnalyticReactions)->Arg(1)->Arg(4)->Arg(12);

void BM_FourierQ(benchmark::State& state) {  // eq (14), coefficients computed once per call as a user would
  const Mechanism m = benchMechanism(1);
  const int order = static_cast<int>(state.range(0));
  int i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(analytic::calcGravityTorqueFourier(m, nextAngle(i), order));
}
BENCHMARK(BM_FourierQ)->Arg(2)->Arg(4)->Arg(8)->Arg(12);

void BM_SimbodyEvaluate(benchmark::State& state) {  // U, Q (holding torque), reactions, kinematics
  simbody_models::KCrankModel model(benchMechanism(static_cast<int>(state.range(0))));
  int i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(model.evaluate(nextAngle(i)));
}
BENCHMARK(BM_SimbodyEvaluate)->Arg(1)->Arg(2)->Arg(4)->Arg(6)->Arg(12)->Unit(benchmark::kMicrosecond);

void BM_SimbodyHoldingTorque(benchmark::State& state) {
  simbody_models::KCrankModel model(benchMechanism(static_cast<int>(state.range(0))));
  int i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(model.calcHoldingTorque(nextAngle(i)));
}
BENCHMARK(BM_SimbodyHoldingTorque)->Arg(1)->Arg(2)->Arg(4)->Arg(6)->Arg(12)->Unit(benchmark::kMicrosecond);

void BM_SimbodyPotentialEnergy(benchmark::State& state) {
  simbody_models::KCrankModel model(benchMechanism(static_cast<int>(state.range(0))));
  int i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(model.calcPotentialEnergy(nextAngle(i)));
}
BENCHMARK(BM_SimbodyPotentialEnergy)->Arg(1)->Arg(2)->Arg(4)->Arg(6)->Arg(12)->Unit(benchmark::kMicrosecond);

// The reduced model (two-mass rods, one distance constraint per cylinder) for the same U and Q.
void BM_SimbodyReducedHoldingTorque(benchmark::State& state) {
  simbody_models::KCrankGravityModel model(benchMechanism(static_cast<int>(state.range(0))));
  int i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(model.calcHoldingTorque(nextAngle(i)));
}
BENCHMARK(BM_SimbodyReducedHoldingTorque)->Arg(1)->Arg(2)->Arg(4)->Arg(6)->Arg(12)->Unit(benchmark::kMicrosecond);

void BM_SimbodyReducedVirtualPowerQ(benchmark::State& state) {
  simbody_models::KCrankGravityModel model(benchMechanism(static_cast<int>(state.range(0))));
  int i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(model.calcVirtualPowerQ(nextAngle(i)));
}
BENCHMARK(BM_SimbodyReducedVirtualPowerQ)->Arg(1)->Arg(12)->Unit(benchmark::kMicrosecond);

void BM_SimbodyReducedPotentialEnergy(benchmark::State& state) {
  simbody_models::KCrankGravityModel model(benchMechanism(static_cast<int>(state.range(0))));
  int i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(model.calcPotentialEnergy(nextAngle(i)));
}
BENCHMARK(BM_SimbodyReducedPotentialEnergy)->Arg(1)->Arg(2)->Arg(4)->Arg(6)->Arg(12)->Unit(benchmark::kMicrosecond);

// The whole default campaign of `crankcheck validate`, every task in turn on one thread (the command itself spreads
// them over --jobs threads). Timing tasks are skipped: they would measure themselves.
void BM_DefaultCampaign(benchmark::State& state) {
  validation::CampaignOptions options;
  options.quick = state.range(0) != 0;
  for (auto _ : state)
    for (const validation::Task& task : validation::buildCampaign(options))
      if (!task.measures_time) benchmark::DoNotOptimize(task.run());
}
BENCHMARK(BM_DefaultCampaign)->Arg(1)->Arg(0)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
}  // namespace crankcheck

BENCHMARK_MAIN();
