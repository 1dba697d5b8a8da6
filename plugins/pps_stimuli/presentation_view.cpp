#include "presentation_view.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "somasim/numeric.hpp"
#include "somasim/robot/camera_view.hpp"

namespace somasim::plugins {

namespace {
// Spacing of the path points tested against the images [m]; the body is tested at the first,
// the middle and the last of them (the costly part of the test).
constexpr double kImageStep = 0.02;
constexpr int kMaxImageSteps = 100000;  // 2 km of path
}  // namespace

PresentationView::PresentationView(const robot::RobotModel& model, std::vector<int> cameras,
                                   double until, double margin_px)
    : model_(model), cameras_(std::move(cameras)), until_(until), margin_px_(margin_px) {}

std::optional<std::string> PresentationView::unseen(
    const std::vector<Eigen::Isometry3d>& link_poses, PresentationMotion motion,
    const Eigen::Vector3d& start, const Eigen::Vector3d& end, double reach) const {
  const double length = (end - start).norm();
  double checked = 0.0;  // length of the path that must be seen [m]
  if (motion == PresentationMotion::kApproach) checked = std::max(0.0, length - until_);
  if (motion == PresentationMotion::kReceding) checked = length;
  const int steps = to_integer_clamped<int>(checked / kImageStep, 0, kMaxImageSteps, Rounding::kUp);
  const Eigen::Vector3d direction =
      length > 0 ? Eigen::Vector3d((end - start) / length) : Eigen::Vector3d::Zero();
  const auto point = [&](int i) {
    const double s = steps == 0 ? 0.0 : checked * static_cast<double>(i) / steps;
    return std::pair<Eigen::Vector3d, double>(start + s * direction, length - s);
  };
  const auto report = [&](const robot::Camera& camera, robot::Sight sight, double to_end) {
    return fmt::format("'{}': {} {:.2f} m from the end of the path", camera.name,
                       robot::sight_name(sight), to_end);
  };
  for (const int c : cameras_) {
    const robot::Camera& camera = model_.cameras()[static_cast<std::size_t>(c)];
    const Eigen::Isometry3d pose = robot::camera_pose(camera, link_poses);
    for (int i = 0; i <= steps; ++i) {
      const auto [p, to_end] = point(i);
      const auto uv = robot::project_point(camera, pose, p);
      // The whole object where it appears, its centre afterwards.
      const double depth = (pose.inverse() * p).z();
      const double extent = i == 0 && uv ? camera.fx * reach / depth : 0.0;
      if (!uv || !robot::inside_image(camera, *uv, margin_px_ + extent))
        return report(camera, uv ? robot::Sight::kOutOfImage : robot::Sight::kBehind, to_end);
    }
  }
  for (const int c : cameras_) {
    const robot::Camera& camera = model_.cameras()[static_cast<std::size_t>(c)];
    for (const int i : {0, steps / 2, steps}) {
      const auto [p, to_end] = point(i);
      const robot::Sight sight = robot::camera_sight(model_, link_poses, camera, p, margin_px_);
      if (sight != robot::Sight::kSeen) return report(camera, sight, to_end);
    }
  }
  return std::nullopt;
}

}  // namespace somasim::plugins
