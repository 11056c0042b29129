// Cost per crank angle of each method, measured side by side in one run (Google Benchmark). Ratios between the
// rows are what the reports use: absolute times drift on shared machines.
//   build/bin/crankcheck_bench [--benchmark_format=json]

#include <benchmark/benchmark.h>
#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <random>
#include <vector>

#include "bench_cases.h"
#include "crankcheck/analytic/batch.h"
#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/analytic/torsion_forced.h"
#include "crankcheck/analytic/torsion_steady.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/simbody_models/grid_sweep.h"
#include "crankcheck/simbody_models/k_crank_gravity_model.h"
#include "crankcheck/simbody_models/k_crank_model.h"
#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/engines.h"

namespace crankcheck {
namespace {

using bench::benchMechanism;

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

// Batches of 1e6 angles (bench_cases.h, the same the accuracy tests check): items_per_second counts angles
// (ns per angle = 1e9 / items_per_second).
using bench::kBatch;
std::vector<double> randomAngles() { return bench::benchAngles(); }

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

// ---- The batch kernels (batch.h), arbitrary angles and the uniform grid, k = range(0).

// Every output array of the kernels, allocated once per benchmark.
struct Outputs {
  std::vector<double> Q, tau, F_X, F_Y, shake[5];
  std::vector<std::vector<double>> kin[3], cyl[5];
  std::vector<analytic::PistonKinematicsSpans> kinematics;
  std::vector<analytic::CylinderReactionsSpans> cylinders;
  explicit Outputs(int k) {
    for (auto* v : {&Q, &tau, &F_X, &F_Y, &shake[0], &shake[1], &shake[2], &shake[3], &shake[4]}) v->assign(kBatch, 0.0);
    for (auto& v : kin) v.assign(static_cast<size_t>(k), std::vector<double>(kBatch, 0.0));
    for (auto& v : cyl) v.assign(static_cast<size_t>(k), std::vector<double>(kBatch, 0.0));
    for (int j = 0; j < k; ++j) {
      kinematics.push_back({kin[0][j], kin[1][j], kin[2][j]});
      cylinders.push_back({cyl[0][j], cyl[1][j], cyl[2][j], cyl[3][j], cyl[4][j]});
    }
  }
  analytic::ReactionsSpans reactions(bool per_cylinder) {
    return {tau, F_X, F_Y, per_cylinder ? std::span<const analytic::CylinderReactionsSpans>(cylinders)
                                        : std::span<const analytic::CylinderReactionsSpans>()};
  }
  analytic::ShakingSpans shaking() { return {shake[0], shake[1], shake[2], shake[3], shake[4]}; }
};

enum Quantity { kQ, kU, kKinematics, kReactions, kReactionTotals, kShaking };

// One batch of kBatch angles: arbitrary (phi != nullptr) or the grid.
void runKernel(Quantity q, const Mechanism& m, const std::vector<double>* phi, Outputs& o) {
  using namespace analytic;
  const double phi0 = bench::kGridPhi0, step = bench::kGridStep;
  switch (q) {
    case kQ: phi ? calcGravityTorqueBatch(m, *phi, o.Q) : calcGravityTorqueOnGrid(m, phi0, step, o.Q); break;
    case kU: phi ? calcPotentialEnergyBatch(m, *phi, o.Q) : calcPotentialEnergyOnGrid(m, phi0, step, o.Q); break;
    case kKinematics:
      phi ? calcPistonKinematicsBatch(m, *phi, o.kinematics) : calcPistonKinematicsOnGrid(m, phi0, step, o.kinematics);
      break;
    case kReactions:
    case kReactionTotals:
      phi ? calcReactionsBatch(m, *phi, o.reactions(q == kReactions))
          : calcReactionsOnGrid(m, phi0, step, o.reactions(q == kReactions));
      break;
    case kShaking: phi ? calcShakingBatch(m, *phi, o.shaking()) : calcShakingOnGrid(m, phi0, step, o.shaking()); break;
  }
}

template <Quantity q, bool grid>
void BM_Kernel(benchmark::State& state) {
  const int k = static_cast<int>(state.range(0));
  const Mechanism m = benchMechanism(k);
  const std::vector<double> phi = randomAngles();
  Outputs o(k);
  for (auto _ : state) {
    runKernel(q, m, grid ? nullptr : &phi, o);
    benchmark::ClobberMemory();
  }
  setPerAngle(state);
  state.SetLabel(analytic::getBatchTargetName());
}
// Q (eq 13), U (eq 12), x_p, v_p, a_p of every cylinder, the reactions (5 per cylinder) with the drive torque and
// bearing force, the same totals alone, the shaking force and moment (5).
BENCHMARK(BM_Kernel<kQ, false>)->Name("BM_BatchQ")->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Kernel<kU, false>)->Name("BM_BatchU")->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Kernel<kKinematics, false>)->Name("BM_BatchKinematics")->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Kernel<kReactions, false>)->Name("BM_BatchReactions")->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Kernel<kReactionTotals, false>)->Name("BM_BatchReactionTotals")->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Kernel<kShaking, false>)->Name("BM_BatchShaking")->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Kernel<kQ, true>)->Name("BM_GridQ")->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Kernel<kU, true>)->Name("BM_GridU")->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Kernel<kKinematics, true>)->Name("BM_GridKinematics")->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Kernel<kReactions, true>)->Name("BM_GridReactions")->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Kernel<kReactionTotals, true>)->Name("BM_GridReactionTotals")->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Kernel<kShaking, true>)->Name("BM_GridShaking")->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);

