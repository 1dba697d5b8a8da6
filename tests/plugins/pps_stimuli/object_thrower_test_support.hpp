#pragma once
// Helpers of the object_thrower tests: a thrower aimed at a hand-made left forearm patch, the
// world fed by hand from the spawn requests (no physics).
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "somasim/pps/ports.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_loader.hpp"
#include "somasim/skin/ports.hpp"
#include "somasim/testing/harness.hpp"

namespace object_thrower_test {

using somasim::JointState;
using somasim::ObjectSpawn;
using somasim::ObjectSpawns;
using somasim::ObjectStates;
using somasim::SkinPart;
using somasim::SkinTaxels;
using somasim::pps::Stimulus;
using somasim::testing::Harness;

inline const std::string kRobot = std::string(SOMASIM_SOURCE_DIR) + "/assets/robots/icub_v1.yaml";

// A thrower node 't' aimed at the left forearm (unless `params` names the parts); `inputs` adds
// optional wires.
inline std::string thrower(const std::string& params, const std::string& inputs = "") {
  const bool parts = params.rfind("parts:", 0) == 0;
  return "base_rate_hz: 20\nrobots: {icub: " + kRobot +
         "}\nnodes:\n  t: {plugin: object_thrower, params: {robot: icub" +
         (parts ? "" : ", parts: left_forearm") + (params.empty() ? "" : ", " + params) +
         "}, inputs: {taxels: harness.taxels, state: harness.state, objects: harness.objects" +
         (inputs.empty() ? "" : ", " + inputs) + "}}\n";
}

inline SkinPart forearm() {
  SkinPart p;
  p.name = "left_forearm";
  p.link = "l_forearm";
  p.taxel_ids = {0, 1, 2};
  p.positions = {{0.1, -0.2, 0.3}, {0.12, -0.2, 0.3}, {0.1, -0.25, 0.28}};
  p.normals = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d(0, -1, 1).normalized(),
               Eigen::Vector3d::UnitX()};
  p.positions_link = p.positions;
  p.normals_link = p.normals;
  return p;
}

// forearm() with its three taxels on the real left forearm, posed by `link` (root <- l_forearm):
// on the skin (2.1 cm from the link's axis, 7 cm along it) at `angles_deg` round it.
inline SkinPart forearm_ring(const Eigen::Isometry3d& link, const double (&angles_deg)[3]) {
  SkinPart part = forearm();
  part.positions_link.clear();
  part.normals_link.clear();
  for (const double deg : angles_deg) {
    const double a = deg * M_PI / 180.0;
    part.normals_link.push_back({std::cos(a), 0.0, std::sin(a)});
    part.positions_link.push_back(Eigen::Vector3d(0.0, -0.07, 0.0) +
                                  0.021 * part.normals_link.back());
  }
  for (std::size_t k = 0; k < 3; ++k) {
    part.positions[k] = link * part.positions_link[k];
    part.normals[k] = link.linear() * part.normals_link[k];
  }
  return part;
}

inline int dofs() {
  return somasim::robot::load_robot_model_shared(kRobot)->num_dofs();
}

inline void feed_world(Harness& h) {
  h.input<SkinTaxels>("taxels").parts = {forearm()};
  h.input<JointState>("state").position = Eigen::VectorXd::Zero(dofs());
  h.input<JointState>("state").velocity = Eigen::VectorXd::Zero(dofs());
}

// The object of spawn `s`, where the world would have put it `t` after its spawn.
inline void feed_object(Harness& h, const ObjectSpawn& s, double t) {
  ObjectStates& o = h.input<ObjectStates>("objects");
  Eigen::Isometry3d pose = s.pose;
  pose.translation() += t * s.linear_velocity;
  o.names = {s.name};
  o.present = {true};
  o.poses = {pose};
  o.linear_velocity = {s.linear_velocity};
  o.angular_velocity = {Eigen::Vector3d::Zero()};
  o.radius = {s.size.x()};
}

// Steps once (the first spawn), feeds its object 0.05 s later and steps again; returns the
// perceived stimulus and the truth.
inline std::pair<Stimulus, Stimulus> first_perception(Harness& h) {
  feed_world(h);
  EXPECT_TRUE(h.step());
  const auto& spawns = h.output<ObjectSpawns>("t.spawns").recent;
  EXPECT_EQ(spawns.size(), 1u);
  feed_object(h, spawns.back(), 0.05);
  EXPECT_TRUE(h.step());
  return {h.output<Stimulus>("t.stimulus"), h.output<Stimulus>("t.truth")};
}

// Runs to the end; every spawn request once, in order.
inline std::vector<ObjectSpawn> all_spawns(Harness& h, bool feed = true) {
  if (feed) feed_world(h);
  std::vector<ObjectSpawn> out;
  std::uint64_t last = 0;
  while (h.step())
    for (const auto& s : h.output<ObjectSpawns>("t.spawns").recent)
      if (s.id > last) {
        last = s.id;
        out.push_back(s);
      }
  h.finish();
  return out;
}

inline std::string error_of(const std::string& yaml) {
  try {
    Harness h(yaml);
  } catch (const somasim::InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace object_thrower_test
