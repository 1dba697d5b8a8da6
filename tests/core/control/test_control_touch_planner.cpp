// TouchPlanner (the double-touch approach) against forward kinematics of the iCub model: points
// around the left forearm's cover, generated, planned from the double-touch home posture.
#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "somasim/control/touch_planner.hpp"
#include "somasim/robot/joint_text.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/robot_loader.hpp"

using somasim::control::PlanResult;
using somasim::control::TouchIk;
using somasim::control::TouchPath;
using somasim::control::TouchPlanner;
using somasim::control::TouchPlannerOptions;
using somasim::control::TouchTarget;

namespace {

const std::string kRobot = std::string(SOMASIM_SOURCE_DIR) + "/assets/robots/icub_v1.yaml";

struct DoubleTouchScene {
  std::shared_ptr<const somasim::robot::RobotModel> model =
      somasim::robot::load_robot_model_shared(kRobot);
  Eigen::VectorXd home = somasim::robot::parse_posture_deg(
      *model,
      "l_shoulder_pitch: -60, l_shoulder_roll: 30, l_shoulder_yaw: 30, l_elbow: 55, "
      "l_wrist_prosup: -45, r_shoulder_pitch: -45, r_shoulder_roll: 30, r_shoulder_yaw: 30, "
      "r_elbow: 70");
  int forearm = model->link_index("l_forearm");
  somasim::robot::FrameRef tip = model->frame_ref("r_index_tip");

  TouchPlanner planner(const TouchPlannerOptions& options) const {
    somasim::control::TouchIkOptions io;
    io.position_tolerance = 1e-4;
    io.posture_gain = 0.03;
    TouchIk ik(model, tip, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), forearm, {}, io);
    return TouchPlanner(model, std::move(ik), options);
  }
};

// A point on the forearm cover (radius 0.021 m about the link's y axis), link frame.
TouchTarget cover_point(double angle, double along) {
  TouchTarget t;
  t.normal = Eigen::Vector3d(std::cos(angle), 0.0, std::sin(angle));
  t.point = Eigen::Vector3d(0.0, along, 0.0) + 0.021 * t.normal;
  t.tilt = 25.0 * M_PI / 180.0;
  t.tangent = Eigen::Vector3d::UnitY().cross(t.normal);
  return t;
}

}  // namespace

// Every plan found runs from start_distance in to press_depth below the skin, with postures
// within the joint limits, each of which puts the fingertip on the target's normal line at its
// distance near the skin (checked by forward kinematics, not by the planner's own solver).
TEST(TouchPlanner, PlansRunAlongTheNormalFromStartDistanceToThePress) {
  const DoubleTouchScene s;
  TouchPlannerOptions options;
  TouchPlanner planner = s.planner(options);
  somasim::robot::RobotData data(*s.model);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> angle(200.0 * M_PI / 180.0, 290.0 * M_PI / 180.0);
  std::uniform_real_distribution<double> along(-0.09, -0.04);
  int planned = 0;
  for (int trial = 0; trial < 8; ++trial) {
    const TouchTarget target = cover_point(angle(rng), along(rng));
    TouchPath path;
    std::string detail;
    if (planner.plan(target, s.home, s.home, path, detail) != PlanResult::kOk) continue;
    ++planned;
    ASSERT_GE(path.distance.size(), 2u);
    EXPECT_NEAR(path.start(), options.start_distance, 1e-12);
    EXPECT_NEAR(path.end(), -options.press_depth, 1e-12);
    for (std::size_t i = 1; i < path.distance.size(); ++i)
      EXPECT_LT(path.distance[i], path.distance[i - 1]);
    for (std::size_t i = 0; i < path.posture.size(); ++i) {
      const Eigen::VectorXd& q = path.posture[i];
      for (int d = 0; d < s.model->num_dofs(); ++d) {
        EXPECT_GE(q[d], s.model->lower_limits()[d] - 1e-9);
        EXPECT_LE(q[d], s.model->upper_limits()[d] + 1e-9);
      }
      if (path.distance[i] > options.align_distance) continue;
      somasim::robot::forward_kinematics(*s.model, data, q);
      const Eigen::Isometry3d forearm = data.link_poses[static_cast<std::size_t>(s.forearm)];
      const Eigen::Vector3d tip = somasim::robot::frame_pose(data, s.tip).translation();
      const Eigen::Vector3d n = forearm.linear() * target.normal;
      const Eigen::Vector3d expected = forearm * target.point + path.distance[i] * n;
      EXPECT_LT((tip - expected).norm(), 2e-3)
          << "waypoint " << i << " at d = " << path.distance[i];
    }
  }
  EXPECT_GE(planned, 4) << "of 8 generated targets";
}

// Between the waypoints the interpolated fingertip keeps to the approach line: sampling the path
// at any distance gives a posture whose fingertip is within the path tolerance of the line.
TEST(TouchPlanner, SampledPosturesStayOnTheApproachLine) {
  const DoubleTouchScene s;
  TouchPlannerOptions options;
  TouchPlanner planner = s.planner(options);
  somasim::robot::RobotData data(*s.model);
  const TouchTarget target = cover_point(225.0 * M_PI / 180.0, -0.07);
  TouchPath path;
  std::string detail;
  ASSERT_EQ(planner.plan(target, s.home, s.home, path, detail), PlanResult::kOk) << detail;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> d(path.end(), std::min(path.start(), 0.05));
  Eigen::VectorXd q;
  for (int k = 0; k < 40; ++k) {
    const double dk = d(rng);
    path.sample(dk, q);
    somasim::robot::forward_kinematics(*s.model, data, q);
    const Eigen::Isometry3d forearm = data.link_poses[static_cast<std::size_t>(s.forearm)];
    const Eigen::Vector3d n = forearm.linear() * target.normal;
    const Eigen::Vector3d rel =
        somasim::robot::frame_pose(data, s.tip).translation() - forearm * target.point;
    EXPECT_LT((rel - rel.dot(n) * n).norm(), options.path_tolerance + 1e-3) << "d = " << dk;
  }
}

// A target inside the other arm's reach but turned away from it (the far side of the forearm)
// is refused with a reason, not planned through the forearm.
TEST(TouchPlanner, TheFarSideOfTheForearmIsRefusedWithAReason) {
  const DoubleTouchScene s;
  TouchPlanner planner = s.planner({});
  const TouchTarget target = cover_point(60.0 * M_PI / 180.0, -0.07);
  TouchPath path;
  std::string detail;
  const PlanResult r = planner.plan(target, s.home, s.home, path, detail);
  EXPECT_NE(r, PlanResult::kOk);
  EXPECT_FALSE(detail.empty());
}
