// believed_kinematics: zero offsets change nothing, a joint offset moves exactly the links it
// supports (as forward kinematics says), encoder noise, bad input with whole messages.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_loader.hpp"
#include "somasim/skin/ports.hpp"
#include "somasim/testing/harness.hpp"

using somasim::InputError;
using somasim::JointState;
using somasim::LinkPoses;
using somasim::RunError;
using somasim::SkinPart;
using somasim::SkinTaxels;
using somasim::testing::Harness;
namespace robot = somasim::robot;

namespace {

const std::string kRobot = std::string(SOMASIM_SOURCE_DIR) + "/assets/robots/icub_v1.yaml";

std::shared_ptr<const robot::RobotModel> icub() {
  return robot::load_robot_model_shared(kRobot);
}

std::string believed(const std::string& params) {
  return "base_rate_hz: 20\nrobots: {icub: " + kRobot +
         "}\nnodes:\n  bk: {plugin: believed_kinematics, params: {robot: icub" +
         (params.empty() ? "" : ", " + params) +
         "}, inputs: {state: harness.state, taxels: harness.taxels}}\n";
}

// The left arm raised and bent, the right arm bent.
Eigen::VectorXd posture() {
  const auto model = icub();
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model->num_dofs());
  const double deg = M_PI / 180.0;
  q[model->dof_index("l_shoulder_pitch")] = -40 * deg;
  q[model->dof_index("l_shoulder_roll")] = 40 * deg;
  q[model->dof_index("l_elbow")] = 60 * deg;
  q[model->dof_index("r_elbow")] = 50 * deg;
  q[model->dof_index("r_wrist_pitch")] = 10 * deg;
  return q;
}

// A few taxels on the forearm and the palm, posed by the TRUE kinematics at q.
SkinTaxels true_taxels(const Eigen::VectorXd& q) {
  const auto model = icub();
  robot::RobotData data(*model);
  robot::forward_kinematics(*model, data, q);
  SkinTaxels skin;
  for (const auto& [name, link] : {std::pair<std::string, std::string>{"left_forearm", "l_forearm"},
                                   {"right_palm", "r_hand"}}) {
    SkinPart p;
    p.name = name;
    p.link = link;
    p.taxel_ids = {3, 7, 11};
    p.positions_link = {{0.03, 0.0, 0.02}, {-0.01, 0.025, 0.05}, {0.0, -0.02, 0.08}};
    p.normals_link = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                      Eigen::Vector3d(0, -1, 1).normalized()};
    const Eigen::Isometry3d& t = data.link_poses[static_cast<std::size_t>(model->link_index(link))];
    for (std::size_t k = 0; k < 3; ++k) {
      p.positions.push_back(t * p.positions_link[k]);
      p.normals.push_back(t.linear() * p.normals_link[k]);
    }
    skin.parts.push_back(p);
  }
  return skin;
}

void feed(Harness& h, const Eigen::VectorXd& q) {
  h.input<JointState>("state").position = q;
  h.input<JointState>("state").velocity = Eigen::VectorXd::Constant(q.size(), 0.25);
  h.input<SkinTaxels>("taxels") = true_taxels(q);
}

