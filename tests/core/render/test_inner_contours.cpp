// Inner contours of hypothesis tiles (the software rasterizer with a depth test): generated
// scenes of a small box in front of, behind or flush with a larger one, checked against the
// small box's own outline; creases of a box at generated poses against its visible edges and of
// a faceted cylinder against its rims; the errors for options that cannot draw them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "somasim/error.hpp"
#include "somasim/render/hypothesis_batch.hpp"
#include "tile_scenes.hpp"

using namespace somasim;
using namespace somasim::render;
using somasim::render::testing::error_of;
using somasim::render::testing::eye;
using somasim::render::testing::pose;

namespace {

HypothesisBatchOptions contours(bool inner) {
  HypothesisBatchOptions o;
  o.contour = true;
  o.inner_contours = inner;
  return o;
}

HypothesisBatchOptions creases() {
  HypothesisBatchOptions o = contours(true);
  o.crease_contours = true;
  return o;
}

// Pixels set in `b` but not in `a`, in image coordinates.
std::vector<cv::Point> added(const CameraTiles& a, const CameraTiles& b) {
  std::vector<cv::Point> out;
  EXPECT_EQ(a.roi, b.roi);
  for (int r = 0; r < a.roi.height; ++r)
    for (int c = 0; c < a.roi.width; ++c) {
      EXPECT_FALSE(a.tiles[0].at<std::uint8_t>(r, c) != 0 && b.tiles[0].at<std::uint8_t>(r, c) == 0)
          << "an outer contour pixel is missing at " << c << ", " << r;
      if (a.tiles[0].at<std::uint8_t>(r, c) == 0 && b.tiles[0].at<std::uint8_t>(r, c) != 0)
        out.emplace_back(a.roi.x + c, a.roi.y + r);
    }
  return out;
}

bool set_at(const CameraTiles& t, cv::Point p) {
  return t.roi.contains(p) && t.tiles[0].at<std::uint8_t>(p.y - t.roi.y, p.x - t.roi.x) != 0;
}

// Farther apart along the line of sight than the boxes' half-diagonals together: they do not
// intersect (an intersection curve is an inner boundary of neither outline).
constexpr double kApart = 0.06;  // [m]

using Scene = somasim::render::testing::TwoBoxes;

// A 6 × 5 × 2 cm box 0.25-0.4 m ahead, turned up to ~25°, and a 1.2 × 1.2 × 3 cm box whose
// centre projects well inside it, `depth_shift` [m] along the line of sight from the big box's
// centre (negative: nearer the camera).
Scene generated_scene(std::mt19937& rng, double depth_shift) {
  return somasim::render::testing::two_boxes(rng, depth_shift, 0.012, 0.01);
}

}  // namespace

// A small box in front of a big one: the inner contour is the small box's outline where it lies
// over the big box; the outer contour is unchanged.
TEST(InnerContours, AnOccludingMeshIsOutlinedInside) {
  const std::vector<TriangleMesh> meshes = {tessellate_box(Eigen::Vector3d(0.06, 0.05, 0.02)),
                                            tessellate_box(Eigen::Vector3d(0.012, 0.012, 0.03))};
  HypothesisRenderer renderer(meshes, 2, RenderBackend::kOsmesa, Rasterizer::kSoftware);
  std::mt19937 rng(3);
  for (int k = 0; k < 30; ++k) {
    const Scene s = generated_scene(rng, -kApart);
    HypothesisBatch both{{0, 1}, {{s.big, s.small}}, {eye()}};
    HypothesisBatch alone{{1}, {{s.small}}, {eye()}};
    const CameraTiles plain = renderer.render(both, contours(false)).cameras[0];
    const CameraTiles inner = renderer.render(both, contours(true)).cameras[0];
    const CameraTiles own = renderer.render(alone, contours(false)).cameras[0];
    const std::vector<cv::Point> extra = added(plain, inner);
    int own_count = 0;
    for (const cv::Mat& t : own.tiles) own_count = cv::countNonZero(t);
    EXPECT_GT(extra.size(), own_count / 3) << "case " << k;
    for (const cv::Point& p : extra)
      EXPECT_TRUE(set_at(own, p)) << "case " << k << ": inner contour pixel " << p
                                  << " is not on the small box's outline";
  }
}

