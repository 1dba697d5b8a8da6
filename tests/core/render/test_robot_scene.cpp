// The robot's scene: meshes from the RobotModel, cameras from its camera frames, id masks
// checked against render::Camera::project.
#include <gtest/gtest.h>

#include <cmath>

#include "somasim/error.hpp"
#include "somasim/render/context.hpp"
#include "somasim/render/robot_scene.hpp"
#include "somasim/render/scene_renderer.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/robot_loader.hpp"
#include "somasim/units.hpp"

namespace render = somasim::render;
namespace robot = somasim::robot;

namespace {

std::shared_ptr<const robot::RobotModel> icub() {
  static const auto m =
      robot::load_robot_model_shared(SOMASIM_SOURCE_DIR "/assets/robots/icub_v1.yaml");
  return m;
}

// Link poses at `posture` (joint name -> degrees), the other joints at 0.
std::vector<Eigen::Isometry3d> poses(const std::map<std::string, double>& posture = {}) {
  robot::RobotData data(*icub());
  Eigen::VectorXd q = Eigen::VectorXd::Zero(icub()->num_dofs());
  for (const auto& [joint, deg] : posture) q[icub()->dof_index(joint)] = somasim::deg_to_rad(deg);
  robot::forward_kinematics(*icub(), data, q);
  return data.link_poses;
}

// The right hand in front of the eyes (palm about 0.28 m ahead, near both image centres).
const std::map<std::string, double> kHandBeforeEyes = {
    {"r_shoulder_pitch", -90}, {"r_shoulder_roll", 5}, {"r_shoulder_yaw", 25}, {"r_elbow", 40}};

// Pixels of `ids` equal to `id`: count, centroid (u, v), bounding rectangle.
struct Blob {
  int count = 0;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  int u_min = 1 << 30, u_max = -1, v_min = 1 << 30, v_max = -1;
};
Blob blob(const cv::Mat& ids, std::int32_t id) {
  Blob b;
  for (int r = 0; r < ids.rows; ++r)
    for (int c = 0; c < ids.cols; ++c)
      if (ids.at<std::int32_t>(r, c) == id) {
        ++b.count;
        b.centroid += Eigen::Vector2d(c, r);
        b.u_min = std::min(b.u_min, c), b.u_max = std::max(b.u_max, c);
        b.v_min = std::min(b.v_min, r), b.v_max = std::max(b.v_max, r);
      }
  if (b.count) b.centroid /= b.count;
  return b;
}

struct Renderer {
  render::OsmesaContext context;
  render::SceneRenderer renderer{context.gl()};
  render::RobotScene scene{renderer, icub(), {32}};
};

}  // namespace

TEST(RobotScene, CameraFrameIsTheModelsCameraFrame) {
  const auto p = poses({{"neck_yaw", 20}, {"l_eye_pan", -10}});
  const render::Camera cam = render::camera_for(*icub(), "left_eye", p);
  const robot::Camera& model_cam = icub()->cameras()[icub()->find_camera("left_eye")];
  EXPECT_TRUE(cam.pose_root.isApprox(p[model_cam.link] * model_cam.pose, 1e-12));
  EXPECT_EQ(cam.name, "left_eye");
  EXPECT_EQ(cam.intrinsics.width, 320);
  EXPECT_EQ(cam.intrinsics.height, 240);
  EXPECT_DOUBLE_EQ(cam.intrinsics.fx, 257.34);
  EXPECT_DOUBLE_EQ(cam.intrinsics.cx, 160);
  // The eyes look forward: the iCub's front is -x of its root frame.
  EXPECT_LT(render::camera_for(*icub(), "right_eye", poses()).pose_root.linear()(0, 2), -0.9);
}

TEST(RobotScene, UnknownCameraListsTheModelsCameras) {
  try {
    render::camera_for(*icub(), "nose", poses());
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "camera 'nose' is not in robot 'icub_v1' (cameras: left_eye, right_eye)");
  }
}

TEST(RobotScene, WrongNumberOfLinkPosesIsAnError) {
  try {
    render::camera_for(*icub(), "left_eye", {});
    FAIL();
  } catch (const somasim::RunError& e) {
    EXPECT_EQ(std::string(e.what()),
              "link poses: expected " + std::to_string(icub()->num_links()) + ", got 0");
  }
}

