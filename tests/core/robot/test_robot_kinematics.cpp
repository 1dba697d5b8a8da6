// Forward kinematics against the iKin reference poses, Jacobians against finite differences,
// compiled chains against the tree, and the merged tree against the standalone DH chains.
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include <gtest/gtest.h>

#include "robot_test_support.hpp"
#include "somasim/error.hpp"
#include "somasim/robot/kinematic_chain.hpp"
#include "somasim/robot/kinematics.hpp"

namespace somasim::robot {
namespace {
using test::kDeg;
using test::load_icub;

// iKin reference poses (independent numpy computation of the DH tables), typed in from
// fk_test_vectors.csv: variant, chain, q [deg] in chain order, top three rows of T.
struct Reference {
  const char* variant;
  const char* chain;
  std::vector<double> q_deg;
  double t[3][4];
};

const std::vector<Reference> kReferences = {
    {"icub_v1",
     "right_arm",
     {0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
     {{0, 1, 0, -0.010817}, {0, 0, -1, 0.094116}, {-1, 0, 0, -0.176780}}},
    {"icub_v1",
     "left_arm",
     {0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
     {{0, 1, 0, -0.010817}, {0, 0, -1, -0.094116}, {-1, 0, 0, -0.176780}}},
    {"icub_v1",
     "right_arm",
     {0, 0, 0, -30, 30, 0, 45, 0, 0, 0},
     {{-0.955438, 0.180919, -0.233253, -0.298183},
      {0.274101, 0.250418, -0.928525, 0.210512},
      {-0.109577, -0.951083, -0.288849, 0.029234}}},
    {"icub_v1",
     "left_arm",
     {0, 0, 0, -30, 30, 0, 45, 0, 0, 0},
     {{-0.955438, 0.180919, 0.233253, -0.298183},
      {-0.274101, -0.250418, -0.928525, -0.210512},
      {-0.109577, -0.951083, 0.288849, 0.029234}}},
    {"icub_v1",
     "right_arm",
     {10, -5, 20, -45, 40, 10, 60, -20, -10, 5},
     {{-0.762337, -0.048824, -0.645336, -0.244770},
      {0.636973, 0.119793, -0.761521, 0.318054},
      {0.114488, -0.991598, -0.060223, 0.092723}}},
    {"icub_v2",
     "right_arm",
     {0, 0, 0, -30, 30, 0, 45, 0, 0, 0},
     {{-0.955438, 0.180919, -0.233253, -0.304333},
      {0.274101, 0.250418, -0.928525, 0.202342},
      {-0.109577, -0.951083, -0.288849, 0.025913}}},
    {"icub_v1",
     "left_eye",
     {0, 0, 0, 0, 0, 0, 0, 0},
     {{0, 0, -1, -0.062810}, {1, 0, 0, -0.034000}, {0, -1, 0, 0.340800}}},
    {"icub_v1",
     "right_eye",
     {0, 0, 0, 0, 0, 0, 0, 0},
     {{0, 0, -1, -0.062810}, {1, 0, 0, 0.034000}, {0, -1, 0, 0.340800}}},
    {"icub_v2",
     "left_eye",
     {0, 0, 0, 0, 0, 0, 0, 0},
     {{0, 0, -1, -0.056400}, {1, 0, 0, -0.034000}, {0, -1, 0, 0.346850}}},
    {"icub_v1",
     "left_eye",
     {0, 0, 0, -10, 0, 0, -10, 0},
     {{0, 0.342020, -0.939693, -0.082031},
      {1, 0, 0, -0.034000},
      {0, -0.939693, -0.342020, 0.329495}}},
    {"icub_v1",
     "right_eye",
     {0, 0, 0, -20, 5, 15, -10, 8},
     {{-0.095103, 0.494498, -0.863960, -0.104867},
      {0.990330, -0.041059, -0.132514, 0.025984},
      {-0.101001, -0.868208, -0.485811, 0.310803}}},
};

// ≤ 0.5 mm and ≤ 0.1° are required; the reference is printed to 1e-6, so check much tighter.
void expect_pose(const Eigen::Isometry3d& got, const double (&t)[3][4], const std::string& what) {
  for (int r = 0; r < 3; ++r) {
    EXPECT_NEAR(got.translation()[r], t[r][3], 2e-6) << what << " position row " << r;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got.linear()(r, c), t[r][c], 2e-6) << what;
  }
}

TEST(RobotKinematics, IkinReferencePosesThroughChainsAndTree) {
  for (const auto& ref : kReferences) {
    const RobotModel model = load_icub(ref.variant);
    const KinematicChain chain = KinematicChain::named(model, ref.chain);
    ASSERT_EQ(chain.num_dofs(), static_cast<int>(ref.q_deg.size()));
    Eigen::VectorXd q(chain.num_dofs());
    for (int k = 0; k < chain.num_dofs(); ++k) q[k] = ref.q_deg[k] * kDeg;
    const std::string what = std::string(ref.variant) + " " + ref.chain;
    expect_pose(chain.forward(q), ref.t, what + " (chain)");

    RobotData data(model);
    Eigen::VectorXd full = Eigen::VectorXd::Zero(model.num_dofs());
    for (int k = 0; k < chain.num_dofs(); ++k) full[chain.dof_indices()[k]] = q[k];
    forward_kinematics(model, data, full);
    expect_pose(frame_pose(data, model.frame_ref(model.find_chain(ref.chain)->tip_frame)), ref.t,
                what + " (tree)");
  }
}

TEST(RobotKinematics, IcubFramesAndChainsAtZero) {
  const RobotModel model = load_icub();
  EXPECT_EQ(model.num_dofs(), 23);
  const KinematicChain arm = KinematicChain::named(model, "right_arm");
  EXPECT_EQ(arm.joint_names(),
            (std::vector<std::string>{"torso_pitch", "torso_roll", "torso_yaw", "r_shoulder_pitch",
                                      "r_shoulder_roll", "r_shoulder_yaw", "r_elbow",
                                      "r_wrist_prosup", "r_wrist_pitch", "r_wrist_yaw"}));
  // Palm frame at q = 0: x = (0, 0, -1) from wrist to fingers, z = (0, -1, 0) out of the palm.
  const Eigen::Isometry3d palm = arm.forward(Eigen::VectorXd::Zero(10));
  EXPECT_LT((palm.linear().col(0) - Eigen::Vector3d(0, 0, -1)).norm(), 1e-9);
  EXPECT_LT((palm.linear().col(2) - Eigen::Vector3d(0, -1, 0)).norm(), 1e-9);
  EXPECT_LT((palm.translation() - Eigen::Vector3d(-0.0108, 0.0941, -0.1768)).norm(), 1e-4);
  // Cameras: z forward (-x of the root), x to the robot's right, y down.
  RobotData data(model);
  forward_kinematics(model, data, Eigen::VectorXd::Zero(model.num_dofs()));
  const Camera& cam = model.cameras()[model.find_camera("left_eye")];
  const Eigen::Isometry3d c = data.link_poses[cam.link] * cam.pose;
  EXPECT_LT((c.linear().col(2) - Eigen::Vector3d(-1, 0, 0)).norm(), 1e-9);
  EXPECT_LT((c.linear().col(0) - Eigen::Vector3d(0, 1, 0)).norm(), 1e-9);
  EXPECT_LT((c.translation() - Eigen::Vector3d(-0.0628, -0.034, 0.3408)).norm(), 1e-4);
  EXPECT_DOUBLE_EQ(cam.fx, 257.34);
  EXPECT_EQ(cam.width, 320);
  EXPECT_DOUBLE_EQ(cam.near, 0.04);
  // Fingertip beyond the palm along x.
  const Eigen::Vector3d tip = frame_pose(data, model.frame_ref("r_index_tip")).translation();
  EXPECT_LT(tip.z(), palm.translation().z() - 0.08);
  ASSERT_EQ(model.skin_patches().size(), 2u);
  EXPECT_EQ(model.skin_patches()[0].body_part, "left_forearm");
  EXPECT_EQ(model.skin_patches()[0].params.at("radius"), 0.021);
  EXPECT_GT(model.link(model.link_index("r_upper_arm")).inertial.mass, 0.3);
}

// The merged tree reproduces each standalone DH chain, including the chains whose torso-yaw
// parameters differ from the first chain's (left arm, eyes) and the right eye's shared tilt.
TEST(RobotKinematics, MergedTreeEqualsStandaloneDhChains) {
  const RobotModel model = load_icub();
  std::mt19937_64 rng(3);
  const std::vector<std::pair<const char*, const std::vector<test::DhRow>*>> chains = {
      {"left_arm", &test::kLeftArmV1},
      {"right_arm", &test::kRightArmV1},
      {"left_eye", &test::kLeftEyeV1},
      {"right_eye", &test::kRightEyeV1}};
  RobotData data(model);
  for (int trial = 0; trial < 50; ++trial) {
    Eigen::VectorXd q(model.num_dofs());
    for (int d = 0; d < model.num_dofs(); ++d)
      q[d] = std::uniform_real_distribution<double>(model.lower_limits()[d],
                                                    model.upper_limits()[d])(rng);
    forward_kinematics(model, data, q);
    for (const auto& [name, rows] : chains) {
      const KinematicChain chain = KinematicChain::named(model, name);
      Eigen::VectorXd qc(chain.num_dofs());
      chain.gather(q, qc);
      const Eigen::Matrix4d expected = test::dh_forward(*rows, qc);
      const Eigen::Matrix4d tree =
          frame_pose(data, model.frame_ref(model.find_chain(name)->tip_frame)).matrix();
      EXPECT_LT((tree - expected).norm(), 1e-12) << name;
      EXPECT_LT((chain.forward(qc).matrix() - expected).norm(), 1e-12) << name;
    }
  }
}

TEST(RobotKinematics, OffsetsShiftJointValues) {
  const RobotModel model = load_icub();
  const KinematicChain arm = KinematicChain::named(model, "right_arm");
  Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(10, 0.05, 0.4);
  Eigen::VectorXd beta = Eigen::VectorXd::LinSpaced(10, -0.1, 0.1);
  const Eigen::VectorXd sum = q + beta;
  EXPECT_LT((arm.forward(q, beta).matrix() - arm.forward(sum).matrix()).norm(), 1e-14);
  RobotData data(model);
  Eigen::VectorXd full = Eigen::VectorXd::Zero(model.num_dofs());
  Eigen::VectorXd full_beta = Eigen::VectorXd::Zero(model.num_dofs());
  for (int k = 0; k < 10; ++k) {
    full[arm.dof_indices()[k]] = q[k];
    full_beta[arm.dof_indices()[k]] = beta[k];
  }
  forward_kinematics(model, data, full, full_beta);
  EXPECT_LT(
      (frame_pose(data, model.frame_ref("r_palm")).matrix() - arm.forward(sum).matrix()).norm(),
      1e-14);
}

// Angular velocity from two rotations: log(R1 R0ᵀ) / h.
Eigen::Vector3d rotation_rate(const Eigen::Matrix3d& r0, const Eigen::Matrix3d& r1, double h) {
  const Eigen::AngleAxisd aa(r1 * r0.transpose());
  return aa.angle() * aa.axis() / h;
}

TEST(RobotKinematics, TreeJacobianMatchesFiniteDifferences) {
  const RobotModel model = load_icub();
  RobotData data(model);
  std::mt19937_64 rng(5);
  const int link = model.link_index("l_hand");
  const Eigen::Vector3d point(0.03, -0.01, 0.02);
  Matrix6Xd jac(6, model.num_dofs());
  for (int trial = 0; trial < 10; ++trial) {
    Eigen::VectorXd q = Eigen::VectorXd::Random(model.num_dofs()) * 0.8;
    forward_kinematics(model, data, q);
    point_jacobian(model, data, link, point, jac);
    const Eigen::Isometry3d t0 = data.link_poses[link];
    const double h = 1e-7;
    for (int d = 0; d < model.num_dofs(); ++d) {
      Eigen::VectorXd qh = q;
      qh[d] += h;
      forward_kinematics(model, data, qh);
      const Eigen::Isometry3d t1 = data.link_poses[link];
      const Eigen::Vector3d v = (t1 * point - t0 * point) / h;
      EXPECT_LT((jac.col(d).head<3>() - v).norm(), 1e-6) << "dof " << d;
      EXPECT_LT((jac.col(d).tail<3>() - rotation_rate(t0.linear(), t1.linear(), h)).norm(), 1e-6)
          << "dof " << d;
    }
  }
}

TEST(RobotKinematics, ChainJacobianMatchesTreeAndFiniteDifferences) {
  const RobotModel model = load_icub();
  const KinematicChain arm = KinematicChain::named(model, "right_arm");
  RobotData data(model);
  Matrix6Xd jc(6, arm.num_dofs()), jt(6, model.num_dofs());
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd q = Eigen::VectorXd::Random(10);
    Eigen::Isometry3d tip;
    arm.forward_jacobian(q, tip, jc);
    EXPECT_LT((tip.matrix() - arm.forward(q).matrix()).norm(), 1e-14);
    Eigen::VectorXd full = Eigen::VectorXd::Zero(model.num_dofs());
    for (int k = 0; k < 10; ++k) full[arm.dof_indices()[k]] = q[k];
    forward_kinematics(model, data, full);
    frame_jacobian(model, data, model.frame_ref("r_palm"), jt);
    for (int k = 0; k < 10; ++k) {
      EXPECT_LT((jc.col(k) - jt.col(arm.dof_indices()[k])).norm(), 1e-12);
      Eigen::VectorXd qh = q;
      qh[k] += 1e-7;
      const Eigen::Isometry3d t1 = arm.forward(qh);
      EXPECT_LT((jc.col(k).head<3>() - (t1.translation() - tip.translation()) / 1e-7).norm(), 1e-6);
      EXPECT_LT((jc.col(k).tail<3>() - rotation_rate(tip.linear(), t1.linear(), 1e-7)).norm(),
                1e-6);
    }
  }
}

TEST(RobotKinematics, PrismaticAndTiltedAxesInChains) {
  const RobotModel model = parse_robot_model(R"(robot: slide
links:
  a: {}
  b: {}
  c: {}
joints:
  j1: {type: revolute, parent: root, child: a, axis: [1, 1, 0], origin: {xyz: [0.1, 0, 0]}, limits_deg: [-90, 90]}
  j2: {type: prismatic, parent: a, child: b, axis: [0, 1, 1], origin: {rpy_deg: [10, 20, 30]}, limits: [0, 0.5], offset: 0.05}
  j3: {type: fixed, parent: b, child: c, origin: {xyz: [0, 0, 0.2]}}
frames:
  tool: {link: c, origin: {xyz: [0.01, 0.02, 0.03]}}
)",
                                             "slide.yaml", ".");
  const KinematicChain chain(model, "tool");
  RobotData data(model);
  Matrix6Xd jc(6, 2), jt(6, 2);
  const Eigen::Vector2d q(0.3, 0.2);
  forward_kinematics(model, data, q);
  Eigen::Isometry3d tip;
  chain.forward_jacobian(q, tip, jc);
  EXPECT_LT((tip.matrix() - frame_pose(data, model.frame_ref("tool")).matrix()).norm(), 1e-14);
  frame_jacobian(model, data, model.frame_ref("tool"), jt);
  EXPECT_LT((jc - jt).norm(), 1e-14);
  EXPECT_LT((jt.col(1).head<3>() - data.joint_axes[1]).norm(), 1e-14);
  EXPECT_EQ(jt.col(1).tail<3>().norm(), 0.0);
}

TEST(RobotKinematics, EyeVersionVergence) {
  const EyePans pans = eye_pans(0.2, 0.1);
  EXPECT_DOUBLE_EQ(pans.left, 0.25);
  EXPECT_DOUBLE_EQ(pans.right, 0.15);
  const auto [version, vergence] = version_vergence(pans);
  EXPECT_DOUBLE_EQ(version, 0.2);
  EXPECT_DOUBLE_EQ(vergence, 0.1);
}

TEST(RobotKinematics, SizeErrors) {
  const RobotModel model = load_icub();
  RobotData data(model);
  try {
    forward_kinematics(model, data, Eigen::VectorXd::Zero(3));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "robot 'icub_v1': expected 23 joint values, got 3");
  }
  try {
    (void)KinematicChain(model, "r_palm", "l_hand");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "robot 'icub_v1': 'r_palm' does not descend from link 'l_hand'; expected a base "
                 "link on the path from the root to the tip");
  }
  try {
    (void)model.frame_ref("r_plam");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "robot 'icub_v1': unknown frame or link 'r_plam' (did you mean 'r_palm'?)");
  }
}