// Behind the big box, the small box adds at most the big box's own outline where it occludes the
// small one; flush with the big box's front face, nothing.
TEST(InnerContours, AnOccludedOrFlushMeshAddsNoOutlineOfItsOwn) {
  const std::vector<TriangleMesh> meshes = {tessellate_box(Eigen::Vector3d(0.06, 0.05, 0.02)),
                                            tessellate_box(Eigen::Vector3d(0.012, 0.012, 0.02))};
  HypothesisRenderer renderer(meshes, 1, RenderBackend::kOsmesa, Rasterizer::kSoftware);
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 30; ++k) {
    Scene s = generated_scene(rng, kApart);
    HypothesisBatch behind{{0, 1}, {{s.big, s.small}}, {eye()}};
    HypothesisBatch big_alone{{0}, {{s.big}}, {eye()}};
    const CameraTiles own = renderer.render(big_alone, contours(false)).cameras[0];
    for (const cv::Point& p : added(renderer.render(behind, contours(false)).cameras[0],
                                    renderer.render(behind, contours(true)).cameras[0]))
      EXPECT_TRUE(set_at(own, p)) << "case " << k << ": inner contour pixel " << p
                                  << " is not on the big box's outline";
    // Flush: the same orientation, the small box's front face in the big one's front face
    // plane (both 2 cm deep), its centre within the big face.
    s.small = s.big;
    s.small.translate(Eigen::Vector3d(0.015 * u(rng), 0.012 * u(rng), 0.0));
    HypothesisBatch flush{{0, 1}, {{s.big, s.small}}, {eye()}};
    EXPECT_TRUE(added(renderer.render(flush, contours(false)).cameras[0],
                      renderer.render(flush, contours(true)).cameras[0])
                    .empty())
        << "flush case " << k;
  }
}

// The depth test, not the triangles' winding, decides what is seen: the same boxes wound the
// other way give the same tiles, with creases too (their back faces are told by the winding).
TEST(InnerContours, TheSameTilesWhicheverWayTheMeshesWind) {
  std::vector<TriangleMesh> meshes = {tessellate_box(Eigen::Vector3d(0.06, 0.05, 0.02)),
                                      tessellate_box(Eigen::Vector3d(0.012, 0.012, 0.03))};
  std::vector<TriangleMesh> reversed = meshes;
  for (TriangleMesh& m : reversed)
    for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3)
      std::swap(m.indices[t + 1], m.indices[t + 2]);
  HypothesisRenderer a(meshes, 1, RenderBackend::kOsmesa, Rasterizer::kSoftware);
  HypothesisRenderer b(reversed, 1, RenderBackend::kOsmesa, Rasterizer::kSoftware);
  std::mt19937 rng(5);
  for (int k = 0; k < 20; ++k) {
    const Scene s = generated_scene(rng, k % 2 == 0 ? -kApart : kApart);
    HypothesisBatch batch{{0, 1}, {{s.big, s.small}}, {eye()}};
    for (const HypothesisBatchOptions& options : {contours(true), creases()}) {
      const cv::Mat ta = a.render(batch, options).cameras[0].tiles[0];
      const cv::Mat tb = b.render(batch, options).cameras[0].tiles[0];
      EXPECT_EQ(cv::countNonZero(ta != tb), 0)
          << "case " << k << (options.crease_contours ? ", creases" : "");
    }
  }
}

// A camera-frame point's pixel coordinates.
Eigen::Vector2d project(const Camera& camera, const Eigen::Vector3d& root_point) {
  const Eigen::Vector3d p = camera.pose_root.inverse() * root_point;
  const PinholeIntrinsics& k = camera.intrinsics;
  return {k.fx * p.x() / p.z() + k.cx, k.fy * p.y() / p.z() + k.cy};
}

double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                           const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

// A box at generated poses: the crease pixels lie on the projections of its edges between two
// faces that both face the camera, and they draw most of those edges' length.
TEST(InnerContours, CreasesOutlineTheVisibleEdgesOfABox) {
  const Eigen::Vector3d size(0.06, 0.04, 0.03);
  const std::vector<TriangleMesh> meshes = {tessellate_box(size)};
  HypothesisRenderer renderer(meshes, 1, RenderBackend::kOsmesa, Rasterizer::kSoftware);
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Camera camera = eye();
  int with_creases = 0;
  for (int k = 0; k < 30; ++k) {
    const Eigen::Isometry3d box =
        pose(Eigen::Vector3d(0.3 + 0.05 * u(rng), 0.04 * u(rng), 0.03 * u(rng)),
             Eigen::Vector3d(1.2 * u(rng), 1.2 * u(rng), 1.2 * u(rng)));
    HypothesisBatch batch{{0}, {{box}}, {camera}};
    const std::vector<cv::Point> extra = added(renderer.render(batch, contours(true)).cameras[0],
                                               renderer.render(batch, creases()).cameras[0]);
    // Edges: along axis a at the corners (±, ±) of the other two; its faces' normals ±e_b, ±e_c.
    std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> visible;
    double visible_px = 0.0;
    const Eigen::Vector3d eye_position = camera.pose_root.translation();
    for (int a = 0; a < 3; ++a) {
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      for (const double sb : {-1.0, 1.0})
        for (const double sc : {-1.0, 1.0}) {
          auto faces_camera = [&](int axis, double sign) {
            Eigen::Vector3d centre = Eigen::Vector3d::Zero();
            centre[axis] = sign * 0.5 * size[axis];
            const Eigen::Vector3d normal = box.linear().col(axis) * sign;
            return normal.dot(eye_position - box * centre) > 0.0;
          };
          if (!faces_camera(b, sb) || !faces_camera(c, sc)) continue;
          Eigen::Vector3d p = Eigen::Vector3d::Zero();
          p[b] = sb * 0.5 * size[b];
          p[c] = sc * 0.5 * size[c];
          Eigen::Vector3d q = p;
          p[a] = -0.5 * size[a];
          q[a] = 0.5 * size[a];
          visible.emplace_back(project(camera, box * p), project(camera, box * q));
          visible_px += (visible.back().second - visible.back().first).norm();
        }
    }
    for (const cv::Point& px : extra) {
      double nearest = 1e9;
      for (const auto& [p, q] : visible)
        nearest = std::min(nearest, distance_to_segment(Eigen::Vector2d(px.x, px.y), p, q));
      EXPECT_LT(nearest, 1.5) << "case " << k << ": crease pixel " << px << " on no visible edge";
    }
    EXPECT_GT(static_cast<double>(extra.size()), 0.5 * visible_px - 12.0) << "case " << k;
    with_creases += extra.empty() ? 0 : 1;
  }
  EXPECT_GE(with_creases, 25);
}

