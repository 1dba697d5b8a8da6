// URDF robots: read by urdfdom (the model's values) and by TinyXML (the elements' lines and the
// file's order, which urdfdom's maps lose), checked with located messages, and written as
// somasim robot-description YAML for the loader.
#include "urdf_import.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>

#include <console_bridge/console.h>
#include <fmt/format.h>
#include <tinyxml.h>
#include <urdf_parser/urdf_parser.h>
#include <yaml-cpp/yaml.h>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "somasim/error.hpp"

namespace somasim::robot::detail {
namespace fs = std::filesystem;

namespace {

constexpr double kPi = 3.14159265358979323846;
/// A continuous joint is a revolute joint with these limits [deg]: no limit in practice.
constexpr double kContinuousLimitDeg = 1e6;

/// What TinyXML tells about one <link> or <joint>: its line and the attributes the checks need.
struct ElementInfo {
  std::string name;
  int line = 0;
};

struct JointInfo : ElementInfo {
  std::string type, parent, child;
};

/// Messages collected for one file, thrown together.
class Problems {
 public:
  explicit Problems(std::string display) : display_(std::move(display)) {}
  void add(int line, const std::string& what) {
    items_.push_back(fmt::format("{}:{}: {}", display_, line, what));
  }
  void throw_if_any() const {
    if (items_.empty()) return;
    std::string all;
    for (const auto& m : items_) all += (all.empty() ? "" : "\n") + m;
    throw InputError(all);
  }

 private:
  std::string display_;
  std::vector<std::string> items_;
};

std::vector<fs::path> split_path(const char* value) {
  std::vector<fs::path> out;
  if (!value) return out;
  std::stringstream ss(value);
  for (std::string dir; std::getline(ss, dir, ':');)
    if (!dir.empty()) out.emplace_back(dir);
  return out;
}

/// Resolves a URDF mesh file name; `problem` says why it cannot be used ("" when it can).
fs::path resolve_mesh(const std::string& uri, const fs::path& dir, std::string& problem) {
  std::error_code ec;
  fs::path file;
  if (uri.rfind("package://", 0) == 0) {
    const std::string rest = uri.substr(10);
    const std::size_t slash = rest.find('/');
    const std::string package = rest.substr(0, slash);
    const std::string inside = slash == std::string::npos ? "" : rest.substr(slash + 1);
    const auto path = resource_path();
    for (const fs::path& root : path)
      if (fs::is_directory(root / package, ec)) {
        file = root / package / inside;
        break;
      }
    if (file.empty()) {
      std::string shown;
      for (const auto& p : path) shown += (shown.empty() ? "" : ":") + p.string();
      problem = fmt::format(
          "'{}': no package '{}' in the resource path ({}); add the directory that holds '{}' "
          "to SOMASIM_RESOURCE_PATH or pass --resource-path",
          uri, package, shown.empty() ? "empty" : shown, package);
      return {};
    }
  } else if (uri.rfind("file://", 0) == 0) {
    file = uri.substr(7);
  } else {
    file = dir / uri;
  }
  // Absolute: the loader resolves relative names against the description's directory again.
  file = fs::absolute(file, ec).lexically_normal();
  if (!fs::is_regular_file(file, ec))
    problem = fmt::format("'{}': no such file ({})", uri, file.string());
  return file;
}

Eigen::Isometry3d isometry(const urdf::Pose& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() << p.position.x, p.position.y, p.position.z;
  t.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z)
                   .normalized()
                   .toRotationMatrix();
  return t;
}

void emit_numbers(YAML::Emitter& out, std::initializer_list<double> values) {
  out << YAML::Flow << YAML::BeginSeq;
  for (double v : values) out << v;
  out << YAML::EndSeq;
}

void emit_pose(YAML::Emitter& out, const urdf::Pose& pose) {
  const Eigen::Isometry3d t = isometry(pose);
  out << YAML::Key << "origin" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key
      << "matrix" << YAML::Value << YAML::BeginSeq;
  for (int r = 0; r < 4; ++r) emit_numbers(out, {t(r, 0), t(r, 1), t(r, 2), t(r, 3)});
  out << YAML::EndSeq << YAML::EndMap;
}

/// One shape; meshes resolved through `meshes` (URDF name -> file).
void emit_shape(YAML::Emitter& out, const urdf::Geometry& g, const urdf::Pose& origin,
                const std::map<std::string, fs::path>& meshes,
                const std::optional<urdf::Color>& colour) {
  out << YAML::Flow << YAML::BeginMap;
  switch (g.type) {
    case urdf::Geometry::SPHERE:
      out << YAML::Key << "type" << YAML::Value << "sphere" << YAML::Key << "radius" << YAML::Value
          << static_cast<const urdf::Sphere&>(g).radius;
      break;
    case urdf::Geometry::BOX: {
      const auto& d = static_cast<const urdf::Box&>(g).dim;
      out << YAML::Key << "type" << YAML::Value << "box" << YAML::Key << "size" << YAML::Value;
      emit_numbers(out, {d.x, d.y, d.z});
      break;
    }
    case urdf::Geometry::CYLINDER: {
      const auto& c = static_cast<const urdf::Cylinder&>(g);
      out << YAML::Key << "type" << YAML::Value << "cylinder" << YAML::Key << "radius"
          << YAML::Value << c.radius << YAML::Key << "length" << YAML::Value << c.length;
      break;
    }
    case urdf::Geometry::MESH: {
      const auto& m = static_cast<const urdf::Mesh&>(g);
      out << YAML::Key << "type" << YAML::Value << "mesh" << YAML::Key << "file" << YAML::Value
          << meshes.at(m.filename).string() << YAML::Key << "scale" << YAML::Value;
      emit_numbers(out, {m.scale.x, m.scale.y, m.scale.z});
      break;
    }
  }
  emit_pose(out, origin);
  if (colour) {
    out << YAML::Key << "colour" << YAML::Value;
    emit_numbers(out, {std::clamp(static_cast<double>(colour->r), 0.0, 1.0),
                       std::clamp(static_cast<double>(colour->g), 0.0, 1.0),
                       std::clamp(static_cast<double>(colour->b), 0.0, 1.0)});
  }
  out << YAML::EndMap;
}

/// urdfdom reports through console_bridge; its errors are caught here for the message.
class ConsoleCapture : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR)
      messages += (messages.empty() ? "" : "; ") + text;
  }
  std::string messages;
};