TEST(RobotScene, SphereProjectsWhereTheCameraSays) {
  Renderer r;
  const auto p = poses({{"neck_pitch", -10}, {"neck_yaw", 15}});
  for (const char* eye : {"left_eye", "right_eye"}) {
    const render::Camera cam = render::camera_for(*icub(), eye, p);
    for (const Eigen::Vector3d& in_cam :
         {Eigen::Vector3d(0.03, -0.02, 0.45), Eigen::Vector3d(-0.08, 0.05, 0.6)}) {
      somasim::ObjectStates objects;
      objects.names = {"ball"};
      objects.present = {true};
      objects.shape = {somasim::ObjectShape::kSphere};
      objects.size = {Eigen::Vector3d(0.01, 0, 0)};
      objects.poses = {Eigen::Isometry3d(Eigen::Translation3d(cam.pose_root * in_cam))};
      std::vector<render::DrawItem> items;
      const Eigen::Vector3d viewpoint = cam.pose_root.translation();
      r.scene.add_robot(p, items, &viewpoint);
      r.scene.add_objects(objects, items);
      const auto images = r.renderer.render(items, cam);
      const Blob b = blob(images.ids, render::object_id(0));
      ASSERT_GT(b.count, 20) << eye;
      const Eigen::Vector2d expected = *cam.project(objects.poses[0].translation());
      EXPECT_LT((b.centroid - expected).norm(), 0.5) << eye << " " << in_cam.transpose();
    }
  }
}

TEST(RobotScene, RightHandBeforeTheEyesIsSeenByBothWithinItsProjectedBounds) {
  Renderer r;
  const auto p = poses(kHandBeforeEyes);
  const int hand = icub()->link_index("r_hand");
  EXPECT_GT(r.scene.triangle_count(), 1000u);  // includes the forearm cover mesh
  for (const char* eye : {"left_eye", "right_eye"}) {
    const render::Camera cam = render::camera_for(*icub(), eye, p);
    std::vector<render::DrawItem> items;
    const Eigen::Vector3d viewpoint = cam.pose_root.translation();
    r.scene.add_robot(p, items, &viewpoint);
    const auto images = r.renderer.render(items, cam);
    const Blob b = blob(images.ids, render::link_id(hand));
    EXPECT_GT(b.count, 1000) << eye;
    // Bounds of the hand's projected shapes (corners of each drawn shape's bounding box).
    double u0 = 1e9, u1 = -1e9, v0 = 1e9, v1 = -1e9;
    for (const robot::Geometry& g : icub()->link(hand).visual) {
      const render::Bounds box = render::bounds(render::geometry_mesh(g, 32));
      for (int k = 0; k < 8; ++k) {
        const Eigen::Vector3d corner((k & 1) ? box.max.x() : box.min.x(),
                                     (k & 2) ? box.max.y() : box.min.y(),
                                     (k & 4) ? box.max.z() : box.min.z());
        const auto uv = cam.project(p[hand] * g.origin * corner);
        ASSERT_TRUE(uv);
        u0 = std::min(u0, uv->x()), u1 = std::max(u1, uv->x());
        v0 = std::min(v0, uv->y()), v1 = std::max(v1, uv->y());
      }
    }
    EXPECT_GE(b.u_min, std::floor(u0)) << eye;
    EXPECT_LE(b.u_max, std::ceil(u1)) << eye;
    EXPECT_GE(b.v_min, std::floor(v0)) << eye;
    EXPECT_LE(b.v_max, std::ceil(v1)) << eye;
  }
}

// The green marker on the right index fingertip (a visual with its own colour) is drawn green,
// inside the disc where the camera projects it (centred on the frame r_index_tip; partly hidden
// by the fingers in this posture); the rest of the hand stays skin-coloured.
TEST(RobotScene, FingertipMarkerIsDrawnInItsOwnColour) {
  Renderer r;
  const auto p = poses(kHandBeforeEyes);
  const robot::Frame& tip =
      icub()->frames()[static_cast<std::size_t>(icub()->find_frame("r_index_tip"))];
  const Eigen::Vector3d tip_root = p[static_cast<std::size_t>(tip.link)] * tip.pose.translation();
  const double marker_radius = icub()->link(tip.link).visual.back().radius;
  for (const char* eye : {"left_eye", "right_eye"}) {
    const render::Camera cam = render::camera_for(*icub(), eye, p);
    std::vector<render::DrawItem> items;
    const Eigen::Vector3d viewpoint = cam.pose_root.translation();
    r.scene.add_robot(p, items, &viewpoint);
    const auto images = r.renderer.render(items, cam);
    const Eigen::Vector2d centre = *cam.project(tip_root);
    // Projected radius of the sphere (f r / z) and a pixel for the rasterisation.
    const double radius_px =
        cam.intrinsics.fx * marker_radius / (cam.to_camera(tip_root).z() - marker_radius) + 1.0;
    int green = 0, skin = 0, outside = 0;
    for (int row = 0; row < images.rgb.rows; ++row)
      for (int col = 0; col < images.rgb.cols; ++col) {
        const cv::Vec3b c = images.rgb.at<cv::Vec3b>(row, col);  // R, G, B
        if (c[1] > 2 * c[0] && c[1] > 2 * c[2]) {
          ++green;
          if ((Eigen::Vector2d(col, row) - centre).norm() > radius_px) ++outside;
        } else if (c[0] > c[1] && c[1] > c[2] && c[0] > 120) {
          ++skin;
        }
      }
    EXPECT_GT(green, 25) << eye;
    EXPECT_EQ(outside, 0) << eye;
    EXPECT_GT(skin, 10 * green) << eye;
  }
}
