// bullet_world at 1 kHz, the ball_on_forearm scene: the iCub holding a posture while one ball at a
// time (0.4 s lifetime, a new one every 0.4 s) is thrown at its left forearm (double-precision
// Bullet).
//   BM_WorldPlugin/L: one scheduler tick of the plugin (commands, physics, joint state, link
//                     poses, contacts, object states, blow-up checks) through the harness.
//   BM_RawBulletStep/L (baseline): the same scene (same robot, motors, filter and ball) stepped
//                     with btMultiBodyDynamicsWorld::stepSimulation, the ball spawns and the
//                     limit-constraint switching only.
//   BM_WorldMoving/K: the free robot (no joint locked) waving its right arm (shoulder pitch and
//                     elbow on sinusoids, position commands with feed-forward) while balls are
//                     thrown at its left forearm; K = 0 `joint_motion: dynamic`, K = 1 `kinematic`.
//                     Counters: tracking_deg (largest |q - q*| of the waving joints after the first
//                     second), contacts/step. K = 2: `dynamic` with `joint_servo: computed_torque`.
//   BM_WorldAfterObjects/N: BM_WorldPlugin/1 after N objects have come and gone (a long run's
//                     history: N = 0, 2,000, 20,000); the same rate at every N means the step
//                     costs per object present, not per object ever spawned.
// L = 0: every joint held by its motor; L = 1: `locked_joints: all` (the robot as static
// geometry). items_per_second = physics steps per second; real time factor = steps/s / 1000.
// Define SOMASIM_BENCH_NO_LOCKED to build the L = 0 cases against a version without locking.
#include <benchmark/benchmark.h>

#include <cmath>

#include "bullet_world.hpp"
#include "moving_scene.hpp"
#include "somasim/robot/joint_text.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/robot_loader.hpp"
#include "somasim/testing/harness.hpp"

namespace {
using namespace somasim::bullet_world;
using somasim::bench::ball;
using somasim::bench::kPosture;
using somasim::bench::kRobot;
using somasim::bench::kThrowPeriod;
#ifdef SOMASIM_BENCH_NO_LOCKED
constexpr int kSolverIterations = 30;  // the default of the version without locking
#else
constexpr int kSolverIterations = 20;  // the plugin's default
#endif

void BM_WorldPlugin(benchmark::State& state) {
  const bool locked = state.range(0) != 0;
  const auto model = somasim::robot::load_robot_model_shared(kRobot);
  somasim::testing::Harness h(
      "base_rate_hz: 1000\nrobots: {icub: " + kRobot +
      "}\nnodes:\n  world: {plugin: bullet_world, params: {initial_posture_deg: '" + kPosture +
      "'" + (locked ? ", locked_joints: all" : "") + "}, inputs: {spawns: harness.spawns}}\n");
  auto& spawns = h.input<somasim::ObjectSpawns>("spawns");
  std::uint64_t step = 0, contacts = 0;
  for (auto _ : state) {
    if (step % kThrowPeriod == 0) spawns.recent = {ball(step / kThrowPeriod + 1, *model)};
    h.step();
    contacts += h.output<somasim::Contacts>("world.contacts").points.size();
    ++step;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["contacts/step"] = static_cast<double>(contacts) / static_cast<double>(step);
  h.finish();
}
BENCHMARK(BM_WorldPlugin)
    ->Arg(0)
#ifndef SOMASIM_BENCH_NO_LOCKED
    ->Arg(1)
#endif
    ->Unit(benchmark::kMicrosecond);

void BM_WorldMoving(benchmark::State& state) {
  somasim::bench::run_bullet_moving(state, somasim::bench::kDrives[state.range(0)]);
}
BENCHMARK(BM_WorldMoving)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

void BM_WorldAfterObjects(benchmark::State& state) {
  const auto history = static_cast<std::uint64_t>(state.range(0));
  const auto model = somasim::robot::load_robot_model_shared(kRobot);
  somasim::testing::Harness h(
      "base_rate_hz: 1000\nrobots: {icub: " + kRobot +
      "}\nnodes:\n  world: {plugin: bullet_world, params: {initial_posture_deg: '" + kPosture +
      "', locked_joints: all}, inputs: {spawns: harness.spawns}}\n");
  auto& spawns = h.input<somasim::ObjectSpawns>("spawns");
  // The history: `history` small balls 2 m away, in batches of 1,000, each gone a step later.
  for (std::uint64_t done = 0; done < history;) {
    spawns.recent.clear();
    for (int k = 0; k < 1000 && done < history; ++k, ++done) {
      somasim::ObjectSpawn s;
      s.id = done + 1;
      s.name = "old" + std::to_string(done);
      s.size.x() = 0.01;
      const int row = k / 30, column = k % 30;  // a 30-wide grid
      s.pose.translation() = Eigen::Vector3d(2.0 + 0.03 * column, 0.03 * row, 1.0);
      s.remove_after_s = 1e-3;
      spawns.recent.push_back(s);
    }
    h.step(2);
  }
  std::uint64_t step = 0;
  for (auto _ : state) {
    if (step % kThrowPeriod == 0) spawns.recent = {ball(history + step / kThrowPeriod + 1, *model)};
    h.step();
    ++step;
  }
  state.SetItemsProcessed(state.iterations());
  h.finish();
}
BENCHMARK(BM_WorldAfterObjects)->Arg(0)->Arg(2000)->Arg(20000)->Unit(benchmark::kMicrosecond);

void BM_RawBulletStep(benchmark::State& state) {
  const bool locked = state.range(0) != 0;
  const auto model = somasim::robot::load_robot_model_shared(kRobot);
  const Eigen::VectorXd q0 = somasim::robot::parse_posture_deg(*model, kPosture);
  const double dt = 1e-3;
  PhysicsWorld physics(Eigen::Vector3d(0, 0, -9.81), kSolverIterations);
#ifdef SOMASIM_BENCH_NO_LOCKED
  SelfCollisionFilter filter(*model);
  physics.set_pair_filter(&filter);
  ShapeStore shapes;
  RobotMultiBody robot(model, physics.world(), shapes, q0, LinkMaterial{});
#else
  const std::vector<bool> lock(model->num_dofs(), locked);
  SelfCollisionFilter filter(*model, lock);
  physics.set_pair_filter(&filter);
  ShapeStore shapes;
  RobotMultiBody robot(model, physics.world(), shapes, q0, LinkMaterial{}, lock);
#endif
  JointMotors motors(robot, physics.world(), MotorGains{}, dt, q0);
  ObjectManager objects(physics.world(), shapes, ObjectMaterial{0.8, 0.0005, 0.0});
  std::uint64_t step = 0;
  for (auto _ : state) {
    const double t = static_cast<double>(step) * dt;
    if (step % kThrowPeriod == 0) objects.add(ball(step / kThrowPeriod + 1, *model), t);
    objects.remove_expired(t);
#ifndef SOMASIM_BENCH_NO_LOCKED
    motors.update_limits();
#endif
    physics.step(dt);
    ++step;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_RawBulletStep)
    ->Arg(0)
#ifndef SOMASIM_BENCH_NO_LOCKED
    ->Arg(1)
#endif
    ->Unit(benchmark::kMicrosecond);

}  // namespace
