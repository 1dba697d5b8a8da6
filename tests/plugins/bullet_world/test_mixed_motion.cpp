// bullet_world with `kinematic_joints`: the listed joints follow their commands exactly while the
// others stay dynamic (motors or computed torques); link poses are the forward kinematics of the
// joint state; computed torques leave out the kinematic groups' masses; a ball landing on a
// kinematic forearm is reported with a force and does not move it; mixes that cannot be built
// are located errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "somasim/robot/kinematics.hpp"
#include "world_test_support.hpp"

using somasim::Contacts;
using somasim::InputError;
using somasim::JointCommand;
using somasim::JointCommandMode;
using somasim::JointState;
using somasim::LinkPoses;
using somasim::ObjectSpawns;
using somasim::testing::Harness;
using namespace world_test;

namespace {

constexpr double kDeg = M_PI / 180.0;
const char* const kLeftArm[] = {"l_shoulder_pitch", "l_shoulder_roll", "l_shoulder_yaw", "l_elbow",
                                "l_wrist_prosup",   "l_wrist_pitch",   "l_wrist_yaw"};
const std::string kLeftArmKinematic =
    "kinematic_joints: [l_shoulder_pitch, l_shoulder_roll, l_shoulder_yaw, l_elbow, "
    "l_wrist_prosup, l_wrist_pitch, l_wrist_yaw]";

Eigen::VectorXd arms_forward(const somasim::robot::RobotModel& model) {
  return with_joints_deg(model, rest_posture(model),
                         {{"l_shoulder_pitch", -40},
                          {"l_shoulder_roll", 40},
                          {"l_elbow", 60},
                          {"r_shoulder_pitch", -40},
                          {"r_shoulder_roll", 40},
                          {"r_elbow", 60}});
}

// Both elbows and the left shoulder pitch on sinusoids around `q0`.
JointCommand waving(const somasim::robot::RobotModel& model, const Eigen::VectorXd& q0, double t) {
  JointCommand c = hold(q0);
  for (const char* name : {"l_shoulder_pitch", "l_elbow", "r_elbow"}) {
    const int d = model.dof_index(name);
    c.position[d] = q0[d] + 15 * kDeg * std::sin(3.0 * t);
    c.velocity[d] = 45 * kDeg * std::cos(3.0 * t);
  }
  return c;
}

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no exception>";
}

}  // namespace

TEST(MixedMotion, AKinematicArmFollowsExactlyWhileTheOtherArmIsDynamic) {
  const auto model = icub();
  const Eigen::VectorXd q0 = arms_forward(*model);
  Harness h(world_yaml("initial_posture_deg: " + posture_param(*model, q0) + ", " +
                       kLeftArmKinematic +
                       ", locked_joints: [torso_pitch, torso_roll, torso_yaw]"));
  auto& cmd = h.input<JointCommand>("cmd");
  const auto& state = h.output<JointState>("world.joint_state");
  const auto& poses = h.output<LinkPoses>("world.link_poses");
  somasim::robot::RobotData fk(*model);
  double left_worst = 0.0, right_worst = 0.0, pose_worst = 0.0;
  const int r_elbow = model->dof_index("r_elbow");
  for (int k = 0; k < 1500; ++k) {
    cmd = waving(*model, q0, k * 1e-3);
    for (const char* name : {"torso_pitch", "torso_roll", "torso_yaw"})
      cmd.mode[static_cast<std::size_t>(model->dof_index(name))] = JointCommandMode::kNone;
    h.step();
    for (const char* name : kLeftArm) {
      const int d = model->dof_index(name);
      left_worst = std::max(left_worst, std::abs(state.position[d] - cmd.position[d]));
    }
    if (k > 500)
      right_worst =
          std::max(right_worst, std::abs(state.position[r_elbow] - cmd.position[r_elbow]));
    if (k % 100 == 0) {
      somasim::robot::forward_kinematics(*model, fk, state.position);
      for (int i = 0; i < model->num_links(); ++i)
        pose_worst =
            std::max(pose_worst, (poses.poses[i].matrix() - fk.link_poses[i].matrix()).norm());
    }
  }
  EXPECT_LT(left_worst, 1e-12);         // kinematic: the state is the command
  EXPECT_GT(right_worst, 1e-3 * kDeg);  // dynamic: motors lag a moving command ...
  EXPECT_LT(right_worst, 1.0 * kDeg);   // ... and track it
  EXPECT_LT(pose_worst, 1e-9);
  EXPECT_EQ(h.finish(), "");
}

