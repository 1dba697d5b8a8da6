#include "somasim/robot/camera_view.hpp"

#include "somasim/robot/clearance.hpp"

namespace somasim::robot {

namespace {
// Links this close to the optical centre [m] carry the camera and are not occluders.
constexpr double kCarrierDistance = 0.03;
}  // namespace

Eigen::Isometry3d camera_pose(const Camera& camera,
                              const std::vector<Eigen::Isometry3d>& link_poses) {
  return link_poses.at(static_cast<std::size_t>(camera.link)) * camera.pose;
}

std::optional<Eigen::Vector2d> project_point(const Camera& camera, const Eigen::Isometry3d& pose,
                                             const Eigen::Vector3d& point) {
  const Eigen::Vector3d p = pose.inverse() * point;
  if (!(p.z() > std::max(camera.near, 1e-6))) return std::nullopt;
  return Eigen::Vector2d(camera.cx + camera.fx * p.x() / p.z(),
                         camera.cy + camera.fy * p.y() / p.z());
}

bool inside_image(const Camera& camera, const Eigen::Vector2d& uv, double margin_px) {
  return uv.x() >= margin_px - 0.5 && uv.x() <= camera.width - 0.5 - margin_px &&
         uv.y() >= margin_px - 0.5 && uv.y() <= camera.height - 0.5 - margin_px;
}

Sight camera_sight(const RobotModel& model, const std::vector<Eigen::Isometry3d>& link_poses,
                   const Camera& camera, const Eigen::Vector3d& point, double margin_px) {
  if (link_poses.size() != static_cast<std::size_t>(model.num_links())) return Sight::kBehind;
  const Eigen::Isometry3d pose = camera_pose(camera, link_poses);
  const auto uv = project_point(camera, pose, point);
  if (!uv) return Sight::kBehind;
  if (camera.far > 0 && (pose.inverse() * point).z() > camera.far) return Sight::kBehind;
  if (!inside_image(camera, *uv, margin_px)) return Sight::kOutOfImage;
  const Eigen::Vector3d centre = pose.translation();
  std::vector<int> carriers;
  for (int l = 0; l < model.num_links(); ++l) {
    const Eigen::Isometry3d link_from_root = link_poses[static_cast<std::size_t>(l)].inverse();
    for (const auto& g : model.link(l).collision)
      if (distance_to_shape(g, link_from_root * centre) < kCarrierDistance) {
        carriers.push_back(l);
        break;
      }
  }
  return segment_clear_of_robot(model, link_poses, centre, point, 0.0, carriers)
             ? Sight::kSeen
             : Sight::kHiddenByBody;
}

const char* sight_name(Sight sight) {
  switch (sight) {
    case Sight::kSeen:
      return "seen";
    case Sight::kBehind:
      return "behind the camera";
    case Sight::kOutOfImage:
      return "outside the image";
    case Sight::kHiddenByBody:
      return "hidden by the robot's body";
  }
  return "unknown";
}

}  // namespace somasim::robot