urdf::ModelInterfaceSharedPtr parse_with_urdfdom(const std::string& xml, std::string& errors) {
  static std::mutex console_mutex;  // console_bridge's handler is process-wide
  const std::lock_guard lock(console_mutex);
  ConsoleCapture capture;
  console_bridge::useOutputHandler(&capture);
  urdf::ModelInterfaceSharedPtr model;
  try {
    model = urdf::parseURDF(xml);
  } catch (const std::exception& e) {
    capture.messages += e.what();
  }
  console_bridge::restorePreviousOutputHandler();
  errors = capture.messages;
  return model;
}

double number_attribute(const TiXmlElement* e, const char* name, double fallback) {
  double v = fallback;
  if (e) e->QueryDoubleAttribute(name, &v);
  return v;
}

/// The checks urdfdom either does not make or reports without a line.
void check_elements(const TiXmlElement* robot, const fs::path& dir, MissingMeshes missing,
                    Problems& problems, std::vector<ElementInfo>& links,
                    std::vector<JointInfo>& joints, std::map<std::string, fs::path>& meshes) {
  std::map<std::string, int> link_line;
  for (auto* l = robot->FirstChildElement("link"); l; l = l->NextSiblingElement("link")) {
    const char* name = l->Attribute("name");
    if (!name) {
      problems.add(l->Row(), "a <link> without a name; expected <link name=\"...\">");
      continue;
    }
    if (link_line.count(name))
      problems.add(l->Row(), fmt::format("link '{}' is defined twice (first at line {})", name,
                                         link_line[name]));
    link_line.emplace(name, l->Row());
    links.push_back({name, l->Row()});
    if (const auto* in = l->FirstChildElement("inertial")) {
      const auto* mass = in->FirstChildElement("mass");
      if (number_attribute(mass, "value", 0) < 0)
        problems.add(mass->Row(),
                     fmt::format("link '{}': mass {} is negative; expected a mass >= 0 [kg]", name,
                                 number_attribute(mass, "value", 0)));
      if (const auto* i = in->FirstChildElement("inertia")) {
        const double ixx = number_attribute(i, "ixx", 0), iyy = number_attribute(i, "iyy", 0),
                     izz = number_attribute(i, "izz", 0), ixy = number_attribute(i, "ixy", 0),
                     ixz = number_attribute(i, "ixz", 0), iyz = number_attribute(i, "iyz", 0);
        Eigen::Matrix3d m;
        m << ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz;
        const double smallest =
            Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m, Eigen::EigenvaluesOnly)
                .eigenvalues()
                .minCoeff();
        // Published models have moments that are zero to rounding (thin parts): only a
        // clearly negative principal moment is refused.
        const double largest = m.cwiseAbs().maxCoeff();
        if (!(smallest >= -(1e-9 * largest + 1e-15)))
          problems.add(i->Row(),
                       fmt::format("link '{}': the inertia is not positive semi-definite (smallest "
                                   "principal moment {:.3g} kg m^2); expected a physical inertia",
                                   name, smallest));
      }
    }
    for (const char* kind : {"visual", "collision"})
      for (auto* v = l->FirstChildElement(kind); v; v = v->NextSiblingElement(kind)) {
        const auto* g = v->FirstChildElement("geometry");
        const auto* mesh = g ? g->FirstChildElement("mesh") : nullptr;
        const char* file = mesh ? mesh->Attribute("filename") : nullptr;
        if (!file || meshes.count(file)) continue;
        std::string problem;
        const fs::path found = resolve_mesh(file, dir, problem);
        if (problem.empty())
          meshes[file] = found;
        else if (missing == MissingMeshes::kError)
          problems.add(mesh->Row(), fmt::format("link '{}': mesh {}", name, problem));
      }
  }
  std::map<std::string, int> joint_line;
  std::map<std::string, std::string> parent_of;  // child link -> joint
  for (auto* j = robot->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
    JointInfo info;
    info.line = j->Row();
    const char* name = j->Attribute("name");
    const char* type = j->Attribute("type");
    const auto* parent = j->FirstChildElement("parent");
    const auto* child = j->FirstChildElement("child");
    info.name = name ? name : "";
    info.type = type ? type : "";
    info.parent = parent && parent->Attribute("link") ? parent->Attribute("link") : "";
    info.child = child && child->Attribute("link") ? child->Attribute("link") : "";
    const std::string item = fmt::format("joint '{}'", info.name);
    if (info.name.empty()) {
      problems.add(info.line, "a <joint> without a name; expected <joint name=\"...\">");
      continue;
    }
    if (joint_line.count(info.name))
      problems.add(info.line, fmt::format("{} is defined twice (first at line {})", item,
                                          joint_line[info.name]));
    joint_line.emplace(info.name, info.line);
    if (info.type == "floating" || info.type == "planar")
      problems.add(info.line,
                   fmt::format("{} is {}: somasim robots have a fixed root and 1-dof joints; "
                               "expected revolute, continuous, prismatic or fixed",
                               item, info.type));
    for (const auto& [role, link] : {std::pair{"parent", info.parent}, {"child", info.child}})
      if (!link_line.count(link))
        problems.add(info.line, fmt::format("{}: its {} link '{}' is not defined in the file", item,
                                            role, link));
    if (!info.child.empty() && parent_of.count(info.child))
      problems.add(info.line, fmt::format("{}: link '{}' already has a parent joint ('{}'); "
                                          "expected one parent per link",
                                          item, info.child, parent_of[info.child]));
    parent_of.emplace(info.child, info.name);
    if (const auto* limit = j->FirstChildElement("limit");
        limit && (info.type == "revolute" || info.type == "prismatic")) {
      const double lower = number_attribute(limit, "lower", 0),
                   upper = number_attribute(limit, "upper", 0);
      if (lower > upper)
        problems.add(limit->Row(),
                     fmt::format("{}: limit lower {} > upper {}; expected lower <= upper (an "
                                 "omitted bound is 0)",
                                 item, lower, upper));
    }
    joints.push_back(info);
  }
  // One root, no cycles: walking up from every link ends at the same parentless link.
  std::set<std::string> roots;
  for (const auto& l : links)
    if (!parent_of.count(l.name)) roots.insert(l.name);
  if (roots.size() > 1) {
    std::string names;
    for (const auto& r : roots) names += (names.empty() ? "'" : ", '") + r + "'";
    problems.add(robot->Row(),
                 fmt::format("{} links have no parent joint ({}); expected one root link",
                             roots.size(), names));
  }
  std::map<std::string, std::string> parent_link;
  for (const auto& j : joints) parent_link[j.child] = j.parent;
  for (const auto& l : links) {
    std::set<std::string> seen{l.name};
    for (auto it = parent_link.find(l.name); it != parent_link.end();
         it = parent_link.find(it->second))
      if (!seen.insert(it->second).second) {
        problems.add(joint_line[parent_of[l.name]],
                     fmt::format("joint cycle through link '{}'; expected a tree", l.name));
        return;
      }
  }
}

}  // namespace

