// Projection of the iCub's eye cameras over head and eye postures (neck pitch / roll / yaw, eye
// tilt / version / vergence), cameras from camera_for() posed by forward kinematics:
//   - a small sphere renders with its pixel centroid within 0.5 px of the pinhole projection of
//     its centre, in both eyes;
//   - every pixel of a plane at a known distance has the documented depth (metric z along the
//     optical axis, not the range along the ray) within 1 mm;
//   - the id mask of every visible link lies inside the projection of its bounding box.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "somasim/render/context.hpp"
#include "somasim/render/robot_scene.hpp"
#include "somasim/render/scene_renderer.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/robot_loader.hpp"
#include "somasim/units.hpp"

namespace render = somasim::render;
namespace robot = somasim::robot;
using somasim::deg_to_rad;

namespace {

std::shared_ptr<const robot::RobotModel> icub() {
  static const auto m =
      robot::load_robot_model_shared(SOMASIM_SOURCE_DIR "/assets/robots/icub_v1.yaml");
  return m;
}

// A head and eye posture [deg], as the iCub's head encoders give it.
struct HeadPosture {
  std::string name;
  double neck_pitch = 0, neck_roll = 0, neck_yaw = 0, eyes_tilt = 0, version = 0, vergence = 0;
};

const std::vector<HeadPosture> kPostures = {
    {"rest", 0, 0, 0, 0, 0, 0},
    {"down_left_converged", -20, 10, 25, -10, 10, 15},
    {"up_right_rolled", 15, -20, -30, 10, -20, 5},
    {"far_down_strong_vergence", -35, 30, 45, -25, 30, 20},
    {"near_limits", 25, -50, -50, 12, -40, 0},
};

void PrintTo(const HeadPosture& p, std::ostream* os) {
  *os << p.name;
}

// Link poses with the head at `head` and the right hand in front of the eyes.
std::vector<Eigen::Isometry3d> link_poses(const HeadPosture& head) {
  const robot::RobotModel& m = *icub();
  std::map<std::string, double> deg = {
      {"r_shoulder_pitch", -90},       {"r_shoulder_roll", 5},
      {"r_shoulder_yaw", 25},          {"r_elbow", 40},
      {"neck_pitch", head.neck_pitch}, {"neck_roll", head.neck_roll},
      {"neck_yaw", head.neck_yaw},     {"eyes_tilt", head.eyes_tilt}};
  const robot::EyePans pans = robot::eye_pans(head.version, head.vergence);
  deg["l_eye_pan"] = pans.left;
  deg["r_eye_pan"] = pans.right;
  Eigen::VectorXd q = Eigen::VectorXd::Zero(m.num_dofs());
  for (const auto& [joint, d] : deg) {
    const int i = m.dof_index(joint);
    q[i] = deg_to_rad(d);
    EXPECT_GE(q[i], m.lower_limits()[i]) << joint;  // the postures are reachable
    EXPECT_LE(q[i], m.upper_limits()[i]) << joint;
  }
  robot::RobotData data(m);
  robot::forward_kinematics(m, data, q);
  return data.link_poses;
}

// Renders, in both eyes, a square slab `extent` [m] wide and 1 mm thick whose centre is 0.6 m
// ahead on the optical axis, its normal tilted from the axis by 20° and 12°, covering the whole
// image; checks every pixel's depth against the ray-plane intersection's z within 1 mm.
void expect_plane_depth(render::SceneRenderer& renderer, const HeadPosture& head, double extent) {
  constexpr double kDistance = 0.6;    // [m] along the optical axis to the plane's centre
  constexpr double kThickness = 1e-3;  // [m]
  const render::MeshHandle slab =
      renderer.upload(render::tessellate_box(Eigen::Vector3d(extent, extent, kThickness)));
  const auto poses = link_poses(head);
  double worst = 0.0, largest_range_gap = 0.0, nearest_corner = 1e9;
  for (const char* eye : {"left_eye", "right_eye"}) {
    const render::Camera cam = render::camera_for(*icub(), eye, poses);
    const render::PinholeIntrinsics& k = cam.intrinsics;
    // The slab's z axis is its normal.
    Eigen::Isometry3d in_cam = Eigen::Isometry3d::Identity();
    in_cam.linear() = (Eigen::AngleAxisd(deg_to_rad(20), Eigen::Vector3d::UnitY()) *
                       Eigen::AngleAxisd(deg_to_rad(-12), Eigen::Vector3d::UnitX()))
                          .toRotationMatrix();
    in_cam.translation() = Eigen::Vector3d(0.02, -0.01, kDistance);
    for (int i = 0; i < 4; ++i)
      nearest_corner =
          std::min(nearest_corner, (in_cam * Eigen::Vector3d((i & 1 ? 0.5 : -0.5) * extent,
                                                             (i & 2 ? 0.5 : -0.5) * extent, 0))
                                       .z());
    const auto images = renderer.render({{slab, cam.pose_root * in_cam, {1, 1, 1}, 3}}, cam);
    // The face seen: normal n (away from the camera), through the centre moved by half the
    // thickness towards the camera.
    const Eigen::Vector3d n = in_cam.linear().col(2);
    const Eigen::Vector3d face = in_cam.translation() - 0.5 * kThickness * n;
    for (int r = 0; r < k.height; ++r)
      for (int c = 0; c < k.width; ++c) {
        ASSERT_EQ(images.ids.at<std::int32_t>(r, c), 3) << eye << " pixel " << c << ", " << r;
        const Eigen::Vector3d ray((c - k.cx) / k.fx, (r - k.cy) / k.fy, 1.0);  // z = 1
        const double z = n.dot(face) / n.dot(ray);
        const double depth = images.depth.at<float>(r, c);
        worst = std::max(worst, std::abs(depth - z));
        largest_range_gap = std::max(largest_range_gap, z * ray.norm() - z);
        ASSERT_NEAR(depth, z, 1e-3) << eye << " pixel " << c << ", " << r;
      }
  }
  // The test tells z from the range: they differ by far more than the tolerance at the corners.
  EXPECT_GT(largest_range_gap, 0.05);
  std::cout << head.name << ": " << extent << " m plane (nearest corner at z = " << nearest_corner
            << " m), worst |depth - z| " << worst * 1e3
            << " mm over every pixel of both eyes (range - z up to " << largest_range_gap * 1e3
            << " mm)\n";
}

class Projection : public ::testing::TestWithParam<HeadPosture> {
 protected:
  render::OsmesaContext context;
  render::SceneRenderer renderer{context.gl()};
};

}  // namespace

