// The C++ side of the Python module's speed comparison (docs/python.md, tests/python/measure_batch.py): the analytic
// engine on 1e6 crank angles, as C++ calls it, so that `Scene.evaluate(phi)` from Python can be held against it.
// build/bin/crankcheck_python_batch_bench [--benchmark_format=json]
//
// The scenes are the example scenes scenes/single_cylinder.toml (k = 1) and scenes/inline4_four_stroke.toml (k = 4,
// with [gas]); the angles phi_i = i x 1e-5 rad, i < 1e6 (0 to 10 rad, given as an array, not as a grid): the same
// in measure_batch.py. Rows (scene:0 the single cylinder, scene:1 the inline four):
//   BM_PythonBatchKernels/scene:S/fresh:0   the batch kernels of analytic/batch.h for every quantity they compute (U,
//                                           Q, kinematics, reactions with every cylinder, shaking) into output vectors
//                                           allocated once: the kernels' own time
//   BM_PythonBatchKernels/scene:S/fresh:1   the same with the outputs allocated for each call as NumPy allocates its
//                                           arrays (malloc; from 4 MiB on advised to use transparent huge pages,
//                                           madvise(MADV_HUGEPAGE), as NumPy >= 1.22 does on Linux)
//   BM_PythonBatchEvaluate/scene:S/fresh:1  python/src/batch_evaluation.cc's evaluateAnalyticBatch for every quantity
//                                           of eval (the kernels plus the rod's angle and derivatives and the gas
//                                           force from the scalar functions), fresh outputs: the C++ under
//                                           Scene.evaluate(phi)

#include <benchmark/benchmark.h>
#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "batch_evaluation.h"
#include "crankcheck/analytic/batch.h"
#include "crankcheck/scene/scene_file.h"

#ifndef CRANKCHECK_SCENES_DIR
#error "the build defines CRANKCHECK_SCENES_DIR"
#endif

