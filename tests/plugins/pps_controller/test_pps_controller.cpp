// pps_controller: above-threshold forearm taxels vote a point P and normal N; integrating the
// command moves that point of the arm along -N (avoid) / +N (reach) at 0.10 m/s (checked with
// forward kinematics); below the threshold nothing moves; persistence, then return home; the
// workspace radius; bad thresholds and a body part outside the chain.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "kinematic_world.hpp"
#include "somasim/port_types.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/skin/ports.hpp"
#include "somasim/testing/harness.hpp"

using somasim::JointCommand;
using somasim::JointState;
using somasim::SkinPart;
using somasim::SkinTaxels;
using somasim::TaxelValues;
using somasim::testing::Harness;
using somasim::testing::KinematicWorld;

namespace {

constexpr double kRate = 100.0;
constexpr double kDt = 1.0 / kRate;

std::string graph(const std::string& params) {
  return "base_rate_hz: 100\nrobots: {icub: " + somasim::testing::icub_path() +
         "}\nnodes:\n  pc: {plugin: pps_controller, params: {robot: icub, chain: left_arm, "
         "body_part: left_forearm, " +
         params +
         "}, inputs: {taxels: harness.taxels, activations: harness.act, state: "
         "harness.state}}\n";
}

std::string error_of(const std::string& yaml, int ticks = 1) {
  try {
    KinematicWorld world(kDt);
    Harness h(yaml);
    for (int k = 0; k < ticks; ++k) {
      h.input<JointState>("state") = world.state;
      h.input<TaxelValues>("act").values.assign(4, 0.0);
      h.step();
    }
    return "no error";
  } catch (const somasim::InputError& e) {
    const std::string m = e.what();
    return m.substr(m.find("node"));
  }
}

// A patch of four taxels on a forearm link, posed from the world's joints each tick.
struct Skin {
  explicit Skin(const std::string& link_name = "l_forearm") {
    part.name = "left_forearm";
    part.link = link_name;
    part.taxel_ids = {0, 1, 2, 3};
    part.positions_link = {
        {0.02, 0.0, -0.05}, {0.0, 0.02, -0.06}, {-0.02, 0.0, -0.07}, {0, 0, -0.08}};
    const Eigen::Vector3d n0 = Eigen::Vector3d(1.0, 0.3, 0.0).normalized();
    const Eigen::Vector3d n1 = Eigen::Vector3d(0.8, 0.6, 0.1).normalized();
    part.normals_link = {n0, n1, n0, n1};
  }
  void pose(const KinematicWorld& w) {
    somasim::robot::RobotData data(*w.model);
    somasim::robot::forward_kinematics(*w.model, data, w.state.position);
    const auto& t = data.link_poses[w.model->link_index(part.link)];
    part.positions.clear();
    part.normals.clear();
    for (std::size_t i = 0; i < part.taxel_ids.size(); ++i) {
      part.positions.push_back(t * part.positions_link[i]);
      part.normals.push_back(t.linear() * part.normals_link[i]);
    }
  }
  SkinPart part;
};

Eigen::Vector3d point_at(const KinematicWorld& w, const Eigen::Vector3d& p_link) {
  somasim::robot::RobotData data(*w.model);
  somasim::robot::forward_kinematics(*w.model, data, w.state.position);
  return data.link_poses[w.model->link_index("l_forearm")] * p_link;
}

// One control tick with the kinematic world in the loop.
void tick(Harness& h, KinematicWorld& world, Skin& skin, const std::vector<double>& act) {
  skin.pose(world);
  h.input<SkinTaxels>("taxels").parts = {skin.part};
  h.input<TaxelValues>("act").values = act;
  h.input<JointState>("state") = world.state;
  ASSERT_TRUE(h.step());
  world.apply(h.output<JointCommand>("pc.command"));
}

// The voted point P and normal N (root frame) for `act` at the world's posture.
void vote(const Skin& skin, const std::vector<double>& act, double threshold, Eigen::Vector3d& p,
          Eigen::Vector3d& n) {
  double sum = 0;
  p.setZero();
  n.setZero();
  for (std::size_t i = 0; i < act.size(); ++i) {
    if (act[i] <= threshold) continue;
    sum += act[i];
    p += act[i] * skin.part.positions[i];
    n += act[i] * skin.part.normals[i];
  }
  p /= sum;
  n.normalize();
}

void expect_moves_voted_point(const std::string& mode, double sign) {
  KinematicWorld world(kDt);
  Skin skin;
  Harness h(graph("mode: " + mode));
  const std::vector<double> act = {0.9, 0.5, 0.3, 0.7};  // taxel 2 is below the threshold
  skin.pose(world);
  Eigen::Vector3d p0, n0;
  vote(skin, act, 0.4, p0, n0);
  // The material point of the forearm at P (fixed in the link frame: activations are constant).
  somasim::robot::RobotData data(*world.model);
  somasim::robot::forward_kinematics(*world.model, data, world.state.position);
  const Eigen::Vector3d p_link =
      data.link_poses[world.model->link_index("l_forearm")].inverse() * p0;
  const Eigen::Vector3d start = p0;
  double along = 0.0;
  for (int k = 0; k < 100; ++k) {
    Eigen::Vector3d p, n;
    skin.pose(world);
    vote(skin, act, 0.4, p, n);
    const Eigen::Vector3d before = point_at(world, p_link);
    ASSERT_NEAR((before - p).norm(), 0.0, 1e-9) << k;
    tick(h, world, skin, act);
    EXPECT_EQ(h.output<double>("pc.triggered"), 1.0);
    EXPECT_NEAR((h.output<Eigen::Vector3d>("pc.point") - p).norm(), 0.0, 1e-12) << k;
    EXPECT_NEAR((h.output<Eigen::Vector3d>("pc.velocity") - sign * 0.10 * n).norm(), 0.0, 1e-12);
    const Eigen::Vector3d moved = point_at(world, p_link) - before;
    const Eigen::Vector3d dir = sign * n;
    EXPECT_NEAR(moved.dot(dir), 0.10 * kDt, 2e-5) << k;           // speed
    EXPECT_LT((moved - moved.dot(dir) * dir).norm(), 2e-5) << k;  // direction
    along += moved.dot(dir);
  }
  EXPECT_NEAR(along, 0.10, 0.002);
  // Overall it went mostly along the initial ±N (the normal turns a little with the forearm).
  EXPECT_GT((point_at(world, p_link) - start).dot(sign * n0), 0.09);
  EXPECT_EQ(h.finish(), "");
  EXPECT_EQ(h.metric("pc", "triggers").get<long>(), 1);
  EXPECT_NEAR(h.metric("pc", "triggered_time_s").get<double>(), 1.0, 1e-9);
  // The metric is the farthest of the part's taxels: at least as far as the controlled point.
  const double metric = h.metric("pc", "max_distance_from_home_m").get<double>();
  EXPECT_GE(metric, (point_at(world, p_link) - start).norm() - 1e-9);
  EXPECT_LT(metric, (point_at(world, p_link) - start).norm() + 0.01);
}

}  // namespace