TEST_P(Projection, SmallSphereCentroidIsThePinholeProjectionInBothEyes) {
  constexpr double kRadius = 0.01;  // [m]
  const render::MeshHandle ball = renderer.upload(render::tessellate_sphere(kRadius, 48));
  const auto poses = link_poses(GetParam());
  const render::Camera left = render::camera_for(*icub(), "left_eye", poses);
  const render::Camera right = render::camera_for(*icub(), "right_eye", poses);
  // Points [m] in a frame between the eyes, its axes half way between theirs (x right, y down,
  // z ahead).
  Eigen::Isometry3d between = Eigen::Isometry3d::Identity();
  between.linear() = Eigen::Quaterniond(left.pose_root.linear())
                         .slerp(0.5, Eigen::Quaterniond(right.pose_root.linear()))
                         .toRotationMatrix();
  between.translation() = 0.5 * (left.pose_root.translation() + right.pose_root.translation());
  const std::vector<Eigen::Vector3d> points = {{0.0, 0.0, 0.5},     {0.06, -0.04, 0.4},
                                               {-0.1, 0.05, 0.7},   {0.03, 0.08, 0.35},
                                               {-0.05, -0.07, 0.8}, {0.12, 0.06, 0.6}};
  double worst = 0.0;
  for (const render::Camera& cam : {left, right})
    for (const Eigen::Vector3d& p : points) {
      const Eigen::Vector3d centre = between * p;
      const auto uv = cam.project(centre);
      ASSERT_TRUE(uv) << cam.name << " " << p.transpose();
      // Well inside the image (a test set-up check): the whole disc is drawn.
      ASSERT_TRUE(uv->x() > 20 && uv->x() < 300 && uv->y() > 20 && uv->y() < 220)
          << cam.name << " " << p.transpose() << ": " << uv->transpose();
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      pose.translation() = centre;
      const auto images = renderer.render({{ball, pose, {1, 1, 1}, 5}}, cam);
      double n = 0;
      Eigen::Vector2d sum = Eigen::Vector2d::Zero();
      for (int r = 0; r < images.ids.rows; ++r)
        for (int c = 0; c < images.ids.cols; ++c)
          if (images.ids.at<std::int32_t>(r, c) == 5) {
            n += 1;
            sum += Eigen::Vector2d(c, r);  // pixel (c, r) is centred at (u, v) = (c, r)
          }
      ASSERT_GT(n, 20) << cam.name << " " << p.transpose();
      const double error = (sum / n - *uv).norm();
      worst = std::max(worst, error);
      EXPECT_LT(error, 0.5) << cam.name << " " << p.transpose() << ": centroid "
                            << (sum / n).transpose() << ", projection " << uv->transpose();
    }
  std::cout << GetParam().name << ": worst sphere centroid error " << worst << " px over "
            << 2 * points.size() << " views\n";
}

