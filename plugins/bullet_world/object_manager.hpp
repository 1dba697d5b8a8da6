#pragma once
/// @file
/// Objects of the world (spheres, boxes, cylinders, meshes) that are static, dynamic, or
/// kinematic (moved at a constant velocity by setting their pose every step). Objects keep their
/// index for the whole run; removed ones stay as empty slots (ObjectStates::present = false).
///
/// Object frame: the shape's centre (mesh: the mesh file's origin). ObjectSpawn::size:
/// sphere (r, -, -); box half extents; cylinder (r, half height, -) along z; mesh: per-axis scale
/// (0 = 1). Poses and velocities in the root frame.
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <BulletDynamics/Dynamics/btRigidBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <LinearMath/btDefaultMotionState.h>

#include "collision_shapes.hpp"
#include "somasim/robot/ports.hpp"

namespace somasim::bullet_world {

struct ObjectMaterial {
  double friction = 0.8;
  double rolling_friction = 0.0;  ///< [m]
  double restitution = 0.0;
};

class ObjectManager {
 public:
  ObjectManager(btMultiBodyDynamicsWorld& world, ShapeStore& shapes,
                const ObjectMaterial& material);
  ~ObjectManager();
  ObjectManager(const ObjectManager&) = delete;
  ObjectManager& operator=(const ObjectManager&) = delete;

  /// Adds an object at time `t` [s] (spawn must be valid: see robot::spawn_problem); returns its
  /// index. Meshes may throw InputError (unreadable file).
  int add(const ObjectSpawn& spawn, double t);
  /// Removes an object (its slot stays).
  void remove(int index);
  /// Removes objects whose lifetime ended by time `t`; returns how many.
  int remove_expired(double t);
  /// Removes dynamic objects farther than `radius` [m] from the root; returns how many.
  int remove_beyond(double radius);
  /// Sets the poses kinematic objects must reach at `t_next` [s] (call before stepping).
  void move_kinematic(double t_next);
  /// Removes the present objects named `name`; returns how many.
  int remove_named(const std::string& name);

  int size() const { return static_cast<int>(objects_.size()); }
  const std::string& name(int i) const { return objects_[i].name; }
  bool present(int i) const { return objects_[i].body != nullptr; }
  const btRigidBody& body(int i) const { return *objects_[i].body; }
  btRigidBody& body(int i) { return *objects_[i].body; }
  ObjectMotion motion(int i) const { return objects_[i].motion; }
  Eigen::Isometry3d pose(int i) const;

  /// Writes every object's state (removed ones keep their last state, present = false).
  void write_states(ObjectStates& states) const;

 private:
  struct Object {
    std::string name;
    ObjectMotion motion = ObjectMotion::kDynamic;
    Eigen::Isometry3d start_pose = Eigen::Isometry3d::Identity();
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
    double spawn_time = 0.0;
    double remove_time = std::numeric_limits<double>::infinity();
    double radius = 0.0;
    ObjectShape shape = ObjectShape::kSphere;
    Eigen::Vector3d size = Eigen::Vector3d::Zero();
    std::string mesh;
    std::unique_ptr<btDefaultMotionState> motion_state;
    std::unique_ptr<btRigidBody> body;
    Eigen::Isometry3d last_pose = Eigen::Isometry3d::Identity();
    Eigen::Vector3d last_linear = Eigen::Vector3d::Zero();
    Eigen::Vector3d last_angular = Eigen::Vector3d::Zero();
  };
  btMultiBodyDynamicsWorld& world_;
  ShapeStore& shapes_;
  ObjectMaterial material_;
  std::vector<Object> objects_;
};

}  // namespace somasim::bullet_world
