#include "physics_world.hpp"

#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>

#include "bullet_math.hpp"
#include "sphere_contact_dispatcher.hpp"

namespace somasim::bullet_world {

PhysicsWorld::PhysicsWorld(const Eigen::Vector3d& gravity, int solver_iterations)
    : config_(std::make_unique<btDefaultCollisionConfiguration>()),
      dispatcher_(std::make_unique<SphereContactDispatcher>(config_.get())),
      broadphase_(std::make_unique<btDbvtBroadphase>()),
      solver_(std::make_unique<btMultiBodyConstraintSolver>()),
      world_(std::make_unique<btMultiBodyDynamicsWorld>(dispatcher_.get(), broadphase_.get(),
                                                        solver_.get(), config_.get())) {
  world_->setGravity(to_bt(gravity));
  btContactSolverInfo& info = world_->getSolverInfo();
  info.m_numIterations = solver_iterations;
  // Determinism: the solver must not randomise its constraint order.
  info.m_solverMode &= ~SOLVER_RANDMIZE_ORDER;
}

PhysicsWorld::~PhysicsWorld() {
  // Owners of bodies removed them already; the pair cache may still reference the filter.
  world_->getPairCache()->setOverlapFilterCallback(nullptr);
}

void PhysicsWorld::set_pair_filter(btOverlapFilterCallback* filter) {
  world_->getPairCache()->setOverlapFilterCallback(filter);
}

}  // namespace somasim::bullet_world
