// PPS at scale (configs/pps_scale.yaml): the iCub with the generated whole-arm and torso skin
// (assets/robots/icub_v1_full_skin.yaml: 4,245 taxels, each its own virtual taxel), locked in
// the config's posture.
//   BM_ScaleScene/1: one 1 kHz scheduler tick of the config's graph (bullet_world, skin at
//                    50 Hz, object_thrower and one pps_learner over the seven parts at 20 Hz),
//                    objects approaching every part in turn. items_per_second = simulated
//                    milliseconds per second; counter real_time_factor = items/s / 1000 (the
//                    steady state: start-up and the final report are not included).
//   BM_ScaleScene/0 (baseline): the same graph without the learner.
//   BM_SkinLearnerTick/1: one 20 Hz tick of skin + learner alone at 4,245 taxels, fed with link
//                    poses, a stimulus approaching a taxel of each part in turn and a contact
//                    at its end (one learning event per 2.5 s). items_per_second = ticks/s; a
//                    real time factor of 10 leaves 5 ms per tick for everything.
//   BM_SkinLearnerTick/0 (baseline): the same with learn: false (activations only).
#include <benchmark/benchmark.h>

#include <string>

#include "somasim/pps/ports.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_loader.hpp"
#include "somasim/skin/ports.hpp"
#include "somasim/testing/harness.hpp"

namespace {

const std::string kRobot = SOMASIM_SOURCE_DIR "/assets/robots/icub_v1_full_skin.yaml";
const std::string kParts =
    "left_upper_arm right_upper_arm left_forearm right_forearm left_palm right_palm torso";
// The posture of configs/pps_scale.yaml.
const std::string kPosture =
    "l_shoulder_pitch: -40, l_shoulder_roll: 40, l_shoulder_yaw: 10, l_elbow: 60, "
    "r_shoulder_pitch: -40, r_shoulder_roll: 40, r_shoulder_yaw: 10, r_elbow: 60";
// The learner parameters of configs/pps_scale.yaml.
const std::string kLearner =
    "ttc: unsigned, ttc_max: 3.0, rf_shape: cone_mirrored_cylinder, buffer_horizon: 3.0, "
    "save: ''";
const std::string kSkin =
    "skin: {plugin: skin, rate_hz: 50, params: {"
    "group_size: 1, figure: false}, inputs: {link_poses: "
    "world.link_poses, contacts: world.contacts}}";

std::string scene_yaml(bool learner) {
  std::string y = "base_rate_hz: 1000\nrobots: {icub: " + kRobot + "}\nnodes:\n";
  y += "  world: {plugin: bullet_world, params: {initial_posture_deg: '" + kPosture +
       "', locked_joints: all}, inputs: {spawns: {from: thrower.spawns, delayed: true}}}\n";
  y += "  " + kSkin + "\n";
  y += "  thrower: {plugin: object_thrower, rate_hz: 20, params: {parts: '" + kParts +
       "', approaches: 1000000, speed_min: 0.05, speed_max: 0.15, pause: 0.5, position_noise: "
       "0.001}, inputs: {taxels: skin.taxels, state: world.joint_state, objects: world.objects, "
       "link_poses: world.link_poses}}\n";
  if (learner)
    y += "  pps: {plugin: pps_learner, rate_hz: 20, params: {body_part: '" + kParts + "', " +
         kLearner +
         "}, inputs: {stimulus: thrower.stimulus, taxels: skin.taxels, contacts: "
         "skin.contacts}}\n";
  return y;
}

void BM_ScaleScene(benchmark::State& state) {
  const bool learner = state.range(0) != 0;
  somasim::testing::Harness h(scene_yaml(learner));
  for (auto _ : state) h.step();
  state.SetItemsProcessed(state.iterations());
  state.counters["real_time_factor"] = benchmark::Counter(
      1e-3 * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  h.finish();
  state.counters["skin_events"] = h.metric("skin", "events_total").get<double>();
}
BENCHMARK(BM_ScaleScene)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond)->MinTime(3.0);

void BM_SkinLearnerTick(benchmark::State& state) {
  const bool learn = state.range(0) != 0;
  const auto model = somasim::robot::load_robot_model_shared(kRobot);
  std::string y = "base_rate_hz: 20\nrobots: {icub: " + kRobot + "}\nnodes:\n";
  y += "  skin: {plugin: skin, params: {"
       "group_size: 1, figure: false}, inputs: {link_poses: harness.links, contacts: "
       "harness.contacts}}\n";
  y += "  pps: {plugin: pps_learner, params: {body_part: '" + kParts + "', " + kLearner +
       ", learn: " + (learn ? "true" : "false") +
       "}, inputs: {stimulus: harness.stimulus, taxels: skin.taxels, contacts: skin.contacts}}\n";
  somasim::testing::Harness h(y);
  // The config's posture, from the model's kinematics.
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model->num_dofs());
  for (const auto& [joint, deg] :
       std::vector<std::pair<std::string, double>>{{"l_shoulder_pitch", -40},
                                                   {"l_shoulder_roll", 40},
                                                   {"l_shoulder_yaw", 10},
                                                   {"l_elbow", 60},
                                                   {"r_shoulder_pitch", -40},
                                                   {"r_shoulder_roll", 40},
                                                   {"r_shoulder_yaw", 10},
                                                   {"r_elbow", 60}})
    q[model->dof_index(joint)] = deg * M_PI / 180.0;
  somasim::robot::RobotData data(*model);
  somasim::robot::forward_kinematics(*model, data, q);
  h.input<somasim::LinkPoses>("links").poses = data.link_poses;
  auto& stimulus = h.input<somasim::pps::Stimulus>("stimulus");
  auto& contacts = h.input<somasim::Contacts>("contacts");
  h.step();
  const auto& skin = h.output<somasim::SkinTaxels>("skin.taxels");
  std::size_t taxels = 0;
  for (const auto& part : skin.parts) taxels += part.taxel_ids.size();

  constexpr int kCycle = 50, kApproach = 40;  // ticks: 2 s approach, contact, 0.5 s pause
  constexpr double kStart = 0.25;             // [m] from the taxel
  std::uint64_t tick = 0;
  for (auto _ : state) {
    const std::uint64_t cycle = tick / kCycle;
    const int phase = static_cast<int>(tick % kCycle);
    const auto& part = skin.parts[cycle % skin.parts.size()];
    const std::size_t k = (cycle * 37) % part.taxel_ids.size();
    const Eigen::Vector3d n = part.normals[k];
    stimulus.present = phase <= kApproach;
    stimulus.radius = 0.025;
    stimulus.velocity = -(kStart / (kApproach / 20.0)) * n;
    stimulus.position =
        part.positions[k] + (0.025 + kStart * (1.0 - phase / double(kApproach))) * n;
    contacts.points.clear();
    if (phase == kApproach) {
      somasim::Contact c;
      c.link_a = model->link_index(part.link);
      c.object_b = 0;
      c.point_in_a = part.positions_link[k];
      c.point = part.positions[k];
      c.normal_force = 1.0;
      contacts.points.push_back(c);
    }
    h.step();
    ++tick;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["taxels"] = static_cast<double>(taxels);
  h.finish();
  state.counters["events"] = h.metric("pps", "events").get<double>();
}
BENCHMARK(BM_SkinLearnerTick)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond)->MinTime(2.0);

}  // namespace
