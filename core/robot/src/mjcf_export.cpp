// A somasim robot written as a MuJoCo model (MJCF).
#include "somasim/robot/mjcf_export.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "somasim/robot/dynamics.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/self_collision.hpp"
#include "xml_text.hpp"

namespace somasim::robot {
namespace {

/// Joint limits at or beyond this [rad] are written as an unlimited joint.
constexpr double kUnlimitedRad = 1e3;

using detail::num;
using detail::xml_escaped;

std::string vec(const Eigen::Vector3d& v) {
  return fmt::format("{} {} {}", num(v.x()), num(v.y()), num(v.z()));
}

/// pos="x y z" quat="w x y z" of a pose in its parent's frame.
std::string pose_attributes(const Eigen::Isometry3d& t) {
  const Eigen::Quaterniond q(t.linear());
  return fmt::format(R"(pos="{}" quat="{} {} {} {}")", vec(t.translation()), num(q.w()), num(q.x()),
                     num(q.y()), num(q.z()));
}

/// The transform of a movable joint at q = 0: pre · M(offset) · post.
Eigen::Isometry3d rest_transform(const Joint& j) {
  Eigen::Isometry3d t = j.pre;
  if (j.type == JointType::Revolute) t.rotate(Eigen::AngleAxisd(j.offset, j.axis));
  if (j.type == JointType::Prismatic) t.translate(j.axis * j.offset);
  return t * j.post;
}

/// The mass properties written for each link (bullet_world's: frame links of moving groups
/// without mass get some).
std::vector<Inertial> physical_inertials(const RobotModel& model, const MjcfOptions& options) {
  return robot::physical_inertials(model, options.frame_link_mass, options.min_principal_inertia);
}

/// <inertial> of a link (principal axes), or nothing for a massless one.
std::string inertial_element(const Inertial& in, double min_principal_inertia) {
  if (in.mass <= 0.0) return {};
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(in.inertia);
  Eigen::Matrix3d axes = eig.eigenvectors();
  if (axes.determinant() < 0) axes.col(2) = -axes.col(2);
  const Eigen::Vector3d principal = eig.eigenvalues().cwiseMax(min_principal_inertia);
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
  frame.linear() = axes;
  frame.translation() = in.com;
  return fmt::format(R"(<inertial {} mass="{}" diaginertia="{}"/>)", pose_attributes(frame),
                     num(in.mass), vec(principal));
}

std::string geom_element(const Geometry& g, const std::string& mesh_name) {
  const std::string pose = pose_attributes(g.origin);
  switch (g.type) {
    case GeometryType::Sphere:
      return fmt::format(R"(<geom type="sphere" size="{}" {}/>)", num(g.radius), pose);
    case GeometryType::Box:
      return fmt::format(R"(<geom type="box" size="{}" {}/>)", vec(0.5 * g.size), pose);
    case GeometryType::Cylinder:
      return fmt::format(R"(<geom type="cylinder" size="{} {}" {}/>)", num(g.radius),
                         num(0.5 * g.length), pose);
    case GeometryType::Capsule:
      return fmt::format(R"(<geom type="capsule" size="{} {}" {}/>)", num(g.radius),
                         num(0.5 * g.length), pose);
    case GeometryType::Mesh:
      return fmt::format(R"(<geom type="mesh" mesh="{}" {}/>)", xml_escaped(mesh_name), pose);
  }
  return {};
}

/// `damping`: the servo's kd, or 0 for none.
std::string joint_element(const Joint& j, double damping) {
  const Eigen::Isometry3d post_inverse = j.post.inverse();
  const std::string type = j.type == JointType::Revolute ? "hinge" : "slide";
  const bool limited = !(j.lower <= -kUnlimitedRad && j.upper >= kUnlimitedRad);
  return fmt::format(R"(<joint name="{}" type="{}" pos="{}" axis="{}" limited="{}"{}{}/>)",
                     xml_escaped(j.name), type, vec(post_inverse.translation()),
                     vec(post_inverse.linear() * j.axis), limited ? "true" : "false",
                     limited ? fmt::format(R"( range="{} {}")", num(j.lower), num(j.upper)) : "",
                     damping > 0.0 ? fmt::format(R"( damping="{}")", num(damping)) : "");
}

class Writer {
 public:
  Writer(const RobotModel& model, const MjcfOptions& options)
      : model_(model),
        options_(options),
        inertials_(physical_inertials(model, options)),
        gains_(mjcf_servo_gains(model, options)),
        children_(model.num_links()) {
    for (int i = 1; i < model.num_links(); ++i) children_[model.link(i).parent_link].push_back(i);
  }

