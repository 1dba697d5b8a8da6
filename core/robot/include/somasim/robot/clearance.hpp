#pragma once
/// @file
/// A conservative test of whether a point is clear of the robot's collision geometry, e.g. to
/// start a thrown object outside the robot.
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Geometry>

#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_model.hpp"

namespace somasim::robot {

/// True when `point` [m, root frame] is farther than `margin` [m] from every collision shape of
/// the robot posed by `link_poses` (root <- link, model link order). Each shape is bounded by a
/// sphere around its origin (sphere: r; box: half diagonal; cylinder: hypot(r, length/2);
/// capsule: r + length/2; mesh: not bounded), so the test errs on the side of "not clear".
/// With a wrong number of poses it returns true (nothing to test against).
bool point_clear_of_robot(const RobotModel& model, const std::vector<Eigen::Isometry3d>& link_poses,
                          const Eigen::Vector3d& point, double margin);

/// Distance [m] from `point` (in the frame of the link that owns `shape`) to the primitive
/// `shape`: positive outside, negative inside (the depth). Meshes: +infinity (not modelled).
double distance_to_shape(const Geometry& shape, const Eigen::Vector3d& point);

/// True when the straight segment `from` -> `to` [m, root frame], sampled every 2 mm, stays
/// farther than `margin` [m] from every collision shape of the links not in `ignored_links`
/// (model link indices), the robot posed by `link_poses`; meshes are not tested. E.g. the path
/// of an object's centre to the taxel it is aimed at, margin = the object's bounding radius, the
/// aimed link ignored: nothing else is in its way. With a wrong number of poses it returns true.
bool segment_clear_of_robot(const RobotModel& model,
                            const std::vector<Eigen::Isometry3d>& link_poses,
                            const Eigen::Vector3d& from, const Eigen::Vector3d& to, double margin,
                            std::span<const int> ignored_links = {});

/// One sphere of a cover: centre [m] in the object's frame, radius [m].
struct CoverSphere {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0.0;
};

/// Spheres whose union holds an object of `shape` and `size` (as ObjectSpawn::size: sphere
/// (r), box half extents, cylinder (r, half height) along z), in the object's frame: tighter
/// than one bounding sphere for elongated shapes (a cylinder: one sphere per radius of its
/// length; a box: its eight octants). Meshes: empty (not bounded).
std::vector<CoverSphere> sphere_cover(ObjectShape shape, const Eigen::Vector3d& size);

/// True when an object (its `cover`, turned into the root frame by `rotation`) moved with its
/// centre along `from` -> `to` [m, root frame] stays farther than `clearance` [m] from every
/// collision shape of the links not in `ignored_links` (segment_clear_of_robot per sphere).
bool object_path_clear_of_robot(const RobotModel& model,
                                const std::vector<Eigen::Isometry3d>& link_poses,
                                std::span<const CoverSphere> cover, const Eigen::Matrix3d& rotation,
                                const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                                double clearance, std::span<const int> ignored_links = {});

/// The collision primitive an object of `shape` and `size` (as ObjectSpawn::size) is, centred on
/// the object's frame (a cylinder along its z); nullopt for meshes.
std::optional<Geometry> object_geometry(ObjectShape shape, const Eigen::Vector3d& size);

/// True when `object` (a primitive in the object's frame, e.g. object_geometry's, turned into the
/// root frame by `rotation`) moved with its centre along `from` -> `to` [m, root frame] stays
/// farther than `clearance` [m] from each of `shapes` (primitives of one link posed by
/// `link_pose`: root <- link). Exact surface distances (shape_distance) at samples 2 mm apart,
/// those closer to an evaluated sample than its distance minus the clearance skipped; meshes are
/// not tested. Unlike object_path_clear_of_robot's cover of spheres this is not inflated: it
/// tells an object that passes 1 mm from a shape from one that touches it.
bool object_path_clear_of_shapes(const Geometry& object, const Eigen::Matrix3d& rotation,
                                 const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                                 std::span<const Geometry> shapes,
                                 const Eigen::Isometry3d& link_pose, double clearance);

}  // namespace somasim::robot
