#include "crankcheck/box2d_models/free_run.h"

#include <box2d/box2d.h>

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "model.h"

namespace crankcheck::box2d_models {

Trajectory runBox2dFree(const Mechanism& m, const Box2dRunOptions& o) {
  if (!m.flywheel_inertia.has_value() || !(*m.flywheel_inertia > 0.0))
    throw std::invalid_argument("Box2D free run: the scene needs [flywheel].inertia > 0 (the crank runs free with its "
                                "flywheel)");
  if (!(std::isfinite(o.start.omega) && o.start.omega != 0.0))
    throw std::invalid_argument("Box2D free run: the release speed (the start state's crank speed) must be != 0");
  Mechanism gasless = m;  // the free run is under gravity alone
  gasless.gas.reset();
  const detail::Model model =
      detail::buildModel(gasless, o, {.motor = false, .extra_crank_inertia = *m.flywheel_inertia});
  b2World* world = model.world.get();
  const b2Body* crank = model.crank;

  const float dt = static_cast<float>(o.dt);
  Trajectory run;  // omega belongs to the step's start (box2d_models/free_run.h)
  run.time.reserve(static_cast<std::size_t>(o.steps));
  run.phi.reserve(static_cast<std::size_t>(o.steps));
  run.omega.reserve(static_cast<std::size_t>(o.steps));
  run.omega_time.reserve(static_cast<std::size_t>(o.steps));
  const auto started = std::chrono::steady_clock::now();
  for (long i = 0; i < o.steps; ++i) {
    world->Step(dt, o.velocity_iterations, o.position_iterations);
    const double omega = crank->GetAngularVelocity();
    // b2Island::Solve scales a velocity down to b2_maxRotation / dt (in float): a crank at the cap no longer runs free.
    if (std::fabs(omega) * dt >= (1.0 - 1e-5) * b2_maxRotation)
      throw std::runtime_error("Box2D free run: the crank's speed reached Box2D's b2_maxRotation (pi/2 per step) at "
                               "t = " + std::to_string((i + 1) * o.dt) + " s; take a smaller step");
    run.time.push_back(static_cast<double>(i + 1) * o.dt);
    run.phi.push_back(crank->GetAngle());
    run.omega.push_back(omega);
    run.omega_time.push_back(run.time.back() - o.dt);  // the step's start
  }
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - started;
  run.seconds_per_step = elapsed.count() / static_cast<double>(o.steps);
  return run;
}

}  // namespace crankcheck::box2d_models