TEST(PpsController, AvoidMovesTheVotedPointAlongMinusN) {
  expect_moves_voted_point("avoid", -1.0);
}

TEST(PpsController, ReachMovesTheVotedPointAlongPlusN) {
  expect_moves_voted_point("reach", 1.0);
}

TEST(PpsController, BelowTheThresholdNothingMoves) {
  KinematicWorld world(kDt);
  Skin skin;
  Harness h(graph("threshold: 0.4"));
  const Eigen::VectorXd q0 = world.state.position;
  for (int k = 0; k < 50; ++k) {
    tick(h, world, skin, {0.4, 0.39, 0.0, 0.2});  // equal to the threshold does not vote
    EXPECT_EQ(h.output<double>("pc.triggered"), 0.0);
    EXPECT_EQ(h.output<Eigen::Vector3d>("pc.velocity").norm(), 0.0);
  }
  EXPECT_EQ((world.state.position - q0).norm(), 0.0);
  EXPECT_EQ(h.finish(), "");
  EXPECT_EQ(h.metric("pc", "triggers").get<long>(), 0);
  EXPECT_EQ(h.metric("pc", "max_distance_from_home_m").get<double>(), 0.0);
}

// With trigger_hold_s 0.05 an activation of one camera frame (5 ticks) moves nothing; one of
// two frames triggers at its sixth tick.
TEST(PpsController, ACrossingShorterThanTheHoldTimeMovesNothing) {
  KinematicWorld world(kDt);
  Skin skin;
  Harness h(graph("trigger_hold_s: 0.05, persistence: 0.0, return_after: 100"));
  const Eigen::VectorXd q0 = world.state.position;
  const std::vector<double> on = {0.8, 0.8, 0.8, 0.8}, off = {0, 0, 0, 0};
  for (int k = 0; k < 5; ++k) tick(h, world, skin, on);
  for (int k = 0; k < 10; ++k) tick(h, world, skin, off);
  EXPECT_EQ((world.state.position - q0).norm(), 0.0);
  for (int k = 0; k < 10; ++k) {
    tick(h, world, skin, on);
    EXPECT_EQ(h.output<double>("pc.triggered"), k >= 5 ? 1.0 : 0.0) << k;
  }
  EXPECT_GT((world.state.position - q0).norm(), 0.0);
  EXPECT_EQ(h.finish(), "");
  EXPECT_EQ(h.metric("pc", "triggers").get<long>(), 1);
}