// ---- The machine's limits for the same data.

// Memory: read the 8-byte angle and write range(0) 8-byte outputs per angle, as the kernels do, with no arithmetic
// (memcpy of the input into each output, in blocks that stay in L1 so the input is read from memory once).
// Outputs per angle: Q, U 1; kinematics 3k; reactions 3 + 5k; reaction totals 3; shaking 5.
void BM_MemoryFloor(benchmark::State& state) {
  const size_t outputs = static_cast<size_t>(state.range(0));
  const std::vector<double> phi = randomAngles();
  std::vector<std::vector<double>> out(outputs, std::vector<double>(kBatch));
  constexpr size_t kBlock = 2048;
  for (auto _ : state) {
    for (size_t start = 0; start < kBatch; start += kBlock) {
      const size_t n = std::min(kBlock, kBatch - start);
      for (auto& o : out) std::memcpy(o.data() + start, phi.data() + start, n * sizeof(double));
    }
    benchmark::ClobberMemory();
  }
  setPerAngle(state);
  state.counters["bytes_per_angle"] = static_cast<double>(8 * (1 + outputs));
}
BENCHMARK(BM_MemoryFloor)->Arg(1)->Arg(3)->Arg(5)->Arg(8)->Arg(12)->Arg(23)->Unit(benchmark::kMillisecond);

// The vector units' peak on this CPU (AVX-512, 8 doubles per instruction): independent chains, no memory. Items are
// doubles (lanes) per second. Skipped on a CPU without AVX-512F.
extern "C" {
struct BenchSleefD8x2 {
  __m512d x, y;
};
BenchSleefD8x2 Sleef_sincosd8_u10avx512f(__m512d);
}

constexpr int kChains = 12;
constexpr int kPeakIterations = 1 << 16;
volatile double g_opaque_one = 1.0;  // start values the compiler cannot fold the loops over

