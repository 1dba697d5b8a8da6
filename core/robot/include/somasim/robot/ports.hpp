#pragma once
/// @file
/// Port value types of the robot and its world (bullet_world, skin, controllers, stimulus
/// sources): joint state and commands, link poses, contacts, objects. Joint vectors are in the
/// robot model's dof order (RobotModel::dof_joint); poses and vectors are in the root frame
/// unless a field says otherwise. Units: [m], [rad], [s], [N], [kg].
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "somasim/port_type.hpp"

namespace somasim {

/// Measured joint state of the whole robot.
struct JointState {
  Eigen::VectorXd position;  ///< [rad] (prismatic: [m]), size = number of dofs
  Eigen::VectorXd velocity;  ///< [rad/s]
};

/// What a controller asks of each joint.
enum class JointCommandMode : std::uint8_t { kNone = 0, kPosition = 1, kVelocity = 2 };

/// Joint commands for the whole robot; joints with mode kNone are left to other controllers
/// (a joint_command_mux merges several) or hold their last command.
struct JointCommand {
  std::vector<JointCommandMode> mode;  ///< per dof
  Eigen::VectorXd position;            ///< target [rad] where mode == kPosition
  Eigen::VectorXd velocity;  ///< target [rad/s] where mode == kVelocity (and feed-forward)
};

/// Poses of every link of the robot model, in link order.
struct LinkPoses {
  std::vector<Eigen::Isometry3d> poses;  ///< root <- link
};

/// One contact point between two bodies. A body is a robot link (`link` >= 0) or an object
/// (`object` >= 0, index into ObjectStates); exactly one of the two is set for each side.
struct Contact {
  int link_a = -1, object_a = -1;
  int link_b = -1, object_b = -1;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();       ///< on body a [m], root frame
  Eigen::Vector3d point_in_a = Eigen::Vector3d::Zero();  ///< the same point in a's frame [m]
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();     ///< unit, from b towards a, root frame
  double normal_force = 0.0;                             ///< [N], >= 0
  double time_s = 0.0;                                   ///< sim time of the contact [s]
};

/// Contact points of the current step, and of the recent past for consumers that run slower
/// than the world (a 50 Hz skin must not miss a 3 ms impact): `recent` holds every point of the
/// last `history` seconds in time order; consumers process the points newer than the last time
/// they saw.
struct Contacts {
  std::vector<Contact> points;
  std::vector<Contact> recent;
};

enum class ObjectShape : std::uint8_t { kSphere, kBox, kCylinder, kMesh };
/// How an object moves. kKinematic: along its path (pose + t · linear_velocity) whatever it meets,
/// pushing the robot without bound. kGuided: a dynamic body (its mass, no gravity, no rotation)
/// pulled along the same path by a bounded force (bullet_world's guide_max_force), as a hand
/// holds an object: it follows the path in free space and is stopped by what it meets.
enum class ObjectMotion : std::uint8_t { kStatic, kDynamic, kKinematic, kGuided };

/// A request to add an object to the world (consumed once per `id`).
struct ObjectSpawn {
  std::uint64_t id = 0;  ///< strictly increasing per producer
  std::string name;
  ObjectShape shape = ObjectShape::kSphere;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  ///< sphere: (r,-,-); box: half extents;
                                                   ///< cylinder: (r, half height, -) [m]
  std::string mesh;                                ///< mesh file for kMesh
  ObjectMotion motion = ObjectMotion::kDynamic;
  double mass = 0.1;                                          ///< [kg] (dynamic, guided)
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();     ///< initial pose, root frame
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();  ///< initial / path [m/s]
  double remove_after_s = 0.0;                                ///< > 0: removed after this long
};

/// Spawn requests of a producer (it prunes old ones; the world tracks ids it has seen).
struct ObjectSpawns {
  std::vector<ObjectSpawn> recent;
  /// Names of objects to remove now (e.g. withdrawn by the person holding them); a producer may
  /// list a name until the object is gone — removing an absent object does nothing.
  std::vector<std::string> withdraw;
};

/// State of every object in the world, in spawn order (removed objects keep their slot with
/// `present = false`, so indices stay valid).
struct ObjectStates {
  std::vector<std::string> names;
  std::vector<bool> present;
  std::vector<Eigen::Isometry3d> poses;
  std::vector<Eigen::Vector3d> linear_velocity;   ///< [m/s]
  std::vector<Eigen::Vector3d> angular_velocity;  ///< [rad/s]
  std::vector<double> radius;                     ///< bounding-sphere radius [m]
  /// The geometry each object was spawned with (as in ObjectSpawn), so that consumers other
  /// than the physics (a renderer, an evaluator) can draw or measure it.
  std::vector<ObjectShape> shape;
  std::vector<Eigen::Vector3d> size;  ///< as ObjectSpawn::size [m] (mesh: the scale)
  std::vector<std::string> mesh;      ///< mesh file for kMesh, else ""
};

template <>
struct PortTraits<JointState> {
  static constexpr const char* name = "joint_state";
  static constexpr const char* header = "somasim/robot/ports.hpp";
  static std::vector<std::string> csv_columns(const JointState& s) {
    std::vector<std::string> c;
    for (int i = 0; i < s.position.size(); ++i) c.push_back(fmt::format("q{} [rad]", i));
    for (int i = 0; i < s.velocity.size(); ++i) c.push_back(fmt::format("dq{} [rad/s]", i));
    return c;
  }
  static void csv_write(const JointState& s, std::string& row) {
    for (int i = 0; i < s.position.size(); ++i) csv_append(row, s.position[i]);
    for (int i = 0; i < s.velocity.size(); ++i) csv_append(row, s.velocity[i]);
  }
};
template <>
struct PortTraits<JointCommand> {
  static constexpr const char* name = "joint_command";
  static constexpr const char* header = "somasim/robot/ports.hpp";
};
template <>
struct PortTraits<LinkPoses> {
  static constexpr const char* name = "link_poses";
  static constexpr const char* header = "somasim/robot/ports.hpp";
};
template <>
struct PortTraits<Contacts> {
  static constexpr const char* name = "contacts";
  static constexpr const char* header = "somasim/robot/ports.hpp";
};
template <>
struct PortTraits<ObjectSpawns> {
  static constexpr const char* name = "object_spawns";
  static constexpr const char* header = "somasim/robot/ports.hpp";
};
template <>
struct PortTraits<ObjectStates> {
  static constexpr const char* name = "object_states";
  static constexpr const char* header = "somasim/robot/ports.hpp";
};

}  // namespace somasim
