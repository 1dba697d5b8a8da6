#pragma once
// Helpers of the bullet_world tests: harness YAML, postures computed with the kinematics API,
// temporary files.
#include <filesystem>
#include <map>
#include <memory>
#include <random>
#include <string>

#include <Eigen/Geometry>

#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_model.hpp"
#include "somasim/testing/harness.hpp"

namespace world_test {

inline const std::string kRobot = SOMASIM_SOURCE_DIR "/assets/robots/icub_v1.yaml";

std::shared_ptr<const somasim::robot::RobotModel> icub();

/// A one-node graph: `world` (bullet_world at 1 kHz) with its inputs wired to harness.cmd and
/// harness.spawns; `params` is extra flow-map content ("key: value, ...").
std::string world_yaml(const std::string& params = "", bool wire_inputs = true);

/// "joint: deg, ..." for every dof of q.
std::string posture_param(const somasim::robot::RobotModel& model, const Eigen::VectorXd& q);

/// Arms hanging beside the body, elbows slightly bent.
Eigen::VectorXd rest_posture(const somasim::robot::RobotModel& model);
/// The right palm facing up in front of the robot (IK on the right_arm chain).
Eigen::VectorXd palm_up_posture(const somasim::robot::RobotModel& model);

/// A posture drawn inside the limits, 10° clear of them, for every joint.
Eigen::VectorXd random_posture(const somasim::robot::RobotModel& model, std::mt19937& rng);

/// Joint values from named degrees (others from `base`).
Eigen::VectorXd with_joints_deg(const somasim::robot::RobotModel& model, Eigen::VectorXd base,
                                const std::map<std::string, double>& deg);

somasim::ObjectSpawn sphere(std::uint64_t id, const std::string& name, double radius,
                            const Eigen::Vector3d& position,
                            somasim::ObjectMotion motion = somasim::ObjectMotion::kDynamic);

/// A position command holding q for every dof.
somasim::JointCommand hold(const Eigen::VectorXd& q);

/// A temporary file with `text`, removed with the object.
class TempFile {
 public:
  TempFile(const std::string& name, const std::string& text);
  ~TempFile();
  const std::filesystem::path& path() const { return path_; }
  std::string str() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

}  // namespace world_test
