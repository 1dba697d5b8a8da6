// Occluders in hypothesis batches (another body part drawn into every tile's depth test only):
// generated scenes of a box hypothesis with a smaller box in front of or behind it, checked
// against the boxes rendered alone; the errors for occluders the renderer cannot draw.
#include <gtest/gtest.h>

#include <limits>
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

HypothesisBatchOptions drawn(bool contour, bool inner) {
  HypothesisBatchOptions o;
  o.contour = contour;
  o.inner_contours = inner;
  return o;
}

// A tile placed in a whole image of the eye's size.
cv::Mat whole_image(const CameraTiles& t, std::size_t hypothesis = 0) {
  cv::Mat image = cv::Mat::zeros(240, 320, CV_8U);
  t.tiles[hypothesis].copyTo(image(t.roi));
  return image;
}

// The hypothesis (big): a 6 × 5 × 2 cm box 0.25-0.4 m ahead, turned up to ~25°. The occluder
// (small): a 2 × 2 × 3 cm box whose centre projects inside the big box's outline or over its
// border, `depth_shift` [m] along the line of sight from the big box's centre (negative: nearer).
using Scene = somasim::render::testing::TwoBoxes;

Scene generated_scene(std::mt19937& rng, double depth_shift) {
  return somasim::render::testing::two_boxes(rng, depth_shift, 0.03, 0.025);
}

// Farther apart along the line of sight than the boxes' half-diagonals together.
constexpr double kApart = 0.07;  // [m]

const std::vector<TriangleMesh>& boxes() {
  static const std::vector<TriangleMesh> meshes = {
      tessellate_box(Eigen::Vector3d(0.06, 0.05, 0.02)),
      tessellate_box(Eigen::Vector3d(0.02, 0.02, 0.03))};
  return meshes;
}

}  // namespace

// In front of the hypothesis, an occluder hides exactly the pixels of its own silhouette: the
// tile is the hypothesis' silhouette less the occluder's, and its contour is the hypothesis'
// outline where nothing hides it (not the occluder's outline across it), with or without inner
// contours.
TEST(Occluders, AnOccluderInFrontHidesExactlyItsOwnSilhouette) {
  HypothesisRenderer renderer(boxes(), 2, RenderBackend::kOsmesa, Rasterizer::kSoftware);
  std::mt19937 rng(5);
  int partly_hidden = 0;
  for (int k = 0; k < 40; ++k) {
    const Scene s = generated_scene(rng, -kApart);
    const HypothesisBatch alone{{0}, {{s.big}}, {eye()}};
    const HypothesisBatch occluder_alone{{1}, {{s.small}}, {eye()}};
    HypothesisBatch occluded = alone;
    occluded.occluders = {{1, s.small}};
    const cv::Mat own = whole_image(renderer.render(alone, drawn(false, false)).cameras[0]);
    const cv::Mat occluder =
        whole_image(renderer.render(occluder_alone, drawn(false, false)).cameras[0]);
    const cv::Mat expected = own & ~occluder;
    const CameraTiles silhouette = renderer.render(occluded, drawn(false, false)).cameras[0];
    EXPECT_EQ(cv::countNonZero(whole_image(silhouette) != expected), 0) << "case " << k;
    // Where the occluder hides the hypothesis its outline is not the hypothesis': no contour.
    const cv::Mat expected_contour = silhouette_contour(own | occluder, 1) & expected;
    for (const bool inner : {false, true}) {
      const CameraTiles contour = renderer.render(occluded, drawn(true, inner)).cameras[0];
      EXPECT_EQ(cv::countNonZero(whole_image(contour) != expected_contour), 0)
          << "case " << k << (inner ? ", inner contours" : "");
    }
    const int hidden = cv::countNonZero(own & occluder);
    partly_hidden += hidden > 0 && hidden < cv::countNonZero(own);
  }
  EXPECT_GT(partly_hidden, 20) << "the generated scenes hardly overlap";
}

// Behind the hypothesis an occluder changes nothing; the occluders are drawn alike for every
// hypothesis and whatever the worker count.
TEST(Occluders, AnOccluderBehindChangesNothingAndEveryHypothesisSeesTheSame) {
  HypothesisRenderer one(boxes(), 1, RenderBackend::kOsmesa, Rasterizer::kSoftware);
  HypothesisRenderer three(boxes(), 3, RenderBackend::kOsmesa, Rasterizer::kSoftware);
  std::mt19937 rng(12);
  for (int k = 0; k < 20; ++k) {
    const Scene behind = generated_scene(rng, kApart);
    const Scene in_front = generated_scene(rng, -kApart);
    HypothesisBatch batch{{0}, {{behind.big}, {in_front.big}}, {eye()}};
    for (const bool inner : {false, true}) {
      const CameraTiles plain = one.render(batch, drawn(true, inner)).cameras[0];
      HypothesisBatch occluded = batch;
      occluded.occluders = {{1, behind.small}};
      const CameraTiles with_behind = one.render(occluded, drawn(true, inner)).cameras[0];
      EXPECT_EQ(cv::countNonZero(whole_image(plain, 0) != whole_image(with_behind, 0)), 0)
          << "case " << k;
      const CameraTiles threaded = three.render(occluded, drawn(true, inner)).cameras[0];
      for (std::size_t h = 0; h < 2; ++h)
        EXPECT_EQ(cv::countNonZero(whole_image(threaded, h) != whole_image(with_behind, h)), 0)
            << "case " << k << ", hypothesis " << h;
    }
  }
}

TEST(Occluders, OccludersTheRendererCannotDrawAreRefused) {
  const Scene s = [] {
    std::mt19937 rng(1);
    return generated_scene(rng, -kApart);
  }();
  HypothesisBatch batch{{0}, {{s.big}}, {eye()}};
  HypothesisRenderer software(boxes(), 1, RenderBackend::kOsmesa, Rasterizer::kSoftware);
  batch.occluders = {{2, s.small}};
  EXPECT_EQ(error_of([&] { software.render(batch); }),
            "hypothesis batch: occluder 0 is mesh 2, but 2 meshes were uploaded");
  Eigen::Isometry3d broken = s.small;
  broken.translation().x() = std::numeric_limits<double>::quiet_NaN();
  batch.occluders = {{1, s.small}, {1, broken}};
  EXPECT_EQ(error_of([&] { software.render(batch); }),
            "hypothesis batch: occluder 1 has a non-finite pose");
  batch.occluders.assign(kMaxMeshesPerHypothesis + 1, Occluder{1, s.small});
  EXPECT_EQ(error_of([&] { software.render(batch); }),
            "hypothesis batch: at most 16 occluders, got 17");
  HypothesisRenderer gl(boxes(), 1, RenderBackend::kOsmesa, Rasterizer::kGl);
  batch.occluders = {{1, s.small}};
  EXPECT_EQ(error_of([&] { gl.render(batch); }),
            "hypothesis batch: occluders need the software rasterizer");
}
