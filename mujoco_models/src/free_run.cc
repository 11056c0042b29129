// The free run as MuJoCo's users run it (free_run.h): the soft model stepped by MuJoCo's integrators from the
// exactly closed state of KCrankMujocoModel's Impl.
#include "crankcheck/mujoco_models/free_run.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "k_crank_mujoco_model_impl.h"
#include "mjcf_writer.h"
#include "model_support.h"

namespace crankcheck::mujoco_models {

FreeRunResult simulateFreeRun(const Mechanism& m, double omega0, Variant variant, const FreeRunSettings& settings) {
  if (variant == Variant::kExact)
    throw std::invalid_argument("mujoco: no free run in the exact way (MuJoCo's integrators step its soft constraints: "
                                "use mujoco-soft or mujoco-soft-stiff)");
  if (!m.flywheel_inertia)
    throw std::invalid_argument("[flywheel].inertia: missing key (the free run needs the flywheel inertia)");
  if (!(std::isfinite(omega0) && omega0 > 0.0)) throw std::invalid_argument("the release speed omega0 must be > 0");
  int integrator = mjINT_RK4;
  if (settings.integrator == "Euler") integrator = mjINT_EULER;
  else if (settings.integrator == "implicit") integrator = mjINT_IMPLICIT;
  else if (settings.integrator != "RK4" && !settings.integrator.empty())
    throw std::invalid_argument("MuJoCo has no integrator \"" + settings.integrator + "\" (Euler, RK4, implicit)");
  if (!(settings.accuracy > 0.0 && settings.accuracy <= 0.1))
    throw std::invalid_argument("MuJoCo's time step must be a fraction of a revolution in (0, 0.1]");
  if (settings.revolutions < 1) throw std::invalid_argument("the free run needs at least one revolution");
  if (settings.gas || settings.load_torque != 0.0)
    throw std::invalid_argument("MuJoCo's free run takes neither gas forces nor a load torque (Engine::simulates_loads)");

  // The release state, closed exactly (Newton on MuJoCo's kinematics), at phi = 0 with omega0.
  std::vector<double> qpos, qvel;
  int crank_q = 0;
  {
    KCrankMujocoModel::Impl exact(m, Variant::kExact);
    exact.calcClosedState(0.0, omega0, qpos, qvel);
    crank_q = exact.crankJoint();
  }
  ModelPtr model(loadModel(calcMjcf(m, variant)));
  setCrankPinAnchors(model.get(), m);
  model->opt.integrator = integrator;
  model->opt.timestep = settings.accuracy * 2.0 * M_PI / omega0;
  if (!settings.gravity) mju_zero(model->opt.gravity, 3);
  DataPtr data(mj_makeData(model.get()));
  mjData* d = data.get();
  mju_copy(d->qpos, qpos.data(), model->nq);
  mju_copy(d->qvel, qvel.data(), model->nv);
  const int crank_v = model->jnt_dofadr[mj_name2id(model.get(), mjOBJ_JOINT, "crank")];

  FreeRunResult r;
  const double target = 2.0 * M_PI * settings.revolutions;
  const long long max_steps = static_cast<long long>(20.0 * settings.revolutions / settings.accuracy) + 1000;
  for (long long step = 0;; ++step) {
    mj_forward(model.get(), d);  // everything at this state, its energies (mjENBL_ENERGY) among them
    checkRowsFit(d);
    const double phi = d->qpos[crank_q], w = d->qvel[crank_v], e = d->energy[0] + d->energy[1];
    if (!(std::isfinite(phi) && std::isfinite(w) && std::isfinite(e)))
      throw std::runtime_error("MuJoCo's free run became non-finite at t = " + num(d->time) + " s");
    r.trajectory.time.push_back(d->time);
    r.trajectory.phi.push_back(phi);
    r.trajectory.omega.push_back(w);
    r.energy.push_back(e);
    if (phi >= target) break;
    if (step == max_steps)
      throw std::runtime_error("MuJoCo's free run did not complete " + std::to_string(settings.revolutions) +
                               " revolutions in " + std::to_string(max_steps) + " steps (phi = " + num(phi) + " rad)");
    if (integrator == mjINT_EULER) mj_Euler(model.get(), d);
    else if (integrator == mjINT_RK4) mj_RungeKutta(model.get(), d, 4);
    else mj_step(model.get(), d);  // the implicit integrator has no function of its own in 2.2.2
    ++r.steps;
  }
  // The first revolution: the time the crank passes 2 pi (linear between the two steps around it: the steps are a
  // small fraction of a revolution), the extreme speeds at the steps before it.
  size_t i = 1;
  while (r.trajectory.phi[i] < 2.0 * M_PI) ++i;
  const double t1 = r.trajectory.time[i - 1] + (2.0 * M_PI - r.trajectory.phi[i - 1]) / (r.trajectory.phi[i] - r.trajectory.phi[i - 1]) * (r.trajectory.time[i] - r.trajectory.time[i - 1]);
  r.omega_min = r.omega_max = r.trajectory.omega[0];
  for (size_t s = 0; s <= i; ++s) {
    r.omega_min = std::min(r.omega_min, r.trajectory.omega[s]);
    r.omega_max = std::max(r.omega_max, r.trajectory.omega[s]);
  }
  r.omega_mean = 2.0 * M_PI / t1;
  r.delta = (r.omega_max - r.omega_min) / r.omega_mean;
  double drift = 0.0;
  for (double e : r.energy) drift = std::max(drift, std::fabs(e - r.energy[0]));
  r.energy_drift_per_revolution = drift / std::fabs(r.energy[0]) / settings.revolutions;
  return r;
}

}  // namespace crankcheck::mujoco_models
