// Robot description loader: kinematic tree: links, joints, parents, ordering.

#include "robot_loader_internal.hpp"

namespace somasim::robot::detail {

namespace {

const std::vector<std::string> kJointTypes = {"revolute", "prismatic", "fixed"};

}  // namespace

int RobotLoader::add_link(const std::string& name) {
  if (auto it = link_index_.find(name); it != link_index_.end()) return it->second;
  links_.push_back({});
  links_.back().name = name;
  link_index_[name] = static_cast<int>(links_.size()) - 1;
  return static_cast<int>(links_.size()) - 1;
}

std::vector<std::string> RobotLoader::link_names() const {
  std::vector<std::string> out;
  for (const auto& l : links_) out.push_back(l.name);
  return out;
}

void RobotLoader::read_link_declarations(const YAML::Node& links) {
  if (!links) return;
  if (!reader_.expect_map(links, "", "links", "a map of link names to link properties")) return;
  for (const auto& kv : links) {
    const std::string name = kv.first.Scalar();
    const int i = add_link(name);
    links_[i].decl = kv.second;
    links_[i].decl_key = kv.first;
    links_[i].declared = true;
  }
}

bool RobotLoader::attach(int child, int joint, const YAML::Node& at, const std::string& item,
                         const std::string& key) {
  if (child == 0) {
    reader_.error(at, item, key,
                  "the root link '" + root_name_ + "' cannot be the child of a joint");
    return false;
  }
  if (links_[child].parent_joint >= 0) {
    const JointBuild& other = joints_[links_[child].parent_joint];
    reader_.error(at, item, key,
                  "link '" + links_[child].name + "' already has a parent joint ('" +
                      other.joint.name + "' of " + other.source +
                      "); expected each link to have exactly one parent joint");
    return false;
  }
  links_[child].parent_joint = joint;
  return true;
}

int RobotLoader::add_joint(JointBuild jb) {
  if (jb.joint.type != JointType::Fixed) jb.joint.dof = num_dofs_++;
  joint_index_[jb.joint.name] = static_cast<int>(joints_.size());
  joints_.push_back(std::move(jb));
  return static_cast<int>(joints_.size()) - 1;
}

int RobotLoader::add_fixed_link(const std::string& name, int parent, const Eigen::Isometry3d& pose,
                                const std::string& source, const YAML::Node& at,
                                const std::string& key) {
  const int child = add_link(name);
  JointBuild jb;
  jb.joint.name = name + "_fixed";
  jb.joint.type = JointType::Fixed;
  jb.joint.parent_link = parent;
  jb.joint.child_link = child;
  jb.joint.pre = pose;
  jb.source = source;
  jb.at = at;
  const int ji = static_cast<int>(joints_.size());
  if (attach(child, ji, at, source, key)) add_joint(std::move(jb));
  return child;
}

std::optional<Eigen::Vector2d> RobotLoader::read_limits(
    const YAML::Node& map, const std::string& key, const std::string& item,
    const std::string& prefix, double unit_scale, const std::string& unit) {
  const auto v = reader_.numbers(map, key, item, prefix, true, 2, unit);
  if (!v) return std::nullopt;
  if ((*v)[0] > (*v)[1]) {
    reader_.error(map[key], item, prefix + key,
                  fmt::format("min {} > max {}; expected [min, max] with min <= max",
                              map[key][0].Scalar(), map[key][1].Scalar()));
    return std::nullopt;
  }
  return Eigen::Vector2d((*v)[0] * unit_scale, (*v)[1] * unit_scale);
}

void RobotLoader::read_joints(const YAML::Node& joints) {
  if (!joints) return;
  if (!reader_.expect_map(joints, "", "joints", "a map of joint names to joints")) return;
  for (const auto& kv : joints) {
    const std::string name = kv.first.Scalar();
    const std::string item = "joint '" + name + "'";
    const YAML::Node n = kv.second;
    if (joint_index_.count(name)) {
      reader_.error(kv.first, item, "",
                    "a joint of this name already exists (in " +
                        joints_[joint_index_[name]].source + "); expected unique joint names");
      continue;
    }
    if (!reader_.expect_map(n, item, "", "a map with 'type', 'parent', 'child'")) continue;
    const auto type = reader_.string(n, "type", item, "", true);
    if (!type) continue;
    const auto t = std::find(kJointTypes.begin(), kJointTypes.end(), *type);
    if (t == kJointTypes.end()) {
      reader_.error(n["type"], item, "type",
                    "unknown joint type " + in_quotes(*type) + did_you_mean(*type, kJointTypes) +
                        "; expected one of: " + join_names(kJointTypes));
      continue;
    }
    JointBuild jb;
    jb.joint.name = name;
    jb.joint.type = static_cast<JointType>(t - kJointTypes.begin());
    jb.source = item;
    jb.at = kv.first;
    std::vector<std::string> keys = {"type", "parent", "child", "origin", "post"};
    if (jb.joint.type == JointType::Revolute)
      keys.insert(keys.end(), {"axis", "offset_deg", "limits_deg"});
    if (jb.joint.type == JointType::Prismatic)
      keys.insert(keys.end(), {"axis", "offset", "limits"});
    reader_.check_keys(n, keys, item, "");
    const auto parent = reader_.string(n, "parent", item, "", true);
    const auto child = reader_.string(n, "child", item, "", true);
    const auto pre = reader_.pose(n, "origin", item, "");
    const auto post = reader_.pose(n, "post", item, "");
    bool ok = parent && child && pre && post;
    if (jb.joint.type != JointType::Fixed) {
      const bool revolute = jb.joint.type == JointType::Revolute;
      const double scale = revolute ? kDeg : 1.0;
      const auto axis = reader_.numbers(n, "axis", item, "", false, 3);
      if (axis && axis->norm() < 1e-9) {
        reader_.error(n["axis"], item, "axis", "expected a non-zero direction, got [0, 0, 0]");
        ok = false;
      } else if (axis) {
        jb.joint.axis = axis->normalized();
      } else if (n["axis"]) {
        ok = false;
      }
      const std::string off_key = revolute ? "offset_deg" : "offset";
      const auto offset = reader_.number(n, off_key, item, "", false, revolute ? "deg" : "m");
      if (n[off_key] && !offset) ok = false;
      jb.joint.offset = offset.value_or(0) * scale;
      const auto limits = read_limits(n, revolute ? "limits_deg" : "limits", item, "", scale,
                                      revolute ? "deg" : "m");
      if (!limits)
        ok = false;
      else {
        jb.joint.lower = (*limits)[0];
        jb.joint.upper = (*limits)[1];
      }
    }
    if (!ok) {
      if (child) unattached_ok_.insert(*child);  // already reported: say nothing more about it
      continue;
    }
    jb.joint.pre = *pre;
    jb.joint.post = *post;
    jb.parent_name = *parent;
    jb.parent_node = n["parent"];
    jb.explicit_parent = true;
    jb.child_node = n["child"];
    const int c = add_link(*child);
    jb.joint.child_link = c;
    if (attach(c, static_cast<int>(joints_.size()), n["child"], item, "child"))
      add_joint(std::move(jb));
  }
}

void RobotLoader::resolve_joint_parents() {
  for (auto& jb : joints_) {
    if (!jb.explicit_parent) continue;
    auto it = link_index_.find(jb.parent_name);
    if (it == link_index_.end()) {
      reader_.error(jb.parent_node, jb.source, "parent",
                    "unknown link " + in_quotes(jb.parent_name) +
                        "; expected the root, a link under 'links', a chain link or another "
                        "joint's child" +
                        did_you_mean(jb.parent_name, link_names()));
      jb.joint.parent_link = -1;
      continue;
    }
    jb.joint.parent_link = it->second;
  }
}

void RobotLoader::check_tree() {
  for (std::size_t l = 1; l < links_.size(); ++l)
    if (links_[l].parent_joint < 0 && links_[l].declared && !unattached_ok_.count(links_[l].name))
      reader_.error(links_[l].decl_key, "link '" + links_[l].name + "'", "",
                    "not attached to the robot; expected a joint or a chain link with child '" +
                        links_[l].name + "'");
  std::vector<int> state(links_.size(), 0);  // 0 unknown, 1 reaches root, 2 broken
  state[0] = 1;
  for (std::size_t start = 1; start < links_.size(); ++start) {
    std::vector<int> path;
    int l = static_cast<int>(start);
    while (state[l] == 0 && std::find(path.begin(), path.end(), l) == path.end()) {
      path.push_back(l);
      const int j = links_[l].parent_joint;
      if (j < 0 || joints_[j].joint.parent_link < 0) {
        l = -1;
        break;
      }
      l = joints_[j].joint.parent_link;
    }
    const bool cycle = l >= 0 && state[l] == 0;
    if (cycle) {
      // The cycle is the part of `path` from l on; report it once, at its first joint in file
      // order, following the joints parent → child.
      std::vector<int> cyc(std::find(path.begin(), path.end(), l), path.end());
      std::reverse(cyc.begin(), cyc.end());
      std::size_t first = 0;
      for (std::size_t k = 1; k < cyc.size(); ++k)
        if (links_[cyc[k]].parent_joint < links_[cyc[first]].parent_joint) first = k;
      std::rotate(cyc.begin(), cyc.begin() + static_cast<long>(first), cyc.end());
      std::string text;
      for (int c : cyc) {
        const Joint& j = joints_[links_[c].parent_joint].joint;
        text += fmt::format("{}'{}' ({} -> {})", text.empty() ? "" : ", ", j.name,
                            links_[j.parent_link].name, links_[j.child_link].name);
      }
      const JointBuild& jb = joints_[links_[cyc[0]].parent_joint];
      reader_.error(jb.at, jb.source, "",
                    "joints form a cycle: " + text +
                        "; expected every link to lead back to "
                        "the root link '" +
                        root_name_ + "'");
    }
    const int result = (l >= 0 && state[l] == 1) ? 1 : 2;
    if (cycle) state[l] = 2;
    for (int p : path) state[p] = result;
  }
}

void RobotLoader::order_tree() {
  std::vector<std::vector<int>> children(links_.size());
  for (std::size_t j = 0; j < joints_.size(); ++j)
    children[joints_[j].joint.parent_link].push_back(static_cast<int>(j));
  std::vector<int> link_order = {0};
  std::vector<int> joint_order;
  std::vector<int> stack(children[0].rbegin(), children[0].rend());
  while (!stack.empty()) {
    const int j = stack.back();
    stack.pop_back();
    joint_order.push_back(j);
    const int c = joints_[j].joint.child_link;
    link_order.push_back(c);
    stack.insert(stack.end(), children[c].rbegin(), children[c].rend());
  }
  SOMASIM_CHECK(link_order.size() == links_.size(), "every link reaches the root");
  std::vector<int> new_link(links_.size());
  for (std::size_t i = 0; i < link_order.size(); ++i) new_link[link_order[i]] = static_cast<int>(i);
  std::vector<LinkBuild> links;
  std::vector<JointBuild> joints;
  for (int l : link_order) links.push_back(std::move(links_[l]));
  for (int j : joint_order) joints.push_back(std::move(joints_[j]));
  for (std::size_t j = 0; j < joints.size(); ++j) {
    joints[j].joint.parent_link = new_link[joints[j].joint.parent_link];
    joints[j].joint.child_link = new_link[joints[j].joint.child_link];
    links[joints[j].joint.child_link].parent_joint = static_cast<int>(j);
  }
  links_ = std::move(links);
  joints_ = std::move(joints);
  link_index_.clear();
  for (std::size_t i = 0; i < links_.size(); ++i) link_index_[links_[i].name] = static_cast<int>(i);
  built_links_.resize(links_.size());
  for (std::size_t i = 0; i < links_.size(); ++i) {
    built_links_[i].name = links_[i].name;
    built_links_[i].parent_joint = links_[i].parent_joint;
    built_links_[i].parent_link = i == 0 ? -1 : joints_[links_[i].parent_joint].joint.parent_link;
  }
}

}  // namespace somasim::robot::detail