TEST(MixedMotion, ComputedTorquesHoldTheDynamicJointsUnderAWavingKinematicArm) {
  const auto model = icub();
  const Eigen::VectorXd q0 = arms_forward(*model);
  Harness h(world_yaml("initial_posture_deg: " + posture_param(*model, q0) + ", " +
                       kLeftArmKinematic + ", joint_servo: computed_torque"));
  auto& cmd = h.input<JointCommand>("cmd");
  const auto& state = h.output<JointState>("world.joint_state");
  double worst = 0.0;
  for (int k = 0; k < 1000; ++k) {
    cmd = waving(*model, q0, k * 1e-3);
    cmd.position[model->dof_index("r_elbow")] = q0[model->dof_index("r_elbow")];
    cmd.velocity.setZero();
    h.step();
    for (int d = 0; d < model->num_dofs(); ++d)
      if (k > 300 && model->joint(model->dof_joint(d)).name.rfind("l_", 0) != 0)
        worst = std::max(worst, std::abs(state.position[d] - q0[d]));
  }
  EXPECT_LT(worst, 0.05 * kDeg);  // torso, head and right arm held (not loaded by the left arm)
  EXPECT_EQ(h.finish(), "");
}

TEST(MixedMotion, ABallLandingOnAKinematicForearmIsFeltAndDoesNotMoveIt) {
  const auto model = icub();
  const Eigen::VectorXd q0 = arms_forward(*model);
  somasim::robot::RobotData fk(*model);
  somasim::robot::forward_kinematics(*model, fk, q0);
  const Eigen::Vector3d target =
      fk.link_poses[model->link_index("l_forearm")] * Eigen::Vector3d(0, -0.07, 0);
  Harness h(
      world_yaml("initial_posture_deg: " + posture_param(*model, q0) + ", " + kLeftArmKinematic));
  somasim::ObjectSpawn ball = sphere(1, "ball", 0.02, target + Eigen::Vector3d(0, 0, 0.2));
  ball.mass = 0.2;
  ball.linear_velocity = Eigen::Vector3d(0, 0, -2.0);
  h.input<ObjectSpawns>("spawns").recent = {ball};
  h.input<JointCommand>("cmd") = hold(q0);
  const auto& state = h.output<JointState>("world.joint_state");
  const auto& contacts = h.output<Contacts>("world.contacts");
  const int forearm = model->link_index("l_forearm");
  double moved = 0.0, force = 0.0;
  for (int k = 0; k < 300; ++k) {
    h.step();
    for (const char* name : kLeftArm) {
      const int d = model->dof_index(name);
      moved = std::max(moved, std::abs(state.position[d] - q0[d]));
    }
    for (const auto& c : contacts.points)
      if (c.link_a == forearm && c.object_b == 0) force = std::max(force, c.normal_force);
  }
  EXPECT_GT(force, 1.0);  // a 0.2 kg ball at 2 m/s, stopped by the arm
  EXPECT_LT(moved, 1e-12);
  EXPECT_EQ(h.finish(), "");
}