  std::string document() {
    std::string assets;
    for (const Link& link : model_.links())
      for (const Geometry& g : link.collision)
        if (g.type == GeometryType::Mesh)
          assets += fmt::format(R"(    <mesh name="{}" file="{}" scale="{}"/>)",
                                xml_escaped(mesh_name(meshes_++)), xml_escaped(g.mesh_file),
                                vec(g.mesh_scale)) +
                    "\n";
    meshes_ = 0;
    std::string out = fmt::format(
        "<mujoco model=\"{}\">\n"
        "  <!-- Written by somasim from robot '{}'. -->\n"
        "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n"
        "  <option timestep=\"{}\" gravity=\"{}\"/>\n"
        "  <default><geom friction=\"{} {} {}\" condim=\"{}\"/></default>\n",
        xml_escaped(model_.name()), xml_escaped(model_.name()), num(options_.timestep),
        vec(options_.gravity), num(options_.friction), num(options_.rolling_friction),
        num(options_.rolling_friction), options_.rolling_friction > 0.0 ? 6 : 3);
    if (!assets.empty()) out += "  <asset>\n" + assets + "  </asset>\n";
    out += "  <worldbody>\n";
    write_body(out, 0, options_.base_pose, 2);
    out += "  </worldbody>\n";
    out += exclusions();
    if (options_.servos) out += actuators();
    out += "</mujoco>\n";
    return out;
  }

 private:
  static std::string mesh_name(int k) { return fmt::format("somasim_mesh_{}", k); }

  void write_body(std::string& out, int link_index, const Eigen::Isometry3d& pose, int depth) {
    const std::string indent(2 * static_cast<std::size_t>(depth), ' ');
    const Link& link = model_.link(link_index);
    out += fmt::format("{}<body name=\"{}\" {}>\n", indent, xml_escaped(link.name),
                       pose_attributes(pose));
    const std::string inner = indent + "  ";
    if (link.parent_joint >= 0 && model_.joint(link.parent_joint).dof >= 0) {
      const Joint& j = model_.joint(link.parent_joint);
      out += inner + joint_element(j, options_.servos ? gains_.kd[j.dof] : 0.0) + "\n";
    }
    const std::string inertial =
        inertial_element(inertials_[link_index], options_.min_principal_inertia);
    if (!inertial.empty()) out += inner + inertial + "\n";
    for (const Geometry& g : link.collision)
      out += inner +
             geom_element(g, g.type == GeometryType::Mesh ? mesh_name(meshes_++) : std::string()) +
             "\n";
    for (const int child : children_[link_index]) {
      const Joint& j = model_.joint(model_.link(child).parent_joint);
      write_body(out, child, j.dof >= 0 ? rest_transform(j) : j.pre * j.post, depth + 1);
    }
    out += indent + "</body>\n";
  }

  std::string exclusions() const {
    const auto exempt = collision_exempt_links(model_);
    std::string out;
    for (int a = 0; a < model_.num_links(); ++a)
      for (int b = a + 1; b < model_.num_links(); ++b)
        if (exempt[a][b] && !model_.link(a).collision.empty() && !model_.link(b).collision.empty())
          out += fmt::format("    <exclude body1=\"{}\" body2=\"{}\"/>\n",
                             xml_escaped(model_.link(a).name), xml_escaped(model_.link(b).name));
    return out.empty() ? out : "  <contact>\n" + out + "  </contact>\n";
  }

