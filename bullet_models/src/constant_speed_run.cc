#include "crankcheck/bullet_models/constant_speed_run.h"

#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointFeedback.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletDynamics/Featherstone/btMultiBodyPoint2Point.h>

#include <chrono>
#include <functional>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "crankcheck/scene/gas.h"

namespace crankcheck::bullet_models {
namespace {

// Debian's libbullet-dev ships both builds; bullet-float64.pc gives -DBT_USE_DOUBLE_PRECISION and the -float64
// libraries together. A mismatch between the define and the library would corrupt every btVector3 passed across.
static_assert(std::is_same_v<btScalar, double>, "crankcheck's Bullet models need Bullet in double precision (bullet-float64)");

void requireOption(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("Bullet run: " + what);
}

void refuse(const std::string& key, const std::string& why) {
  throw std::invalid_argument("Bullet cannot build this scene: " + key + " " + why);
}

/// Bullet's world with a look between its two passes: the free pass (solveExternalForces: the articulated-body
/// algorithm without the constraints, which sets every joint feedback) and the constraint pass that adds the
/// constraints' share to the feedback.
class FeedbackWorld : public btMultiBodyDynamicsWorld {
 public:
  using btMultiBodyDynamicsWorld::btMultiBodyDynamicsWorld;
  std::function<void()> after_free_pass;
  void solveExternalForces(btContactSolverInfo& info) override {
    btMultiBodyDynamicsWorld::solveExternalForces(info);
    if (after_free_pass) after_free_pass();
  }
};

struct CylinderLinks {
  int piston = 0, rod = 0;            // link indices
  btVector3 wrist_pin_in_rod{0, 0, 0};  // [m] A from the rod's centre of mass, in the rod's frame
  btVector3 e{0, 0, 0}, n{0, 0, 0};     // the cylinder's axis and its normal
  std::unique_ptr<btMultiBodyPoint2Point> wrist_pin;
  btMultiBodyJointFeedback piston_feedback{}, rod_feedback{};
};

/// A link's joint feedback's force (the linear part of btMultiBodyJointFeedback::m_reactionForces, m_topVec, which
/// Bullet 3.24 gives in the link's frame) in global axes, turned by the link's orientation at the step's start (the
/// positions Bullet computed it at). `columns`: the link's X, Y, Z axes in global axes.
Vec3 toGlobal(const std::array<btVector3, 3>& columns, const btVector3& local) {
  const btVector3 f = columns[0] * local[0] + columns[1] * local[1] + columns[2] * local[2];
  return {f[0], f[1], f[2]};
}

Vec3 toGlobal(const std::array<btVector3, 3>& columns, const btMultiBodyJointFeedback& feedback) {
  return toGlobal(columns, feedback.m_reactionForces.m_topVec);
}

std::array<btVector3, 3> getOrientation(const btMultiBody& body, int link) {
  return {body.localDirToWorld(link, btVector3(1.0, 0.0, 0.0)), body.localDirToWorld(link, btVector3(0.0, 1.0, 0.0)),
          body.localDirToWorld(link, btVector3(0.0, 0.0, 1.0))};
}

/// Bullet's model of m in the pose of o.start with every joint's speed set from it, in its world: the crank driven
/// by its joint motor at o.start.omega (`driven`), or free with the scene's flywheel added to the crank (not driven).
/// Its members are declared in the order their destruction needs: the world first, then what it refers to.
struct Model {
  Model() = default;
  Model(const Model&) = delete;
  Model& operator=(const Model&) = delete;
  ~Model() {
    if (!world) return;
    if (motor) world->removeMultiBodyConstraint(motor.get());
    for (CylinderLinks& c : cylinders)
      if (c.wrist_pin) world->removeMultiBodyConstraint(c.wrist_pin.get());
    for (auto& collider : colliders) world->removeCollisionObject(collider.get());
    world->removeMultiBody(body.get());
  }
  int crank_link = 0;
  std::unique_ptr<btMultiBody> body;
  btMultiBodyJointFeedback crank_feedback{};
  std::vector<CylinderLinks> cylinders;
  std::unique_ptr<btMultiBodyJointMotor> motor;  // null in a free run
  btSphereShape shape{0.01};
  std::vector<std::unique_ptr<btMultiBodyLinkCollider>> colliders;
  btDefaultCollisionConfiguration configuration;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  btDbvtBroadphase broadphase;
  btMultiBodyConstraintSolver solver;
  std::unique_ptr<FeedbackWorld> world;
};

/// The one construction of both runs: checks o and what the model cannot build, then builds it (Model).
std::unique_ptr<Model> buildModel(const Mechanism& m, const BulletRunOptions& o, bool driven) {
  const int k = m.machine.cylinders;
  const StartState& start = o.start;
  requireOption(std::isfinite(o.dt) && o.dt > 0.0, "dt must be a positive number of seconds");
  requireOption(o.steps > 0, "steps must be > 0");
  requireOption(static_cast<int>(start.cylinders.size()) == k,
                "start has " + std::to_string(start.cylinders.size()) + " cylinders, the mechanism " + std::to_string(k));
  requireOption(o.solver_iterations >= 1, "solver_iterations must be >= 1");
  requireOption(o.erp > 0.0 && o.erp <= 1.0, "erp must be in (0, 1]");
  requireOption(std::isfinite(o.linear_damping) && o.linear_damping >= 0.0, "linear_damping must be >= 0");
  requireOption(std::isfinite(o.angular_damping) && o.angular_damping >= 0.0, "angular_damping must be >= 0");
  requireOption(o.max_coordinate_velocity > 0.0, "max_coordinate_velocity must be > 0");
  requireOption(o.loop_max_impulse > 0.0, "loop_max_impulse must be > 0");
  if (driven) {
    requireOption(o.motor_max_impulse > 0.0, "motor_max_impulse must be > 0");
    if (!(std::fabs(m.machine.speed) > 0.0))
      refuse("[engine].speed_rpm", "must be != 0 (the run drives the crank at the scene's constant speed)");
  } else {
    requireOption(std::isfinite(start.omega), "start.omega (the release speed) must be finite");
    if (!m.flywheel_inertia) refuse("[flywheel].inertia", "is required: the free run's crank carries the flywheel");
    if (!(std::isfinite(*m.flywheel_inertia) && *m.flywheel_inertia >= 0.0))
      refuse("[flywheel].inertia", "must be a finite inertia >= 0");
  }
  checkSteppedScene(m, "Bullet");
  const double rod_inertia = calcRodCentroidalInertia(m);
  const double omega = start.omega;
  const LumpedCrank lumped = calcLumpedCrank(m, "Bullet");
  const double crank_mass = lumped.mass;
  // About the centre of mass, along Z. The free run's flywheel turns with the crank about O: its inertia adds (it does
  // not move the centre of mass).
  const double crank_inertia = lumped.inertia_about_cm + (driven ? 0.0 : *m.flywheel_inertia);
  // The crank's centre of mass at the start angle (the lumped crank's is at phi = 0).
  const double cx0 = lumped.p_OBcm[0], cy0 = lumped.p_OBcm[1];
  const double cx = cx0 * std::cos(start.phi) - cy0 * std::sin(start.phi), cy = cx0 * std::sin(start.phi) + cy0 * std::cos(start.phi);

  // Every link's frame is parallel to the world's in the start's pose with every joint coordinate 0 except the
  // pistons' (x_p), so the offsets below are global vectors at the start. Only the inertia about Z acts (every joint
  // is about Z or along the plane; a diagonal tensor spinning about Z has no gyroscopic moment), so all three
  // diagonal entries are that one.
  auto model = std::make_unique<Model>();
  const int crank_link = model->crank_link;
  const int links = 1 + 2 * k;
  model->body = std::make_unique<btMultiBody>(links, 1.0, btVector3(1.0, 1.0, 1.0), /*fixedBase=*/true, /*canSleep=*/false);
  btMultiBody* body = model->body.get();
  body->setBaseWorldTransform(btTransform::getIdentity());
  const btQuaternion identity = btQuaternion::getIdentity();
  const btVector3 z_axis(0.0, 0.0, 1.0);
  body->setupRevolute(crank_link, crank_mass, btVector3(crank_inertia, crank_inertia, crank_inertia), -1, identity, z_axis,
                      btVector3(0.0, 0.0, 0.0), btVector3(cx, cy, 0.0), true);
  std::vector<CylinderLinks>& cylinders = model->cylinders;
  cylinders.resize(static_cast<std::size_t>(k));
  for (int j = 0; j < k; ++j) {
    CylinderLinks& c = cylinders[static_cast<std::size_t>(j)];
    const CylinderStartState& s = start.cylinders[static_cast<std::size_t>(j)];
    const double z = getAxialPosition(m, j);
    const double delta = s.p_WA_W[0] * s.n[0] + s.p_WA_W[1] * s.n[1];  // A = x_p e + delta n
    c.piston = 1 + 2 * j;
    c.rod = 2 + 2 * j;
    c.e = btVector3(s.e[0], s.e[1], 0.0);
    c.n = btVector3(s.n[0], s.n[1], 0.0);
    // The piston: a particle on its line; its prismatic joint holds every rotation, so its inertia never acts (any
    // positive value will do, the rod's keeps the system's scale).
    body->setupPrismatic(c.piston, m.piston.mass, btVector3(rod_inertia, rod_inertia, rod_inertia), -1, identity, c.e,
                         delta * c.n + btVector3(0.0, 0.0, z), btVector3(0.0, 0.0, 0.0), true);
    // The rod: its centre of mass G and its joint at B on the crank, as the start places them.
    const btVector3 g(s.rod.p_WBcm_W[0], s.rod.p_WBcm_W[1], z);
    const btVector3 b(s.p_WB_W[0], s.p_WB_W[1], z);
    body->setupRevolute(c.rod, m.rod.mass, btVector3(rod_inertia, rod_inertia, rod_inertia), crank_link, identity, z_axis,
                        b - btVector3(cx, cy, 0.0), g - b, true);
    c.wrist_pin_in_rod = btVector3(s.p_WA_W[0], s.p_WA_W[1], z) - g;
  }
  body->getLink(crank_link).m_jointFeedback = &model->crank_feedback;
  for (CylinderLinks& c : cylinders) {
    body->getLink(c.piston).m_jointFeedback = &c.piston_feedback;
    body->getLink(c.rod).m_jointFeedback = &c.rod_feedback;
  }
  body->finalizeMultiDof();
  body->setLinearDamping(o.linear_damping);
  body->setAngularDamping(o.angular_damping);
  body->setMaxCoordinateVelocity(o.max_coordinate_velocity);
  body->setJointVel(crank_link, omega);
  for (int j = 0; j < k; ++j) {
    const CylinderLinks& c = cylinders[static_cast<std::size_t>(j)];
    const CylinderStartState& s = start.cylinders[static_cast<std::size_t>(j)];
    body->setJointPos(c.piston, s.x_p);
    body->setJointVel(c.piston, s.v_p);
    body->setJointVel(c.rod, s.rod.omega - omega);  // relative to the crank
  }
  btAlignedObjectArray<btQuaternion> world_to_local;
  btAlignedObjectArray<btVector3> local_origin;
  world_to_local.resize(links + 1);  // forwardKinematics fills the base's and every link's entry
  local_origin.resize(links + 1);
  body->forwardKinematics(world_to_local, local_origin);

  if (driven) model->motor = std::make_unique<btMultiBodyJointMotor>(body, crank_link, omega, o.motor_max_impulse);
  for (CylinderLinks& c : cylinders) {
    c.wrist_pin = std::make_unique<btMultiBodyPoint2Point>(body, c.rod, body, c.piston, c.wrist_pin_in_rod,
                                                           btVector3(0.0, 0.0, 0.0));
    c.wrist_pin->setMaxAppliedImpulse(o.loop_max_impulse);
  }
  // A constraint sizes its Jacobians and its impulse records from the finalised body.
  if (model->motor) model->motor->finalizeMultiDof();
  for (CylinderLinks& c : cylinders) c.wrist_pin->finalizeMultiDof();

  // Every link carries a collider that collides with nothing (group and mask 0): Bullet's solver takes a multibody's
  // constraints island by island, and an island is found through the links' colliders; without them the motor and
  // the loops would never be solved.
  for (int i = 0; i < links; ++i) {
    model->colliders.push_back(std::make_unique<btMultiBodyLinkCollider>(body, i));
    btMultiBodyLinkCollider& collider = *model->colliders.back();
    collider.setCollisionShape(&model->shape);
    btTransform transform;
    transform.setIdentity();
    transform.setOrigin(body->localPosToWorld(i, btVector3(0.0, 0.0, 0.0)));
    collider.setWorldTransform(transform);
    collider.setActivationState(DISABLE_DEACTIVATION);
    body->getLink(i).m_collider = &collider;
  }
  model->dispatcher = std::make_unique<btCollisionDispatcher>(&model->configuration);
  model->world = std::make_unique<FeedbackWorld>(model->dispatcher.get(), &model->broadphase, &model->solver, &model->configuration);
  FeedbackWorld& world = *model->world;
  world.setGravity(btVector3(0.0, -m.machine.gravity, 0.0));
  btContactSolverInfo& info = world.getSolverInfo();
  info.m_numIterations = o.solver_iterations;
  info.m_erp = o.erp;
  info.m_erp2 = o.erp;
  world.addMultiBody(body);
  for (auto& collider : model->colliders) world.addCollisionObject(collider.get(), 0, 0);
  if (model->motor) world.addMultiBodyConstraint(model->motor.get());
  for (CylinderLinks& c : cylinders) world.addMultiBodyConstraint(c.wrist_pin.get());
  return model;
}

}  // namespace

BulletRun runBulletAtConstantSpeed(const Mechanism& m, const BulletRunOptions& o) {
  const std::unique_ptr<Model> model = buildModel(m, o, /*driven=*/true);
  const int k = m.machine.cylinders;
  const StartState& start = o.start;
  // Gas (docs/CONVENTIONS.md "Gas"): p_j at the cycle angle phi - firing_j, the force -p_j A e_j on piston j.
  const double bore_area = m.gas ? calcBoreArea(*m.gas) : 0.0;
  if (m.gas) requireOption(static_cast<int>(m.firing_angles.size()) == k, "[gas] needs one firing angle per cylinder");
  btMultiBody* body = model->body.get();
  FeedbackWorld& world = *model->world;
  const int crank_link = model->crank_link;
  std::vector<CylinderLinks>& cylinders = model->cylinders;
  const btMultiBodyJointFeedback& crank_feedback = model->crank_feedback;
  btMultiBodyJointMotor* motor = model->motor.get();

  const std::array<btVector3, 3> piston_orientation{btVector3(1.0, 0.0, 0.0), btVector3(0.0, 1.0, 0.0), btVector3(0.0, 0.0, 1.0)};
  const long steps = o.steps;
  BulletRun run;
  run.samples.reserve(static_cast<std::size_t>(steps));
  // The joint feedback after the free pass (the link frame's force, before the constraint pass adds to it).
  btVector3 crank_free(0, 0, 0);
  std::vector<btVector3> rod_free(static_cast<std::size_t>(k));
  world.after_free_pass = [&] {
    crank_free = crank_feedback.m_reactionForces.m_topVec;
    for (int j = 0; j < k; ++j) rod_free[static_cast<std::size_t>(j)] = cylinders[static_cast<std::size_t>(j)].rod_feedback.m_reactionForces.m_topVec;
  };
  double phi = start.phi;
  std::vector<double> v_start(static_cast<std::size_t>(k));
  const auto started = std::chrono::steady_clock::now();
  for (long i = 0; i < steps; ++i) {
    // maxSubSteps 0: one step of exactly dt. With substeps Bullet would step at its fixedTimeStep (1/60 s unless
    // given) and report states interpolated between its steps, neither of which is the step under test.
    // The pistons' frames never turn (identity); the crank's and the rods' are read before the step.
    const std::array<btVector3, 3> crank_start = getOrientation(*body, crank_link);
    std::vector<std::array<btVector3, 3>> rod_start;
    for (const CylinderLinks& c : cylinders) rod_start.push_back(getOrientation(*body, c.rod));
    for (int j = 0; j < k; ++j) {
      const CylinderLinks& c = cylinders[static_cast<std::size_t>(j)];
      v_start[static_cast<std::size_t>(j)] = body->getJointVel(c.piston);
      // Held through the step; stepSimulation clears every applied force at its end.
      if (m.gas) body->addLinkForce(c.piston, -calcGasPressure(*m.gas, phi - m.firing_angles[static_cast<std::size_t>(j)]) * bore_area * c.e);
    }
    world.stepSimulation(o.dt, 0);
    BulletSample sample;
    sample.t = static_cast<double>(i + 1) * o.dt;
    sample.phi_start = phi;
    phi = start.phi + body->getJointPos(crank_link);
    sample.phi = phi;
    sample.crank_speed = body->getJointVel(crank_link);
    sample.drive_torque = motor->getAppliedImpulse(0) / o.dt;
    sample.bearing_feedback = toGlobal(crank_start, crank_feedback);
    sample.bearing_feedback_free = toGlobal(crank_start, crank_free);
    sample.cylinders.reserve(static_cast<std::size_t>(k));
    for (const CylinderLinks& c : cylinders) {
      BulletCylinderSample cs;
      cs.crank_pin_feedback = toGlobal(rod_start[sample.cylinders.size()], c.rod_feedback);
      cs.crank_pin_feedback_free = toGlobal(rod_start[sample.cylinders.size()], rod_free[sample.cylinders.size()]);
      cs.slider_feedback = toGlobal(piston_orientation, c.piston_feedback);
      cs.wall_force = cs.slider_feedback[0] * c.n[0] + cs.slider_feedback[1] * c.n[1];
      cs.x_p = body->getJointPos(c.piston);
      cs.v_p = body->getJointVel(c.piston);
      cs.a_p = (cs.v_p - v_start[sample.cylinders.size()]) / o.dt;
      // The point-to-point rows are along -X, -Y, -Z on the rod (A) and +X, +Y, +Z on the piston (B).
      for (int row = 0; row < 3; ++row) cs.wrist_pin[static_cast<std::size_t>(row)] = c.wrist_pin->getAppliedImpulse(row) / o.dt;
      const btVector3 on_rod = body->localPosToWorld(c.rod, c.wrist_pin_in_rod);
      const btVector3 on_piston = body->localPosToWorld(c.piston, btVector3(0.0, 0.0, 0.0));
      cs.loop_error = (on_rod - on_piston).length();
      sample.cylinders.push_back(cs);
    }
    run.samples.push_back(std::move(sample));
  }
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - started;
  run.seconds_per_step = steps > 0 ? elapsed.count() / static_cast<double>(steps) : 0.0;
  return run;
}

Trajectory runBulletFree(const Mechanism& m, const BulletRunOptions& o) {
  const std::unique_ptr<Model> model = buildModel(m, o, /*driven=*/false);
  btMultiBody& body = *model->body;
  const long steps = o.steps;
  Trajectory run;
  run.time.reserve(static_cast<std::size_t>(steps));
  run.phi.reserve(static_cast<std::size_t>(steps));
  run.omega.reserve(static_cast<std::size_t>(steps));
  run.omega_time.reserve(static_cast<std::size_t>(steps));
  // Semi-implicit Euler: the joint speed after the step is the one stepPositionsMultiDof moved the joint by,
  // phi_i - phi_{i-1} = dt omega_i (tests/bullet/bullet_free_run_test.cc verifies it): the middle of the step.
  const double lag = 0.5 * o.dt;
  const auto started = std::chrono::steady_clock::now();
  for (long i = 0; i < steps; ++i) {
    model->world->stepSimulation(o.dt, 0);  // one step of exactly dt (runBulletAtConstantSpeed says why)
    run.time.push_back(static_cast<double>(i + 1) * o.dt);
    run.phi.push_back(o.start.phi + body.getJointPos(model->crank_link));
    run.omega.push_back(body.getJointVel(model->crank_link));  // the crank's joint speed is its angular velocity about +Z
    run.omega_time.push_back(run.time.back() - lag);
  }
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - started;
  run.seconds_per_step = elapsed.count() / static_cast<double>(steps);
  return run;
}

}  // namespace crankcheck::bullet_models