__attribute__((target("avx512f"))) double runFmaPeak() {
  __m512d acc[kChains];
  for (int c = 0; c < kChains; ++c) acc[c] = _mm512_set1_pd(g_opaque_one + c * 1e-3);
  const __m512d a = _mm512_set1_pd(0.999999), b = _mm512_set1_pd(1e-7);
  for (int i = 0; i < kPeakIterations; ++i)
    for (int c = 0; c < kChains; ++c) acc[c] = _mm512_fmadd_pd(acc[c], a, b);
  __m512d sum = acc[0];
  for (int c = 1; c < kChains; ++c) sum = _mm512_add_pd(sum, acc[c]);
  return _mm512_reduce_add_pd(sum);
}
__attribute__((target("avx512f"))) double runSqrtPeak() {
  __m512d x[kChains];
  for (int c = 0; c < kChains; ++c) x[c] = _mm512_set1_pd(g_opaque_one + 1.0 + c);
  for (int i = 0; i < kPeakIterations; ++i)
    for (int c = 0; c < kChains; ++c) x[c] = _mm512_sqrt_pd(x[c]);  // converges to 1, stays normal
  __m512d sum = x[0];
  for (int c = 1; c < kChains; ++c) sum = _mm512_add_pd(sum, x[c]);
  return _mm512_reduce_add_pd(sum);
}
__attribute__((target("avx512f"))) double runDivPeak() {
  __m512d x[kChains];
  for (int c = 0; c < kChains; ++c) x[c] = _mm512_set1_pd(g_opaque_one + 1.0 + c);
  const __m512d one = _mm512_set1_pd(g_opaque_one);
  for (int i = 0; i < kPeakIterations; ++i)
    for (int c = 0; c < kChains; ++c) x[c] = _mm512_div_pd(one, x[c]);  // x, 1/x, x, ...
  __m512d sum = x[0];
  for (int c = 1; c < kChains; ++c) sum = _mm512_add_pd(sum, x[c]);
  return _mm512_reduce_add_pd(sum);
}
// SLEEF's sincos alone, 8 lanes, from registers: the vector floor of one sin and one cos.
__attribute__((target("avx512f"))) double runSinCosPeak() {
  __m512d x = _mm512_mul_pd(_mm512_set1_pd(g_opaque_one), _mm512_set_pd(0.1, 0.7, 1.3, 1.9, 2.5, 3.1, 3.7, 4.3));
  __m512d sum = _mm512_setzero_pd();
  const __m512d step = _mm512_set1_pd(1e-3);
  for (int i = 0; i < kPeakIterations / 16; ++i) {
    const BenchSleefD8x2 sc = Sleef_sincosd8_u10avx512f(x);
    sum = _mm512_add_pd(sum, _mm512_add_pd(sc.x, sc.y));
    x = _mm512_add_pd(x, step);
  }
  return _mm512_reduce_add_pd(sum);
}

template <double (*kRun)(), int kLanesPerIteration>
void BM_VectorPeak(benchmark::State& state) {
  if (!__builtin_cpu_supports("avx512f")) {
    state.SkipWithError("no AVX-512F");
    return;
  }
  for (auto _ : state) benchmark::DoNotOptimize(kRun());
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * kLanesPerIteration);
}
BENCHMARK(BM_VectorPeak<runFmaPeak, kPeakIterations * kChains * 8>)->Name("BM_VectorPeakFma");
BENCHMARK(BM_VectorPeak<runSqrtPeak, kPeakIterations * kChains * 8>)->Name("BM_VectorPeakSqrt");
BENCHMARK(BM_VectorPeak<runDivPeak, kPeakIterations * kChains * 8>)->Name("BM_VectorPeakDiv");
BENCHMARK(BM_VectorPeak<runSinCosPeak, kPeakIterations / 16 * 8>)->Name("BM_VectorPeakSinCos");

