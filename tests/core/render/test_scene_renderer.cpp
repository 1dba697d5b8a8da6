// Rendered images against analytic figures: silhouettes, metric depth, ids, shading, projection,
// occlusion, the "drew no pixel" check and byte-identical repeats.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <iostream>

#include <opencv2/imgproc.hpp>

#include "somasim/error.hpp"
#include "somasim/render/context.hpp"
#include "somasim/render/scene_renderer.hpp"

using namespace somasim;
using namespace somasim::render;

namespace {

constexpr double kF = 300.0;  // focal length [px]

// 320 x 240 camera at the root origin looking along root +x (root z up): camera x = root -y,
// camera y = root -z. The optical axis goes through the centre of pixel (160, 120).
Camera forward_camera() {
  Camera c;
  c.name = "test_cam";
  c.intrinsics = {320, 240, kF, kF, 160.0, 120.0, 0.05, 10.0};
  Eigen::Matrix3d r;
  r.col(0) = -Eigen::Vector3d::UnitY();
  r.col(1) = -Eigen::Vector3d::UnitZ();
  r.col(2) = Eigen::Vector3d::UnitX();
  c.pose_root.linear() = r;
  return c;
}

Eigen::Isometry3d at(double x, double y, double z) {
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  p.translation() = Eigen::Vector3d(x, y, z);
  return p;
}

class SceneRendererTest : public ::testing::Test {
 protected:
  OsmesaContext context;
  SceneRenderer renderer{context.gl()};
};

std::string run_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const RunError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no RunError thrown";
  return "";
}

}  // namespace

TEST_F(SceneRendererTest, SphereStraightAheadMatchesTheAnalyticDiscAndDepth) {
  const double r = 0.1, d = 1.0;
  const MeshHandle sphere = renderer.upload(tessellate_sphere(r, 96));
  const Camera cam = forward_camera();
  RenderOptions options;
  options.background = {0.2f, 0.4f, 0.6f};
  const RenderedImages img =
      renderer.render({{sphere, at(d, 0, 0), {1.0f, 0.5f, 0.25f}, 7}}, cam, options);
  ASSERT_EQ(img.rgb.type(), CV_8UC3);
  ASSERT_EQ(img.depth.type(), CV_32F);
  ASSERT_EQ(img.ids.type(), CV_32S);
  ASSERT_EQ(img.ids.rows, 240);
  ASSERT_EQ(img.ids.cols, 320);

  // Silhouette: a disc of radius f r / sqrt(d² - r²) px.
  const double rho = kF * r / std::sqrt(d * d - r * r);
  const double disc = M_PI * rho * rho;
  const int count = cv::countNonZero(img.ids == 7);
  const int other = cv::countNonZero((img.ids != 7) & (img.ids != 0));
  EXPECT_EQ(other, 0);
  EXPECT_NEAR(count, disc, 0.02 * disc);
  std::cout << "sphere silhouette: " << count << " px, analytic disc " << disc << " px ("
            << 100.0 * (count - disc) / disc << " %)\n";

  // Depth at the centre pixel: the sphere's nearest point, d - r along the camera z.
  EXPECT_NEAR(img.depth.at<float>(120, 160), d - r, 1e-3);
  EXPECT_EQ(img.ids.at<std::int32_t>(120, 160), 7);
  // Depth over the whole disc (away from its rim) against the ray-sphere intersection.
  double worst = 0.0;
  for (int row = 0; row < 240; ++row)
    for (int col = 0; col < 320; ++col) {
      const double x = (col - 160.0) / kF, y = (row - 120.0) / kF;  // ray (x, y, 1)
      const double a = x * x + y * y + 1.0, disc_q = d * d - a * (d * d - r * r);
      const bool inside = img.ids.at<std::int32_t>(row, col) == 7;
      if (!inside) {
        EXPECT_EQ(img.depth.at<float>(row, col), 0.0f);
        continue;
      }
      if (std::hypot(col - 160.0, row - 120.0) > rho - 2.0) continue;  // rim: tessellation
      const double z = (d - std::sqrt(disc_q)) / a;
      worst = std::max(worst, std::abs(img.depth.at<float>(row, col) - z));
    }
  EXPECT_LT(worst, 2e-3);
  std::cout << "sphere depth: centre " << img.depth.at<float>(120, 160) << " m (analytic " << d - r
            << "), worst over the disc " << worst * 1e3 << " mm\n";

  // Background colour where nothing is drawn.
  EXPECT_EQ(img.rgb.at<cv::Vec3b>(0, 0), cv::Vec3b(51, 102, 153));
  EXPECT_EQ(img.ids.at<std::int32_t>(0, 0), 0);
}

