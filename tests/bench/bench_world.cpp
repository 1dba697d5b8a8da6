// bullet_world at 1 kHz: the iCub holding its posture, a static table with four balls resting on
// it and one on the robot's right forearm (double-precision Bullet).
//   BM_WorldPlugin: one scheduler tick of the plugin (commands, physics, joint state, link poses,
//                   contacts, object states, blow-up checks) through the harness.
//   BM_RawBulletStep (baseline): btMultiBodyDynamicsWorld::stepSimulation of the same scene
//                   (same robot, motors, filter and objects), nothing else.
// items_per_second = physics steps per second; real time factor = steps/s / 1000.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "bullet_world.hpp"
#include "posture_param.hpp"
#include "somasim/robot/robot_cache.hpp"
#include "somasim/testing/harness.hpp"

namespace {
namespace fs = std::filesystem;
using namespace somasim::bullet_world;

const std::string kRobot = SOMASIM_SOURCE_DIR "/assets/robots/icub_v1.yaml";
const std::string kPosture = "r_shoulder_roll: 20, l_shoulder_roll: 20, r_elbow: 20, l_elbow: 20";

std::vector<somasim::ObjectSpawn> scene_objects() {
  std::vector<somasim::ObjectSpawn> objects;
  somasim::ObjectSpawn table;
  table.name = "table";
  table.shape = somasim::ObjectShape::kBox;
  table.size = Eigen::Vector3d(0.15, 0.3, 0.02);
  table.motion = somasim::ObjectMotion::kStatic;
  table.pose.translation() = Eigen::Vector3d(-0.45, 0, -0.1);
  objects.push_back(table);
  for (int i = 0; i < 4; ++i) {
    somasim::ObjectSpawn ball;
    ball.id = i + 1;
    ball.name = "ball" + std::to_string(i);
    ball.size.x() = 0.03;
    ball.mass = 0.05;
    ball.pose.translation() = Eigen::Vector3d(-0.45, -0.2 + 0.13 * i, -0.05);
    objects.push_back(ball);
  }
  return objects;
}

fs::path write_scene() {
  const fs::path file =
      fs::temp_directory_path() / ("somasim-bench-world-" + std::to_string(::getpid()) + ".yaml");
  std::ofstream out(file);
  out << "objects:\n"
      << "  - {name: table, shape: box, size: [0.3, 0.6, 0.04], motion: static,"
         " xyz: [-0.45, 0, -0.1]}\n";
  for (int i = 0; i < 4; ++i)
    out << "  - {name: ball" << i << ", shape: sphere, radius: 0.03, mass: 0.05, xyz: [-0.45, "
        << -0.2 + 0.13 * i << ", -0.05]}\n";
  return file;
}

void BM_WorldPlugin(benchmark::State& state) {
  const fs::path scene = write_scene();
  somasim::testing::Harness h(
      "base_rate_hz: 1000\nnodes:\n  world: {plugin: bullet_world, "
      "params: {robot: " +
      kRobot + ", scene: " + scene.string() + ", initial_posture_deg: '" + kPosture + "'}}\n");
  h.step(500);  // let the balls settle
  for (auto _ : state) h.step();
  state.SetItemsProcessed(state.iterations());
  h.finish();
  state.counters["contacts"] = h.output<somasim::Contacts>("world.contacts").points.size();
  fs::remove(scene);
}
BENCHMARK(BM_WorldPlugin)->Unit(benchmark::kMicrosecond);

void BM_RawBulletStep(benchmark::State& state) {
  const auto model = somasim::robot::shared_robot_model(kRobot);
  const Eigen::VectorXd q0 = parse_posture(kPosture, *model);
  const double dt = 1e-3;
  PhysicsWorld physics(Eigen::Vector3d(0, 0, -9.81), static_cast<int>(state.range(0)));
  SelfCollisionFilter filter(*model);
  physics.set_pair_filter(&filter);
  ShapeStore shapes;
  RobotMultiBody robot(model, physics.world(), shapes, q0, LinkMaterial{});
  JointMotors motors(robot, physics.world(), MotorGains{}, dt, q0);
  ObjectManager objects(physics.world(), shapes, ObjectMaterial{0.8, 0.0005, 0.0});
  for (const auto& o : scene_objects()) objects.add(o, 0.0);
  for (int i = 0; i < 500; ++i) physics.step(dt);
  for (auto _ : state) physics.step(dt);
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_RawBulletStep)->Arg(30)->Arg(10)->Unit(benchmark::kMicrosecond);

}  // namespace
