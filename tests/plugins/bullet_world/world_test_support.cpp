#include "world_test_support.hpp"

#include <unistd.h>

#include <cmath>
#include <fstream>
#include <random>

#include <fmt/format.h>

#include "somasim/robot/inverse_kinematics.hpp"
#include "somasim/robot/kinematic_chain.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/robot_loader.hpp"

namespace world_test {
namespace fs = std::filesystem;
using somasim::robot::RobotModel;

std::shared_ptr<const RobotModel> icub() {
  return somasim::robot::load_robot_model_shared(kRobot);
}

std::string world_yaml(const std::string& params, bool wire_inputs) {
  std::string y = "base_rate_hz: 1000\nrobots: {icub: " + kRobot +
                  "}\nnodes:\n  world:\n    plugin: bullet_world\n";
  y += "    params: {" + params + "}\n";
  if (wire_inputs) y += "    inputs: {commands: harness.cmd, spawns: harness.spawns}\n";
  return y;
}

std::string posture_param(const RobotModel& model, const Eigen::VectorXd& q) {
  std::string s = "'";
  for (int d = 0; d < model.num_dofs(); ++d)
    s += fmt::format("{}{}: {:.12f}", d ? ", " : "", model.joint(model.dof_joint(d)).name,
                     q[d] * 180.0 / M_PI);
  return s + "'";
}

Eigen::VectorXd with_joints_deg(const RobotModel& model, Eigen::VectorXd q,
                                const std::map<std::string, double>& deg) {
  for (const auto& [name, v] : deg) q[model.dof_index(name)] = v * M_PI / 180.0;
  return q;
}

Eigen::VectorXd rest_posture(const RobotModel& model) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model.num_dofs());
  for (int d = 0; d < model.num_dofs(); ++d)
    q[d] = std::clamp(0.0, model.lower_limits()[d], model.upper_limits()[d]);
  return with_joints_deg(
      model, q,
      {{"r_shoulder_roll", 20}, {"l_shoulder_roll", 20}, {"r_elbow", 20}, {"l_elbow", 20}});
}

Eigen::VectorXd palm_up_posture(const RobotModel& model) {
  // Arm joints only (torso upright): a deterministic random search, then coordinate descent, of
  // a posture with the palm normal up and the palm in front of the chest, away from the body.
  const Eigen::VectorXd rest = rest_posture(model);
  const somasim::robot::KinematicChain chain(model, "r_palm", "chest");
  somasim::robot::RobotData data(model);
  somasim::robot::forward_kinematics(model, data, rest);
  const Eigen::Isometry3d chest = data.link_poses[model.link_index("chest")];
  const Eigen::Vector3d goal(-0.25, 0.12, 0.05);  // root frame [m]
  auto cost = [&](const Eigen::VectorXd& qc) {
    const Eigen::Isometry3d palm = chest * chain.forward(qc);
    return 100.0 * (1.0 - palm.linear()(2, 2)) + (palm.translation() - goal).norm();
  };
  std::mt19937_64 rng(3);
  Eigen::VectorXd best(chain.num_dofs());
  double best_cost = 1e9;
  for (int i = 0; i < 20000; ++i) {
    Eigen::VectorXd qc(chain.num_dofs());
    for (int k = 0; k < chain.num_dofs(); ++k)
      qc[k] = std::uniform_real_distribution<double>(chain.lower_limits()[k],
                                                     chain.upper_limits()[k])(rng);
    if (const double c = cost(qc); c < best_cost) best_cost = c, best = qc;
  }
  for (double h = 0.05; h > 1e-7; h *= 0.5)
    for (int sweep = 0; sweep < 50; ++sweep) {
      bool improved = false;
      for (int k = 0; k < chain.num_dofs(); ++k)
        for (double dir : {-1.0, 1.0}) {
          Eigen::VectorXd qc = best;
          qc[k] = std::clamp(qc[k] + dir * h, chain.lower_limits()[k], chain.upper_limits()[k]);
          if (const double c = cost(qc); c < best_cost) best_cost = c, best = qc, improved = true;
        }
      if (!improved) break;
    }
  Eigen::VectorXd q = rest;
  for (int k = 0; k < chain.num_dofs(); ++k) q[chain.dof_indices()[k]] = best[k];
  return q;
}

Eigen::VectorXd random_posture(const RobotModel& model, std::mt19937& rng) {
  constexpr double kMargin = 10 * M_PI / 180.0;
  Eigen::VectorXd q(model.num_dofs());
  for (int d = 0; d < model.num_dofs(); ++d) {
    const double lo = model.lower_limits()[d] + kMargin;
    const double hi = model.upper_limits()[d] - kMargin;
    q[d] = lo < hi ? std::uniform_real_distribution<double>(lo, hi)(rng)
                   : 0.5 * (model.lower_limits()[d] + model.upper_limits()[d]);
  }
  return q;
}

somasim::ObjectSpawn sphere(std::uint64_t id, const std::string& name, double radius,
                            const Eigen::Vector3d& position, somasim::ObjectMotion motion) {
  somasim::ObjectSpawn s;
  s.id = id;
  s.name = name;
  s.shape = somasim::ObjectShape::kSphere;
  s.size = Eigen::Vector3d(radius, 0, 0);
  s.motion = motion;
  s.mass = 0.05;
  s.pose.translation() = position;
  return s;
}

somasim::JointCommand hold(const Eigen::VectorXd& q) {
  somasim::JointCommand c;
  c.mode.assign(q.size(), somasim::JointCommandMode::kPosition);
  c.position = q;
  c.velocity = Eigen::VectorXd::Zero(q.size());
  return c;
}

TempFile::TempFile(const std::string& name, const std::string& text) {
  static int counter = 0;
  const fs::path dir =
      fs::temp_directory_path() /
      ("somasim-world-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  fs::create_directories(dir);
  path_ = dir / name;
  std::ofstream(path_) << text;
}

TempFile::~TempFile() {
  std::error_code ec;
  fs::remove_all(path_.parent_path(), ec);
}

}  // namespace world_test