TEST_F(SceneRendererTest, LitSideIsBrighterThanTheFarSide) {
  const MeshHandle sphere = renderer.upload(tessellate_sphere(0.1, 96));
  const Camera cam = forward_camera();
  RenderOptions options;
  options.light_direction_root = {0.0, -1.0, 0.0};  // towards the camera's right (root -y)
  options.ambient = 0.3f;
  const RenderedImages img =
      renderer.render({{sphere, at(1.0, 0, 0), {1.0f, 0.5f, 0.25f}, 3}}, cam, options);
  // Row of the centre: the right half is lit, the left half only ambient.
  double right = 0, left = 0;
  int n_right = 0, n_left = 0, min_r = 255, max_r = 0;
  for (int col = 0; col < 320; ++col) {
    if (img.ids.at<std::int32_t>(120, col) != 3) continue;
    const cv::Vec3b p = img.rgb.at<cv::Vec3b>(120, col);
    (col > 160 ? right : left) += p[0];
    (col > 160 ? n_right : n_left) += 1;
    min_r = std::min<int>(min_r, p[0]);
    max_r = std::max<int>(max_r, p[0]);
  }
  ASSERT_GT(n_right, 20);
  ASSERT_GT(n_left, 20);
  EXPECT_GT(right / n_right, left / n_left + 60.0);
  EXPECT_GE(min_r, 76);  // ambient only: 0.3 · 255 = 76.5
  EXPECT_LE(min_r, 77);
  EXPECT_GE(max_r, 250);  // nearly facing the light: the full albedo
  // Channels follow the albedo (R, G, B order): 1 : 0.5 : 0.25.
  const cv::Vec3b lit = img.rgb.at<cv::Vec3b>(120, 200);
  EXPECT_NEAR(lit[1], lit[0] * 0.5, 1.0);
  EXPECT_NEAR(lit[2], lit[0] * 0.25, 1.0);
  std::cout << "sphere row 120: mean R right " << right / n_right << ", left " << left / n_left
            << ", min " << min_r << ", max " << max_r << "\n";
}

TEST_F(SceneRendererTest, BoxSeenFromTheSideShowsItsFrontFace) {
  // Box 0.2 deep (root x), 0.3 wide (y), 0.1 high (z), centred 1.5 m ahead: the camera sees the
  // face x = 1.4 as a 0.3 x 0.1 m rectangle.
  const MeshHandle box = renderer.upload(tessellate_box({0.2, 0.3, 0.1}));
  const Camera cam = forward_camera();
  RenderOptions options;
  options.light_direction_root = {-1.0, 0.0, 1.0};  // n · l = cos 45° on the front face
  const RenderedImages img =
      renderer.render({{box, at(1.5, 0, 0), {1.0f, 1.0f, 1.0f}, 11}}, cam, options);
  // Expected pixel columns / rows: centres inside the projected edges.
  const double half_w = kF * 0.15 / 1.4, half_h = kF * 0.05 / 1.4;
  const cv::Rect bbox = cv::boundingRect(img.ids == 11);
  EXPECT_NEAR(bbox.x, 160.0 - half_w, 1.0);
  EXPECT_NEAR(bbox.x + bbox.width, 160.0 + half_w, 1.0);
  EXPECT_NEAR(bbox.y, 120.0 - half_h, 1.0);
  EXPECT_NEAR(bbox.y + bbox.height, 120.0 + half_h, 1.0);
  const double area = 4 * half_w * half_h;
  const int count = cv::countNonZero(img.ids == 11);
  EXPECT_EQ(count, bbox.area());  // a full rectangle
  const double cols = std::floor(160.0 + half_w) - std::ceil(160.0 - half_w) + 1;
  const double rows = std::floor(120.0 + half_h) - std::ceil(120.0 - half_h) + 1;
  EXPECT_EQ(count, cols * rows);  // exactly the pixel centres inside the projected face
  EXPECT_NEAR(count, area, 0.05 * area);
  // Flat face: one depth (1.4 m) and one colour (0.3 + 0.7 cos 45° = 0.795 -> 203).
  double min_z = 1e9, max_z = 0;
  for (int row = bbox.y; row < bbox.y + bbox.height; ++row)
    for (int col = bbox.x; col < bbox.x + bbox.width; ++col) {
      min_z = std::min<double>(min_z, img.depth.at<float>(row, col));
      max_z = std::max<double>(max_z, img.depth.at<float>(row, col));
      EXPECT_EQ(img.rgb.at<cv::Vec3b>(row, col), cv::Vec3b(203, 203, 203));
    }
  EXPECT_NEAR(min_z, 1.4, 1e-3);
  EXPECT_NEAR(max_z, 1.4, 1e-3);
  std::cout << "box face: " << count << " px (analytic " << area << "), bbox " << bbox << ", depth "
            << min_z << ".." << max_z << " m\n";
}

