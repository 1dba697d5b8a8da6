// joint_trajectory: linear and minimum-jerk profiles through YAML waypoints, done flag, targets
// on the port, other joints left alone, parameter errors.
#include <cmath>

#include <gtest/gtest.h>

#include "kinematic_world.hpp"
#include "somasim/control/joint_target.hpp"
#include "somasim/port_types.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/testing/harness.hpp"

using somasim::JointCommand;
using somasim::JointCommandMode;
using somasim::JointState;
using somasim::JointTarget;
using somasim::testing::Harness;
using somasim::testing::KinematicWorld;

namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kRate = 100.0;

std::string graph(const std::string& params, bool with_target = false) {
  return "base_rate_hz: 100\nrobots: {icub: " + somasim::testing::icub_path() +
         "}\nnodes:\n  traj: {plugin: joint_trajectory, params: {" + params +
         "}, inputs: {state: harness.state" + (with_target ? ", target: harness.target" : "") +
         "}}\n";
}

// Steps the controller with the kinematic world in the loop; calls `check(t)` after each tick
// with t the time of the step that produced the outputs.
template <class Check>
void run(Harness& h, KinematicWorld& world, int ticks, Check check) {
  for (int k = 0; k < ticks; ++k) {
    h.input<JointState>("state") = world.state;
    ASSERT_TRUE(h.step());
    world.apply(h.output<JointCommand>("traj.command"));
    check(k / kRate);
  }
}

struct Sample {
  double q = 0, qd = 0, done = 0;
  JointCommandMode mode = JointCommandMode::kNone;
};

// Elbow from 20 deg to 60 deg in 1 s, then to 30 deg in 0.5 s; records the elbow command.
std::vector<Sample> elbow_run(const std::string& profile) {
  KinematicWorld world(1.0 / kRate);
  const int elbow = world.dof("r_elbow");
  world.state.position[elbow] = 20 * kDeg;
  Harness h(
      graph("joints: r_elbow, targets_deg: [60, 30], durations: [1.0, 0.5], profile: " + profile));
  std::vector<Sample> out;
  run(h, world, 200, [&](double) {
    const auto& c = h.output<JointCommand>("traj.command");
    out.push_back({c.position[elbow] / kDeg, c.velocity[elbow] / kDeg,
                   h.output<double>("traj.done"), c.mode[elbow]});
  });
  return out;
}

}  // namespace

TEST(JointTrajectory, MinimumJerkStartMidEndWithZeroEndVelocity) {
  const auto s = elbow_run("minimum_jerk");
  EXPECT_NEAR(s[0].q, 20.0, 1e-9);  // starts from the measured state
  EXPECT_NEAR(s[0].qd, 0.0, 1e-9);
  EXPECT_NEAR(s[50].q, 40.0, 1e-9);                       // s(1/2) = 1/2
  EXPECT_NEAR(s[50].qd, 1.875 * 40.0 / 1.0, 1e-9);        // peak speed 15/8 Δ/T
  EXPECT_NEAR(s[25].q, 20.0 + 40.0 * 0.103515625, 1e-9);  // s(1/4) = 53/512
  EXPECT_NEAR(s[100].q, 60.0, 1e-9);                      // first waypoint at t = 1 s, at rest
  EXPECT_NEAR(s[100].qd, 0.0, 1e-9);
  EXPECT_NEAR(s[125].q, 45.0, 1e-9);  // half way down the second segment
  EXPECT_NEAR(s[150].q, 30.0, 1e-9);  // last waypoint at t = 1.5 s
  EXPECT_NEAR(s[150].qd, 0.0, 1e-9);
  EXPECT_NEAR(s[199].q, 30.0, 1e-12);  // and held there
  EXPECT_EQ(s[199].qd, 0.0);
  // Velocity vanishes smoothly at the ends of a segment (no step): 30 τ² Δ/T one tick in.
  EXPECT_NEAR(s[99].qd, 30 * 1e-4 * 0.9801 * 40.0, 1e-9);
  EXPECT_NEAR(s[1].qd, 30 * 1e-4 * 0.9801 * 40.0, 1e-9);
  for (const auto& x : s) EXPECT_EQ(x.mode, JointCommandMode::kPosition);
}

TEST(JointTrajectory, LinearProfileHasConstantVelocity) {
  const auto s = elbow_run("linear");
  EXPECT_NEAR(s[0].q, 20.0, 1e-9);
  EXPECT_NEAR(s[25].q, 30.0, 1e-9);
  EXPECT_NEAR(s[50].q, 40.0, 1e-9);
  for (int k = 0; k < 100; ++k) EXPECT_NEAR(s[k].qd, 40.0, 1e-9) << k;
  for (int k = 100; k < 150; ++k) EXPECT_NEAR(s[k].qd, -60.0, 1e-9) << k;
  EXPECT_NEAR(s[100].q, 60.0, 1e-9);
  EXPECT_NEAR(s[120].q, 48.0, 1e-9);
  EXPECT_NEAR(s[150].q, 30.0, 1e-9);
  EXPECT_EQ(s[150].qd, 0.0);
}

TEST(JointTrajectory, DoneWhenTheLastWaypointIsReached) {
  const auto s = elbow_run("minimum_jerk");
  for (int k = 0; k < 150; ++k) EXPECT_EQ(s[k].done, 0.0) << k;
  for (int k = 150; k < 200; ++k) EXPECT_EQ(s[k].done, 1.0) << k;
}

