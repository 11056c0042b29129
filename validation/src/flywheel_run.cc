#include "flywheel_run.h"

#include "crankcheck/validation/engines.h"

namespace crankcheck::validation {

std::vector<const Engine*> listLoadedRunEngines() {
  std::vector<const Engine*> out;
  for (const Engine* e : listReferenceEngines())
    if (e->simulate && e->simulates_loads) out.push_back(e);
  return out;
}

FreeRunSettings makeFlywheelRunSettings(const Engine& engine, bool gas, double load_torque) {
  FreeRunSettings settings;
  settings.integrator = engine.integrators.front();
  settings.gas = gas;
  settings.load_torque = load_torque;
  settings.revolutions = 2;
  settings.accuracy = engine.gated ? kFlywheelRunAccuracy : engine.default_accuracy;
  return settings;
}

}  // namespace crankcheck::validation