TEST_F(SceneRendererTest, RenderedPositionsMatchProjectForATurnedCamera) {
  const MeshHandle ball = renderer.upload(tessellate_sphere(0.02, 48));
  Camera cam = forward_camera();
  cam.name = "turned";
  cam.intrinsics.cx = 150.3;
  cam.intrinsics.cy = 131.7;
  cam.intrinsics.fy = 280.0;
  cam.pose_root.translation() = Eigen::Vector3d(-0.2, 0.1, 0.3);
  cam.pose_root.linear() = Eigen::AngleAxisd(0.25, Eigen::Vector3d::UnitZ()) *
                           Eigen::AngleAxisd(0.15, Eigen::Vector3d::UnitY()) *
                           cam.pose_root.linear();
  const std::vector<Eigen::Vector3d> points = {
      {1.0, 0.2, 0.1}, {0.8, 0.4, 0.0}, {1.2, -0.1, 0.35}, {0.9, 0.05, -0.05}};
  std::vector<DrawItem> items;
  for (std::size_t i = 0; i < points.size(); ++i)
    items.push_back({ball, at(points[i].x(), points[i].y(), points[i].z()), Eigen::Vector3f::Ones(),
                     static_cast<std::int32_t>(i + 1)});
  const RenderedImages img = renderer.render(items, cam);
  double worst = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto uv = cam.project(points[i]);
    ASSERT_TRUE(uv);
    const cv::Moments m = cv::moments(img.ids == static_cast<int>(i + 1), true);
    ASSERT_GT(m.m00, 40.0) << "point " << i;
    const Eigen::Vector2d centroid(m.m10 / m.m00, m.m01 / m.m00);
    worst = std::max(worst, (centroid - *uv).norm());
    EXPECT_LT((centroid - *uv).norm(), 0.3)
        << "point " << i << ": centroid " << centroid.transpose() << ", project "
        << uv->transpose();
    // Depth at the nearest pixel: where that pixel's ray (x, y, 1) t meets the sphere, z = t.
    const int col = static_cast<int>(std::lround(uv->x()));
    const int row = static_cast<int>(std::lround(uv->y()));
    const Eigen::Vector3d ray((col - cam.intrinsics.cx) / cam.intrinsics.fx,
                              (row - cam.intrinsics.cy) / cam.intrinsics.fy, 1.0);
    const Eigen::Vector3d c = cam.to_camera(points[i]);
    const double b = ray.dot(c), a = ray.squaredNorm();
    const double z = (b - std::sqrt(b * b - a * (c.squaredNorm() - 0.02 * 0.02))) / a;
    EXPECT_NEAR(img.depth.at<float>(row, col), z, 1e-3) << "point " << i;
  }
  std::cout << "silhouette centroids vs project(): worst " << worst << " px\n";
}

TEST_F(SceneRendererTest, NearerItemsHideFartherOnesAndHiddenItemsAreNoError) {
  const MeshHandle sphere = renderer.upload(tessellate_sphere(0.05, 48));
  const MeshHandle wall = renderer.upload(tessellate_box({0.01, 1.0, 1.0}));
  const Camera cam = forward_camera();
  // The sphere (id 1) in front of the wall (id 2); a second sphere (id 3) hidden behind the wall.
  const RenderedImages img = renderer.render({{sphere, at(0.8, 0, 0), {1, 0, 0}, 1},
                                              {wall, at(1.5, 0, 0), {0, 1, 0}, 2},
                                              {sphere, at(2.0, 0.1, 0), {0, 0, 1}, 3}},
                                             cam);
  EXPECT_EQ(img.ids.at<std::int32_t>(120, 160), 1);
  EXPECT_EQ(img.ids.at<std::int32_t>(120, 240), 2);  // the wall spans columns 60..260
  EXPECT_NEAR(img.depth.at<float>(120, 240), 1.495, 1e-3);
  EXPECT_EQ(cv::countNonZero(img.ids == 3), 0);
}

