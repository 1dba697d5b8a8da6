// bullet_world beside MuJoCo (the benchmark peer) on one scene (moving_scene.hpp): the free iCub
// at 1 kHz holding a posture under position control and waving its right arm, one ball at a time
// thrown at its left forearm. MuJoCo steps the model `somasim robot export-mjcf` writes from the
// same loaded robot (same frames, axes, limits, inertias, collision shapes and exclusions) with
// its position servos (bandwidth 40 /s like bullet_world's motors, ±20 N·m, gravity and Coriolis
// fed forward), and a free ball of the same radius and mass reset at each throw.
//   BM_BulletMoving/0: bullet_world `joint_motion: dynamic` (through the plugin harness)
//   BM_BulletMoving/1: bullet_world `joint_motion: kinematic`
//   BM_BulletMoving/2: bullet_world `joint_motion: dynamic`, `joint_servo: computed_torque`
//   BM_BulletMoving/3: the same with `rolling_friction: 0` (sliding friction only)
//   BM_BulletMoving/4: both arms kinematic (`kinematic_joints`), torso, head and eyes dynamic
//                      (motor constraints); /5: the same with `joint_servo: computed_torque`
//   BM_MujocoMoving/0: mj_step of the exported model (MuJoCo's default solver and integrator),
//                      sliding friction only (condim 3): the contact model of BM_BulletMoving/3
//   BM_MujocoMoving/1: with bullet_world's default rolling and spinning friction, 0.5 mm
//                      (condim 6): the contact model of BM_BulletMoving/0-2
// items_per_second = physics steps per second. Counters: tracking_deg (largest |q − q*| of the
// waving joints after the first second), contacts/step (bullet_world: the contact points it
// reports; MuJoCo: ncon, every contact its collision stage keeps).
// Alternate the cases: --benchmark_repetitions=3 --benchmark_enable_random_interleaving=true.
#include <benchmark/benchmark.h>

#include <mujoco/mujoco.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>

#include "moving_scene.hpp"
#include "somasim/robot/mjcf_export.hpp"

namespace {
using namespace somasim::bench;

/// The exported robot plus the ball, loaded by MuJoCo.
struct MujocoScene {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  somasim::robot::ServoGains gains;
  int ball_qpos = 0, ball_qvel = 0;

  MujocoScene(const somasim::robot::RobotModel& model, const Eigen::VectorXd& q0,
              double rolling_friction) {
    somasim::robot::MjcfOptions options;
    options.posture = q0;
    options.rolling_friction = rolling_friction;
    gains = somasim::robot::mjcf_servo_gains(model, options);
    std::string mjcf = somasim::robot::to_mjcf(model, options);
    const double inertia = 0.4 * kBallMass * kBallRadius * kBallRadius;
    mjcf.insert(mjcf.find("  </worldbody>"),
                fmt::format("    <body name=\"ball\" pos=\"0 0 -10\"><freejoint/>"
                            "<inertial pos=\"0 0 0\" mass=\"{}\" diaginertia=\"{} {} {}\"/>"
                            "<geom type=\"sphere\" size=\"{}\"/></body>\n",
                            kBallMass, inertia, inertia, inertia, kBallRadius));
    const auto file = std::filesystem::temp_directory_path() /
                      fmt::format("somasim_bench_peer_{}.xml", ::getpid());
    std::ofstream(file) << mjcf;
    char error[1000] = "";
    m = mj_loadXML(file.c_str(), nullptr, error, sizeof error);
    std::filesystem::remove(file);
    if (!m) throw std::runtime_error(error);
    d = mj_makeData(m);
    const std::vector<int> dofs = somasim::robot::mjcf_joint_dofs(model);
    for (std::size_t k = 0; k < dofs.size(); ++k)
      if (dofs[k] != static_cast<int>(k)) throw std::runtime_error("dofs not in tree order");
    for (int k = 0; k < model.num_dofs(); ++k) d->qpos[k] = q0[k];
    ball_qpos = m->jnt_qposadr[m->njnt - 1];
    ball_qvel = m->jnt_dofadr[m->njnt - 1];
    mj_forward(m, d);
  }
  ~MujocoScene() {
    mj_deleteData(d);
    mj_deleteModel(m);
  }
  MujocoScene(const MujocoScene&) = delete;
  MujocoScene& operator=(const MujocoScene&) = delete;

  void throw_ball(const somasim::ObjectSpawn& s) {
    const Eigen::Vector3d p = s.pose.translation();
    const double pose[7] = {p.x(), p.y(), p.z(), 1, 0, 0, 0};
    std::copy(pose, pose + 7, d->qpos + ball_qpos);
    const double velocity[6] = {
        s.linear_velocity.x(), s.linear_velocity.y(), s.linear_velocity.z(), 0, 0, 0};
    std::copy(velocity, velocity + 6, d->qvel + ball_qvel);
  }
};

void BM_BulletMoving(benchmark::State& state) {
  run_bullet_moving(state, kDrives[state.range(0)]);
}
BENCHMARK(BM_BulletMoving)->DenseRange(0, 5)->Unit(benchmark::kMicrosecond);

void BM_MujocoMoving(benchmark::State& state) {
  const auto model = somasim::robot::load_robot_model_shared(kRobot);
  const Eigen::VectorXd q0 = somasim::robot::parse_posture_deg(*model, kPosture);
  MujocoScene scene(*model, q0, state.range(0) != 0 ? 0.0005 : 0.0);
  const int n = model->num_dofs();
  const Wave wave(*model);
  Eigen::VectorXd target = q0, velocity = Eigen::VectorXd::Zero(n);
  std::uint64_t step = 0, contacts = 0;
  double tracking = 0.0;
  for (auto _ : state) {
    const double t = static_cast<double>(step) * 1e-3;
    wave.apply(t, q0, target, velocity);
    if (step % kThrowPeriod == 0) scene.throw_ball(ball(step / kThrowPeriod + 1, *model));
    // qfrc_bias of the last step's state (gravity, Coriolis) fed forward.
    for (int k = 0; k < n; ++k)
      scene.d->ctrl[k] = target[k] + scene.gains.kd[k] / scene.gains.kp[k] * velocity[k] +
                         scene.d->qfrc_bias[k] / scene.gains.kp[k];
    mj_step(scene.m, scene.d);
    if (t >= 1.0)
      for (const int k : {wave.pitch, wave.elbow})
        tracking = std::max(tracking, std::abs(scene.d->qpos[k] - target[k]));
    contacts += static_cast<std::uint64_t>(scene.d->ncon);
    ++step;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["tracking_deg"] = tracking * 180.0 / M_PI;
  state.counters["contacts/step"] = static_cast<double>(contacts) / static_cast<double>(step);
}
BENCHMARK(BM_MujocoMoving)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
