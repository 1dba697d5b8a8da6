// TouchIk (both arms solved for a self-touch), LinkClearance and posture text, against forward
// kinematics of the iCub model.
#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "somasim/control/link_clearance.hpp"
#include "somasim/control/touch_ik.hpp"
#include "somasim/error.hpp"
#include "somasim/robot/joint_text.hpp"
#include "somasim/robot/robot_loader.hpp"

using somasim::control::LinkClearance;
using somasim::control::TouchIk;
using somasim::control::TouchTarget;

namespace {

const std::string kRobot = std::string(SOMASIM_SOURCE_DIR) + "/assets/robots/icub_v1.yaml";

std::shared_ptr<const somasim::robot::RobotModel> icub() {
  return somasim::robot::load_robot_model_shared(kRobot);
}

TouchIk finger_on_forearm(const somasim::control::TouchIkOptions& options = {}) {
  const auto m = icub();
  return TouchIk(m, m->frame_ref("r_index_tip"), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                 m->link_index("l_forearm"), {}, options);
}

Eigen::VectorXd home_posture() {
  return somasim::robot::parse_posture_deg(
      *icub(),
      "l_shoulder_pitch: -60, l_shoulder_roll: 30, l_shoulder_yaw: 30, l_elbow: 55, "
      "l_wrist_prosup: -45, r_shoulder_pitch: -45, r_shoulder_roll: 30, r_shoulder_yaw: 30, "
      "r_elbow: 70");
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const somasim::InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(TouchIk, SolvesBothArmsButNotTheSharedTorso) {
  const auto m = icub();
  TouchIk ik = finger_on_forearm();
  // Right arm (7) moves the fingertip, the left shoulder, elbow and prosup (5) the forearm.
  EXPECT_EQ(ik.effector_dofs(), 7);
  ASSERT_EQ(ik.solved_dofs().size(), 12u);
  for (const char* j : {"torso_pitch", "torso_roll", "torso_yaw", "l_wrist_pitch"}) {
    const int d = m->dof_index(j);
    EXPECT_EQ(std::count(ik.solved_dofs().begin(), ik.solved_dofs().end(), d), 0) << j;
  }
  EXPECT_EQ(ik.solved_dofs().front(), m->dof_index("r_shoulder_pitch"));
  EXPECT_EQ(ik.solved_dofs()[7], m->dof_index("l_shoulder_pitch"));
}

// A reachable self-touch: the relative pose of the fingertip and the forearm at a random
// posture, asked for from the home posture.
TEST(TouchIk, PutsTheFingertipOnTheTargetAlongTheInwardNormal) {
  const auto m = icub();
  TouchIk ik = finger_on_forearm();
  somasim::robot::RobotData data(*m);
  std::mt19937_64 rng(7);
  const auto fr = m->frame_ref("r_index_tip");
  const int lf = m->link_index("l_forearm");
  int solved = 0;
  for (int trial = 0; trial < 10; ++trial) {
    Eigen::VectorXd q = home_posture();
    for (int d : ik.solved_dofs())
      q[d] = std::uniform_real_distribution<double>(m->lower_limits()[d] + 0.05,
                                                    m->upper_limits()[d] - 0.05)(rng);
    somasim::robot::forward_kinematics(*m, data, q);
    const Eigen::Isometry3d tip = somasim::robot::frame_pose(data, fr);
    const Eigen::Isometry3d forearm = data.link_poses[static_cast<std::size_t>(lf)];
    TouchTarget t;
    t.normal = -(forearm.linear().transpose() * tip.linear().col(0));
    t.distance = 0.05;
    t.point = forearm.inverse() * tip.translation() - t.distance * t.normal;

    Eigen::VectorXd sol = home_posture();
    const auto r = ik.solve(t, home_posture(), sol);
    if (!r.success) continue;
    ++solved;
    // Independent check by forward kinematics of the solution.
    somasim::robot::forward_kinematics(*m, data, sol);
    const Eigen::Isometry3d tip2 = somasim::robot::frame_pose(data, fr);
    const Eigen::Isometry3d fa2 = data.link_poses[static_cast<std::size_t>(lf)];
    const Eigen::Vector3d n = fa2.linear() * t.normal;
    EXPECT_LT((tip2.translation() - (fa2 * t.point + t.distance * n)).norm(), 5e-4);
    EXPECT_LT(std::acos(std::clamp(tip2.linear().col(0).dot(-n), -1.0, 1.0)), 0.03);
    EXPECT_NEAR(r.position_error, (tip2.translation() - (fa2 * t.point + t.distance * n)).norm(),
                1e-12);
    // Within the limits; the torso untouched.
    for (int d = 0; d < m->num_dofs(); ++d) {
      EXPECT_GE(sol[d], m->lower_limits()[d] - 1e-12);
      EXPECT_LE(sol[d], m->upper_limits()[d] + 1e-12);
    }
    EXPECT_EQ(sol[m->dof_index("torso_yaw")], home_posture()[m->dof_index("torso_yaw")]);
  }
  EXPECT_GE(solved, 8);
}

TEST(TouchIk, TiltLeansTheAxisAndLiftsTheSideTowardTheTangent) {
  const auto m = icub();
  TouchIk ik = finger_on_forearm();
  const int lf = m->link_index("l_forearm");
  const auto fr = m->frame_ref("r_index_tip");
  // Taxel 23 of the generated layout: on the forearm cover (radius 0.021 m), link frame.
  TouchTarget t;
  const double a = 225.0 * M_PI / 180.0;  // around the forearm (cover angle), toward the hand
  t.normal = Eigen::Vector3d(std::cos(a), 0.0, std::sin(a));
  t.point = Eigen::Vector3d(0.0, -0.07, 0.0) + 0.021 * t.normal;
  t.tilt = 25.0 * M_PI / 180.0;
  int solved = 0;
  for (const double sign : {1.0, -1.0}) {
    t.tangent = sign * Eigen::Vector3d::UnitY().cross(t.normal);
    Eigen::VectorXd q = home_posture();
    const auto r = ik.solve(t, home_posture(), q);
    if (!r.success) continue;
    ++solved;
    somasim::robot::RobotData data(*m);
    somasim::robot::forward_kinematics(*m, data, q);
    const Eigen::Matrix3d rf = data.link_poses[static_cast<std::size_t>(lf)].linear();
    const Eigen::Matrix3d rh = somasim::robot::frame_pose(data, fr).linear();
    const Eigen::Vector3d n = rf * t.normal, tan = rf * t.tangent.normalized();
    // The finger leans 25 deg from -n toward the tangent; the other fingers are lifted.
    EXPECT_NEAR(std::acos(std::clamp(rh.col(0).dot(-n), -1.0, 1.0)), t.tilt, 0.03);
    EXPECT_GT(rh.col(0).dot(tan), 0.3);
    EXPECT_NEAR(rh.col(1).dot(n), std::sin(t.tilt), 0.03);
    EXPECT_LT(r.roll_error, 0.03);
    // evaluate() agrees with the solver's figures.
    const auto e = ik.evaluate(t, q);
    EXPECT_TRUE(e.success);
    EXPECT_NEAR(e.position_error, r.position_error, 1e-12);
  }
  EXPECT_GE(solved, 1);
}

TEST(TouchIk, ReportsFailureWithTheBestPostureForAnUnreachableTarget) {
  const auto m = icub();
  TouchIk ik = finger_on_forearm();
  TouchTarget t;
  t.point = Eigen::Vector3d(0.0, -0.07, 0.021);
  t.distance = 2.0;  // two metres from the forearm: out of reach
  Eigen::VectorXd q = home_posture();
  const auto r = ik.solve(t, home_posture(), q);
  EXPECT_FALSE(r.success);
  EXPECT_GT(r.position_error, 1.0);
  EXPECT_GT(r.iterations, 0);
  for (int d = 0; d < m->num_dofs(); ++d) {
    EXPECT_GE(q[d], m->lower_limits()[d] - 1e-12);
    EXPECT_LE(q[d], m->upper_limits()[d] + 1e-12);
  }
}

TEST(TouchIk, BadInputIsReported) {
  const auto m = icub();
  const auto tip = m->frame_ref("r_index_tip");
  EXPECT_EQ(error_of([&] {
              TouchIk(m, tip, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                      m->link_index("l_forearm"));
            }),
            "touch IK: the effector axis is zero");
  EXPECT_EQ(
      error_of([&] { TouchIk(m, tip, Eigen::Vector3d::UnitX(), Eigen::Vector3d::Zero(), 9999); }),
      "touch IK: target link index 9999 is not a link of robot 'icub_v1'");
  EXPECT_EQ(error_of([&] {
              TouchIk(m, tip, Eigen::Vector3d::UnitX(), Eigen::Vector3d::Zero(),
                      m->link_index("r_hand"));
            }),
            "touch IK: no joint moves link 'r_hand' or link 'r_hand' without moving both "
            "(nothing to solve)");
  TouchIk ik = finger_on_forearm();
  Eigen::VectorXd q = Eigen::VectorXd::Zero(3);
  EXPECT_EQ(error_of([&] { ik.solve(TouchTarget{}, home_posture(), q); }),
            "touch IK: expected " + std::to_string(m->num_dofs()) + " joint values, got 3");
}

TEST(LinkClearance, SegmentDistances) {
  using somasim::control::segment_distance;
  const Eigen::Vector3d o = Eigen::Vector3d::Zero(), x = Eigen::Vector3d::UnitX();
  // Crossing skew segments one unit apart along z.
  EXPECT_NEAR(segment_distance(-x, x, Eigen::Vector3d(0, -1, 1), Eigen::Vector3d(0, 1, 1)), 1.0,
              1e-12);
  // Parallel, overlapping: the gap.
  EXPECT_NEAR(segment_distance(o, x, Eigen::Vector3d(0.5, 2, 0), Eigen::Vector3d(1.5, 2, 0)), 2.0,
              1e-12);
  // End to end along a line.
  EXPECT_NEAR(segment_distance(o, x, Eigen::Vector3d(3, 0, 0), Eigen::Vector3d(4, 0, 0)), 2.0,
              1e-12);
  // Points.
  EXPECT_NEAR(segment_distance(o, o, Eigen::Vector3d(0, 3, 4), Eigen::Vector3d(0, 3, 4)), 5.0,
              1e-12);
}

TEST(LinkClearance, CapsulesBoundTheShapesAndFindTheClosestLinks) {
  const auto m = icub();
  // The right hand: a palm box and five finger cylinders.
  const auto caps = somasim::control::link_capsules(*m, m->link_index("r_hand"));
  ASSERT_EQ(caps.size(), 6u);
  EXPECT_NEAR(caps[0].radius, 0.5 * std::hypot(0.065, 0.022), 1e-12);  // box: cross-section
  EXPECT_NEAR((caps[0].b - caps[0].a).norm(), 0.069, 1e-12);           // along its longest edge
  EXPECT_NEAR(caps[1].radius, 0.0065, 1e-12);                          // index finger
  EXPECT_NEAR((caps[1].b - caps[1].a).norm(), 0.080 - 0.013, 1e-9);    // rims rounded

  somasim::robot::RobotData data(*m);
  somasim::robot::forward_kinematics(*m, data, home_posture());
  LinkClearance arms(*m, {m->link_index("r_hand")}, {m->link_index("l_hand")});
  const auto far = arms.check(data.link_poses);
  EXPECT_GT(far.distance, 0.05);
  EXPECT_EQ(far.link_a, m->link_index("r_hand"));
  EXPECT_EQ(far.link_b, m->link_index("l_hand"));
  // The same link against itself overlaps; ignoring it leaves nothing to compare.
  LinkClearance self(*m, {m->link_index("r_hand")}, {m->link_index("r_hand")});
  EXPECT_LT(self.check(data.link_poses).distance, 0.0);
  LinkClearance ignored(*m, {m->link_index("r_hand")}, {m->link_index("r_hand")},
                        {{m->link_index("r_hand"), -1, m->link_index("r_hand")}});
  EXPECT_EQ(ignored.check(data.link_poses).link_a, -1);
}

TEST(PostureText, ParsesDegreesAndReportsBadPairs) {
  const auto m = icub();
  const Eigen::VectorXd q =
      somasim::robot::parse_posture_deg(*m, "l_elbow: 60, r_shoulder_pitch: -30");
  EXPECT_NEAR(q[m->dof_index("l_elbow")], 60.0 * M_PI / 180.0, 1e-12);
  EXPECT_NEAR(q[m->dof_index("r_shoulder_pitch")], -30.0 * M_PI / 180.0, 1e-12);
  // Unlisted joints: 0 clamped into the limits (the elbow's lower limit is 5.5 deg).
  EXPECT_NEAR(q[m->dof_index("r_elbow")], 5.5 * M_PI / 180.0, 1e-9);
  EXPECT_EQ(q[m->dof_index("torso_yaw")], 0.0);
  EXPECT_EQ(error_of([&] { somasim::robot::parse_posture_deg(*m, "l_elbw: 60"); }),
            "unknown joint 'l_elbw' (did you mean 'l_elbow'?) (movable joints of the robot)");
  EXPECT_EQ(error_of([&] { somasim::robot::parse_posture_deg(*m, "l_elbow 60"); }),
            "expected 'joint: value', got 'l_elbow 60' (entries separated by ',')");
  EXPECT_EQ(error_of([&] { somasim::robot::parse_posture_deg(*m, "l_elbow: 200"); }),
            "joint 'l_elbow': 200 deg is outside the limits [5.5, 106]");
}
