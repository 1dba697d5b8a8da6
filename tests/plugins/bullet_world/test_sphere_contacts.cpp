// bullet_world's collision dispatcher: a sphere against a convex shape keeps one contact point
// per manifold (Bullet caches up to four while it rests or rolls); other pairs keep Bullet's
// manifolds.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>
#include <vector>

#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h>
#include <BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/testing/harness.hpp"
#include "sphere_contact_dispatcher.hpp"
#include "world_test_support.hpp"

using somasim::bullet_world::SphereContactDispatcher;

namespace {

// A rigid-body world with bullet_world's dispatcher.
struct Scene {
  btDefaultCollisionConfiguration config;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  std::unique_ptr<btDiscreteDynamicsWorld> world;
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btRigidBody>> bodies;

  Scene()
      : dispatcher(std::make_unique<SphereContactDispatcher>(&config)),
        world(std::make_unique<btDiscreteDynamicsWorld>(dispatcher.get(), &broadphase, &solver,
                                                        &config)) {
    world->setGravity(btVector3(0, 0, -9.81));
  }
  void step() { world->stepSimulation(1e-3, 0, 1e-3); }

  btRigidBody* add(std::unique_ptr<btCollisionShape> shape, double mass, const btVector3& at) {
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape->calculateLocalInertia(mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape.get(), inertia);
    info.m_startWorldTransform.setOrigin(at);
    info.m_friction = 0.8;
    info.m_rollingFriction = 0.0005;
    info.m_spinningFriction = 0.0005;
    auto body = std::make_unique<btRigidBody>(info);
    world->addRigidBody(body.get());
    shapes.push_back(std::move(shape));
    bodies.push_back(std::move(body));
    return bodies.back().get();
  }
  ~Scene() {
    for (auto& b : bodies) world->removeRigidBody(b.get());
  }
};

}  // namespace

// Balls of random size dropped from random points above the left forearm of the free robot (that
// arm as in configs/ball_on_forearm.yaml, computed torques): every step, the points reported
// between a ball and a link lie on different collision shapes of the link, never within 2 mm of
// each other (with Bullet's own manifolds, up to four points lie within 1 mm while
// a ball rests or rolls on the forearm).
TEST(SphereContacts, BallsOnTheForearmTouchAtOnePointPerShape) {
  const auto model = world_test::icub();
  const Eigen::VectorXd q0 = world_test::with_joints_deg(*model, world_test::rest_posture(*model),
                                                         {{"l_shoulder_pitch", -40},
                                                          {"l_shoulder_roll", 40},
                                                          {"l_shoulder_yaw", 10},
                                                          {"l_elbow", 60}});
  somasim::robot::RobotData data(*model);
  somasim::robot::forward_kinematics(*model, data, q0);
  const Eigen::Vector3d target =
      data.link_poses[model->link_index("l_forearm")] * Eigen::Vector3d(0, -0.07, 0);
  somasim::testing::Harness h(
      world_test::world_yaml("initial_posture_deg: " + world_test::posture_param(*model, q0) +
                             ", joint_servo: computed_torque"));
  h.input<somasim::JointCommand>("cmd") = world_test::hold(q0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> radius(0.01, 0.03), side(-0.04, 0.04);
  int touching_steps = 0;
  for (std::uint64_t k = 1; k <= 12; ++k) {
    const double r = radius(rng);
    const Eigen::Vector3d start = target + Eigen::Vector3d(side(rng), side(rng), 0.05 + r);
    auto ball = world_test::sphere(k, "ball" + std::to_string(k), r, start);
    ball.remove_after_s = 0.4;
    h.input<somasim::ObjectSpawns>("spawns").recent = {ball};
    for (int step = 0; step < 400; ++step) {
      h.step();
      h.input<somasim::ObjectSpawns>("spawns").recent.clear();
      const auto& points = h.output<somasim::Contacts>("world.contacts").points;
      touching_steps += points.empty() ? 0 : 1;
      for (std::size_t a = 0; a < points.size(); ++a)
        for (std::size_t b = a + 1; b < points.size(); ++b) {
          const bool same_pair =
              points[a].link_a == points[b].link_a && points[a].object_b == points[b].object_b &&
              points[a].link_b == points[b].link_b && points[a].object_a == points[b].object_a;
          if (same_pair) {
            EXPECT_GT((points[a].point - points[b].point).norm(), 0.002)
                << "ball " << k << ", step " << step;
          }
        }
    }
  }
  EXPECT_GT(touching_steps, 600);  // the balls rest on the forearm for most of their time
  EXPECT_EQ(h.finish(), "");
}

TEST(SphereContacts, BoxesKeepBulletsManifolds) {
  Scene scene;
  scene.add(std::make_unique<btBoxShape>(btVector3(0.2, 0.2, 0.02)), 0.0, btVector3(0, 0, 0));
  btRigidBody* box = scene.add(std::make_unique<btBoxShape>(btVector3(0.03, 0.03, 0.03)), 0.1,
                               btVector3(0, 0, 0.06));
  box->setActivationState(DISABLE_DEACTIVATION);
  for (int step = 0; step < 500; ++step) scene.step();
  const btCollisionDispatcher& d = *scene.dispatcher;
  int most = 0;
  for (int m = 0; m < d.getNumManifolds(); ++m)
    most = std::max(most, d.getManifoldByIndexInternal(m)->getNumContacts());
  EXPECT_EQ(most, 4);  // a face resting on a face: Bullet's four-point patch
}
