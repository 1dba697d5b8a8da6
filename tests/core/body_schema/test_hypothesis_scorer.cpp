// The hypothesis scorer against images of the "real" arm: the iCub rendered with its visual
// geometry and true joint offsets, segmented by colour (silhouettes) or turned into edge
// distance maps, scored with the internal model's proxy geometry.
#include <gtest/gtest.h>

#include <cstdio>
#include <limits>
#include <numbers>

#include "real_arm_views.hpp"
#include "somasim/body_schema/hypothesis_scorer.hpp"
#include "somasim/body_schema/observation.hpp"
#include "somasim/error.hpp"

namespace somasim::body_schema {
namespace {

using testing::arm_dofs;
using testing::icub;
using testing::look;
using testing::RealEyes;
const Eigen::Matrix<double, 7, 1>& kBeta = testing::true_offsets_deg();

Eigen::VectorXd encoders() {
  return testing::hand_before_eyes();
}

// Columns: the truth, the nominal model, and the truth with one joint 2 deg off (each joint,
// both signs).
Eigen::MatrixXd candidate_particles() {
  Eigen::MatrixXd p(7, 2 + 14);
  p.col(0) = kBeta;
  p.col(1).setZero();
  for (int j = 0; j < 7; ++j)
    for (int s = 0; s < 2; ++s) {
      p.col(2 + 2 * j + s) = kBeta;
      p(j, 2 + 2 * j + s) += s == 0 ? 2.0 : -2.0;
    }
  return p;
}

std::vector<cv::Mat> edge_distance_maps(const RealEyes& eyes) {
  std::vector<cv::Mat> distances;
  for (const cv::Mat& rgb : eyes.rgb) distances.push_back(edge_distance_map(rgb));
  return distances;
}

// The edge likelihood with the released code's λ = 25/255.
ScorerOptions edge_options() {
  ScorerOptions options;
  options.kind = LikelihoodKind::kEdges;
  options.edge_lambda = 25.0 / 255.0;
  return options;
}

TEST(HypothesisScorer, TheTrueOffsetsExplainTheSilhouettesBest) {
  const Eigen::VectorXd q = encoders();
  const RealEyes eyes = look(q);
  std::vector<cv::Mat> masks;
  for (const cv::Mat& rgb : eyes.rgb) {
    masks.push_back(segment_colour(rgb, HsvRange{}));
    EXPECT_GT(cv::countNonZero(masks.back()), 1500);
  }
  HypothesisScorer scorer(icub(), arm_hypothesis_model(*icub(), {"r_hand"}, 8), arm_dofs(), 2,
                          ScorerOptions{});
  const std::vector<double> l = scorer.score(q, candidate_particles(), eyes.cameras, masks);
  std::printf("silhouette L: truth %.4f, nominal %.4f, 2 deg off:", l[0], l[1]);
  for (std::size_t m = 2; m < l.size(); ++m) std::printf(" %.4f", l[m]);
  std::printf("\n");
  EXPECT_GT(l[0], 0.7);  // both eyes' Jaccard indices multiplied: proxy geometry, not exact
  EXPECT_LT(l[1], 0.6 * l[0]);
  for (std::size_t m = 2; m < l.size(); ++m) EXPECT_LT(l[m], l[0]) << "candidate " << m;
}

TEST(HypothesisScorer, TheTrueOffsetsExplainTheEdgesBest) {
  const Eigen::VectorXd q = encoders();
  const RealEyes eyes = look(q);
  const std::vector<cv::Mat> distances = edge_distance_maps(eyes);
  ScorerOptions options = edge_options();
  HypothesisScorer scorer(icub(), arm_hypothesis_model(*icub(), {"r_hand"}, 8), arm_dofs(), 1,
                          options);
  const std::vector<double> l = scorer.score(q, candidate_particles(), eyes.cameras, distances);
  std::printf("edge L: truth %.4f, nominal %.4f, 2 deg off:", l[0], l[1]);
  for (std::size_t m = 2; m < l.size(); ++m) std::printf(" %.4f", l[m]);
  std::printf("\n");
  EXPECT_LT(l[1], 0.6 * l[0]);
  int better = 0;
  for (std::size_t m = 2; m < l.size(); ++m) better += l[m] > l[0] ? 1 : 0;
  EXPECT_LE(better, 2);  // edges of a shaded hand are noisier than silhouettes
}

// Drawn per primitive with a depth test, the hand's contours also run where the thumb and the
// fingers cross the palm; the truth still explains the edges best.
TEST(HypothesisScorer, InnerContoursOutlineThePrimitivesInsideTheHand) {
  const ArmHypothesisModel per_link = arm_hypothesis_model(*icub(), {"r_hand"}, 8);
  const ArmHypothesisModel per_primitive = arm_hypothesis_model(*icub(), {"r_hand"}, 8, true);
  ASSERT_EQ(per_link.meshes.size(), 1U);
  ASSERT_EQ(per_primitive.meshes.size(), 6U);  // palm, four fingers, thumb
  EXPECT_EQ(per_primitive.mesh_link, std::vector<std::size_t>(6, 0));
  std::size_t triangles = 0;
  for (const render::TriangleMesh& m : per_primitive.meshes) triangles += m.triangle_count();
  EXPECT_EQ(triangles, per_link.meshes[0].triangle_count());

  const Eigen::VectorXd q = encoders();
  const RealEyes eyes = look(q);
  const std::vector<cv::Mat> distances = edge_distance_maps(eyes);
  ScorerOptions options = edge_options();
  options.rasterizer = render::Rasterizer::kSoftware;
  HypothesisScorer outer(icub(), per_link, arm_dofs(), 1, options);
  options.inner_contours = true;
  HypothesisScorer inner(icub(), per_primitive, arm_dofs(), 1, options);
  const Eigen::MatrixXd particles = candidate_particles();
  outer.score(q, particles, eyes.cameras, distances);
  // `more` draws more contour pixels than `fewer`, and the truth (particle 0) still explains the
  // hand's edges best: the nominal model far worse, at most 2 of the 2°-off particles better.
  auto more_contour_truth_best = [&](HypothesisScorer& more, const HypothesisScorer& fewer,
                                     const char* what) {
    const std::vector<double> l = more.score(q, particles, eyes.cameras, distances);
    for (std::size_t c = 0; c < eyes.cameras.size(); ++c)
      EXPECT_GT(cv::countNonZero(more.last_batch().cameras[c].tiles[0]),
                cv::countNonZero(fewer.last_batch().cameras[c].tiles[0]) + 20)
          << what << ", camera " << c;
    std::printf("edge L with %s: truth %.4f, nominal %.4f, 2 deg off:", what, l[0], l[1]);
    for (std::size_t m = 2; m < l.size(); ++m) std::printf(" %.4f", l[m]);
    std::printf("\n");
    EXPECT_LT(l[1], 0.6 * l[0]) << what;
    int better = 0;
    for (std::size_t m = 2; m < l.size(); ++m) better += l[m] > l[0] ? 1 : 0;
    EXPECT_LE(better, 2) << what;
  };
  more_contour_truth_best(inner, outer, "inner contours");
  // Creases too (the palm box's edges, the fingers' rims).
  options.crease_contours = true;
  HypothesisScorer creased(icub(), per_primitive, arm_dofs(), 1, options);
  more_contour_truth_best(creased, inner, "creases");
  options.inner_contours = false;
  EXPECT_THROW(HypothesisScorer(icub(), per_primitive, arm_dofs(), 1, options), InputError);
  options.inner_contours = true;
  options.crease_contours = false;

  ScorerOptions gl = options;
  gl.rasterizer = render::Rasterizer::kGl;
  EXPECT_THROW(HypothesisScorer(icub(), per_primitive, arm_dofs(), 1, gl), InputError);
  ScorerOptions silhouettes = options;
  silhouettes.kind = LikelihoodKind::kSilhouette;
  EXPECT_THROW(HypothesisScorer(icub(), per_primitive, arm_dofs(), 1, silhouettes), InputError);
}

// The other hand as an occluder: drawn by the CPU rasterizer only, posed by offsets of every
// model dof.
TEST(HypothesisScorer, OccludersAreRefusedWhereTheyCannotBeDrawn) {
  const ArmHypothesisModel hand = arm_hypothesis_model(*icub(), {"r_hand"}, 8);
  const ArmHypothesisModel other_hand = arm_hypothesis_model(*icub(), {"l_hand"}, 8);
  ScorerOptions options = edge_options();
  EXPECT_THROW(HypothesisScorer(icub(), hand, arm_dofs(), 1, options,
                                render::RenderBackend::kOsmesa, other_hand),
               InputError);
  options.rasterizer = render::Rasterizer::kSoftware;
  HypothesisScorer scorer(icub(), hand, arm_dofs(), 1, options, render::RenderBackend::kOsmesa,
                          other_hand);
  try {
    scorer.set_occluder_offsets(Eigen::VectorXd::Zero(7));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("occluder offsets: expected"), std::string::npos)
        << e.what();
  }
  Eigen::VectorXd offsets = Eigen::VectorXd::Zero(icub()->num_dofs());
  offsets[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(scorer.set_occluder_offsets(offsets), InputError);
}

TEST(HypothesisScorer, Errors) {
  try {
    arm_hypothesis_model(*icub(), {"r_hand", "r_paw"}, 8);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("r_paw"), std::string::npos) << e.what();
  }
  try {
    likelihood_kind_from_name("colour");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "unknown likelihood 'colour' (expected silhouette or edges)");
  }
}

}  // namespace
}  // namespace somasim::body_schema