// Optional: every row of the shared reference table (skipped when /work/shared is absent).
TEST(RobotKinematics, ValidationAgainstSharedReferenceTable) {
  const std::filesystem::path csv = "/work/shared/body-schema-data/derived/fk_test_vectors.csv";
  if (!std::filesystem::exists(csv)) GTEST_SKIP() << "reference table not available";
  std::ifstream in(csv);
  std::string line;
  int rows = 0;
  const std::map<std::string, std::string> chain_names = {{"arm_right", "right_arm"},
                                                          {"arm_left", "left_arm"},
                                                          {"eye_left", "left_eye"},
                                                          {"eye_right", "right_eye"}};
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("chain,", 0) == 0) continue;
    // chain,version,"q q q",T00..T23
    const auto q0 = line.find('"'), q1 = line.find('"', q0 + 1);
    std::stringstream head(line.substr(0, q0));
    std::string chain, version;
    std::getline(head, chain, ',');
    std::getline(head, version, ',');
    std::stringstream qs(line.substr(q0 + 1, q1 - q0 - 1));
    std::vector<double> q;
    for (double v; qs >> v;) q.push_back(v * kDeg);
    std::stringstream ts(line.substr(q1 + 2));
    double t[12];
    for (double& v : t) {
      std::string cell;
      std::getline(ts, cell, ',');
      v = std::stod(cell);
    }
    const RobotModel model = load_icub(version == "v1" ? "icub_v1" : "icub_v2");
    const KinematicChain kc = KinematicChain::named(model, chain_names.at(chain));
    const Eigen::Isometry3d pose = kc.forward(
        Eigen::Map<const Eigen::VectorXd>(q.data(), static_cast<Eigen::Index>(q.size())));
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) EXPECT_NEAR(pose.matrix()(r, c), t[r * 4 + c], 2e-6) << line;
    ++rows;
  }
  EXPECT_GE(rows, 11);
}

}  // namespace
}  // namespace somasim::robot