TEST_F(SceneRendererTest, ASliverAtTheImageBorderThatCoversNoPixelCentreIsNoError) {
  // A ball below the image whose highest vertex in the image projects 0.05 px inside the last
  // row's outer edge (v = 239.45): it may cover no pixel centre (a ball entering the view, as in
  // ball_on_forearm_camera.yaml at t = 20.6 s).
  const TriangleMesh mesh = tessellate_sphere(0.05, 24);
  const MeshHandle sphere = renderer.upload(mesh);
  const Camera cam = forward_camera();
  // The ball's centre height z [m] at x = 1 m that puts its highest vertex at v = 239.45.
  const auto pole_v = [&](double z) {
    double v = 1e9;
    for (const Eigen::Vector3f& p : mesh.positions)
      v = std::min(v, cam.project(Eigen::Vector3d(1.0, 0, z) + p.cast<double>())->y());
    return v;
  };
  double lo = -1.0, hi = 0.0;  // pole_v(lo) > 239.45 > pole_v(hi)
  for (int i = 0; i < 60; ++i) (pole_v(0.5 * (lo + hi)) > 239.45 ? lo : hi) = 0.5 * (lo + hi);
  ASSERT_NEAR(pole_v(lo), 239.45, 1e-6);
  const RenderedImages img = renderer.render({{sphere, at(1.0, 0, lo), {1, 1, 1}, 5}}, cam);
  EXPECT_EQ(cv::countNonZero(img.ids == 5), 0);
}

TEST_F(SceneRendererTest, AnItemInViewThatDrawsNothingIsAnError) {
  const MeshHandle good = renderer.upload(tessellate_sphere(0.05, 32));
  // A 20 cm segment: large in the image (the check applies) but every triangle has zero area.
  const MeshHandle degenerate = renderer.upload(tessellate_box({0.2, 0.0, 0.0}));
  const Camera cam = forward_camera();
  const std::vector<DrawItem> items = {{good, at(1.0, 0.2, 0), {1, 1, 1}, 4},
                                       {degenerate, at(1.0, 0, 0), {1, 1, 1}, 9}};
  EXPECT_EQ(run_error([&] { renderer.render(items, cam); }),
            "camera 'test_cam': item 1 (id 9) projects into the image but drew no pixel");
  // The check can be switched off ...
  RenderOptions off;
  off.check_drawn = false;
  const RenderedImages img = renderer.render(items, cam, off);
  EXPECT_EQ(cv::countNonZero(img.ids == 9), 0);
  EXPECT_GT(cv::countNonZero(img.ids == 4), 100);
  // ... and a degenerate item out of view (behind the camera) is no error.
  EXPECT_NO_THROW(renderer.render({{degenerate, at(-1.0, 0, 0), {1, 1, 1}, 9}}, cam));
}

TEST_F(SceneRendererTest, ItemsSharingAnIdAreCheckedTogether) {
  // A backdrop (id 7: a wall and a zero-width bar on it) hidden behind a near box that fills the
  // image: the bar alone draws nothing, the group draws the wall — no error. (A camera turned
  // toward a near object stopped a soak run here when each item was checked alone.)
  const MeshHandle near_box = renderer.upload(tessellate_box({0.01, 2.0, 2.0}));
  const MeshHandle wall = renderer.upload(tessellate_box({0.01, 1.0, 1.0}));
  const MeshHandle bar = renderer.upload(tessellate_box({0.0, 0.6, 0.0}));
  const Camera cam = forward_camera();
  const std::vector<DrawItem> hidden = {{near_box, at(0.5, 0, 0), {1, 1, 1}, 1},
                                        {wall, at(2.0, 0, 0), {0, 1, 0}, 7},
                                        {bar, at(1.99, 0, 0.1), {1, 0, 0}, 7}};
  RenderedImages img;
  EXPECT_NO_THROW(img = renderer.render(hidden, cam));
  EXPECT_EQ(cv::countNonZero(img.ids == 7), 0);
  // The bar alone under its own id is still an error.
  EXPECT_EQ(run_error([&] {
              renderer.render({{near_box, at(0.5, 0, 0), {1, 1, 1}, 1},
                               {wall, at(2.0, 0, 0), {0, 1, 0}, 7},
                               {bar, at(1.99, 0, 0.1), {1, 0, 0}, 8}},
                              cam);
            }),
            "camera 'test_cam': item 2 (id 8) projects into the image but drew no pixel");
}

