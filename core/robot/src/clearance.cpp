#include "somasim/robot/clearance.hpp"

#include <cmath>

namespace somasim::robot {

bool point_clear_of_robot(const RobotModel& model, const std::vector<Eigen::Isometry3d>& link_poses,
                          const Eigen::Vector3d& point, double margin) {
  if (link_poses.size() != static_cast<std::size_t>(model.num_links())) return true;
  for (int l = 0; l < model.num_links(); ++l)
    for (const auto& g : model.link(l).collision) {
      double bound = 0.0;
      switch (g.type) {
        case GeometryType::Sphere:
          bound = g.radius;
          break;
        case GeometryType::Box:
          bound = 0.5 * g.size.norm();
          break;
        case GeometryType::Cylinder:
          bound = std::hypot(g.radius, 0.5 * g.length);
          break;
        case GeometryType::Capsule:
          bound = g.radius + 0.5 * g.length;
          break;
        case GeometryType::Mesh:
          continue;
      }
      const Eigen::Vector3d centre =
          link_poses[static_cast<std::size_t>(l)] * g.origin.translation();
      if ((point - centre).norm() < bound + margin) return false;
    }
  return true;
}

}  // namespace somasim::robot
