#include "crankcheck/analytic/engine.h"

#include <cmath>
#include <stdexcept>

#include "crankcheck/analytic/reactions.h"

namespace crankcheck::analytic {
namespace {

class Model final : public EngineModel {
 public:
  explicit Model(const Mechanism& m) : m_(m) {}
  Evaluation evaluate(double phi) override {
    if (!std::isfinite(phi)) throw std::invalid_argument("analytic: crank angle phi must be finite");
    return calcEvaluation(m_, phi);
  }
  void setSpeed(double omega) override {
    if (!std::isfinite(omega)) throw std::invalid_argument("analytic: crank speed omega must be finite");
    m_.engine.speed = omega;
    m_.speed_rpm = omega * (30.0 / M_PI);
  }

 private:
  Mechanism m_;
};

}  // namespace

std::vector<Engine> describeEngines() {
  Engine e;
  e.name = "analytic";
  e.library = "crankcheck's closed forms";
  e.method = "closed-form kinematics (Norton 13.3), energy and Newton-Euler reactions of the exact mechanism";
  e.gated = true;
  e.closed_form = true;  // the closed forms under test: every other engine is compared with this one
  e.build = [](const Mechanism& m) -> std::unique_ptr<EngineModel> { return std::make_unique<Model>(m); };
  return {e};
}

}  // namespace crankcheck::analytic