TEST_P(Projection, DepthOfATiltedPlaneIsItsZAlongTheOpticalAxis) {
  expect_plane_depth(renderer, GetParam(), 1.6);  // all of it in front of the camera
}

TEST_P(Projection, DepthOfAPlaneReachingBehindTheCameraIsItsZ) {
  expect_plane_depth(renderer, GetParam(), 3.0);  // clipped by the near plane
}

TEST_P(Projection, EveryVisibleLinksMaskIsInsideItsProjectedBounds) {
  render::RobotScene scene(renderer, icub(), {16});
  const robot::RobotModel& m = *icub();
  const auto poses = link_poses(GetParam());
  int checked = 0;
  for (const char* eye : {"left_eye", "right_eye"}) {
    const render::Camera cam = render::camera_for(m, eye, poses);
    std::vector<render::DrawItem> items;
    const Eigen::Vector3d viewpoint = cam.pose_root.translation();
    scene.add_robot(poses, items, &viewpoint);
    const auto images = renderer.render(items, cam);
    for (int link = 0; link < m.num_links(); ++link) {
      const cv::Rect box = cv::boundingRect(images.ids == render::link_id(link));
      if (box.area() == 0) continue;
      // The link's mesh bounds (link frame): its projection covers the projection of the mesh
      // when all 8 corners are in front of the camera.
      const render::Bounds b =
          render::bounds(render::link_mesh(m, m.link(link).name, 16, render::LinkShapes::kVisual));
      double u0 = 1e9, u1 = -1e9, v0 = 1e9, v1 = -1e9;
      bool in_front = true;
      for (int i = 0; i < 8; ++i) {
        const Eigen::Vector3d corner((i & 1) ? b.max.x() : b.min.x(),
                                     (i & 2) ? b.max.y() : b.min.y(),
                                     (i & 4) ? b.max.z() : b.min.z());
        const Eigen::Vector3d root = poses[static_cast<std::size_t>(link)] * corner;
        if (cam.to_camera(root).z() <= cam.intrinsics.near) {
          in_front = false;
          break;
        }
        const Eigen::Vector2d uv = *cam.project(root);
        u0 = std::min(u0, uv.x()), u1 = std::max(u1, uv.x());
        v0 = std::min(v0, uv.y()), v1 = std::max(v1, uv.y());
      }
      if (!in_front) continue;
      // Pixel centres (c, r) covered by the link lie inside the projected bounds (up to the
      // rasterizer's sub-pixel snapping, < 0.01 px).
      const std::string what = std::string(eye) + " " + m.link(link).name;
      EXPECT_GE(box.x, u0 - 0.01) << what;
      EXPECT_LE(box.x + box.width - 1, u1 + 0.01) << what;
      EXPECT_GE(box.y, v0 - 0.01) << what;
      EXPECT_LE(box.y + box.height - 1, v1 + 0.01) << what;
      ++checked;
    }
  }
  // At least one link is seen (the right hand is in front of the eyes; some postures turn the
  // head away from it).
  EXPECT_GE(checked, 1);
  std::cout << GetParam().name << ": " << checked << " link masks checked\n";
}

INSTANTIATE_TEST_SUITE_P(HeadPostures, Projection, ::testing::ValuesIn(kPostures),
                         [](const ::testing::TestParamInfo<HeadPosture>& posture) {
                           return posture.param.name;
                         });