// With trigger_at_once_above 0.6 the hold applies to marginal crossings only: one frame at 0.5
// moves nothing, one frame at 0.8 triggers at its first tick.
TEST(PpsController, ACrossingFarAboveTheThresholdDoesNotWaitTheHold) {
  KinematicWorld world(kDt);
  Skin skin;
  Harness h(
      graph("trigger_hold_s: 0.05, trigger_at_once_above: 0.6, persistence: 0.0, "
            "return_after: 100"));
  const Eigen::VectorXd q0 = world.state.position;
  const std::vector<double> marginal = {0.5, 0.45, 0.0, 0.0}, sure = {0.5, 0.8, 0.0, 0.0},
                            off = {0, 0, 0, 0};
  for (int k = 0; k < 5; ++k) {
    tick(h, world, skin, marginal);
    EXPECT_EQ(h.output<double>("pc.triggered"), 0.0) << k;
  }
  for (int k = 0; k < 10; ++k) tick(h, world, skin, off);
  EXPECT_EQ((world.state.position - q0).norm(), 0.0);
  for (int k = 0; k < 5; ++k) {
    tick(h, world, skin, sure);
    EXPECT_EQ(h.output<double>("pc.triggered"), 1.0) << k;
  }
  EXPECT_GT((world.state.position - q0).norm(), 0.0);
  EXPECT_EQ(h.finish(), "");
  EXPECT_EQ(h.metric("pc", "triggers").get<long>(), 1);
}

TEST(PpsController, KeepsMovingForThePersistenceThenReturnsHome) {
  KinematicWorld world(kDt);
  Skin skin;
  Harness h(graph("persistence: 0.3, return_after: 1.0"));
  const Eigen::VectorXd home = world.state.position;
  const std::vector<double> on = {0.8, 0.8, 0.8, 0.8}, off = {0.1, 0.1, 0.1, 0.1};
  for (int k = 0; k < 20; ++k) tick(h, world, skin, on);  // last trigger at tick 19
  // Ticks 20..48 are within 0.3 s of the last trigger: still moving at 0.10 m/s.
  for (int k = 20; k < 49; ++k) {
    tick(h, world, skin, off);
    EXPECT_EQ(h.output<double>("pc.triggered"), 0.0);
    EXPECT_NEAR(h.output<Eigen::Vector3d>("pc.velocity").norm(), 0.10, 1e-12) << k;
  }
  // Then it holds still until 1 s after the last trigger.
  for (int k = 49; k < 119; ++k) {
    const Eigen::VectorXd q = world.state.position;
    tick(h, world, skin, off);
    EXPECT_EQ(h.output<Eigen::Vector3d>("pc.velocity").norm(), 0.0) << k;
    ASSERT_EQ((world.state.position - q).norm(), 0.0) << k;
  }
  const double away = (world.state.position - home).norm();
  EXPECT_GT(away, 0.01);
  // Then back to the start posture (joint space).
  tick(h, world, skin, off);
  EXPECT_LT((world.state.position - home).norm(), away);
  for (int k = 0; k < 500; ++k) tick(h, world, skin, off);
  EXPECT_LT((world.state.position - home).cwiseAbs().maxCoeff(), 0.1 * M_PI / 180.0);
  EXPECT_EQ(h.finish(), "");
  EXPECT_NEAR(h.metric("pc", "triggered_time_s").get<double>(), 0.2, 1e-9);
}

