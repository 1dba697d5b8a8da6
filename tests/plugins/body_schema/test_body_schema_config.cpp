// The body_schema plugins' configuration errors through the public harness: each names the
// node, the key and what was expected (cross-field checks in the configs' validate(), checks
// against the robot model at configure). Every case fails before the filter renders anything.
#include <gtest/gtest.h>

#include <string>

#include "somasim/error.hpp"
#include "somasim/testing/harness.hpp"

using somasim::testing::Harness;

namespace {

const std::string kRobot = SOMASIM_SOURCE_DIR "/assets/robots/icub_v1.yaml";

std::string filter_graph(const std::string& params) {
  return "seed: 1\nbase_rate_hz: 10\nrobots: {icub: " + kRobot +
         "}\nnodes:\n  filter:\n    plugin: body_schema_filter\n    params: {" + params +
         "}\n    inputs: {joint_state: harness.q, left_eye_rgb: harness.left, right_eye_rgb: "
         "harness.right}\n";
}

std::string reach_graph(const std::string& params) {
  return "seed: 1\nbase_rate_hz: 10\nrobots: {icub: " + kRobot +
         "}\nnodes:\n  reach:\n    plugin: reach_controller\n    params: {" +
         (params.find("targets") == std::string::npos  // one valid target unless given
              ? "targets: [0.02, 0.01, 0.2, 36, -62, -106]" + (params.empty() ? "" : ", " + params)
              : params) +
         "}\n    inputs: {joint_state: harness.q, estimate: harness.estimate, true_link_poses: "
         "harness.poses}\n";
}

// The message of the InputError that building `graph` throws ("" when none).
std::string error_of(const std::string& graph) {
  try {
    Harness h(graph);
  } catch (const somasim::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(BodySchemaFilterConfig, CrossFieldChecksAreLocated) {
  EXPECT_EQ(error_of(filter_graph("cameras: []")),
            "<inline>:7:23: node 'filter', key 'params.cameras': expected 1 or 2 camera names, "
            "got 0");
  EXPECT_EQ(error_of(filter_graph("compare_particles: [50, 2.5]")),
            "<inline>:7:33: node 'filter', key 'params.compare_particles': expected whole numbers "
            "of particles in [1, 20000], got 2.5");
  EXPECT_EQ(error_of(filter_graph("compare_particles: [2000000]")),
            "<inline>:7:33: node 'filter', key 'params.compare_particles': expected whole numbers "
            "of particles in [1, 20000], got 2000000");
  EXPECT_EQ(error_of(filter_graph("edge_inner_contours: true, rasterizer: software")),
            "<inline>:7:35: node 'filter', key 'params.edge_inner_contours': needs likelihood: "
            "edges");
  EXPECT_EQ(error_of(filter_graph("likelihood: edges, edge_inner_contours: true")),
            "<inline>:7:54: node 'filter', key 'params.edge_inner_contours': needs rasterizer: "
            "software");
  EXPECT_NE(error_of(filter_graph("likelihood: edges, rasterizer: software, "
                                  "edge_crease_contours: true"))
                .find("node 'filter', key 'params.edge_crease_contours': needs "
                      "edge_inner_contours: true"),
            std::string::npos);
}

// Occluders: drawn by the CPU rasterizer only, never the hand under estimation itself, links of
// the robot, and an occluder estimate wired with nothing to pose.
TEST(BodySchemaFilterConfig, OccludersAreChecked) {
  EXPECT_NE(error_of(filter_graph("occluder_links: [l_hand]"))
                .find("key 'params.occluder_links': needs rasterizer: software"),
            std::string::npos);
  EXPECT_NE(error_of(filter_graph("rasterizer: software, occluder_links: [l_hand, r_hand]"))
                .find("key 'params.occluder_links': link 'r_hand' is also a hypothesis link "
                      "(links)"),
            std::string::npos);
  EXPECT_EQ(error_of(filter_graph("rasterizer: software, occluder_links: [l_hnd]")),
            "<inline>:7:52: node 'filter', key 'params.occluder_links': robot 'icub_v1': unknown "
            "link 'l_hnd' (did you mean 'l_hand'?)");
  EXPECT_EQ(error_of(filter_graph("rasterizer: software, occluder_links: [l_hand, l_forearm]")),
            "");
}

TEST(BodySchemaFilterConfig, EmbeddedBlocksAreCheckedByTheirOwnFields) {
  EXPECT_NE(error_of(filter_graph("kde_sigma_deg: 0"))
                .find("key 'params.kde_sigma_deg': value 0 "
                      "is out of range"),
            std::string::npos);
  EXPECT_NE(error_of(filter_graph("kde_screen_keep: 0"))
                .find("key 'params.kde_screen_keep': value 0 is out of range"),
            std::string::npos);
  EXPECT_NE(error_of(filter_graph("contour_width: 3"))
                .find("key 'params.contour_width': value 3 "
                      "is out of range"),
            std::string::npos);
  EXPECT_NE(
      error_of(filter_graph("likelihood: edge"))
          .find("key 'params.likelihood': expected a string: one of silhouette, edges, got 'edge'"),
      std::string::npos);
}

TEST(BodySchemaFilterConfig, ChecksAgainstTheRobotModel) {
  EXPECT_EQ(error_of(filter_graph("joints: [r_elbow, l_elbow]")),
            "<inline>:7:22: node 'filter', key 'params.joints': joint 'l_elbow' is not in the arm "
            "chain 'right_arm' (joints: torso_pitch, torso_roll, torso_yaw, r_shoulder_pitch, "
            "r_shoulder_roll, r_shoulder_yaw, "
            "r_elbow, r_wrist_prosup, r_wrist_pitch, r_wrist_yaw)");
  EXPECT_NE(error_of(filter_graph("cameras: [left_eye, nose]"))
                .find("camera 'nose' is not in "
                      "robot 'icub_v1'"),
            std::string::npos);
  EXPECT_NE(error_of(filter_graph("true_offsets_deg: 'r_elbw: 5'"))
                .find("key "
                      "'params.true_offsets_"
                      "deg'"),
            std::string::npos);
  EXPECT_NE(error_of(filter_graph("palm_frame: r_paw")).find("key 'params.palm_frame'"),
            std::string::npos);
}

// Mistakes that used to run: a joint or camera listed twice, a true offset on a joint the filter
// does not estimate (it could never be found), 10^8 particles (allocation until killed).
TEST(BodySchemaFilterConfig, DuplicatesUnestimatedTruthAndHugeFiltersAreRefused) {
  EXPECT_NE(error_of(filter_graph("joints: [r_elbow, r_elbow]"))
                .find("key 'params.joints': joint 'r_elbow' is listed twice"),
            std::string::npos);
  EXPECT_NE(error_of(filter_graph("cameras: [left_eye, left_eye]"))
                .find("key 'params.cameras': the two cameras are the same ('left_eye')"),
            std::string::npos);
  EXPECT_NE(error_of(filter_graph("joints: [r_elbow], true_offsets_deg: 'r_wrist_prosup: 5'"))
                .find("key 'params.true_offsets_deg': joint 'r_wrist_prosup' has a true offset "
                      "but is not among the estimated joints (r_elbow)"),
            std::string::npos);
  EXPECT_EQ(error_of(filter_graph("joints: [r_elbow], true_offsets_deg: 'r_elbow: 5'")), "");
  EXPECT_NE(error_of(filter_graph("particles: 100000000"))
                .find("key 'params.particles': value 100000000 is out of range"),
            std::string::npos);
}

TEST(ReachControllerConfig, TargetsAndStartDistance) {
  EXPECT_NE(error_of(reach_graph("targets: [0.1, 0.2, 0.3]")).find("key 'params.targets'"),
            std::string::npos);
  EXPECT_EQ(error_of(reach_graph("")), "");
  EXPECT_NE(error_of(reach_graph("start_distance: [0.05, 0.01]"))
                .find("key "
                      "'params.start_distance'"),
            std::string::npos);
  EXPECT_NE(error_of(reach_graph("palm_frame: r_paw")).find("key 'params.palm_frame'"),
            std::string::npos);
}

// The bimanual report measures the fingers' surfaces from the collision shapes the fingertip
// frames lie on: a frame on a link without a primitive shape is refused where it is written.
TEST(BimanualReportConfig, FingertipsNeedAShapeToMeasureOn) {
  auto graph = [](const std::string& params) {
    return "seed: 1\nbase_rate_hz: 10\nrobots: {icub: " + kRobot +
           "}\nnodes:\n  bimanual:\n    plugin: bimanual_report\n    params: {" + params +
           "}\n    inputs: {true_link_poses: harness.poses, phase: harness.phase}\n";
  };
  EXPECT_EQ(error_of(graph("")), "");
  EXPECT_NE(error_of(graph("fingertips: [r_index_tip, l_eye]"))
                .find("key 'params.fingertips': frame 'l_eye': its link 'l_eye' has no primitive "
                      "collision shape"),
            std::string::npos)
      << error_of(graph("fingertips: [r_index_tip, l_eye]"));
  EXPECT_NE(error_of(graph("fingertips: [r_index_tip, l_nail]")).find("key 'params.fingertips'"),
            std::string::npos);
}
