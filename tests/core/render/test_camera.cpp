// Pinhole camera: the GL matrices reproduce project(), the camera-frame convention, clipping
// depths and intrinsics validation.
#include <gtest/gtest.h>

#include <cmath>

#include "somasim/error.hpp"
#include "somasim/render/camera.hpp"

using namespace somasim;
using namespace somasim::render;

namespace {

Camera test_camera() {
  Camera c;
  c.name = "left_eye";
  c.intrinsics = {320, 240, 300.0, 310.0, 161.5, 118.25, 0.05, 5.0};
  c.pose_root.translation() = Eigen::Vector3d(0.1, -0.2, 0.3);
  c.pose_root.linear() = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) *
                          Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitY()) *
                          Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()))
                             .toRotationMatrix();
  return c;
}

// Pixel (u, v) where GL puts a root point: clip -> NDC -> window, window row 0 = image row 0,
// pixel centres at window (c + 0.5, r + 0.5).
Eigen::Vector3d through_gl(const Camera& c, const Eigen::Vector3d& p) {
  const Eigen::Vector4d clip = c.view_projection() * p.homogeneous();
  const Eigen::Vector3d ndc = clip.head<3>() / clip.w();
  return {(ndc.x() + 1) / 2 * c.intrinsics.width - 0.5,
          (ndc.y() + 1) / 2 * c.intrinsics.height - 0.5, ndc.z()};
}

}  // namespace

TEST(Camera, GlMatricesReproduceThePinholeProjection) {
  const Camera c = test_camera();
  for (const Eigen::Vector3d& cam :
       {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0.2, -0.1, 0.7), Eigen::Vector3d(-0.5, 0.4, 3)}) {
    const Eigen::Vector3d root = c.pose_root * cam;
    const auto uv = c.project(root);
    ASSERT_TRUE(uv);
    EXPECT_NEAR((*uv).x(), 300.0 * cam.x() / cam.z() + 161.5, 1e-9);
    EXPECT_NEAR((*uv).y(), 310.0 * cam.y() / cam.z() + 118.25, 1e-9);
    const Eigen::Vector3d gl = through_gl(c, root);
    EXPECT_NEAR(gl.x(), (*uv).x(), 1e-9);
    EXPECT_NEAR(gl.y(), (*uv).y(), 1e-9);
  }
}

TEST(Camera, NearAndFarPlanesMapToTheDepthRange) {
  const Camera c = test_camera();
  EXPECT_NEAR(through_gl(c, c.pose_root * Eigen::Vector3d(0.01, 0.02, 0.05)).z(), -1.0, 1e-9);
  EXPECT_NEAR(through_gl(c, c.pose_root * Eigen::Vector3d(0.3, -0.2, 5.0)).z(), 1.0, 1e-9);
}

TEST(Camera, FrameIsXRightYDownZForward) {
  Camera c;
  c.intrinsics = {100, 100, 100.0, 100.0, 50.0, 50.0, 0.1, 10.0};
  // Looking along root +x with root z up: camera x = root -y, camera y = root -z.
  Eigen::Matrix3d r;
  r.col(0) = -Eigen::Vector3d::UnitY();
  r.col(1) = -Eigen::Vector3d::UnitZ();
  r.col(2) = Eigen::Vector3d::UnitX();
  c.pose_root.linear() = r;
  EXPECT_TRUE(c.project({2, 0, 0})->isApprox(Eigen::Vector2d(50, 50)));
  EXPECT_LT(c.project({2, -0.5, 0})->x(), 100.0);  // root -y: to the right
  EXPECT_GT(c.project({2, -0.5, 0})->x(), 50.0);
  EXPECT_LT(c.project({2, 0, 0.5})->y(), 50.0);  // up in the world: towards row 0
  EXPECT_FALSE(c.project({-1, 0, 0}));           // behind
  EXPECT_TRUE(c.to_camera({2, 0, 0}).isApprox(Eigen::Vector3d(0, 0, 2)));
  // GL eye frame: z backward, so the point ahead is at z_eye = -2.
  const Eigen::Vector4d eye = view_matrix(c.pose_root) * Eigen::Vector4d(2, 0, 0, 1);
  EXPECT_TRUE(eye.isApprox(Eigen::Vector4d(0, 0, -2, 1)));
}

TEST(Camera, ValidateNamesTheCamera) {
  PinholeIntrinsics k{320, 240, 300.0, 300.0, 160.0, 120.0, 0.05, 5.0};
  EXPECT_NO_THROW(validate(k, "left_eye"));
  auto expect_error = [](const PinholeIntrinsics& bad, const char* part) {
    try {
      validate(bad, "left_eye");
      FAIL() << "accepted";
    } catch (const InputError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("camera 'left_eye'"), std::string::npos) << m;
      EXPECT_NE(m.find(part), std::string::npos) << m;
    }
  };
  PinholeIntrinsics bad = k;
  bad.width = 0;
  expect_error(bad, "image size");
  bad = k;
  bad.fy = -1;
  expect_error(bad, "focal");
  bad = k;
  bad.near = 6.0;
  expect_error(bad, "near");
  bad = k;
  bad.cx = NAN;
  expect_error(bad, "finite");
}