namespace {

using namespace crankcheck;

constexpr size_t kAngles = 1000000;
const char* const kScenes[] = {"single_cylinder", "inline4_four_stroke"};

const Mechanism& scene(int index) {
  static const Mechanism scenes[2] = {loadSceneFile(std::string(CRANKCHECK_SCENES_DIR) + "/" + kScenes[0] + ".toml"),
                                      loadSceneFile(std::string(CRANKCHECK_SCENES_DIR) + "/" + kScenes[1] + ".toml")};
  return scenes[index];
}

// One block of `doubles` values allocated as NumPy 1.24 allocates a large array's data (numpy/core/src/multiarray/
// alloc.c): malloc, then, from 4 MiB on, madvise(MADV_HUGEPAGE) from the first page boundary on (transparent huge
// pages spare most page faults of fresh memory). Uninitialised, as np.empty.
struct FreeDeleter {
  void operator()(double* p) const { std::free(p); }
};
using Block = std::unique_ptr<double[], FreeDeleter>;
Block allocate(size_t doubles) {
  const size_t bytes = doubles * sizeof(double);
  void* p = std::malloc(bytes);
  if (!p) throw std::bad_alloc();
  if (bytes >= (size_t{1} << 22)) {
    const uintptr_t offset = 4096u - reinterpret_cast<uintptr_t>(p) % 4096u;
    ::madvise(static_cast<char*>(p) + offset, bytes - offset, MADV_HUGEPAGE);
  }
  return Block(static_cast<double*>(p));
}

// The angles, in memory allocated as NumPy allocates the array the Python side passes (np.arange).
std::span<const double> angles() {
  static const Block phi = [] {
    Block b = allocate(kAngles);
    for (size_t i = 0; i < kAngles; ++i) b[i] = static_cast<double>(i) * 1e-5;
    return b;
  }();
  return {phi.get(), kAngles};
}

// Output memory: `count` runs of kAngles doubles.
struct Outputs {
  std::vector<Block> blocks;
  explicit Outputs(size_t count) {
    for (size_t b = 0; b < count; ++b) blocks.push_back(allocate(kAngles));
  }
  std::span<double> operator[](size_t b) { return {blocks[b].get(), kAngles}; }
};

// Every kernel of batch.h on phi: U, Q, kinematics (3 k), reactions (3 + 5 k), shaking (5).
size_t kernelOutputs(int k) { return 2 + 3 * static_cast<size_t>(k) + 3 + 5 * static_cast<size_t>(k) + 5; }

void runKernels(const Mechanism& m, std::span<const double> phi, Outputs& o) {
  const int k = m.machine.cylinders;
  size_t b = 0;
  analytic::calcPotentialEnergyBatch(m, phi, o[b++]);
  analytic::calcGravityTorqueBatch(m, phi, o[b++]);
  std::vector<analytic::PistonKinematicsSpans> kinematics;
  for (int j = 0; j < k; ++j) {
    analytic::PistonKinematicsSpans s{o[b], o[b + 1], o[b + 2]};
    b += 3;
    kinematics.push_back(s);
  }
  analytic::calcPistonKinematicsBatch(m, phi, kinematics);
  std::vector<analytic::CylinderReactionsSpans> cylinders;
  for (int j = 0; j < k; ++j) {
    analytic::CylinderReactionsSpans c{o[b], o[b + 1], o[b + 2], o[b + 3], o[b + 4]};
    b += 5;
    cylinders.push_back(c);
  }
  analytic::ReactionsSpans reactions{o[b], o[b + 1], o[b + 2], cylinders};
  b += 3;
  analytic::calcReactionsBatch(m, phi, reactions);
  analytic::calcShakingBatch(m, phi, analytic::ShakingSpans{o[b], o[b + 1], o[b + 2], o[b + 3], o[b + 4]});
}

void BM_PythonBatchKernels(benchmark::State& state) {
  const Mechanism& m = scene(static_cast<int>(state.range(0)));
  const bool fresh = state.range(1) != 0;
  const size_t count = kernelOutputs(m.machine.cylinders);
  std::unique_ptr<Outputs> reused = fresh ? nullptr : std::make_unique<Outputs>(count);
  for (auto _ : state) {
    std::unique_ptr<Outputs> outputs = fresh ? std::make_unique<Outputs>(count) : nullptr;
    Outputs& o = fresh ? *outputs : *reused;
    runKernels(m, angles(), o);
    benchmark::DoNotOptimize(o.blocks.front().get());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(kAngles));
  state.SetLabel(std::string(kScenes[state.range(0)]) + ", " + analytic::getBatchTargetName());
}

void BM_PythonBatchEvaluate(benchmark::State& state) {
  const Mechanism& m = scene(static_cast<int>(state.range(0)));
  const int k = m.machine.cylinders;
  // Every quantity the scene defines, as Scene.evaluate(phi) computes it by default.
  std::vector<const python::QuantityInfo*> wanted;
  size_t count = 0;
  for (const python::QuantityInfo& q : python::listQuantities())
    if (python::isDefined(m, q.name)) {
      wanted.push_back(&q);
      count += static_cast<size_t>(q.components) * static_cast<size_t>(q.per_cylinder ? k : 1);
    }
  for (auto _ : state) {
    // One block per quantity, as the module allocates one NumPy array per quantity.
    std::vector<Block> blocks;
    python::BatchOutput out;
    for (const python::QuantityInfo* q : wanted) {
      blocks.push_back(allocate(kAngles * static_cast<size_t>(q->components) * static_cast<size_t>(q->per_cylinder ? k : 1)));
      out.at(q->name) = blocks.back().get();
    }
    python::evaluateAnalyticBatch(m, angles(), out);
    benchmark::DoNotOptimize(blocks.front().get());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(kAngles));
  state.SetLabel(std::string(kScenes[state.range(0)]) + ", " + std::to_string(count) + " outputs, " +
                 analytic::getBatchTargetName());
}

BENCHMARK(BM_PythonBatchKernels)->ArgNames({"scene", "fresh"})->ArgsProduct({{0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_PythonBatchEvaluate)->ArgNames({"scene", "fresh"})->ArgsProduct({{0, 1}, {1}})
    ->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
