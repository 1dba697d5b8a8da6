#include "robot_commands.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "commands.hpp"
#include "somasim/error.hpp"
#include "somasim/robot/joint_text.hpp"
#include "somasim/robot/mjcf_export.hpp"
#include "somasim/robot/robot_loader.hpp"
#include "somasim/robot/urdf_export.hpp"
#include "somasim/yaml_text.hpp"

namespace somasim::app {
namespace {

/// Writes `text` to `file` through a temporary file renamed into place.
void write_file(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::path tmp = file;
  tmp += ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    if (!out.flush())
      throw InputError(fmt::format("cannot write '{}'; expected a writable file", file.string()));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, file, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw InputError(fmt::format("cannot write '{}': {}", file.string(), ec.message()));
  }
}

}  // namespace

int cmd_robot_export_urdf(const std::string& robot, const std::string& out,
                          const std::string& overlay) {
  try {
    const robot::RobotModel model = robot::load_robot_model(robot);
    const std::string urdf = robot::to_urdf(
        model, out.empty() ? std::filesystem::path()
                           : std::filesystem::absolute(out).lexically_normal().parent_path());
    if (out.empty())
      std::fputs(urdf.c_str(), stdout);
    else
      write_file(out, urdf);
    if (!overlay.empty()) {
      if (out.empty())
        throw InputError("--overlay needs --out: the overlay extends the URDF file written there");
      const auto target = std::filesystem::absolute(out).lexically_normal();
      const auto base = std::filesystem::absolute(overlay).parent_path();
      write_file(overlay,
                 robot::urdf_overlay(model, target.lexically_relative(base).generic_string()));
    }
    if (!out.empty())
      fmt::print(stderr, "{}: {} links, {} joints ({} movable){}\n", out, model.num_links(),
                 model.num_joints(), model.num_dofs(),
                 overlay.empty() ? "" : fmt::format("; frames, cameras and skin in {}", overlay));
    return kExitOk;
  } catch (const InputError& e) {
    fmt::print(stderr, "error: {}\n", escape_control_bytes(e.what()));
    return kExitBadInput;
  }
}

int cmd_robot_export_mjcf(const std::string& robot, const std::string& out,
                          const MjcfExportArgs& args) {
  try {
    const robot::RobotModel model = robot::load_robot_model(robot);
    robot::MjcfOptions options;
    if (!args.posture.empty()) {
      try {
        options.posture = robot::parse_posture_deg(model, args.posture);
      } catch (const InputError& e) {
        throw InputError(fmt::format("--posture: {}", e.what()));
      }
    }
    options.servo_bandwidth = args.servo_bandwidth;
    options.max_torque = args.max_torque;
    options.servos = args.servos;
    const std::string mjcf = robot::to_mjcf(model, options);
    if (out.empty()) {
      std::fputs(mjcf.c_str(), stdout);
    } else {
      write_file(out, mjcf);
      fmt::print(stderr, "{}: {} bodies, {} joints, {} servos\n", out, model.num_links(),
                 model.num_dofs(), args.servos ? model.num_dofs() : 0);
    }
    return kExitOk;
  } catch (const InputError& e) {
    fmt::print(stderr, "error: {}\n", escape_control_bytes(e.what()));
    return kExitBadInput;
  }
}

}  // namespace somasim::app
