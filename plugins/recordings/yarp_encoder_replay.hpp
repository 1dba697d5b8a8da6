#pragma once
// yarp_encoder_replay: joint encoders recorded by yarpdatadumper (e.g. /icub/left_arm/state:o,
// one Bottle of numbers per line) replayed as the robot's joint state and as position commands
// at their recorded times.
//
// `joints` maps the values of a line, in order, to the robot's joints ("-" leaves a value out;
// the iCub's arm ports hold 16 values: shoulder pitch, roll, yaw, elbow, wrist prosup, pitch,
// yaw, then 9 hand joints). Between two messages the state is interpolated linearly (or held,
// `interpolation: hold`); before the first it is the first, after the last the last. Joints
// not mapped read 0 in `state` and are left to other controllers in `command` (mode none).
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "replay_log.hpp"
#include "somasim/plugin_ports.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_model.hpp"

namespace somasim::plugins {

/// How a replay fills the time between two messages.
enum class ReplayInterpolation : std::uint8_t { kLinear, kHold };
inline constexpr NamedValue<ReplayInterpolation> kReplayInterpolationNames[] = {
    {ReplayInterpolation::kLinear, "linear"}, {ReplayInterpolation::kHold, "hold"}};
constexpr std::span<const NamedValue<ReplayInterpolation>> name_table(ReplayInterpolation) {
  return kReplayInterpolationNames;
}

/// The unit of recorded revolute joint values.
enum class AngleUnit : std::uint8_t { kDegrees, kRadians };
inline constexpr NamedValue<AngleUnit> kAngleUnitNames[] = {{AngleUnit::kDegrees, "deg"},
                                                            {AngleUnit::kRadians, "rad"}};
constexpr std::span<const NamedValue<AngleUnit>> name_table(AngleUnit) {
  return kAngleUnitNames;
}

class YarpEncoderReplay : public Plugin {
 public:
  struct Config {
    robot::RobotParam robot;
    ReplayLogParams log;
    std::vector<std::string> joints;
    AngleUnit units = AngleUnit::kDegrees;
    ReplayInterpolation interpolation = ReplayInterpolation::kLinear;
    template <class V>
    void visit(V& v);
  };
  struct Ports {
    Out<JointState> state;
    Out<JointCommand> command;
    template <class V>
    void visit(V& v);
  };

  static PluginSpec spec();
  void configure(NodeContext& ctx) override;
  void step(NodeContext& ctx) override;
  void finish(NodeContext& ctx) override;

 private:
  void map_joints(NodeContext& ctx);
  void decode(NodeContext& ctx);

  Config config_;
  Ports ports_;
  std::shared_ptr<const robot::RobotModel> model_;
  recordings::DatadumperLog log_;
  std::unique_ptr<recordings::ReplayCursor> cursor_;
  std::vector<int> value_dof_;            // per value of a line: dof index, or -1 (left out)
  std::vector<int> mapped_dofs_;          // the dofs the log drives
  std::vector<double> due_s_;             // per message: sim time [s]
  std::vector<Eigen::VectorXd> samples_;  // per message: values of mapped_dofs_ [rad] / [m]
  std::int64_t outside_limits_ = 0;       // samples outside a joint's limits
};

}  // namespace somasim::plugins