// An 8-sided cylinder seen from the side: its sides meet at 45°, below the crease angle, so no
// line runs along it; its rims (90°) are creases.
TEST(InnerContours, ACylindersSidesAreOneSmoothPatch) {
  const double length = 0.08;
  const std::vector<TriangleMesh> meshes = {tessellate_cylinder(0.012, length, 8)};
  HypothesisRenderer renderer(meshes, 1, RenderBackend::kOsmesa, Rasterizer::kSoftware);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Camera camera = eye();
  int rim_pixels = 0;
  for (int k = 0; k < 20; ++k) {
    // Axis across the view (root y), tilted up to ~30° toward the camera, spun about itself.
    const Eigen::Isometry3d cylinder =
        pose(Eigen::Vector3d(0.3, 0.03 * u(rng), 0.03 * u(rng)), Eigen::Vector3d::Zero()) *
        pose(Eigen::Vector3d::Zero(), Eigen::Vector3d(0.0, 0.0, 0.5 * u(rng))) *
        pose(Eigen::Vector3d::Zero(), Eigen::Vector3d(M_PI / 2, 0.0, 0.0)) *
        pose(Eigen::Vector3d::Zero(), Eigen::Vector3d(0.0, 0.0, M_PI * u(rng)));
    HypothesisBatch batch{{0}, {{cylinder}}, {camera}};
    const Eigen::Vector2d a = project(camera, cylinder * Eigen::Vector3d(0, 0, -length / 2));
    const Eigen::Vector2d b = project(camera, cylinder * Eigen::Vector3d(0, 0, length / 2));
    for (const cv::Point& px : added(renderer.render(batch, contours(true)).cameras[0],
                                     renderer.render(batch, creases()).cameras[0])) {
      const double t = (Eigen::Vector2d(px.x, px.y) - a).dot(b - a) / (b - a).squaredNorm();
      EXPECT_GT(std::abs(t - 0.5), 0.25)
          << "case " << k << ": crease pixel " << px << " in the middle of the cylinder";
      ++rim_pixels;
    }
  }
  EXPECT_GT(rim_pixels, 100);  // the rims facing the camera
}

TEST(InnerContours, LabelledBoundariesTakeTheNearerSide) {
  cv::Mat labels = (cv::Mat_<std::uint8_t>(1, 4) << 1, 1, 2, 0);
  cv::Mat depth = (cv::Mat_<float>(1, 4) << 2.0F, 2.0F, 3.0F, 0.0F);
  cv::Mat expected = (cv::Mat_<std::uint8_t>(1, 4) << 0, 0, 255, 0);
  EXPECT_EQ(cv::countNonZero(inner_contour(labels, depth) != expected), 0);
  depth.at<float>(0, 2) = 1.0F;  // mesh 2 now farther: mesh 1's pixel takes the boundary
  expected = (cv::Mat_<std::uint8_t>(1, 4) << 0, 255, 0, 0);
  EXPECT_EQ(cv::countNonZero(inner_contour(labels, depth) != expected), 0);
}

TEST(InnerContours, Errors) {
  const std::vector<TriangleMesh> meshes = {tessellate_box(Eigen::Vector3d(0.06, 0.05, 0.02))};
  HypothesisBatch batch{
      {0}, {{pose(Eigen::Vector3d(0.3, 0, 0), Eigen::Vector3d::Zero())}}, {eye()}};
  HypothesisRenderer gl(meshes, 1, RenderBackend::kOsmesa, Rasterizer::kGl);
  EXPECT_EQ(error_of([&] { gl.render(batch, contours(true)); }),
            "hypothesis batch: inner_contours needs the software rasterizer");
  HypothesisRenderer software(meshes, 1, RenderBackend::kOsmesa, Rasterizer::kSoftware);
  HypothesisBatchOptions silhouettes;
  silhouettes.inner_contours = true;
  EXPECT_EQ(error_of([&] { software.render(batch, silhouettes); }),
            "hypothesis batch: inner_contours needs contour");
  HypothesisBatchOptions outer_only = contours(false);
  outer_only.crease_contours = true;
  EXPECT_EQ(error_of([&] { software.render(batch, outer_only); }),
            "hypothesis batch: crease_contours needs inner_contours");
}
