#include "object_manager.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "body_tag.hpp"
#include "bullet_math.hpp"
#include "somasim/robot/object_geometry.hpp"

namespace somasim::bullet_world {

ObjectManager::ObjectManager(btMultiBodyDynamicsWorld& world, ShapeStore& shapes,
                             const ObjectMaterial& material, const ObjectGuide& guide)
    : world_(world), shapes_(shapes), material_(material), guide_(guide) {}

ObjectManager::~ObjectManager() {
  for (int i : live_) world_.removeRigidBody(objects_[static_cast<std::size_t>(i)].body.get());
}

int ObjectManager::add(const ObjectSpawn& s, double t) {
  Object o;
  o.name = s.name.empty() ? "object" + std::to_string(s.id) : s.name;
  o.motion = s.motion;
  o.start_pose = s.pose;
  o.velocity = s.linear_velocity;
  o.spawn_time = t;
  o.shape = s.shape;
  o.size = s.size;
  o.mesh = s.shape == ObjectShape::kMesh ? s.mesh : std::string();
  if (s.remove_after_s > 0) o.remove_time = t + s.remove_after_s;
  // Moving meshes are convex hulls; static ones keep their exact triangles.
  btCollisionShape* shape =
      shapes_.make(robot::object_geometry(s.shape, s.size, s.mesh),
                   s.motion == ObjectMotion::kStatic ? MeshUse::kTriangles : MeshUse::kConvexHull);
  btVector3 centre;
  btScalar radius = 0;
  shape->getBoundingSphere(centre, radius);
  o.radius = radius + centre.length();

  const bool guided = s.motion == ObjectMotion::kGuided;
  const double mass = s.motion == ObjectMotion::kDynamic || guided ? s.mass : 0.0;
  o.mass = mass;
  btVector3 inertia(0, 0, 0);
  if (mass > 0) shape->calculateLocalInertia(mass, inertia);
  o.motion_state = std::make_unique<btDefaultMotionState>(to_bt(s.pose));
  btRigidBody::btRigidBodyConstructionInfo info(mass, o.motion_state.get(), shape, inertia);
  info.m_friction = material_.friction;
  info.m_rollingFriction = material_.rolling_friction;
  info.m_spinningFriction = material_.rolling_friction;
  info.m_restitution = material_.restitution;
  o.body = std::make_unique<btRigidBody>(info);
  const int index = static_cast<int>(objects_.size());
  set_tag(*o.body, {BodyKind::kObject, index, mass == 0.0, s.motion == ObjectMotion::kKinematic});
  if (s.motion == ObjectMotion::kKinematic)
    o.body->setCollisionFlags(o.body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
  if (s.motion != ObjectMotion::kStatic) o.body->setActivationState(DISABLE_DEACTIVATION);
  if (s.motion == ObjectMotion::kDynamic || guided)
    o.body->setLinearVelocity(to_bt(s.linear_velocity));
  if (guided) {  // held: no gravity, no rotation
    o.body->setFlags(o.body->getFlags() | BT_DISABLE_WORLD_GRAVITY);
    o.body->setGravity(btVector3(0, 0, 0));
    o.body->setAngularFactor(0.0);
    if (guide_.contact_stiffness > 0)
      o.body->setContactStiffnessAndDamping(guide_.contact_stiffness,
                                            2.0 * std::sqrt(guide_.contact_stiffness * mass));
  }
  world_.addRigidBody(o.body.get());
  o.last_pose = s.pose;
  o.last_linear = s.motion == ObjectMotion::kStatic ? Eigen::Vector3d::Zero() : s.linear_velocity;
  objects_.push_back(std::move(o));
  live_.push_back(index);
  return index;
}

void ObjectManager::remove(int i) {
  Object& o = objects_[i];
  if (!o.body) return;
  o.last_pose = pose(i);
  world_.removeRigidBody(o.body.get());
  o.body.reset();
  o.motion_state.reset();
  live_.erase(std::lower_bound(live_.begin(), live_.end(), i));
  removed_since_write_.push_back(i);
}

int ObjectManager::remove_if(const std::function<bool(int)>& doomed) {
  std::vector<int> remove_now;
  for (int i : live_)
    if (doomed(i)) remove_now.push_back(i);
  for (int i : remove_now) remove(i);
  return static_cast<int>(remove_now.size());
}

int ObjectManager::remove_expired(double t) {
  return remove_if([&](int i) { return t >= objects_[i].remove_time - 1e-12; });
}

int ObjectManager::remove_beyond(double radius) {
  return remove_if([&](int i) {
    return (objects_[i].motion == ObjectMotion::kDynamic ||
            objects_[i].motion == ObjectMotion::kGuided) &&
           pose(i).translation().norm() > radius;
  });
}

void ObjectManager::drive(double t, double dt) {
  const double w = guide_.bandwidth;
  for (int i : live_) {
    Object& o = objects_[static_cast<std::size_t>(i)];
    if (o.motion == ObjectMotion::kKinematic) {
      Eigen::Isometry3d p = o.start_pose;
      p.translation() += (t + dt - o.spawn_time) * o.velocity;
      o.motion_state->setWorldTransform(to_bt(p));
    } else if (o.motion == ObjectMotion::kGuided) {
      const Eigen::Vector3d target = o.start_pose.translation() + (t - o.spawn_time) * o.velocity;
      const Eigen::Vector3d p = to_eigen(o.body->getWorldTransform().getOrigin());
      const Eigen::Vector3d v = to_eigen(o.body->getLinearVelocity());
      Eigen::Vector3d force = o.mass * (w * w * (target - p) + 2.0 * w * (o.velocity - v));
      const double norm = force.norm();
      if (norm > guide_.max_force) force *= guide_.max_force / norm;
      o.body->applyCentralForce(to_bt(force));
    }
  }
}

int ObjectManager::remove_named(const std::string& name) {
  return remove_if([&](int i) { return objects_[static_cast<std::size_t>(i)].name == name; });
}

Eigen::Isometry3d ObjectManager::pose(int i) const {
  const Object& o = objects_[i];
  if (!o.body) return o.last_pose;
  return to_eigen(o.body->getWorldTransform());
}

void ObjectManager::write_states(ObjectStates& s) {
  const std::size_t n = objects_.size();
  if (written_ != &s || s.names.size() != written_slots_) written_slots_ = 0;  // all of it
  s.names.resize(n);
  s.present.resize(n);
  s.poses.resize(n);
  s.linear_velocity.resize(n);
  s.angular_velocity.resize(n);
  s.radius.resize(n);
  s.shape.resize(n);
  s.size.resize(n);
  s.mesh.resize(n);
  const auto write_slot = [&](std::size_t i) {
    const Object& o = objects_[i];
    s.names[i] = o.name;
    s.radius[i] = o.radius;
    s.shape[i] = o.shape;
    s.size[i] = o.size;
    s.mesh[i] = o.mesh;
    s.present[i] = o.body != nullptr;
    if (!o.body) {
      s.poses[i] = o.last_pose;
      s.linear_velocity[i].setZero();
      s.angular_velocity[i].setZero();
    }
  };
  for (std::size_t i = written_slots_; i < n; ++i) write_slot(i);  // spawned since
  for (int i : removed_since_write_) write_slot(static_cast<std::size_t>(i));
  for (int i : live_) {
    const btRigidBody& body = *objects_[static_cast<std::size_t>(i)].body;
    const auto k = static_cast<std::size_t>(i);
    s.poses[k] = to_eigen(body.getWorldTransform());
    s.linear_velocity[k] = to_eigen(body.getLinearVelocity());
    s.angular_velocity[k] = to_eigen(body.getAngularVelocity());
  }
  removed_since_write_.clear();
  written_ = &s;
  written_slots_ = n;
}

}  // namespace somasim::bullet_world