std::string config_error(const std::string& yaml) {
  try {
    Harness h(yaml);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// Where the value of the first parameter after `robot` starts (line 3 of believed()).
std::string location() {
  return "<inline>:4:" + std::to_string(78);
}

}  // namespace

TEST(BelievedKinematics, WithoutOffsetsTheBeliefIsTheTruth) {
  Harness h(believed(""));
  const Eigen::VectorXd q = posture();
  feed(h, q);
  ASSERT_TRUE(h.step());
  const auto& state = h.output<JointState>("bk.state");
  ASSERT_EQ(state.position.size(), q.size());
  EXPECT_EQ(state.position, q);
  EXPECT_EQ(state.velocity, h.input<JointState>("state").velocity);
  const auto model = icub();
  robot::RobotData data(*model);
  robot::forward_kinematics(*model, data, q);
  const auto& poses = h.output<LinkPoses>("bk.link_poses").poses;
  ASSERT_EQ(poses.size(), data.link_poses.size());
  for (std::size_t l = 0; l < poses.size(); ++l)
    EXPECT_TRUE(poses[l].isApprox(data.link_poses[l], 1e-12)) << model->link(int(l)).name;
  const SkinTaxels& in = h.input<SkinTaxels>("taxels");
  const auto& out = h.output<SkinTaxels>("bk.taxels");
  ASSERT_EQ(out.parts.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(out.parts[i].name, in.parts[i].name);
    EXPECT_EQ(out.parts[i].link, in.parts[i].link);
    EXPECT_EQ(out.parts[i].taxel_ids, in.parts[i].taxel_ids);
    EXPECT_EQ(out.parts[i].positions_link, in.parts[i].positions_link);
    EXPECT_EQ(out.parts[i].normals_link, in.parts[i].normals_link);
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_LT((out.parts[i].positions[k] - in.parts[i].positions[k]).norm(), 1e-12);
      EXPECT_LT((out.parts[i].normals[k] - in.parts[i].normals[k]).norm(), 1e-12);
    }
  }
}

TEST(BelievedKinematics, AnElbowOffsetMovesTheForearmTaxelsAsForwardKinematicsSays) {
  Harness h(believed("joint_offsets_deg: 'l_elbow: 8'"));
  const Eigen::VectorXd q = posture();
  feed(h, q);
  ASSERT_TRUE(h.step());
  const auto model = icub();
  const int elbow = model->dof_index("l_elbow");
  Eigen::VectorXd qb = q;
  qb[elbow] += 8.0 * M_PI / 180.0;
  EXPECT_LT((h.output<JointState>("bk.state").position - qb).norm(), 1e-15);
  robot::RobotData data(*model);
  robot::forward_kinematics(*model, data, qb);
  const Eigen::Isometry3d forearm = data.link_poses[std::size_t(model->link_index("l_forearm"))];
  const SkinTaxels& in = h.input<SkinTaxels>("taxels");
  const auto& out = h.output<SkinTaxels>("bk.taxels");
  for (std::size_t k = 0; k < 3; ++k) {
    const Eigen::Vector3d expected = forearm * in.parts[0].positions_link[k];
    EXPECT_LT((out.parts[0].positions[k] - expected).norm(), 1e-12);
    EXPECT_LT((out.parts[0].normals[k] - forearm.linear() * in.parts[0].normals_link[k]).norm(),
              1e-12);
    // A rotation about the elbow axis: the distance to the axis is kept and the taxel moves
    // along the arc of 8° (chord 2 r sin 4°).
    robot::RobotData t(*model);
    robot::forward_kinematics(*model, t, q);
    const Eigen::Vector3d axis = t.joint_axes[std::size_t(model->dof_joint(elbow))];
    const Eigen::Vector3d origin = t.joint_origins[std::size_t(model->dof_joint(elbow))];
    const Eigen::Vector3d rel = in.parts[0].positions[k] - origin;
    const double r = (rel - rel.dot(axis) * axis).norm();
    EXPECT_NEAR((out.parts[0].positions[k] - in.parts[0].positions[k]).norm(),
                2.0 * r * std::sin(4.0 * M_PI / 180.0), 1e-9);
    EXPECT_GT(r, 0.02);
    // The right palm does not depend on the left elbow.
    EXPECT_LT((out.parts[1].positions[k] - in.parts[1].positions[k]).norm(), 1e-12);
  }
}

TEST(BelievedKinematics, EncoderNoiseIsGaussianPerRevoluteJointAndSeeded) {
  auto believed_q = [](int seed, int ticks) {
    somasim::LoadOptions o;
    o.seed = seed;
    Harness h(believed("encoder_noise_deg: 0.5"), {}, o);
    feed(h, posture());
    std::vector<double> errors;
    for (int i = 0; i < ticks; ++i) {
      EXPECT_TRUE(h.step());
      const Eigen::VectorXd e = h.output<JointState>("bk.state").position - posture();
      errors.insert(errors.end(), e.data(), e.data() + e.size());
    }
    return errors;
  };
  const auto e = believed_q(3, 40);
  double sum2 = 0.0;
  for (double x : e) sum2 += x * x;
  const double sigma = std::sqrt(sum2 / double(e.size())) * 180.0 / M_PI;
  EXPECT_NEAR(sigma, 0.5, 0.05);  // 40 ticks × all dofs
  EXPECT_EQ(believed_q(3, 5), believed_q(3, 5));
  EXPECT_NE(believed_q(3, 5), believed_q(4, 5));
}

