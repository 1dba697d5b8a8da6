#pragma once
/// @file
/// The immutable robot model: a kinematic tree of links connected by joints, with geometry,
/// mass, named frames, cameras and skin patches. Per-use state (joint values, offsets, link
/// poses) lives in RobotData; it and the algorithms (free functions) are in kinematics.hpp.
///
/// Frames: every pose is in the root frame unless stated otherwise. For the iCub the root frame is
/// the waist frame of the iCub's kinematics (iKin DH tables): x backward, y to the robot's right,
/// z up.
/// Units: [m], [rad] (prismatic joints: [m]), [kg].
///
/// Joint transform (child link pose from parent link pose):
///   T_child = T_parent · pre · M(q + offset) · post
/// where M is a rotation about `axis` (revolute), a translation along `axis` (prismatic) or the
/// identity (fixed). URDF joints are pre = origin, post = I; standard DH links (iKin) are
/// pre = I, axis = z, post = Tz(d)·Tx(a)·Rx(alpha).
#include <map>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "somasim/robot/geometry.hpp"

namespace somasim::robot {

enum class JointType { Revolute, Prismatic, Fixed };

/// "revolute", "prismatic", "fixed".
std::string_view joint_type_name(JointType type);

struct Joint {
  std::string name;
  JointType type = JointType::Fixed;
  int parent_link = -1;
  int child_link = -1;
  Eigen::Isometry3d pre = Eigen::Isometry3d::Identity();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  ///< unit vector in the frame after `pre`
  double offset = 0.0;                              ///< added to q [rad] or [m]
  Eigen::Isometry3d post = Eigen::Isometry3d::Identity();
  double lower = 0.0;  ///< limit on q (without offset) [rad] or [m]
  double upper = 0.0;
  int dof = -1;  ///< index into the joint-value vector; -1 for fixed joints
};

struct Link {
  std::string name;
  int parent_joint = -1;  ///< -1 only for the root (link 0)
  int parent_link = -1;
  std::vector<Geometry> collision;
  std::vector<Geometry> visual;
  Inertial inertial;
};

/// A named frame rigidly attached to a link (palm, fingertips, skin frames, chain tips).
struct Frame {
  std::string name;
  int link = -1;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< in the link frame
};

/// A pinhole camera. Camera frame: z optical axis, x image-right, y image-down;
/// u = fx·x/z + cx, v = fy·y/z + cy [px].
struct Camera {
  std::string name;
  int link = -1;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< camera frame in the link frame
  double fx = 0, fy = 0, cx = 0, cy = 0;                   ///< [px]
  int width = 0, height = 0;                               ///< [px]
  double near = 0, far = 0;                                ///< clipping distances [m]
};

/// Raw description of a skin patch for the skin layout generator: the surface kind
/// ("cylinder" or "box_face"), its pose in the link frame and its numeric parameters exactly as
/// written in the robot description (keys ending in _deg are degrees, the others SI units).
struct SkinPatch {
  std::string body_part;  ///< e.g. "left_forearm"
  int link = -1;
  std::string surface;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  ///< surface frame in the link frame
  std::map<std::string, double> params;
};

/// A named serial chain of the description (e.g. an iKin DH chain): base link → tip frame.
struct ChainInfo {
  std::string name;
  int base_link = 0;
  std::string tip_frame;            ///< name of the frame at the end of the chain (after HN)
  std::vector<std::string> joints;  ///< movable joints from base to tip
};

/// A link, or a frame given by a link and a pose in it.
struct FrameRef {
  int link = -1;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< in the link frame
};

class RobotModel {
 public:
  /// Takes validated parts (the loader reports bad input); structural invariants are checked
  /// with SOMASIM_CHECK: link 0 is the root, links are in topological order (parent before
  /// child), each non-root link has exactly one parent joint, dofs are 0..n-1.
  RobotModel(std::string name, std::vector<Link> links, std::vector<Joint> joints,
             std::vector<Frame> frames, std::vector<Camera> cameras,
             std::vector<SkinPatch> skin_patches, std::vector<ChainInfo> chains);

  const std::string& name() const { return name_; }
  int num_links() const { return static_cast<int>(links_.size()); }
  int num_joints() const { return static_cast<int>(joints_.size()); }
  /// Size of the joint-value vector q (movable joints).
  int num_dofs() const { return static_cast<int>(dof_joints_.size()); }

  const std::vector<Link>& links() const { return links_; }
  const std::vector<Joint>& joints() const { return joints_; }
  const std::vector<Frame>& frames() const { return frames_; }
  const std::vector<Camera>& cameras() const { return cameras_; }
  const std::vector<SkinPatch>& skin_patches() const { return skin_patches_; }
  const std::vector<ChainInfo>& chains() const { return chains_; }
  const Link& link(int i) const { return links_.at(i); }
  const Joint& joint(int i) const { return joints_.at(i); }
  /// Joint index of dof `d`.
  int dof_joint(int d) const { return dof_joints_.at(d); }

  /// Indices, or -1 when absent.
  int find_link(const std::string& name) const;
  int find_joint(const std::string& name) const;
  int find_frame(const std::string& name) const;
  int find_camera(const std::string& name) const;
  const ChainInfo* find_chain(const std::string& name) const;

  /// Indices; throw InputError "robot 'r': unknown link 'x' (did you mean 'y'?)" when absent.
  int link_index(const std::string& name) const;
  int joint_index(const std::string& name) const;
  /// Dof index of a movable joint (InputError for unknown or fixed joints).
  int dof_index(const std::string& joint_name) const;
  /// A frame or a link by name (frames first); InputError when neither exists.
  FrameRef frame_ref(const std::string& name) const;

  /// Movable-joint (dof) indices that move `link`, from the root outwards.
  const std::vector<int>& supporting_dofs(int link) const { return supporting_dofs_.at(link); }
  /// Lower/upper limits of all dofs [rad] or [m].
  const Eigen::VectorXd& lower_limits() const { return lower_; }
  const Eigen::VectorXd& upper_limits() const { return upper_; }
  /// Sum of the link masses [kg].
  double total_mass() const;

 private:
  std::string name_;
  std::vector<Link> links_;
  std::vector<Joint> joints_;
  std::vector<Frame> frames_;
  std::vector<Camera> cameras_;
  std::vector<SkinPatch> skin_patches_;
  std::vector<ChainInfo> chains_;
  std::vector<int> dof_joints_;
  std::vector<std::vector<int>> supporting_dofs_;
  Eigen::VectorXd lower_, upper_;
};

}  // namespace somasim::robot
