#include "crankcheck/validation/timing.h"

#include <benchmark/benchmark.h>

#include <mutex>
#include <string>

namespace crankcheck::validation {
namespace {

class Collector : public benchmark::BenchmarkReporter {
 public:
  bool ReportContext(const Context&) override { return true; }
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs)
      // run_name.function_name is the registered name (benchmark_name() appends "/min_time:...").
      if (!run.error_occurred) nanoseconds[run.run_name.function_name] = run.GetAdjustedRealTime();  // unit: ns
  }
  std::map<std::string, double> nanoseconds;
};

}  // namespace

std::map<std::string, double> measureNanosecondsPerCall(
    const std::vector<std::pair<std::string, std::function<void()>>>& functions, double min_seconds) {
  static std::mutex mutex;  // Google Benchmark's registry is global
  std::lock_guard<std::mutex> lock(mutex);
  static bool initialized = false;
  if (!initialized) {
    std::string program = "crankcheck";
    char* argv[] = {program.data(), nullptr};
    int argc = 1;
    benchmark::Initialize(&argc, argv);
    initialized = true;
  }
  benchmark::ClearRegisteredBenchmarks();
  for (const auto& [name, function] : functions) {
    benchmark::RegisterBenchmark(name.c_str(), [function](benchmark::State& state) {
      for (auto _ : state) function();
    })->MinTime(min_seconds);
  }
  Collector collector;
  benchmark::RunSpecifiedBenchmarks(&collector);
  benchmark::ClearRegisteredBenchmarks();
  return collector.nanoseconds;
}

}  // namespace crankcheck::validation
