#include "crankcheck/validation/profile.h"

#include <atomic>
#include <chrono>
#include <type_traits>

#include "crankcheck/validation/timing.h"

namespace crankcheck::validation {

namespace {

std::atomic<bool> g_profiling{false};

// An engine's model whose evaluations are counted and timed into the calling thread's counters.
class CountedModel : public EngineModel {
 public:
  CountedModel(std::unique_ptr<EngineModel> model, std::string engine) : model_(std::move(model)), engine_(std::move(engine)) {}
  Evaluation evaluate(double phi) override { return counted([&] { return model_->evaluate(phi); }); }
  Evaluation evaluateMotion(double phi) override { return counted([&] { return model_->evaluateMotion(phi); }); }
  void setSpeed(double omega) override { model_->setSpeed(omega); }
  void startAssemblyFrom(const EngineModel& donor) override {
    const auto* counted_donor = dynamic_cast<const CountedModel*>(&donor);
    model_->startAssemblyFrom(counted_donor ? *counted_donor->model_ : donor);
  }
  double calcQ(double phi) override { return counted([&] { return model_->calcQ(phi); }); }
  double calcSecondRouteQ(double phi) override { return counted([&] { return model_->calcSecondRouteQ(phi); }); }

 private:
  // Every route of the model counts as one evaluation.
  template <typename F>
  std::invoke_result_t<F> counted(F&& f) {
    const auto start = std::chrono::steady_clock::now();
    auto result = f();
    EngineUse& use = getThreadEngineUse()[engine_];
    ++use.evaluations;
    use.evaluate_seconds += secondsSince(start);
    return result;
  }

  std::unique_ptr<EngineModel> model_;
  std::string engine_;
};

}  // namespace

void setProfiling(bool on) { g_profiling = on; }
bool isProfiling() { return g_profiling; }

std::map<std::string, EngineUse>& getThreadEngineUse() {
  thread_local std::map<std::string, EngineUse> use;
  return use;
}

std::unique_ptr<EngineModel> buildCounted(const Engine::BuildFunction& build, const std::string& engine, const Mechanism& m) {
  if (!g_profiling) return build(m);
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<EngineModel> model = build(m);
  EngineUse& use = getThreadEngineUse()[engine];
  ++use.builds;
  use.build_seconds += secondsSince(start);
  return std::make_unique<CountedModel>(std::move(model), engine);
}

}  // namespace crankcheck::validation
