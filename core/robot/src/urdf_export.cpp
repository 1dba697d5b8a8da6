// A somasim robot written as URDF, and the overlay that adds what URDF cannot say.
#include "somasim/robot/urdf_export.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>
#include <Eigen/Geometry>

#include "xml_text.hpp"

namespace somasim::robot {
namespace {

/// Joint limits at or beyond this [rad] are written as a continuous joint.
constexpr double kContinuousRad = 1e3;

using detail::num;
using detail::xml_escaped;

/// URDF's rpy: R = Rz(yaw) Ry(pitch) Rx(roll).
std::string origin(const Eigen::Isometry3d& t) {
  const Eigen::Matrix3d r = t.linear();
  const double pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  double roll = 0, yaw = 0;
  if (std::abs(r(2, 0)) < 1 - 1e-12) {
    roll = std::atan2(r(2, 1), r(2, 2));
    yaw = std::atan2(r(1, 0), r(0, 0));
  } else {  // gimbal lock: all of the rotation about z and x as yaw
    yaw = std::atan2(-r(0, 1), r(1, 1));
  }
  const Eigen::Vector3d p = t.translation();
  return fmt::format(R"(<origin xyz="{} {} {}" rpy="{} {} {}"/>)", num(p.x()), num(p.y()),
                     num(p.z()), num(roll), num(pitch), num(yaw));
}

/// A mesh file as written: relative to `base` when given (and reachable so), else absolute.
std::string mesh_name(const std::string& file, const std::filesystem::path& base) {
  const std::filesystem::path absolute = std::filesystem::absolute(file).lexically_normal();
  if (base.empty()) return absolute.string();
  const std::filesystem::path relative = absolute.lexically_relative(base);
  return relative.empty() ? absolute.string() : relative.generic_string();
}

/// The URDF shapes of one somasim shape (a capsule is three).
std::vector<std::string> shapes(const Geometry& g, const std::filesystem::path& mesh_base) {
  switch (g.type) {
    case GeometryType::Sphere:
      return {origin(g.origin) +
              fmt::format(R"(<geometry><sphere radius="{}"/></geometry>)", num(g.radius))};
    case GeometryType::Box:
      return {origin(g.origin) + fmt::format(R"(<geometry><box size="{} {} {}"/></geometry>)",
                                             num(g.size.x()), num(g.size.y()), num(g.size.z()))};
    case GeometryType::Cylinder:
      return {origin(g.origin) +
              fmt::format(R"(<geometry><cylinder radius="{}" length="{}"/></geometry>)",
                          num(g.radius), num(g.length))};
    case GeometryType::Capsule: {
      std::vector<std::string> out = {
          origin(g.origin) +
          fmt::format(R"(<geometry><cylinder radius="{}" length="{}"/></geometry>)", num(g.radius),
                      num(g.length))};
      for (double end : {-0.5, 0.5}) {
        Eigen::Isometry3d cap = g.origin;
        cap.translate(Eigen::Vector3d(0, 0, end * g.length));
        out.push_back(origin(cap) +
                      fmt::format(R"(<geometry><sphere radius="{}"/></geometry>)", num(g.radius)));
      }
      return out;
    }
    case GeometryType::Mesh:
      return {origin(g.origin) +
              fmt::format(R"(<geometry><mesh filename="{}" scale="{} {} {}"/></geometry>)",
                          xml_escaped(mesh_name(g.mesh_file, mesh_base)), num(g.mesh_scale.x()),
                          num(g.mesh_scale.y()), num(g.mesh_scale.z()))};
  }
  return {};
}

void write_link(std::string& out, const Link& link, const std::filesystem::path& mesh_base) {
  out += fmt::format("  <link name=\"{}\">\n", xml_escaped(link.name));
  if (link.inertial.mass > 0) {
    const Eigen::Matrix3d& i = link.inertial.inertia;
    const Eigen::Vector3d& c = link.inertial.com;
    out += fmt::format(
        "    <inertial><origin xyz=\"{} {} {}\" rpy=\"0 0 0\"/><mass value=\"{}\"/>"
        "<inertia ixx=\"{}\" ixy=\"{}\" ixz=\"{}\" iyy=\"{}\" iyz=\"{}\" izz=\"{}\"/></inertial>\n",
        num(c.x()), num(c.y()), num(c.z()), num(link.inertial.mass), num(i(0, 0)), num(i(0, 1)),
        num(i(0, 2)), num(i(1, 1)), num(i(1, 2)), num(i(2, 2)));
  }
  int material = 0;
  for (const Geometry& g : link.visual)
    for (const std::string& s : shapes(g, mesh_base)) {
      std::string colour;
      if (g.colour)
        colour = fmt::format(R"(<material name="{}_{}"><color rgba="{} {} {} 1"/></material>)",
                             xml_escaped(link.name), material++, num(g.colour->x()),
                             num(g.colour->y()), num(g.colour->z()));
      out += "    <visual>" + s + colour + "</visual>\n";
    }
  for (const Geometry& g : link.collision)
    for (const std::string& s : shapes(g, mesh_base))
      out += "    <collision>" + s + "</collision>\n";
  out += "  </link>\n";
}

void write_joint(std::string& out, const RobotModel& model, const Joint& j) {
  const std::string& parent = model.link(j.parent_link).name;
  const std::string& child = model.link(j.child_link).name;
  const bool has_post = !j.post.isApprox(Eigen::Isometry3d::Identity(), 1e-15);
  // Names of the extra link and joint, not taken by the robot's own.
  std::string suffix;
  while (model.find_link(j.name + "_axis_frame" + suffix) >= 0 ||
         model.find_joint(j.name + "_post" + suffix) >= 0)
    suffix += "_";
  const std::string moving_child = has_post ? j.name + "_axis_frame" + suffix : child;
  // URDF has no offset: M(q + offset) = M(offset) M(q), folded into the origin.
  Eigen::Isometry3d pre = j.pre;
  if (j.type == JointType::Revolute) pre.rotate(Eigen::AngleAxisd(j.offset, j.axis));
  if (j.type == JointType::Prismatic) pre.translate(j.axis * j.offset);
  std::string type = "fixed";
  std::string limits;
  if (j.type == JointType::Revolute && j.lower <= -kContinuousRad && j.upper >= kContinuousRad) {
    type = "continuous";
  } else if (j.type != JointType::Fixed) {
    type = j.type == JointType::Revolute ? "revolute" : "prismatic";
    limits = fmt::format(R"(<limit lower="{}" upper="{}" effort="0" velocity="0"/>)", num(j.lower),
                         num(j.upper));
  }
  const std::string axis = j.type == JointType::Fixed
                               ? ""
                               : fmt::format(R"(<axis xyz="{} {} {}"/>)", num(j.axis.x()),
                                             num(j.axis.y()), num(j.axis.z()));
  out += fmt::format(
      "  <joint name=\"{}\" type=\"{}\"><parent link=\"{}\"/><child link=\"{}\"/>{}{}{}</joint>\n",
      xml_escaped(j.name), type, xml_escaped(parent), xml_escaped(moving_child), origin(pre), axis,
      limits);
  if (has_post) {
    out += fmt::format("  <link name=\"{}\"/>\n", xml_escaped(moving_child));
    out += fmt::format(
        "  <joint name=\"{}\" type=\"fixed\"><parent link=\"{}\"/><child link=\"{}\"/>{}"
        "</joint>\n",
        xml_escaped(j.name + "_post" + suffix), xml_escaped(moving_child), xml_escaped(child),
        origin(j.post));
  }
}

void emit_matrix_pose(YAML::Emitter& out, const Eigen::Isometry3d& t) {
  out << YAML::Key << "origin" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key
      << "matrix" << YAML::Value << YAML::BeginSeq;
  for (int r = 0; r < 4; ++r)
    out << YAML::Flow << YAML::BeginSeq << t(r, 0) << t(r, 1) << t(r, 2) << t(r, 3) << YAML::EndSeq;
  out << YAML::EndSeq << YAML::EndMap;
}

}  // namespace

std::string to_urdf(const RobotModel& model, const std::filesystem::path& mesh_base) {
  std::string out = "<?xml version=\"1.0\"?>\n";
  out += fmt::format("<!-- Written by somasim from robot '{}'. -->\n", xml_escaped(model.name()));
  out += fmt::format("<robot name=\"{}\">\n", xml_escaped(model.name()));
  const std::filesystem::path base =
      mesh_base.empty() ? mesh_base : std::filesystem::absolute(mesh_base).lexically_normal();
  for (const Link& link : model.links()) write_link(out, link, base);
  // Movable joints in the order of the joint values, so that q keeps its meaning.
  std::set<int> written;
  for (int d = 0; d < model.num_dofs(); ++d) {
    write_joint(out, model, model.joint(model.dof_joint(d)));
    written.insert(model.dof_joint(d));
  }
  for (int j = 0; j < model.num_joints(); ++j)
    if (!written.count(j)) write_joint(out, model, model.joint(j));
  out += "</robot>\n";
  return out;
}

std::string urdf_overlay(const RobotModel& model, const std::string& urdf_file) {
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << YAML::BeginMap;
  out << YAML::Key << "extends" << YAML::Value << urdf_file;
  out << YAML::Key << "robot" << YAML::Value << model.name();
  out << YAML::Key << "set" << YAML::Value << YAML::BeginMap;
  for (const Frame& f : model.frames()) {
    out << YAML::Key << "frames." + f.name << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "link" << YAML::Value << model.link(f.link).name;
    emit_matrix_pose(out, f.pose);
    out << YAML::EndMap;
  }
  for (const Camera& c : model.cameras()) {
    out << YAML::Key << "cameras." + c.name << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "link" << YAML::Value << model.link(c.link).name;
    emit_matrix_pose(out, c.pose);
    out << YAML::Key << "fx" << YAML::Value << c.fx << YAML::Key << "fy" << YAML::Value << c.fy
        << YAML::Key << "cx" << YAML::Value << c.cx << YAML::Key << "cy" << YAML::Value << c.cy
        << YAML::Key << "width" << YAML::Value << c.width << YAML::Key << "height" << YAML::Value
        << c.height << YAML::Key << "near" << YAML::Value << c.near << YAML::Key << "far"
        << YAML::Value << c.far;
    out << YAML::EndMap;
  }
  // Chains along the tree: the joints between base and tip are the URDF's own.
  for (const ChainInfo& c : model.chains()) {
    out << YAML::Key << "chains." + c.name << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "base" << YAML::Value << model.link(c.base_link).name;
    out << YAML::Key << "tip" << YAML::Value << c.tip_frame;
    out << YAML::EndMap;
  }
  for (const SkinPatch& s : model.skin_patches()) {
    out << YAML::Key << "skin." + s.body_part << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "link" << YAML::Value << model.link(s.link).name;
    out << YAML::Key << "surface" << YAML::Value << s.surface;
    emit_matrix_pose(out, s.origin);
    for (const auto& [key, value] : s.params) out << YAML::Key << key << YAML::Value << value;
    out << YAML::EndMap;
  }
  out << YAML::EndMap << YAML::EndMap;
  return fmt::format(
      "# Written by `somasim robot export-urdf`: the frames, cameras and skin patches of robot "
      "'{}',\n# which URDF cannot hold, added to the URDF it extends.\n{}\n",
      model.name(), out.c_str());
}

}  // namespace somasim::robot