std::optional<MissingMeshes> parse_missing_meshes(const std::string& text) {
  if (text == "error") return MissingMeshes::kError;
  if (text == "skip") return MissingMeshes::kSkip;
  if (text == "collision") return MissingMeshes::kCollision;
  return std::nullopt;
}

bool is_urdf_file(const fs::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".urdf";
}

std::vector<fs::path> resource_path() {
  std::vector<fs::path> path = split_path(std::getenv("SOMASIM_RESOURCE_PATH"));
  for (auto& p : split_path(std::getenv("ROS_PACKAGE_PATH"))) path.push_back(p);
  return path;
}

std::string urdf_to_description(const std::string& xml, const std::string& display,
                                const fs::path& dir, MissingMeshes missing) {
  Problems problems(display);
  TiXmlDocument doc;
  doc.Parse(xml.c_str());
  if (doc.Error()) {
    std::string why = doc.ErrorDesc();
    if (!why.empty() && why.back() == '.') why.pop_back();
    problems.add(std::max(1, doc.ErrorRow()),
                 fmt::format("malformed XML ({}); expected a well-formed URDF document", why));
    problems.throw_if_any();
  }
  const TiXmlElement* robot = doc.FirstChildElement("robot");
  if (!robot) {
    problems.add(doc.RootElement() ? doc.RootElement()->Row() : 1,
                 "expected a URDF document (a <robot> element)");
    problems.throw_if_any();
  }
  std::vector<ElementInfo> links;
  std::vector<JointInfo> joints;
  std::map<std::string, fs::path> meshes;
  check_elements(robot, dir, missing, problems, links, joints, meshes);
  problems.throw_if_any();

  std::string urdfdom_errors;
  const urdf::ModelInterfaceSharedPtr model = parse_with_urdfdom(xml, urdfdom_errors);
  if (!model) {
    problems.add(robot->Row(), "urdfdom cannot read it: " +
                                   (urdfdom_errors.empty() ? "no reason given" : urdfdom_errors));
    problems.throw_if_any();
  }

  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << YAML::BeginMap;
  out << YAML::Key << "robot" << YAML::Value << model->getName();
  out << YAML::Key << "root" << YAML::Value << model->getRoot()->name;
  out << YAML::Key << "links" << YAML::Value << YAML::BeginMap;
  for (const ElementInfo& info : links) {
    const urdf::LinkConstSharedPtr link = model->getLink(info.name);
    out << YAML::Key << info.name << YAML::Value << YAML::BeginMap;
    auto colour_of = [](const urdf::VisualSharedPtr& v) -> std::optional<urdf::Color> {
      if (v->material && v->material->texture_filename.empty()) return v->material->color;
      return std::nullopt;
    };
    // A mesh that was not found (and not reported: `missing` allows it) has no shape.
    auto usable = [&](const urdf::GeometrySharedPtr& g) {
      return g && (g->type != urdf::Geometry::MESH ||
                   meshes.count(static_cast<const urdf::Mesh&>(*g).filename));
    };
    out << YAML::Key << "collision" << YAML::Value << YAML::BeginSeq;
    for (const auto& c : link->collision_array)
      if (usable(c->geometry)) emit_shape(out, *c->geometry, c->origin, meshes, std::nullopt);
    out << YAML::EndSeq;
    out << YAML::Key << "visual" << YAML::Value << YAML::BeginSeq;
    bool lost_visual = false;
    for (const auto& v : link->visual_array) {
      if (usable(v->geometry))
        emit_shape(out, *v->geometry, v->origin, meshes, colour_of(v));
      else
        lost_visual = lost_visual || v->geometry;
    }
    if (lost_visual && missing == MissingMeshes::kCollision)
      for (const auto& c : link->collision_array)
        if (usable(c->geometry)) emit_shape(out, *c->geometry, c->origin, meshes, std::nullopt);
    out << YAML::EndSeq;
    if (link->inertial && link->inertial->mass > 0) {
      const urdf::Inertial& in = *link->inertial;
      // URDF gives the inertia in the inertial frame; somasim wants it in link axes.
      const Eigen::Isometry3d frame = isometry(in.origin);
      Eigen::Matrix3d local;
      local << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
      const Eigen::Matrix3d i = frame.linear() * local * frame.linear().transpose();
      out << YAML::Key << "mass" << YAML::Value << in.mass;
      out << YAML::Key << "com" << YAML::Value;
      emit_numbers(out,
                   {frame.translation().x(), frame.translation().y(), frame.translation().z()});
      out << YAML::Key << "inertia" << YAML::Value;
      emit_numbers(out, {i(0, 0), i(1, 1), i(2, 2), i(0, 1), i(0, 2), i(1, 2)});
    }
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
  out << YAML::Key << "joints" << YAML::Value << YAML::BeginMap;
  for (const JointInfo& info : joints) {
    const urdf::JointConstSharedPtr j = model->getJoint(info.name);
    out << YAML::Key << info.name << YAML::Value << YAML::BeginMap;
    const bool fixed = j->type == urdf::Joint::FIXED;
    const bool prismatic = j->type == urdf::Joint::PRISMATIC;
    out << YAML::Key << "type" << YAML::Value
        << (fixed       ? "fixed"
            : prismatic ? "prismatic"
                        : "revolute");
    out << YAML::Key << "parent" << YAML::Value << j->parent_link_name;
    out << YAML::Key << "child" << YAML::Value << j->child_link_name;
    emit_pose(out, j->parent_to_joint_origin_transform);
    if (!fixed) {
      out << YAML::Key << "axis" << YAML::Value;
      emit_numbers(out, {j->axis.x, j->axis.y, j->axis.z});
      if (prismatic) {
        out << YAML::Key << "limits" << YAML::Value;
        emit_numbers(out, {j->limits ? j->limits->lower : 0.0, j->limits ? j->limits->upper : 0.0});
      } else {
        const bool continuous = j->type == urdf::Joint::CONTINUOUS;
        const double lower =
            continuous ? -kContinuousLimitDeg : (j->limits ? j->limits->lower : 0.0) * 180.0 / kPi;
        const double upper =
            continuous ? kContinuousLimitDeg : (j->limits ? j->limits->upper : 0.0) * 180.0 / kPi;
        out << YAML::Key << "limits_deg" << YAML::Value;
        emit_numbers(out, {lower, upper});
      }
    }
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
  for (const char* empty : {"chains", "frames", "cameras", "skin"})
    out << YAML::Key << empty << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::EndMap;
  out << YAML::EndMap;
  return out.c_str();
}

}  // namespace somasim::robot::detail
