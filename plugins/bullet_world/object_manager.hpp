#pragma once
/// @file
/// Objects of the world (spheres, boxes, cylinders, meshes) that are static, dynamic, kinematic
/// (moved at a constant velocity by setting their pose every step) or guided (dynamic bodies
/// pulled along the same constant-velocity path by a bounded force: see ObjectGuide). Objects
/// keep their index for the whole run; removed ones stay as empty slots
/// (ObjectStates::present = false). What runs every step (drive, the removals, write_states)
/// costs per object present, not per object ever spawned: a long run does not slow down.
///
/// Object frame: the shape's centre (mesh: the mesh file's origin). ObjectSpawn::size:
/// sphere (r, -, -); box half extents; cylinder (r, half height, -) along z; mesh: per-axis scale
/// (0 = 1). Poses and velocities in the root frame.
#include <functional>
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

/// The bounded-force servo that pulls a guided object along its path p*(t) = p0 + (t - t0) v:
/// a = bandwidth² (p* - p) + 2 bandwidth (v - v_body) (critically damped, feed-forward of the
/// path's velocity), F = mass · a with |F| <= max_force. In free space the body stays on the path
/// (it starts on it with the path's velocity); against the robot it presses with at most
/// max_force and never drives a joint without bound. Guided bodies feel no gravity and do not
/// rotate (a hand holds them).
struct ObjectGuide {
  double max_force = 5.0;    ///< [N]
  double bandwidth = 100.0;  ///< [1/s]; stable while bandwidth · dt stays well below 1
  /// Contact stiffness of guided objects [N/m] (0: rigid): a held object and the soft skin give
  /// way, so an object pressed with F sinks about F / stiffness into what it touches (critically
  /// damped with its mass).
  double contact_stiffness = 1000.0;
};

class ObjectManager {
 public:
  ObjectManager(btMultiBodyDynamicsWorld& world, ShapeStore& shapes, const ObjectMaterial& material,
                const ObjectGuide& guide = {});
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
  /// Removes dynamic and guided objects farther than `radius` [m] from the root; returns how
  /// many.
  int remove_beyond(double radius);
  /// Before a step from `t` to `t + dt` [s]: sets the poses kinematic objects reach at t + dt and
  /// applies the guide's force to guided objects.
  void drive(double t, double dt);
  /// Removes the present objects named `name`; returns how many.
  int remove_named(const std::string& name);

  int size() const { return static_cast<int>(objects_.size()); }
  /// Indices of the objects present, ascending.
  const std::vector<int>& live() const { return live_; }
  const std::string& name(int i) const { return objects_[i].name; }
  bool present(int i) const { return objects_[i].body != nullptr; }
  const btRigidBody& body(int i) const { return *objects_[i].body; }
  btRigidBody& body(int i) { return *objects_[i].body; }
  ObjectMotion motion(int i) const { return objects_[i].motion; }
  Eigen::Isometry3d pose(int i) const;

  /// Writes every object's state (removed ones keep their last state, present = false). Only
  /// what changed since the previous call into the same `states` is written (new slots, objects
  /// removed since, the present objects' motion); any other `states` is written whole.
  void write_states(ObjectStates& states);

 private:
  struct Object {
    std::string name;
    ObjectMotion motion = ObjectMotion::kDynamic;
    Eigen::Isometry3d start_pose = Eigen::Isometry3d::Identity();
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
    double mass = 0.0;  ///< [kg] (dynamic, guided)
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
  /// Removes the present objects for which `doomed(index)` holds; returns how many.
  int remove_if(const std::function<bool(int)>& doomed);

  btMultiBodyDynamicsWorld& world_;
  ShapeStore& shapes_;
  ObjectMaterial material_;
  ObjectGuide guide_;
  std::vector<Object> objects_;
  std::vector<int> live_;  // indices of present objects, ascending
  // write_states' bookkeeping: the states it last wrote, how many slots they hold, and the
  // objects removed since (their slots still show them present).
  const ObjectStates* written_ = nullptr;
  std::size_t written_slots_ = 0;
  std::vector<int> removed_since_write_;
};

}  // namespace somasim::bullet_world