// The vector counterpart of the bare loop: one SLEEF sincos and one sqrt per angle over the same 1e6 angles.
__attribute__((target("avx512f"))) void runBareSimd(const double* phi, double* out, size_t n) {
  const __m512d one = _mm512_set1_pd(1.0), l2 = _mm512_set1_pd(0.09);
  for (size_t i = 0; i + 8 <= n; i += 8) {
    const BenchSleefD8x2 sc = Sleef_sincosd8_u10avx512f(_mm512_loadu_pd(phi + i));
    const __m512d root = _mm512_sqrt_pd(_mm512_sub_pd(one, _mm512_mul_pd(l2, _mm512_mul_pd(sc.x, sc.x))));
    _mm512_storeu_pd(out + i, _mm512_add_pd(sc.y, root));
  }
}
void BM_BatchBareSinCosSqrtSimd(benchmark::State& state) {
  if (!__builtin_cpu_supports("avx512f")) {
    state.SkipWithError("no AVX-512F");
    return;
  }
  const std::vector<double> phi = randomAngles();
  std::vector<double> out(kBatch);
  for (auto _ : state) {
    runBareSimd(phi.data(), out.data(), kBatch);
    benchmark::ClobberMemory();
  }
  setPerAngle(state);
}
BENCHMARK(BM_BatchBareSinCosSqrtSimd)->Unit(benchmark::kMillisecond);

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

// Torsion (issue 30): one speed point of the example inline four's crank train (scenes/inline4_four_stroke.toml, its
// [crankshaft], 6000 rpm): Holzer's response summed to 1e-8, and the exact periodic steady state (shooting, Newton,
// Dormand-Prince at 1e-11, the twist's series and the looser run for the error bound). Issue 30 asks at most 1 s.
const Mechanism& torsionScene() {
  static const Mechanism m = loadSceneFile(std::string(CRANKCHECK_SCENES_DIR) + "/inline4_four_stroke.toml");
  return m;
}
void BM_TorsionHolzer(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(analytic::calcHolzerResponse(torsionScene()));
}
BENCHMARK(BM_TorsionHolzer)->Unit(benchmark::kMillisecond);
void BM_TorsionExactSteadyState(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(analytic::calcExactSteadyState(torsionScene()));
}
BENCHMARK(BM_TorsionExactSteadyState)->Unit(benchmark::kMillisecond);

// Every registered engine (validation/engines.h) evaluating everything at one angle (U, Q, kinematics, reactions,
// drive torque, shaking), k = 1 .. 12: one row per engine and k, "which engine, at what cost" (docs/engines.md).
[[maybe_unused]] const bool kEngineBenchmarks = [] {
  for (const Engine& engine : validation::listEngines())
    benchmark::RegisterBenchmark(("BM_EngineEvaluate/" + engine.name).c_str(),
                                 [&engine](benchmark::State& state) {
                                   const std::unique_ptr<EngineModel> model =
                                       engine.build(benchMechanism(static_cast<int>(state.range(0))));
                                   int i = 0;
                                   for (auto _ : state) benchmark::DoNotOptimize(model->evaluate(nextAngle(i)));
                                 })
        ->Arg(1)->Arg(2)->Arg(4)->Arg(6)->Arg(12)->Unit(benchmark::kMicrosecond);
  return true;
}();

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

// Simbody's Q and U over a uniform grid of one turn in half degrees (720 angles; every phase angle of the bench
// mechanisms is a whole number of steps) by superposing one-cylinder models (grid_sweep.h), per angle. The model is
// built inside the timed region, as a sweep would.
constexpr size_t kSimbodyGrid = 720;
void BM_SimbodyGridHoldingTorque(benchmark::State& state) {
  const Mechanism m = benchMechanism(static_cast<int>(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(simbody_models::calcHoldingTorqueOnGrid(m, 0.0, 2.0 * M_PI / kSimbodyGrid, kSimbodyGrid));
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(kSimbodyGrid));
}
BENCHMARK(BM_SimbodyGridHoldingTorque)->Arg(1)->Arg(4)->Arg(12)->Unit(benchmark::kMillisecond);

void BM_SimbodyGridPotentialEnergy(benchmark::State& state) {
  const Mechanism m = benchMechanism(static_cast<int>(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(simbody_models::calcPotentialEnergyOnGrid(m, 0.0, 2.0 * M_PI / kSimbodyGrid, kSimbodyGrid));
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(kSimbodyGrid));
}
BENCHMARK(BM_SimbodyGridPotentialEnergy)->Arg(1)->Arg(12)->Unit(benchmark::kMillisecond);

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