TEST(JointTrajectory, DoneToleranceWaitsForTheMeasuredJoints) {
  KinematicWorld world(1.0 / kRate);
  const int elbow = world.dof("r_elbow");
  world.state.position[elbow] = 20 * kDeg;
  Harness h(graph("joints: r_elbow, targets_deg: [60], durations: [0.5], done_tolerance_deg: 1"));
  for (int k = 0; k < 80; ++k) {
    h.input<JointState>("state") = world.state;  // the joint is stuck: never follows
    ASSERT_TRUE(h.step());
  }
  EXPECT_EQ(h.output<double>("traj.done"), 0.0);
  world.state.position[elbow] = 59.5 * kDeg;
  h.input<JointState>("state") = world.state;
  ASSERT_TRUE(h.step());
  EXPECT_EQ(h.output<double>("traj.done"), 1.0);
}

TEST(JointTrajectory, CommandsOnlyItsJointsAndMovesThemTogether) {
  KinematicWorld world(1.0 / kRate);
  const int sp = world.dof("r_shoulder_pitch"), el = world.dof("r_elbow");
  const Eigen::VectorXd start = world.state.position;
  Harness h(
      graph("joints: \"r_shoulder_pitch  r_elbow\", targets_deg: [-30, 50, -10, 80], "
            "durations: [0.4, 0.6]"));
  run(h, world, 120, [&](double) {
    const auto& c = h.output<JointCommand>("traj.command");
    for (int d = 0; d < world.model->num_dofs(); ++d)
      EXPECT_EQ(c.mode[d],
                d == sp || d == el ? JointCommandMode::kPosition : JointCommandMode::kNone);
  });
  EXPECT_NEAR(world.state.position[sp], -10 * kDeg, 1e-12);
  EXPECT_NEAR(world.state.position[el], 80 * kDeg, 1e-12);
  for (int d = 0; d < world.model->num_dofs(); ++d) {
    if (d != sp && d != el) {
      EXPECT_EQ(world.state.position[d], start[d]);
    }
  }
  EXPECT_EQ(h.output<double>("traj.done"), 1.0);
}

TEST(JointTrajectory, TargetsOnThePortStartFromTheCurrentReference) {
  KinematicWorld world(1.0 / kRate);
  const int n = world.model->num_dofs();
  const int wy = world.dof("r_wrist_yaw");
  world.state.position[wy] = 0.0;
  Harness h(graph("profile: linear", /*with_target=*/true));
  // No target yet: nothing commanded, nothing pending.
  run(h, world, 3, [&](double) {
    for (auto m : h.output<JointCommand>("traj.command").mode)
      EXPECT_EQ(m, JointCommandMode::kNone);
    EXPECT_EQ(h.output<double>("traj.done"), 1.0);
  });
  JointTarget& target = h.input<JointTarget>("target");
  target.id = 1;
  target.active.assign(n, false);
  target.active[wy] = true;
  target.position.setZero(n);
  target.position[wy] = 20 * kDeg;
  target.duration_s = 0.5;
  std::vector<double> q;
  run(h, world, 60,
      [&](double) { q.push_back(h.output<JointCommand>("traj.command").position[wy] / kDeg); });
  EXPECT_NEAR(q[0], 0.0, 1e-9);
  EXPECT_NEAR(q[25], 10.0, 1e-9);
  EXPECT_NEAR(q[50], 20.0, 1e-9);
  EXPECT_EQ(h.output<double>("traj.done"), 1.0);
  // A new goal mid-way starts from where the reference is, not from the measured joint.
  target.id = 2;
  target.position[wy] = -20 * kDeg;
  target.duration_s = 1.0;
  q.clear();
  run(h, world, 30, [&](double) {
    q.push_back(h.output<JointCommand>("traj.command").position[wy] / kDeg);
    EXPECT_EQ(h.output<double>("traj.done"), 0.0);
  });
  EXPECT_NEAR(q[0], 20.0, 1e-9);
  EXPECT_NEAR(q[10], 16.0, 1e-9);
  EXPECT_EQ(h.finish(), "");
  EXPECT_EQ(h.metric("traj", "targets_received"), 2);
}

TEST(JointTrajectory, ParameterErrorsNameTheProblem) {
  const auto error_of = [](const std::string& params) -> std::string {
    try {
      Harness h(graph(params));
      return "no error";
    } catch (const somasim::InputError& e) {
      return e.what();
    }
  };
  // Columns depend on the absolute robot path in the YAML; compare from the node name on.
  const auto tail = [](const std::string& m) { return m.substr(m.find("node")); };
  EXPECT_EQ(tail(error_of("joints: \"r_elbow r_wrist_yaw\", targets_deg: [10, 20, 30], "
                          "durations: [1, 2]")),
            "node 'traj', key 'params.targets_deg': expected 4 values (2 waypoints x 2 joints, "
            "waypoint-major), got 3");
  EXPECT_EQ(tail(error_of("joints: r_elbw, targets_deg: [10], durations: [1]")),
            "node 'traj', key 'params.joints': robot 'icub_v1': unknown joint 'r_elbw' (did you "
            "mean 'r_elbow'?)");
  EXPECT_EQ(tail(error_of("joints: \"r_elbow r_elbow\"")),
            "node 'traj', key 'params.joints': joint 'r_elbow' is listed twice");
  EXPECT_EQ(tail(error_of("joints: r_elbow, targets_deg: [120], durations: [1]")),
            "node 'traj', key 'params.targets_deg': waypoint 0, joint 'r_elbow': 120 is outside "
            "the joint limits [5.5, 106]");
  EXPECT_EQ(tail(error_of("targets_deg: [], durations: [1]")),
            "node 'traj', key 'params.joints': waypoints are given (durations) but no joints");
}