TEST(PpsController, ATriggerDuringTheReturnMovesAgain) {
  KinematicWorld world(kDt);
  Skin skin;
  Harness h(graph("persistence: 0.0, return_after: 0.1"));
  const std::vector<double> on = {0.8, 0.8, 0.8, 0.8}, off = {0, 0, 0, 0};
  for (int k = 0; k < 10; ++k) tick(h, world, skin, on);
  for (int k = 0; k < 30; ++k) tick(h, world, skin, off);
  EXPECT_EQ(h.output<Eigen::Vector3d>("pc.velocity").norm(), 0.0);  // returning (joint space)
  tick(h, world, skin, on);
  EXPECT_NEAR(h.output<Eigen::Vector3d>("pc.velocity").norm(), 0.10, 1e-12);
  EXPECT_EQ(h.finish(), "");
  EXPECT_EQ(h.metric("pc", "triggers").get<long>(), 2);
}

TEST(PpsController, TheControlledPointStaysWithinTheWorkspaceRadius) {
  KinematicWorld world(kDt);
  Skin skin;
  Harness h(graph("workspace_radius: 0.05"));
  const std::vector<double> act = {0.8, 0.8, 0.8, 0.8};
  skin.pose(world);
  Eigen::Vector3d p0, n0;
  vote(skin, act, 0.4, p0, n0);
  somasim::robot::RobotData data(*world.model);
  somasim::robot::forward_kinematics(*world.model, data, world.state.position);
  const Eigen::Vector3d p_link =
      data.link_poses[world.model->link_index("l_forearm")].inverse() * p0;
  const std::vector<Eigen::Vector3d> home = skin.part.positions;
  double farthest = 0.0, farthest_taxel = 0.0;
  for (int k = 0; k < 200; ++k) {  // 2 s at 0.10 m/s would be 0.2 m
    tick(h, world, skin, act);
    farthest = std::max(farthest, (point_at(world, p_link) - p0).norm());
    skin.pose(world);
    for (std::size_t i = 0; i < home.size(); ++i)
      farthest_taxel = std::max(farthest_taxel, (skin.part.positions[i] - home[i]).norm());
  }
  EXPECT_LE(farthest, 0.05 + 1e-9);
  EXPECT_LE(farthest_taxel, 0.05 + 1e-9);
  // It went up to the guard's limit, 2 mm inside (the margin for the real arm's servo lag).
  EXPECT_GT(farthest_taxel, 0.0479);
  EXPECT_GT(farthest, 0.045);                                        // (the voted point nearly)
  EXPECT_LT(h.output<Eigen::Vector3d>("pc.velocity").norm(), 1e-3);  // and stopped there
  EXPECT_EQ(h.finish(), "");
  EXPECT_NEAR(h.metric("pc", "max_distance_from_home_m").get<double>(), farthest_taxel, 1e-9);
}

// A hard push: the voted point jumps between the taxels every few ticks, fast, with a small
// radius. No taxel (so no point the controller can control) ever leaves its sphere.
TEST(PpsController, EveryPointOfThePartStaysWithinTheWorkspaceWhateverTheVote) {
  for (const char* mode : {"avoid", "reach"}) {
    KinematicWorld world(kDt);
    Skin skin;
    Harness h(graph(std::string("mode: ") + mode + ", speed: 0.5, workspace_radius: 0.03"));
    skin.pose(world);
    const std::vector<Eigen::Vector3d> home = skin.part.positions;
    double farthest = 0.0;
    for (int k = 0; k < 400; ++k) {
      std::vector<double> act(4, 0.0);
      act[static_cast<std::size_t>((k / 7) % 4)] = 0.9;  // one taxel at a time, changing
      if (k % 3 == 0) act[static_cast<std::size_t>((k / 11) % 4)] = 0.6;
      tick(h, world, skin, act);
      skin.pose(world);
      for (std::size_t i = 0; i < home.size(); ++i)
        farthest = std::max(farthest, (skin.part.positions[i] - home[i]).norm());
    }
    EXPECT_LE(farthest, 0.03 + 1e-9) << mode;
    EXPECT_GT(farthest, 0.0279) << mode;  // it was pushed to the guard's limit (2 mm inside)
    EXPECT_EQ(h.finish(), "");
    EXPECT_NEAR(h.metric("pc", "max_distance_from_home_m").get<double>(), farthest, 1e-9) << mode;
  }
}

