#pragma once
/// @file
/// RAII owner of a Bullet multibody world and its machinery (collision configuration, dispatcher,
/// broadphase, solver). Bodies are owned elsewhere (RobotMultiBody, ObjectManager) and remove
/// themselves before the world goes away: declare the PhysicsWorld first.
#include <memory>

#include <BulletCollision/BroadphaseCollision/btBroadphaseInterface.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>

#include <Eigen/Core>

namespace somasim::bullet_world {

class PhysicsWorld {
 public:
  /// `gravity` [m/s²] in the root frame; `solver_iterations` of the sequential-impulse solver.
  PhysicsWorld(const Eigen::Vector3d& gravity, int solver_iterations);
  ~PhysicsWorld();
  PhysicsWorld(const PhysicsWorld&) = delete;
  PhysicsWorld& operator=(const PhysicsWorld&) = delete;

  btMultiBodyDynamicsWorld& world() { return *world_; }
  const btMultiBodyDynamicsWorld& world() const { return *world_; }
  btCollisionDispatcher& dispatcher() { return *dispatcher_; }

  /// One fixed step of `dt` [s] (no sub-stepping, no interpolation).
  void step(double dt) { world_->stepSimulation(dt, 0, dt); }

  /// Installs a broadphase pair filter (kept alive by the caller).
  void set_pair_filter(btOverlapFilterCallback* filter);

 private:
  std::unique_ptr<btDefaultCollisionConfiguration> config_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btBroadphaseInterface> broadphase_;
  std::unique_ptr<btMultiBodyConstraintSolver> solver_;
  std::unique_ptr<btMultiBodyDynamicsWorld> world_;
};

}  // namespace somasim::bullet_world