TEST_F(SceneRendererTest, BadItemsNameTheCamera) {
  const MeshHandle ball = renderer.upload(tessellate_sphere(0.05, 16));
  const Camera cam = forward_camera();
  EXPECT_EQ(run_error([&] {
              renderer.render({{MeshHandle{5}, at(1, 0, 0), {1, 1, 1}, 1}}, cam);
            }),
            "camera 'test_cam': item 0 refers to mesh 5, but 1 meshes were uploaded");
  EXPECT_EQ(run_error([&] {
              renderer.render({{ball, at(1, 0, 0), {1, 1, 1}, 0}}, cam);
            }),
            "camera 'test_cam': item 0 has id 0, which is the background");
  EXPECT_EQ(run_error([&] {
              renderer.render({{ball, at(NAN, 0, 0), {1, 1, 1}, 2}}, cam);
            }),
            "camera 'test_cam': item 0 (id 2) has a non-finite pose");
  Camera bad = cam;
  bad.intrinsics.near = 0.0;
  EXPECT_THROW(renderer.render({}, bad), InputError);
}

TEST_F(SceneRendererTest, TwoRendersOfTheSameSceneAreByteIdentical) {
  const MeshHandle sphere = renderer.upload(tessellate_sphere(0.07, 48));
  const MeshHandle capsule = renderer.upload(tessellate_capsule(0.03, 0.2, 32));
  const MeshHandle cylinder = renderer.upload(tessellate_cylinder(0.04, 0.1, 32));
  const Camera cam = forward_camera();
  Eigen::Isometry3d tilted = at(1.1, -0.15, 0.05);
  tilted.linear() =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  const std::vector<DrawItem> scene = {{sphere, at(1.0, 0.1, 0), {0.9f, 0.2f, 0.2f}, 1},
                                       {capsule, tilted, {0.2f, 0.9f, 0.2f}, 2},
                                       {cylinder, at(0.9, 0.0, -0.15), {0.2f, 0.2f, 0.9f}, 3}};
  const auto start = std::chrono::steady_clock::now();
  const RenderedImages a = renderer.render(scene, cam);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  Camera small = cam;  // another size in between: the framebuffer is remade
  small.intrinsics.width = 160;
  small.intrinsics.height = 120;
  small.intrinsics.cx = 80;
  small.intrinsics.cy = 60;
  small.intrinsics.fx = small.intrinsics.fy = 150;
  const RenderedImages s = renderer.render(scene, small);
  EXPECT_EQ(s.rgb.cols, 160);
  const RenderedImages b = renderer.render(scene, cam);
  for (const auto& [x, y] : {std::pair{a.rgb, b.rgb}, {a.depth, b.depth}, {a.ids, b.ids}}) {
    ASSERT_EQ(x.total() * x.elemSize(), y.total() * y.elemSize());
    EXPECT_EQ(std::memcmp(x.data, y.data, x.total() * x.elemSize()), 0);
  }
  for (int id = 1; id <= 3; ++id) EXPECT_GT(cv::countNonZero(a.ids == id), 100) << id;
  std::cout << "320 x 240, 3 items, first render with read-backs: " << ms << " ms\n";
}

TEST_F(SceneRendererTest, OnlyTheRequestedOutputsAreReturned) {
  const MeshHandle ball = renderer.upload(tessellate_sphere(0.05, 16));
  RenderOptions options;
  options.read_rgb = false;
  options.read_depth = false;
  options.read_ids = false;
  const RenderedImages img =
      renderer.render({{ball, at(1, 0, 0), {1, 1, 1}, 1}}, forward_camera(), options);
  EXPECT_TRUE(img.rgb.empty());
  EXPECT_TRUE(img.depth.empty());
  EXPECT_TRUE(img.ids.empty());
}