TEST(PpsController, ThresholdOutsideZeroOneIsALoadError) {
  EXPECT_EQ(
      error_of(graph("threshold: 1.5")),
      "node 'pc', key 'params.threshold': value 1.5 is out of range; expected a number in [0, 1]");
  EXPECT_EQ(
      error_of(graph("threshold: -0.1")),
      "node 'pc', key 'params.threshold': value -0.1 is out of range; expected a number in [0, 1]");
}

TEST(PpsController, ABodyPartOnALinkOutsideTheChainIsABadInput) {
  try {
    KinematicWorld world(kDt);
    Skin skin("r_forearm");
    Harness h(graph(""));
    tick(h, world, skin, {0, 0, 0, 0});
    FAIL() << "expected an InputError";
  } catch (const somasim::InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.substr(m.find("node")),
              "node 'pc', key 'params.body_part': skin part 'left_forearm': link 'r_forearm' is "
              "not in chain 'left_arm' (links: torso_1, torso_2, chest, left_arm_2, l_shoulder_1, "
              "l_shoulder_2, l_upper_arm, l_elbow_1, l_forearm, l_wrist_1, l_hand, left_eye_2)");
  }
}

TEST(PpsController, AMissingBodyPartOrWrongActivationCountIsReported) {
  KinematicWorld world(kDt);
  Skin skin;
  {
    Harness h(graph(""));
    skin.part.name = "left_forarm";
    try {
      tick(h, world, skin, {0, 0, 0, 0});
      FAIL() << "expected an InputError";
    } catch (const somasim::InputError& e) {
      const std::string m = e.what();
      EXPECT_EQ(m.substr(m.find("node")),
                "node 'pc', key 'params.body_part': no skin part 'left_forearm' in the 'taxels' "
                "input (did you mean 'left_forarm'?); parts: left_forarm");
    }
  }
  skin.part.name = "left_forearm";
  Harness h(graph(""));
  try {
    tick(h, world, skin, {0, 0, 0});
    FAIL() << "expected a RunError";
  } catch (const somasim::RunError& e) {
    EXPECT_STREQ(e.what(),
                 "pc: 'activations' has 3 values, but skin part 'left_forearm' has 4 taxels");
  }
}

// Contract 5: a multi-part activations input (labels "part/id", parts concatenated, e.g. one
// pps_learner for several parts): the controller picks its own part's taxels by label.
TEST(PpsController, PicksItsBodyPartFromAMultiPartActivationsInput) {
  KinematicWorld world(kDt);
  Skin skin;
  Harness h(graph(""));
  const std::vector<double> act = {0.9, 0.5, 0.3, 0.7};  // in the order of the part's taxels
  for (int k = 0; k < 5; ++k) {
    skin.pose(world);
    Eigen::Vector3d p, n;
    vote(skin, act, 0.4, p, n);
    h.input<SkinTaxels>("taxels").parts = {skin.part};
    auto& in = h.input<TaxelValues>("act");
    // Another part first (all far above the threshold), then the forearm's taxels out of order.
    in.labels = {"right_palm/0",   "right_palm/1",   "left_forearm/2",
                 "left_forearm/0", "left_forearm/3", "left_forearm/1"};
    in.values = {1.0, 1.0, act[2], act[0], act[3], act[1]};
    h.input<JointState>("state") = world.state;
    ASSERT_TRUE(h.step());
    world.apply(h.output<JointCommand>("pc.command"));
    EXPECT_EQ(h.output<double>("pc.triggered"), 1.0);
    EXPECT_NEAR((h.output<Eigen::Vector3d>("pc.point") - p).norm(), 0.0, 1e-12) << k;
    EXPECT_NEAR((h.output<Eigen::Vector3d>("pc.velocity") + 0.10 * n).norm(), 0.0, 1e-12) << k;
  }
  // Only the other part above the threshold: nothing moves.
  auto& in = h.input<TaxelValues>("act");
  in.values = {1.0, 1.0, 0.0, 0.0, 0.0, 0.0};
  h.input<JointState>("state") = world.state;
  ASSERT_TRUE(h.step());
  EXPECT_EQ(h.output<double>("pc.triggered"), 0.0);
  EXPECT_EQ(h.finish(), "");
  EXPECT_EQ(h.metric("pc", "triggers").get<long>(), 1);
}

