// The hypothesis scorer against images of the "real" arm: the iCub rendered with its visual
// geometry and true joint offsets, segmented by colour (silhouettes) or turned into edge
// distance maps, scored with the internal model's proxy geometry.
#include <gtest/gtest.h>

#include <cstdio>
#include <numbers>

#include "somasim/body_schema/hypothesis_scorer.hpp"
#include "somasim/body_schema/observation.hpp"
#include "somasim/error.hpp"
#include "somasim/render/context.hpp"
#include "somasim/render/robot_scene.hpp"
#include "somasim/robot/robot_loader.hpp"

namespace somasim::body_schema {
namespace {

std::shared_ptr<const robot::RobotModel> icub() {
  static const auto m =
      robot::load_robot_model_shared(SOMASIM_SOURCE_DIR "/assets/robots/icub_v1.yaml");
  return m;
}

const std::vector<std::string> kArmJoints = {
    "r_shoulder_pitch", "r_shoulder_roll", "r_shoulder_yaw", "r_elbow",
    "r_wrist_prosup",   "r_wrist_pitch",   "r_wrist_yaw"};
const Eigen::Matrix<double, 7, 1> kBeta =
    (Eigen::Matrix<double, 7, 1>() << 5, 4, 3, -2, 3, -7, 3).finished();

std::vector<int> arm_dofs() {
  std::vector<int> dofs;
  for (const auto& j : kArmJoints) dofs.push_back(icub()->dof_index(j));
  return dofs;
}

// Encoder readings with the right hand in front of the eyes.
Eigen::VectorXd encoders() {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(icub()->num_dofs());
  const std::map<std::string, double> deg = {{"r_shoulder_pitch", -85}, {"r_shoulder_roll", 10},
                                             {"r_shoulder_yaw", 20},    {"r_elbow", 50},
                                             {"r_wrist_prosup", 10},    {"r_wrist_pitch", -10}};
  for (const auto& [j, d] : deg) q[icub()->dof_index(j)] = d * std::numbers::pi / 180.0;
  return q;
}

struct RealEyes {
  std::vector<render::Camera> cameras;
  std::vector<cv::Mat> rgb;
};

// The real arm (encoders + kBeta) rendered on white by the SceneRenderer on this thread.
RealEyes look(const Eigen::VectorXd& q) {
  render::OsmesaContext context;
  render::SceneRenderer renderer(context.gl());
  render::RobotScene scene(renderer, icub());
  robot::RobotData data(*icub());
  Eigen::VectorXd beta = Eigen::VectorXd::Zero(icub()->num_dofs());
  const std::vector<int> dofs = arm_dofs();
  for (std::size_t j = 0; j < dofs.size(); ++j)
    beta[dofs[j]] = kBeta[static_cast<Eigen::Index>(j)] * std::numbers::pi / 180.0;
  robot::forward_kinematics(*icub(), data, q, beta);
  RealEyes eyes;
  render::RenderOptions options;
  options.background = Eigen::Vector3f::Ones();
  for (const char* eye : {"left_eye", "right_eye"}) {
    const render::Camera cam = render::camera_for(*icub(), eye, data.link_poses);
    std::vector<render::DrawItem> items;
    const Eigen::Vector3d viewpoint = cam.pose_root.translation();
    scene.add_robot(data.link_poses, items, &viewpoint);
    eyes.cameras.push_back(cam);
    eyes.rgb.push_back(renderer.render(items, cam, options).rgb);
  }
  return eyes;
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
  std::vector<cv::Mat> distances;
  for (const cv::Mat& rgb : eyes.rgb) distances.push_back(edge_distance_map(rgb));
  ScorerOptions options;
  options.kind = LikelihoodKind::kEdges;
  options.edge_lambda = 25.0 / 255.0;
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
