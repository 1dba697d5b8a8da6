#pragma once
// The moving-robot scene shared by bench_world and bench_mujoco_peer: the free iCub (no joint
// locked) holding the posture of configs/ball_on_forearm.yaml while waving its right arm (shoulder
// pitch and elbow on sinusoids, position commands with feed-forward velocity), one ball at a time
// thrown at its left forearm (a new one every throw period, 0.3 s flight).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "somasim/robot/joint_text.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_loader.hpp"
#include "somasim/testing/harness.hpp"

namespace somasim::bench {

inline const std::string kRobot = SOMASIM_SOURCE_DIR "/assets/robots/icub_v1.yaml";
// The posture of configs/ball_on_forearm.yaml.
inline const std::string kPosture =
    "l_shoulder_pitch: -40, l_shoulder_roll: 40, l_shoulder_yaw: 10, l_elbow: 60, "
    "r_shoulder_pitch: -40, r_shoulder_roll: 40, r_shoulder_yaw: 10, r_elbow: 60";
inline constexpr int kThrowPeriod = 400;     // [steps] at 1 kHz
inline constexpr double kFlightTime = 0.3;   // [s]
inline constexpr double kBallRadius = 0.02;  // [m]
inline constexpr double kBallMass = 0.05;    // [kg]

// Ball number k thrown from 25 cm in front of / above the left forearm, hitting it after
// kFlightTime; removed after one throw period.
inline ObjectSpawn ball(std::uint64_t k, const robot::RobotModel& model) {
  const Eigen::VectorXd q = robot::parse_posture_deg(model, kPosture);
  robot::RobotData data(model);
  robot::forward_kinematics(model, data, q);
  const Eigen::Vector3d target =
      data.link_poses[model.link_index("l_forearm")] * Eigen::Vector3d(0, -0.07, 0);
  const double side = 0.05 * static_cast<double>(k % 3) - 0.05;
  const Eigen::Vector3d start = target + Eigen::Vector3d(-0.2, side, 0.15);
  ObjectSpawn s;
  s.id = k;
  s.name = "ball" + std::to_string(k);
  s.size.x() = kBallRadius;
  s.mass = kBallMass;
  s.pose.translation() = start;
  s.linear_velocity =
      (target - start) / kFlightTime + Eigen::Vector3d(0, 0, 0.5 * 9.81 * kFlightTime);
  s.remove_after_s = kThrowPeriod * 1e-3;
  return s;
}

/// The wave at time t [s]: position and velocity targets of the waving joints.
struct Wave {
  int pitch = -1, elbow = -1;  ///< dofs of r_shoulder_pitch and r_elbow
  explicit Wave(const robot::RobotModel& model)
      : pitch(model.dof_index("r_shoulder_pitch")), elbow(model.dof_index("r_elbow")) {}
  void apply(double t, const Eigen::VectorXd& q0, Eigen::VectorXd& position,
             Eigen::VectorXd& velocity) const {
    position[pitch] = q0[pitch] + 0.2 * std::sin(2.0 * t);
    velocity[pitch] = 0.4 * std::cos(2.0 * t);
    position[elbow] = q0[elbow] + 0.25 * std::sin(3.0 * t);
    velocity[elbow] = 0.75 * std::cos(3.0 * t);
  }
};

/// bullet_world's parameters for each way of driving the joints (index = benchmark argument).
inline const char* const kDrives[] = {
    "joint_motion: dynamic",                                // motor constraints (default)
    "joint_motion: kinematic",                              // exact, kinematic bodies
    "joint_motion: dynamic, joint_servo: computed_torque",  // inverse-dynamics torques
    "joint_motion: dynamic, joint_servo: computed_torque, rolling_friction: 0",  // sliding only
    // Both arms kinematic, torso, head and eyes dynamic: motors, then computed torques.
    "kinematic_joints: [l_shoulder_pitch, l_shoulder_roll, l_shoulder_yaw, l_elbow, "
    "l_wrist_prosup, l_wrist_pitch, l_wrist_yaw, r_shoulder_pitch, r_shoulder_roll, "
    "r_shoulder_yaw, r_elbow, r_wrist_prosup, r_wrist_pitch, r_wrist_yaw]",
    "joint_servo: computed_torque, kinematic_joints: [l_shoulder_pitch, l_shoulder_roll, "
    "l_shoulder_yaw, l_elbow, l_wrist_prosup, l_wrist_pitch, l_wrist_yaw, r_shoulder_pitch, "
    "r_shoulder_roll, r_shoulder_yaw, r_elbow, r_wrist_prosup, r_wrist_pitch, r_wrist_yaw]",
};

/// The scene stepped by the bullet_world plugin (through the harness) with `params` added to its
/// parameters (e.g. one of kDrives). Counters: tracking_deg (largest |q − q*| of the waving joints
/// after the first second), contacts/step.
inline void run_bullet_moving(benchmark::State& state, const std::string& params) {
  const auto model = robot::load_robot_model_shared(kRobot);
  testing::Harness h("base_rate_hz: 1000\nrobots: {icub: " + kRobot +
                     "}\nnodes:\n  world: {plugin: bullet_world, params: {initial_posture_deg: '" +
                     kPosture + "', " + params +
                     "}, inputs: {spawns: harness.spawns, commands: harness.cmd}}\n");
  auto& spawns = h.input<ObjectSpawns>("spawns");
  auto& cmd = h.input<JointCommand>("cmd");
  const Eigen::VectorXd q0 = robot::parse_posture_deg(*model, kPosture);
  const int n = model->num_dofs();
  cmd.mode.assign(static_cast<std::size_t>(n), JointCommandMode::kPosition);
  cmd.position = q0;
  cmd.velocity = Eigen::VectorXd::Zero(n);
  const Wave wave(*model);
  const auto& joints = h.output<JointState>("world.joint_state");
  std::uint64_t step = 0, contacts = 0;
  double tracking = 0.0;
  for (auto _ : state) {
    const double t = static_cast<double>(step) * 1e-3;
    wave.apply(t, q0, cmd.position, cmd.velocity);
    if (step % kThrowPeriod == 0) spawns.recent = {ball(step / kThrowPeriod + 1, *model)};
    h.step();
    if (t >= 1.0)
      for (const int d : {wave.pitch, wave.elbow})
        tracking = std::max(tracking, std::abs(joints.position[d] - cmd.position[d]));
    contacts += h.output<Contacts>("world.contacts").points.size();
    ++step;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["tracking_deg"] = tracking * 180.0 / M_PI;
  state.counters["contacts/step"] = static_cast<double>(contacts) / static_cast<double>(step);
  h.finish();
}

}  // namespace somasim::bench