// Generated mixes: kinematic subtrees (each drawn joint with every joint below it), some other
// joints locked, a random posture, every free joint waving, motor constraints or computed
// torques. Kinematic joints equal their commands; links behind dynamic joints only are the
// forward kinematics of the joint state; links of kinematic groups are the forward kinematics of
// their kinematic joints now and of the dynamic joints above them one step earlier (the
// documented lag).
TEST(MixedMotion, GeneratedMixesKeepKinematicJointsExactAndPosesConsistent) {
  const auto model = icub();
  const int n = model->num_dofs();
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto below = [&](int e, int d) {
    const std::vector<int>& up =
        model->supporting_dofs(model->joint(model->dof_joint(e)).child_link);
    return std::find(up.begin(), up.end(), d) != up.end();
  };
  int mixed = 0;
  for (int trial = 0; trial < 12; ++trial) {
    std::vector<bool> kinematic(static_cast<std::size_t>(n), false);
    std::vector<bool> locked(static_cast<std::size_t>(n), false);
    for (int d = 0; d < n; ++d)
      if (unit(rng) < 0.2)
        for (int e = 0; e < n; ++e)
          if (below(e, d)) kinematic[static_cast<std::size_t>(e)] = true;
    std::string kinematic_names, locked_names;
    for (int d = 0; d < n; ++d) {
      const auto k = static_cast<std::size_t>(d);
      if (!kinematic[k] && unit(rng) < 0.15) locked[k] = true;
      std::string& list = kinematic[k] ? kinematic_names
                          : locked[k]  ? locked_names
                                       : kinematic_names;
      if (kinematic[k] || locked[k])
        list += (list.empty() ? "" : ", ") + model->joint(model->dof_joint(d)).name;
    }
    const bool any = !kinematic_names.empty();
    const bool all = std::count(kinematic.begin(), kinematic.end(), true) +
                         std::count(locked.begin(), locked.end(), true) ==
                     n;
    mixed += any && !all ? 1 : 0;
    const Eigen::VectorXd q0 = random_posture(*model, rng);
    Harness h(world_yaml("initial_posture_deg: " + posture_param(*model, q0) +
                         ", kinematic_joints: [" + kinematic_names + "], locked_joints: [" +
                         locked_names +
                         "], joint_servo: " + (trial % 2 == 0 ? "constraint" : "computed_torque")));
    auto& cmd = h.input<JointCommand>("cmd");
    const auto& state = h.output<JointState>("world.joint_state");
    const auto& poses = h.output<LinkPoses>("world.link_poses");
    Eigen::VectorXd phase(n);
    for (int d = 0; d < n; ++d) phase[d] = 2.0 * M_PI * unit(rng);
    somasim::robot::RobotData fk_state(*model), fk_mixed(*model);
    double exact = 0.0, dynamic_pose = 0.0, kinematic_pose = 0.0;
    for (int step = 0; step < 300; ++step) {
      const double t = step * 1e-3;
      cmd = hold(q0);
      for (int d = 0; d < n; ++d) {
        const auto k = static_cast<std::size_t>(d);
        if (locked[k]) {
          cmd.mode[k] = JointCommandMode::kNone;
          continue;
        }
        cmd.position[d] = q0[d] + 5 * kDeg * std::sin(4.0 * t + phase[d]);
        cmd.velocity[d] = 20 * kDeg * std::cos(4.0 * t + phase[d]);
      }
      const Eigen::VectorXd before = state.position;
      h.step();
      for (int d = 0; d < n; ++d)
        if (kinematic[static_cast<std::size_t>(d)])
          exact = std::max(exact, std::abs(state.position[d] - cmd.position[d]));
      if (step % 50 != 49) continue;
      Eigen::VectorXd mixed_q = state.position;
      for (int d = 0; d < n; ++d)
        if (!kinematic[static_cast<std::size_t>(d)]) mixed_q[d] = before[d];
      somasim::robot::forward_kinematics(*model, fk_state, state.position);
      somasim::robot::forward_kinematics(*model, fk_mixed, mixed_q);
      for (int i = 0; i < model->num_links(); ++i) {
        const std::vector<int>& up = model->supporting_dofs(i);
        const bool in_kinematic_group = std::any_of(
            up.begin(), up.end(), [&](int d) { return kinematic[static_cast<std::size_t>(d)]; });
        const auto& reference = in_kinematic_group ? fk_mixed : fk_state;
        double& worst = in_kinematic_group ? kinematic_pose : dynamic_pose;
        worst =
            std::max(worst, (poses.poses[i].matrix() - reference.link_poses[i].matrix()).norm());
      }
    }
    SCOPED_TRACE("kinematic [" + kinematic_names + "], locked [" + locked_names + "]");
    EXPECT_LT(exact, 1e-12);
    EXPECT_LT(dynamic_pose, 1e-9);
    EXPECT_LT(kinematic_pose, 1e-9);
    EXPECT_EQ(h.finish(), "");
  }
  EXPECT_GE(mixed, 8);  // most draws mix both kinds
}

TEST(MixedMotion, MixesThatCannotBeBuiltAreLocatedErrors) {
  const std::string key = "node 'world', key 'params.kinematic_joints': ";
  auto message = [](const std::string& params) {
    return error_of([&] { Harness h(world_yaml(params)); });
  };
  EXPECT_NE(message("kinematic_joints: [l_elbow], locked_joints: [l_elbow, l_wrist_prosup, "
                    "l_wrist_pitch, l_wrist_yaw]")
                .find(key + "joint 'l_elbow' is both locked and kinematic (also in locked_joints)"),
            std::string::npos);
  EXPECT_NE(
      message("kinematic_joints: [l_shoulder_pitch]")
          .find(key + "joint 'l_shoulder_pitch' is kinematic but 'l_shoulder_roll' below it is "
                      "dynamic: a kinematic group carries only kinematic or locked joints (add "
                      "'l_shoulder_roll' to kinematic_joints or locked_joints)"),
      std::string::npos);
  EXPECT_NE(message("kinematic_joints: [l_wrist_yaw], joint_motion: kinematic")
                .find(key + "kinematic_joints needs joint_motion: dynamic"),
            std::string::npos);
  EXPECT_NE(message("kinematic_joints: [l_elbw]")
                .find(key + "robot 'icub_v1': unknown joint 'l_elbw' (did you mean 'l_elbow'?)"),
            std::string::npos);
  // A kinematic wrist under a dynamic arm, and every joint kinematic, are fine.
  EXPECT_EQ(message("kinematic_joints: [l_wrist_pitch, l_wrist_yaw]"), "<no exception>");
  EXPECT_EQ(message("kinematic_joints: [all]"), "<no exception>");
  EXPECT_EQ(message("kinematic_joints: [all], locked_joints: [torso_pitch, l_elbow]"),
            "<no exception>");  // 'all': every joint not locked
}