// The offsets as a YAML map (what `--set 'nodes.bk.params.joint_offsets_deg={l_elbow: -4}'`
// gives) mean the same as the quoted text.
TEST(BelievedKinematics, OffsetsAsAMapOrAsText) {
  auto believed_q = [](const std::string& offsets) {
    Harness h(believed("joint_offsets_deg: " + offsets));
    feed(h, posture());
    EXPECT_TRUE(h.step());
    return Eigen::VectorXd(h.output<JointState>("bk.state").position);
  };
  const Eigen::VectorXd text = believed_q("'l_elbow: -4, r_shoulder_roll: 2.5'");
  EXPECT_EQ(believed_q("{l_elbow: -4, r_shoulder_roll: 2.5}"), text);
  EXPECT_NE(text, believed_q("''"));
  EXPECT_EQ(config_error(believed("joint_offsets_deg: {l_elbow: [1, 2]}")),
            location() +
                ": node 'bk', key 'params.joint_offsets_deg': expected a string or a map of "
                "names to values, got a map holding a list");
}

TEST(BelievedKinematics, UnknownJointSuggestsTheNearest) {
  EXPECT_EQ(config_error(believed("joint_offsets_deg: 'l_elbw: 3'")),
            location() +
                ": node 'bk', key 'params.joint_offsets_deg': unknown joint 'l_elbw' (did you "
                "mean 'l_elbow'?) (movable joints of the robot)");
}

TEST(BelievedKinematics, BadOffsetValuesAreNamed) {
  EXPECT_EQ(config_error(believed("joint_offsets_deg: 'l_elbow: 3, r_wrist_yaw: 2x'")),
            location() +
                ": node 'bk', key 'params.joint_offsets_deg': joint 'r_wrist_yaw': expected a "
                "number [deg], got '2x'");
  EXPECT_EQ(config_error(believed("joint_offsets_deg: 'l_elbow 3'")),
            location() +
                ": node 'bk', key 'params.joint_offsets_deg': expected 'joint: value', got "
                "'l_elbow 3' (entries separated by ',')");
  EXPECT_EQ(
      config_error(believed("joint_offsets_deg: 'l_elbow: 3, l_elbow: 1'")),
      location() + ": node 'bk', key 'params.joint_offsets_deg': joint 'l_elbow' is given twice");
}

TEST(BelievedKinematics, AJointStateOfAnotherRobotFailsTheRun) {
  Harness h(believed(""));
  feed(h, posture());
  h.input<JointState>("state").position = Eigen::VectorXd::Zero(5);
  try {
    h.step();
    FAIL() << "no error";
  } catch (const RunError& e) {
    EXPECT_EQ(std::string(e.what()), "input 'state': expected " +
                                         std::to_string(icub()->num_dofs()) +
                                         " joint values (robot '" + icub()->name() + "'), got 5");
  }
}

// Without skin taxels wired, the state and the link poses are still published.
TEST(BelievedKinematics, TaxelsAreOptional) {
  Harness h("base_rate_hz: 20\nrobots: {icub: " + kRobot +
            "}\nnodes:\n  bk: {plugin: believed_kinematics, params: {joint_offsets_deg: 'neck_yaw: "
            "2'}, inputs: {state: harness.state}}\n");
  h.input<JointState>("state").position = posture();
  ASSERT_TRUE(h.step());
  const auto model = icub();
  EXPECT_NEAR(h.output<JointState>("bk.state").position[model->dof_index("neck_yaw")],
              2.0 * M_PI / 180.0, 1e-15);
  EXPECT_EQ(h.output<LinkPoses>("bk.link_poses").poses.size(), std::size_t(model->num_links()));
  EXPECT_TRUE(h.output<SkinTaxels>("bk.taxels").parts.empty());
}
