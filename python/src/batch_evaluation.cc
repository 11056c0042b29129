#include "batch_evaluation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>

#include "crankcheck/analytic/batch.h"
#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/validation/engines.h"

namespace crankcheck::python {

const std::vector<QuantityInfo>& listQuantities() {
  static const std::vector<QuantityInfo> quantities = [] {
    static std::vector<std::string> star_names;  // the storage of the NAME_star names
    const std::vector<Quantity>& catalogue = getQuantityCatalogue();
    size_t last_starred = 0;
    for (size_t i = 0; i < catalogue.size(); ++i)
      if (catalogue[i].dimensionless) {
        star_names.push_back(std::string(catalogue[i].name) + "_star");
        last_starred = i;
      }
    std::vector<QuantityInfo> list;
    for (size_t i = 0; i < catalogue.size(); ++i) {
      const Quantity& q = catalogue[i];
      list.push_back({q.name, q.components, q.per_cylinder, &q, false});
      if (i == last_starred && !star_names.empty()) {
        size_t next = 0;
        for (const Quantity& starred : catalogue)
          if (starred.dimensionless) list.push_back({star_names[next++].c_str(), 1, false, &starred, true});
      }
    }
    return list;
  }();
  return quantities;
}

const QuantityInfo* findQuantity(const std::string& name) {
  for (const QuantityInfo& q : listQuantities())
    if (name == q.name) return &q;
  return nullptr;
}

bool isDefined(const Mechanism& m, const std::string& name) {
  const QuantityInfo* q = findQuantity(name);
  if (!q) return false;
  if (q->star) return m.flywheel_inertia.has_value() && m.machine.speed > 0.0;
  return isQuantityDefined(*q->quantity, m);
}

BatchOutput::BatchOutput() : values(getQuantityCatalogue().size(), nullptr), stars(getQuantityCatalogue().size(), nullptr) {}

double*& BatchOutput::at(const std::string& name) {
  const QuantityInfo* q = findQuantity(name);
  if (!q) throw std::invalid_argument("no quantity called " + name);
  const size_t id = static_cast<size_t>(q->quantity->id);
  return q->star ? stars[id] : values[id];
}

void checkAngles(std::span<const double> phi, const char* name) {
  // One pass without a branch per angle in the common case (all finite), then the first offender for the message.
  bool finite = true;
  for (double x : phi) finite &= std::isfinite(x);
  if (finite) return;
  for (size_t i = 0; i < phi.size(); ++i)
    if (!std::isfinite(phi[i])) {
      char text[96];
      std::snprintf(text, sizeof text, "%s[%zu] = %g: must be a finite number of radians", name, i, phi[i]);
      throw std::invalid_argument(text);
    }
}

namespace {

// Memory for what a kernel computes but nobody asked for: uninitialised doubles, allocated only when needed.
class Scratch {
 public:
  explicit Scratch(size_t n) : n_(n) {}
  double* get() {
    blocks_.push_back(std::unique_ptr<double[]>(new double[n_ == 0 ? 1 : n_]));
    return blocks_.back().get();
  }
  // `wanted`, or scratch memory when it is null.
  double* orScratch(double* wanted) { return wanted ? wanted : get(); }

