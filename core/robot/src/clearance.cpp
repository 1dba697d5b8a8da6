#include "somasim/robot/clearance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "somasim/numeric.hpp"
#include "somasim/robot/shape_distance.hpp"

namespace somasim::robot {
namespace {

// The radius [m] of a sphere about a primitive's origin that holds it; +infinity for meshes.
double bounding_radius(const Geometry& g) {
  switch (g.type) {
    case GeometryType::Sphere:
      return g.radius;
    case GeometryType::Box:
      return 0.5 * g.size.norm();
    case GeometryType::Cylinder:
      return std::hypot(g.radius, 0.5 * g.length);
    case GeometryType::Capsule:
      return g.radius + 0.5 * g.length;
    case GeometryType::Mesh:
      break;
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace

bool point_clear_of_robot(const RobotModel& model, const std::vector<Eigen::Isometry3d>& link_poses,
                          const Eigen::Vector3d& point, double margin) {
  if (link_poses.size() != static_cast<std::size_t>(model.num_links())) return true;
  for (int l = 0; l < model.num_links(); ++l)
    for (const auto& g : model.link(l).collision) {
      const double bound = bounding_radius(g);
      if (!std::isfinite(bound)) continue;  // a mesh
      const Eigen::Vector3d centre =
          link_poses[static_cast<std::size_t>(l)] * g.origin.translation();
      if ((point - centre).norm() < bound + margin) return false;
    }
  return true;
}

double distance_to_shape(const Geometry& g, const Eigen::Vector3d& point) {
  const Eigen::Vector3d p = g.origin.inverse() * point;
  switch (g.type) {
    case GeometryType::Sphere:
      return p.norm() - g.radius;
    case GeometryType::Box: {
      const Eigen::Vector3d q = p.cwiseAbs() - 0.5 * g.size;
      return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
    }
    case GeometryType::Cylinder: {
      const Eigen::Vector2d q(p.head<2>().norm() - g.radius, std::abs(p.z()) - 0.5 * g.length);
      return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
    }
    case GeometryType::Capsule: {
      const double z = std::clamp(p.z(), -0.5 * g.length, 0.5 * g.length);
      return (p - Eigen::Vector3d(0, 0, z)).norm() - g.radius;
    }
    case GeometryType::Mesh:
      break;
  }
  return std::numeric_limits<double>::infinity();
}

bool segment_clear_of_robot(const RobotModel& model,
                            const std::vector<Eigen::Isometry3d>& link_poses,
                            const Eigen::Vector3d& from, const Eigen::Vector3d& to, double margin,
                            std::span<const int> ignored_links) {
  if (link_poses.size() != static_cast<std::size_t>(model.num_links())) return true;
  constexpr double kStep = 0.002;       // [m]
  constexpr int kMaxSamples = 1000000;  // 2 km of path
  const int samples =
      1 + to_integer_clamped<int>((to - from).norm() / kStep, 0, kMaxSamples, Rounding::kUp);
  // Every sample is tested, but not every sample is evaluated: distance_to_shape is an exact
  // distance (1-Lipschitz), so the samples closer to an evaluated one than its distance minus the
  // margin are clear too and are skipped (slightly fewer, for rounding).
  const double spacing = (to - from).norm() / samples;
  for (int l = 0; l < model.num_links(); ++l) {
    if (std::find(ignored_links.begin(), ignored_links.end(), l) != ignored_links.end()) continue;
    const Eigen::Isometry3d link_from_root = link_poses[static_cast<std::size_t>(l)].inverse();
    for (const auto& g : model.link(l).collision)
      for (int i = 0; i <= samples;) {
        const Eigen::Vector3d p = from + (to - from) * (static_cast<double>(i) / samples);
        const double d = distance_to_shape(g, link_from_root * p);
        if (d <= margin) return false;
        if (!std::isfinite(d)) break;  // a shape without a distance (a mesh)
        const double clear_samples = spacing > 0.0 ? 0.999 * (d - margin) / spacing : 0.0;
        i += clear_samples >= samples ? samples + 1
                                      : std::max(1, static_cast<int>(std::ceil(clear_samples)));
      }
  }
  return true;
}

std::vector<CoverSphere> sphere_cover(ObjectShape shape, const Eigen::Vector3d& size) {
  std::vector<CoverSphere> out;
  switch (shape) {
    case ObjectShape::kSphere:
      out.push_back({Eigen::Vector3d::Zero(), size.x()});
      break;
    case ObjectShape::kBox:
      for (const double x : {-0.5, 0.5})
        for (const double y : {-0.5, 0.5})
          for (const double z : {-0.5, 0.5})
            out.push_back(
                {Eigen::Vector3d(x * size.x(), y * size.y(), z * size.z()), 0.5 * size.norm()});
      break;
    case ObjectShape::kCylinder: {
      const double r = size.x(), half = size.y();
      const int n = to_integer_clamped<int>(2.0 * half / r, 1, 10000, Rounding::kUp);
      const double piece = 2.0 * half / n;  // length each sphere holds
      for (int i = 0; i < n; ++i)
        out.push_back(
            {Eigen::Vector3d(0, 0, -half + (i + 0.5) * piece), std::hypot(r, 0.5 * piece)});
      break;
    }
    case ObjectShape::kMesh:
      break;
  }
  return out;
}

bool object_path_clear_of_robot(const RobotModel& model,
                                const std::vector<Eigen::Isometry3d>& link_poses,
                                std::span<const CoverSphere> cover, const Eigen::Matrix3d& rotation,
                                const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                                double clearance, std::span<const int> ignored_links) {
  for (const CoverSphere& s : cover) {
    const Eigen::Vector3d offset = rotation * s.centre;
    if (!segment_clear_of_robot(model, link_poses, from + offset, to + offset, s.radius + clearance,
                                ignored_links))
      return false;
  }
  return true;
}

std::optional<Geometry> object_geometry(ObjectShape shape, const Eigen::Vector3d& size) {
  Geometry g;
  switch (shape) {
    case ObjectShape::kSphere:
      g.type = GeometryType::Sphere;
      g.radius = size.x();
      return g;
    case ObjectShape::kBox:
      g.type = GeometryType::Box;
      g.size = 2.0 * size;
      return g;
    case ObjectShape::kCylinder:
      g.type = GeometryType::Cylinder;
      g.radius = size.x();
      g.length = 2.0 * size.y();
      return g;
    case ObjectShape::kMesh:
      break;
  }
  return std::nullopt;
}

bool object_path_clear_of_shapes(const Geometry& object, const Eigen::Matrix3d& rotation,
                                 const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                                 std::span<const Geometry> shapes,
                                 const Eigen::Isometry3d& link_pose, double clearance) {
  constexpr double kStep = 0.002;       // [m]
  constexpr int kMaxSamples = 1000000;  // 2 km of path
  const double length = (to - from).norm();
  const int samples = 1 + to_integer_clamped<int>(length / kStep, 0, kMaxSamples, Rounding::kUp);
  const double spacing = length / samples;
  const double bound = bounding_radius(object);
  const Eigen::Isometry3d link_from_root = link_pose.inverse();
  const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();
  // The distance [m] between the object at sample i and `shape`, or a lower bound of it above
  // the clearance: the object's bounding sphere's distance, exact distances only near the shape.
  const auto distance = [&](const Geometry& shape, int i) {
    const Eigen::Vector3d centre = from + (to - from) * (static_cast<double>(i) / samples);
    const Eigen::Vector3d object_centre = centre + rotation * object.origin.translation();
    const double lower = distance_to_shape(shape, link_from_root * object_centre) - bound;
    if (lower > clearance) return lower;
    Geometry placed = object;
    placed.origin = Eigen::Isometry3d::Identity();
    placed.origin.translate(centre);
    placed.origin.rotate(rotation);
    placed.origin = placed.origin * object.origin;
    return shape_distance(placed, identity, shape, link_pose);
  };
  for (const Geometry& shape : shapes) {
    if (shape.type == GeometryType::Mesh) continue;
    // The end first: where an object aimed at the skin beside the shape comes closest to it.
    if (distance(shape, samples) <= clearance) return false;
    for (int i = 0; i < samples;) {
      const double d = distance(shape, i);
      if (d <= clearance) return false;
      // Distances between solids change no faster than one of them moves.
      const double clear_samples = spacing > 0.0 ? 0.999 * (d - clearance) / spacing : 0.0;
      i += clear_samples >= samples ? samples + 1
                                    : std::max(1, static_cast<int>(std::ceil(clear_samples)));
    }
  }
  return true;
}

}  // namespace somasim::robot