  std::string actuators() const {
    std::string out;
    for (int d = 0; d < model_.num_dofs(); ++d)
      out += fmt::format(
          "    <general name=\"{}\" joint=\"{}\" gaintype=\"fixed\" gainprm=\"{}\" "
          "biastype=\"affine\" biasprm=\"0 {} 0\" forcelimited=\"true\" forcerange=\"{} {}\"/>\n",
          xml_escaped(model_.joint(model_.dof_joint(d)).name),
          xml_escaped(model_.joint(model_.dof_joint(d)).name), num(gains_.kp[d]),
          num(-gains_.kp[d]), num(-options_.max_torque), num(options_.max_torque));
    return out.empty() ? out : "  <actuator>\n" + out + "  </actuator>\n";
  }

  const RobotModel& model_;
  const MjcfOptions& options_;
  std::vector<Inertial> inertials_;
  ServoGains gains_;
  std::vector<std::vector<int>> children_;
  int meshes_ = 0;
};

}  // namespace

ServoGains mjcf_servo_gains(const RobotModel& model, const MjcfOptions& options) {
  const Eigen::VectorXd q =
      options.posture ? *options.posture : Eigen::VectorXd::Zero(model.num_dofs());
  RobotData data(model);
  forward_kinematics(model, data, q);
  const std::vector<Inertial> inertials = physical_inertials(model, options);
  const int n = model.num_dofs();
  ServoGains gains{Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n)};
  for (int d = 0; d < n; ++d) {
    const Joint& j = model.joint(model.dof_joint(d));
    const Eigen::Isometry3d joint_frame = data.link_poses[j.parent_link] * j.pre;
    const Eigen::Vector3d axis = (joint_frame.linear() * j.axis).normalized();
    const Eigen::Vector3d anchor = joint_frame.translation();
    double inertia = 0.0;
    for (int l = 0; l < model.num_links(); ++l) {
      const auto& dofs = model.supporting_dofs(l);
      if (std::find(dofs.begin(), dofs.end(), d) == dofs.end()) continue;
      const Inertial& in = inertials[l];
      if (in.mass <= 0.0) continue;
      if (j.type == JointType::Prismatic) {
        inertia += in.mass;
        continue;
      }
      const Eigen::Matrix3d r = data.link_poses[l].linear();
      const Eigen::Vector3d arm = data.link_poses[l] * in.com - anchor;
      const Eigen::Vector3d across = arm - arm.dot(axis) * axis;
      inertia += axis.dot(r * in.inertia * r.transpose() * axis) + in.mass * across.squaredNorm();
    }
    inertia = std::max(inertia, options.min_principal_inertia);
    const double w = options.servo_bandwidth;
    gains.kp[d] = inertia * w * w;
    gains.kd[d] = 2.0 * inertia * w;
  }
  return gains;
}

std::vector<int> mjcf_joint_dofs(const RobotModel& model) {
  std::vector<std::vector<int>> children(model.num_links());
  for (int i = 1; i < model.num_links(); ++i) children[model.link(i).parent_link].push_back(i);
  std::vector<int> order;
  std::vector<int> stack{0};
  while (!stack.empty()) {  // depth first, children in model order: the bodies as written
    const int link = stack.back();
    stack.pop_back();
    const int j = model.link(link).parent_joint;
    if (j >= 0 && model.joint(j).dof >= 0) order.push_back(model.joint(j).dof);
    for (auto c = children[link].rbegin(); c != children[link].rend(); ++c) stack.push_back(*c);
  }
  return order;
}

std::string to_mjcf(const RobotModel& model, const MjcfOptions& options) {
  return Writer(model, options).document();
}

}  // namespace somasim::robot