 private:
  size_t n_;
  std::vector<std::unique_ptr<double[]>> blocks_;
};

// What asking for a NAME_star without a flywheel and a speed is told: "U_star, Q_star: not defined ...".
std::string starsNotDefined() {
  std::string names;
  for (const QuantityInfo& q : listQuantities())
    if (q.star) names += (names.empty() ? "" : ", ") + std::string(q.name);
  return names + ": not defined without [flywheel].inertia and a speed";
}

// Component c of cylinder j of a [component][cylinder][angle] block.
double* part(double* base, int c, int j, int k, size_t n) {
  return base + (static_cast<size_t>(c) * static_cast<size_t>(k) + static_cast<size_t>(j)) * n;
}

}  // namespace

bool batchKernelsAccept(const Mechanism& m) {
  // The kernels check the mechanism before any angle (batch.h: std::invalid_argument for what they do not cover);
  // asked for no angle at all, that check is all they do.
  try {
    analytic::calcGravityTorqueBatch(m, {}, {});
    return true;
  } catch (const std::invalid_argument&) {
    return false;
  }
}

void evaluateAnalyticBatch(const Mechanism& m, std::span<const double> phi, const BatchOutput& wanted) {
  checkAngles(phi);
  // The quantities written below (by a kernel or the analytic engine's scalar functions); a quantity of the catalogue
  // without a line here is computed with the rest by the analytic engine itself.
  using Id = QuantityId;
  static const std::vector<Id> computed_here = {
      Id::kU, Id::kQ, Id::kDriveTorque, Id::kBearingForce, Id::kShakingForce, Id::kShakingMoment, Id::kPistonPosition,
      Id::kPistonVelocity, Id::kPistonAcceleration, Id::kCrankPinForce, Id::kWristPinForce, Id::kWallForce,
      Id::kGasForce, Id::kRodAngle, Id::kRodOmega, Id::kRodAlpha};
  bool all_here = true;
  for (const Quantity& q : getQuantityCatalogue())
    if ((wanted[q.id] || wanted.star(q.id)) &&
        std::find(computed_here.begin(), computed_here.end(), q.id) == computed_here.end())
      all_here = false;
  if (!batchKernelsAccept(m) || !all_here) {
    // What the kernels do not cover: the analytic engine itself (calcEvaluation), angle by angle.
    const Engine& analytic = validation::getClosedFormEngine();
    evaluateModel(m, analytic, *analytic.build(m), phi, wanted);
    return;
  }
  const size_t n = phi.size();
  const int k = m.machine.cylinders;
  Scratch scratch(n);
  auto span = [n](double* p) { return std::span<double>(p, n); };
  // What each kernel writes (null: not asked for).
  const struct {
    double *U, *Q, *U_star, *Q_star, *drive_torque, *bearing_force, *shaking_force, *shaking_moment, *x_p, *v_p, *a_p,
        *crank_pin_force, *wrist_pin_force, *wall_force, *gas_force, *rod_angle, *rod_omega, *rod_alpha;
  } out = {wanted[Id::kU], wanted[Id::kQ], wanted.star(Id::kU), wanted.star(Id::kQ), wanted[Id::kDriveTorque],
           wanted[Id::kBearingForce], wanted[Id::kShakingForce], wanted[Id::kShakingMoment], wanted[Id::kPistonPosition],
           wanted[Id::kPistonVelocity], wanted[Id::kPistonAcceleration], wanted[Id::kCrankPinForce],
           wanted[Id::kWristPinForce], wanted[Id::kWallForce], wanted[Id::kGasForce], wanted[Id::kRodAngle],
           wanted[Id::kRodOmega], wanted[Id::kRodAlpha]};

  // U and Q (U_star and Q_star are the same divided by I_w omega^2).
  const bool dimensionless = m.flywheel_inertia && m.machine.speed > 0.0;
  if ((out.U_star || out.Q_star) && !dimensionless)
    throw std::invalid_argument(starsNotDefined());
  const double unit = dimensionless ? *m.flywheel_inertia * m.machine.speed * m.machine.speed : 1.0;
  if (out.U || out.U_star) {
    double* U = scratch.orScratch(out.U);
    analytic::calcPotentialEnergyBatch(m, phi, span(U));
    if (out.U_star)
      for (size_t i = 0; i < n; ++i) out.U_star[i] = U[i] / unit;
  }
  if (out.Q || out.Q_star) {
    double* Q = scratch.orScratch(out.Q);
    analytic::calcGravityTorqueBatch(m, phi, span(Q));
    if (out.Q_star)
      for (size_t i = 0; i < n; ++i) out.Q_star[i] = Q[i] / unit;
  }

  // Piston kinematics.
  if (out.x_p || out.v_p || out.a_p) {
    double *x = out.x_p, *v = out.v_p, *a = out.a_p;
    std::vector<analytic::PistonKinematicsSpans> cylinders;
    for (int j = 0; j < k; ++j) {
      // One scratch run per missing quantity and cylinder (the kernel needs every span).
      cylinders.push_back({span(x ? part(x, 0, j, k, n) : scratch.get()), span(v ? part(v, 0, j, k, n) : scratch.get()),
                           span(a ? part(a, 0, j, k, n) : scratch.get())});
    }
    analytic::calcPistonKinematicsBatch(m, phi, cylinders);
  }

  // Reactions: the totals always; the cylinders' when one of their quantities is asked for.
  const bool cylinder_reactions = out.crank_pin_force || out.wrist_pin_force || out.wall_force;
  if (out.drive_torque || out.bearing_force || cylinder_reactions) {
    double* tau = scratch.orScratch(out.drive_torque);
    double* F_X = out.bearing_force ? part(out.bearing_force, 0, 0, 1, n) : scratch.get();
    double* F_Y = out.bearing_force ? part(out.bearing_force, 1, 0, 1, n) : scratch.get();
    std::vector<analytic::CylinderReactionsSpans> cylinders;
    if (cylinder_reactions)
      for (int j = 0; j < k; ++j) {
        analytic::CylinderReactionsSpans c;
        c.crank_pin_force_X = span(out.crank_pin_force ? part(out.crank_pin_force, 0, j, k, n) : scratch.get());
        c.crank_pin_force_Y = span(out.crank_pin_force ? part(out.crank_pin_force, 1, j, k, n) : scratch.get());
        c.wrist_pin_force_X = span(out.wrist_pin_force ? part(out.wrist_pin_force, 0, j, k, n) : scratch.get());
        c.wrist_pin_force_Y = span(out.wrist_pin_force ? part(out.wrist_pin_force, 1, j, k, n) : scratch.get());
        c.wall_force = span(out.wall_force ? part(out.wall_force, 0, j, k, n) : scratch.get());
        cylinders.push_back(c);
      }
    analytic::ReactionsSpans reactions;
    reactions.drive_torque = span(tau);
    reactions.bearing_force_X = span(F_X);
    reactions.bearing_force_Y = span(F_Y);
    reactions.cylinders = cylinders;
    analytic::calcReactionsBatch(m, phi, reactions);
  }

  // Shaking force and moment.
  if (out.shaking_force || out.shaking_moment) {
    analytic::ShakingSpans s;
    s.force_X = span(out.shaking_force ? part(out.shaking_force, 0, 0, 1, n) : scratch.get());
    s.force_Y = span(out.shaking_force ? part(out.shaking_force, 1, 0, 1, n) : scratch.get());
    s.moment_X = span(out.shaking_moment ? part(out.shaking_moment, 0, 0, 1, n) : scratch.get());
    s.moment_Y = span(out.shaking_moment ? part(out.shaking_moment, 1, 0, 1, n) : scratch.get());
    s.moment_Z = span(out.shaking_moment ? part(out.shaking_moment, 2, 0, 1, n) : scratch.get());
    analytic::calcShakingBatch(m, phi, s);
    if (out.shaking_moment && !hasAxialPositions(m))  // eval: null, never 0
      for (size_t i = 0; i < 2 * n; ++i) out.shaking_moment[i] = std::numeric_limits<double>::quiet_NaN();
  }

  // The rod's angle and its derivatives, and the gas force: no kernel; the analytic engine's own scalar functions,
  // as calcEvaluation calls them (calcCylinderMotion: the rod at calcThrowSinCos(phi, alpha_j), with the cylinder's
  // pin offset, so the two agree by construction whatever the layout).
  if (out.rod_angle || out.rod_omega || out.rod_alpha) {
    for (int j = 0; j < k; ++j) {
      double* beta = out.rod_angle ? part(out.rod_angle, 0, j, k, n) : nullptr;
      double* beta_dot = out.rod_omega ? part(out.rod_omega, 0, j, k, n) : nullptr;
      double* beta_ddot = out.rod_alpha ? part(out.rod_alpha, 0, j, k, n) : nullptr;
      for (size_t i = 0; i < n; ++i) {
        const analytic::RodKinematics rod = analytic::calcCylinderMotion(m, j, phi[i]).rod;
        if (beta) beta[i] = rod.beta;
        if (beta_dot) beta_dot[i] = rod.beta_dot;
        if (beta_ddot) beta_ddot[i] = rod.beta_ddot;
      }
    }
  }
  if (out.gas_force) {
    if (!m.gas) throw std::invalid_argument(std::string(getQuantity(QuantityId::kGasForce).name) + ": not defined without [gas]");
    for (int j = 0; j < k; ++j) {
      double* f = part(out.gas_force, 0, j, k, n);
      for (size_t i = 0; i < n; ++i) f[i] = calcGasForce(m, j, phi[i]);
    }
  }
}

void evaluateModel(const Mechanism& m, const Engine& engine, EngineModel& model, std::span<const double> phi,
                   const BatchOutput& out) {
  checkAngles(phi);
  const size_t n = phi.size();
  const int k = m.machine.cylinders;
  const std::vector<Quantity>& catalogue = getQuantityCatalogue();
  const bool dimensionless = m.flywheel_inertia && m.machine.speed > 0.0;
  for (const Quantity& q : catalogue) {
    if (out.star(q.id) && !dimensionless)
      throw std::invalid_argument(starsNotDefined());
    if (out[q.id] && !isQuantityDefined(q, m)) throw std::invalid_argument(std::string(q.name) + ": not defined without [gas]");
  }
  const double unit = dimensionless ? *m.flywheel_inertia * m.machine.speed * m.machine.speed : 1.0;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (size_t i = 0; i < n; ++i) {
    Evaluation ev;
    try {
      ev = model.evaluate(phi[i]);
    } catch (const std::invalid_argument&) {
      throw;
    } catch (const std::exception& e) {
      char where[96];
      std::snprintf(where, sizeof where, " could not evaluate phi[%zu] = %.17g rad: ", i, phi[i]);
      throw std::runtime_error("engine " + engine.name + ": " + engine.library + where + e.what());
    }
    if (ev.cylinders.size() != static_cast<size_t>(k))
      throw std::runtime_error("engine " + engine.name + " returned " + std::to_string(ev.cylinders.size()) +
                               " cylinders for a scene of " + std::to_string(k));
    for (const Quantity& q : catalogue) {
      if (double* star = out.star(q.id)) star[i] = readQuantity(q, ev)[0] / unit;
      double* base = out[q.id];
      if (!base) continue;
      const int cylinders = q.per_cylinder ? k : 1;
      for (int j = 0; j < cylinders; ++j) {
        const double* v = readQuantity(q, ev, j);
        // A component the scene does not define is NaN (shaking_moment X and Y without axial positions; eval: null).
        for (int c = 0; c < q.components; ++c) part(base, c, j, cylinders, n)[i] = isComponentDefined(q, c, m) ? v[c] : nan;
      }
    }
  }
}

}  // namespace crankcheck::python