TEST(PpsController, ALabelledInputWithoutTheBodyPartIsReported) {
  KinematicWorld world(kDt);
  Skin skin;
  const auto run = [&](std::vector<std::string> labels) {
    Harness h(graph(""));
    skin.pose(world);
    h.input<SkinTaxels>("taxels").parts = {skin.part};
    auto& in = h.input<TaxelValues>("act");
    in.values.assign(labels.size(), 0.5);
    in.labels = std::move(labels);
    h.input<JointState>("state") = world.state;
    try {
      h.step();
    } catch (const somasim::RunError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(run({"right_palm/0", "right_palm/1", "torso/4"}),
            "pc: 'activations' has no values for skin part 'left_forearm' (labels 'part/id' of "
            "right_palm, torso)");
  EXPECT_EQ(run({"left_forearm/0", "left_forearm/1", "left_forearm/3", "right_palm/2"}),
            "pc: 'activations' has no value labelled 'left_forearm/2' (skin part 'left_forearm' "
            "has 4 taxels)");
}

// `base: chest`: the arm moves without the torso, so two arm controllers share no joint.
TEST(PpsController, ABaseLinkLeavesTheJointsBeforeItAlone) {
  KinematicWorld world(kDt);
  Skin skin;
  Harness h(graph("base: chest"));
  tick(h, world, skin, {0.9, 0.9, 0.9, 0.9});
  const auto& c = h.output<JointCommand>("pc.command");
  for (const char* j : {"torso_pitch", "torso_roll", "torso_yaw"})
    EXPECT_EQ(c.mode[static_cast<std::size_t>(world.dof(j))], somasim::JointCommandMode::kNone)
        << j;
  for (const char* j : {"l_shoulder_pitch", "l_elbow", "l_wrist_yaw"})
    EXPECT_EQ(c.mode[static_cast<std::size_t>(world.dof(j))], somasim::JointCommandMode::kVelocity)
        << j;
  EXPECT_NEAR(h.output<Eigen::Vector3d>("pc.velocity").norm(), 0.10, 1e-12);
  EXPECT_EQ(h.finish(), "");
}

namespace {

// The forearm's rotation [rad] and the displacement of its voted point and of a point at the
// wrist [m] after `ticks` of reaching with the given extra params.
struct ReachMotion {
  double rotation = 0.0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d wrist = Eigen::Vector3d::Zero();
};

ReachMotion reach_for(const std::string& params, int ticks) {
  KinematicWorld world(kDt);
  Skin skin;
  Harness h(graph("mode: reach, " + params));
  const std::vector<double> act = {0.9, 0.5, 0.3, 0.7};
  skin.pose(world);
  Eigen::Vector3d p0, n0;
  vote(skin, act, 0.4, p0, n0);
  somasim::robot::RobotData data(*world.model);
  const int forearm = world.model->link_index("l_forearm");
  somasim::robot::forward_kinematics(*world.model, data, world.state.position);
  const Eigen::Isometry3d start = data.link_poses[forearm];
  const Eigen::Vector3d p_link = start.inverse() * p0;
  const Eigen::Vector3d wrist_link(0.0, 0.0, -0.14);  // beyond the patch, toward the hand
  for (int k = 0; k < ticks; ++k) tick(h, world, skin, act);
  somasim::robot::forward_kinematics(*world.model, data, world.state.position);
  const Eigen::Isometry3d end = data.link_poses[forearm];
  ReachMotion m;
  m.rotation = Eigen::AngleAxisd(end.linear() * start.linear().transpose()).angle();
  m.point = end * p_link - start * p_link;
  m.wrist = end * wrist_link - start * wrist_link;
  return m;
}

}  // namespace

// hold_orientation: the part translates (its voted point toward its target, a point at the
// wrist with it; six rows ask more of the joints, so the point may lag the commanded speed);
// without it the forearm turns as the point moves (here by 14 degrees in 5 cm).
TEST(PpsController, HoldingTheOrientationMovesThePartWithoutTurningIt) {
  const ReachMotion held = reach_for("hold_orientation: true", 50);
  const ReachMotion free = reach_for("hold_orientation: false", 50);
  EXPECT_GT(held.point.norm(), 0.035);
  EXPECT_LE(held.point.norm(), 0.05 + 1e-4);
  EXPECT_NEAR(free.point.norm(), 0.05, 0.002);
  EXPECT_LT(held.rotation, 0.002);
  EXPECT_GT(free.rotation, 0.02);
  EXPECT_LT((held.wrist - held.point).norm(), 0.0005);
  EXPECT_GT((free.wrist - free.point).norm(), 0.002);
}
