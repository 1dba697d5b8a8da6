#include "skin_link_shapes.hpp"

#include <cmath>
#include <limits>

#include "somasim/robot/clearance.hpp"

namespace somasim::plugins {

std::vector<robot::Geometry> shapes_beside_skin(
    const std::vector<robot::Geometry>& link_shapes,
    const std::vector<Eigen::Vector3d>& taxel_positions_link) {
  if (link_shapes.size() < 2 || taxel_positions_link.empty()) return {};
  std::size_t own = link_shapes.size();
  double least = std::numeric_limits<double>::infinity();
  for (std::size_t s = 0; s < link_shapes.size(); ++s) {
    if (link_shapes[s].type == robot::GeometryType::Mesh) continue;
    double sum = 0.0;
    for (const Eigen::Vector3d& p : taxel_positions_link)
      sum += std::abs(robot::distance_to_shape(link_shapes[s], p));
    const double mean = sum / static_cast<double>(taxel_positions_link.size());
    if (mean < least) {
      least = mean;
      own = s;
    }
  }
  std::vector<robot::Geometry> beside;
  for (std::size_t s = 0; s < link_shapes.size(); ++s)
    if (s != own) beside.push_back(link_shapes[s]);
  return beside;
}

}  // namespace somasim::plugins
