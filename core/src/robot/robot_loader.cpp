// Loading a robot description: YAML (+ extends/set) → links, DH chains, joints → a validated,
// topologically ordered RobotModel. The format is documented in assets/robots/README.md.
#include "somasim/robot/robot_loader.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>
#include <Eigen/Eigenvalues>

#include "robot_yaml.hpp"
#include "somasim/diagnostics.hpp"
#include "somasim/error.hpp"

namespace somasim::robot {
namespace fs = std::filesystem;
using detail::describe;
using detail::NodeOrigins;
using detail::YamlReader;

namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr int kMaxExtendsDepth = 8;

const std::vector<std::string> kTopKeys = {"robot",   "extends", "set",    "root",
                                           "density", "links",   "joints", "chains",
                                           "frames",  "cameras", "skin"};
const std::vector<std::string> kExtendsKeys = {"robot", "extends", "set"};
const std::vector<std::string> kLinkKeys = {"collision", "visual", "mass",
                                            "density",   "com",    "inertia"};
const std::vector<std::string> kGeometryTypes = {"sphere", "box", "cylinder", "capsule", "mesh"};
const std::vector<std::string> kJointTypes = {"revolute", "prismatic", "fixed"};
const std::vector<std::string> kChainKeys = {"base", "H0", "HN", "tip", "links"};
const std::vector<std::string> kDhKeys = {"joint",      "a",          "d",   "alpha_deg",
                                          "offset_deg", "limits_deg", "link"};
const std::vector<std::string> kFrameKeys = {"link", "origin"};
const std::vector<std::string> kCameraKeys = {"link", "frame", "origin", "fx",   "fy", "cx",
                                              "cy",   "width", "height", "near", "far"};
const std::vector<std::string> kSurfaces = {"cylinder", "box_face"};
const std::vector<std::string> kCylinderSkinKeys = {
    "link",  "surface",       "origin",        "radius",  "z_min",
    "z_max", "angle_min_deg", "angle_max_deg", "spacing", "group_size"};
const std::vector<std::string> kBoxFaceSkinKeys = {"link",   "surface", "origin",    "size_x",
                                                   "size_y", "spacing", "group_size"};

std::string in_quotes(const std::string& s) {
  return "'" + s + "'";
}

Eigen::Isometry3d dh_post(double a, double d, double alpha) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(a, 0, d);  // Tz(d)·Tx(a): the x move is along the new x = x
  t.linear() = Eigen::AngleAxisd(alpha, Eigen::Vector3d::UnitX()).toRotationMatrix();
  return t;
}

Eigen::Isometry3d rot_z(double angle) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return t;
}

// Position [m] and rotation [rad] distance between two transforms.
std::pair<double, double> distance(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const double dp = (a.translation() - b.translation()).norm();
  const double dr = Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle();
  return {dp, dr};
}
bool near(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const auto [dp, dr] = distance(a, b);
  return dp < 1e-9 && dr < 1e-9;
}

std::string read_text(const fs::path& path, bool& ok) {
  std::ifstream in(path, std::ios::binary);
  ok = static_cast<bool>(in) && fs::is_regular_file(path);
  std::stringstream s;
  if (ok) s << in.rdbuf();
  return s.str();
}

struct LinkBuild {
  std::string name;
  YAML::Node decl;        // entry under 'links' (may be undefined)
  YAML::Node decl_key;    // its key node, for messages
  int parent_joint = -1;  // index into joints_
  bool declared = false;
};

struct JointBuild {
  Joint joint;         // parent_link/child_link: indices into links_ (not yet ordered)
  std::string source;  // "chain 'x'" or "joint 'x'", for messages
  std::string parent_name;
  YAML::Node at;           // where to report problems with this joint
  YAML::Node parent_node;  // 'parent' value (explicit joints), to resolve after all links exist
  YAML::Node child_node;
  bool explicit_parent = false;  // an entry under 'joints' (parent resolved by name)
};

class Loader {
 public:
  Loader() : reader_(diags_, origins_) {}

  RobotModel load(const std::string& text, const std::string& display_name,
                  const fs::path& base_dir) {
    YAML::Node root = resolve(text, display_name, base_dir, 0, {});
    read(root);
    diags_.throw_if_any();
    return build();
  }

 private:
  // --- documents, extends and set ------------------------------------------------------------
  YAML::Node parse(const std::string& text, const std::string& display) {
    try {
      return YAML::Load(text);
    } catch (const YAML::ParserException& e) {
      throw InputError(fmt::format("{}:{}:{}: YAML syntax error: {}", display, e.mark.line + 1,
                                   e.mark.column + 1, e.msg));
    }
  }

  YAML::Node resolve(const std::string& text, const std::string& display, const fs::path& dir,
                     int depth, std::vector<fs::path> chain) {
    YAML::Node root = parse(text, display);
    origins_.set_default(display, dir);
    if (!root.IsMap()) {
      reader_.error(root, "", "",
                    "expected a robot description (a map with 'robot', 'links', 'chains', ...), "
                    "got " +
                        describe(root));
      diags_.throw_if_any();
    }
    check_duplicate_keys(root);
    const YAML::Node ext = root["extends"];
    if (!ext) return root;
    reader_.check_keys(root, kExtendsKeys, "", "");
    if (!ext.IsScalar() || ext.Scalar().empty()) {
      reader_.error(ext, "", "extends", "expected a robot description file, got " + describe(ext));
      diags_.throw_if_any();
    }
    const fs::path base_path = (dir / ext.Scalar()).lexically_normal();
    const std::string base_display = (fs::path(display).parent_path() / ext.Scalar()).string();
    chain.push_back(fs::absolute(dir / fs::path(display).filename()).lexically_normal());
    if (depth >= kMaxExtendsDepth ||
        std::find(chain.begin(), chain.end(), fs::absolute(base_path)) != chain.end()) {
      reader_.error(ext, "", "extends",
                    "'" + ext.Scalar() + "' extends itself (directly or through other files)");
      diags_.throw_if_any();
    }
    bool ok = false;
    const std::string base_text = read_text(base_path, ok);
    if (!ok) {
      reader_.error(ext, "", "extends",
                    "cannot read '" + ext.Scalar() + "' (resolved to '" + base_path.string() +
                        "'); expected a readable robot description file");
      diags_.throw_if_any();
    }
    YAML::Node base = resolve(base_text, base_display, base_path.parent_path(), depth + 1, chain);
    // Values of this file are located in this file, the rest in the base.
    if (const YAML::Node name = root["robot"]; name) {
      base["robot"] = name;
      origins_.add(base["robot"], display, dir);
    }
    if (const YAML::Node set = root["set"]; set) {
      if (!reader_.expect_map(set, "", "set", "a map of dotted paths to values")) return base;
      origins_.add(set, display, dir);
      for (const auto& kv : set) apply_set(base, kv.first, kv.second, display, dir, base_display);
    }
    return base;
  }

  // 'set: {chains.right_arm.links.7.d: -0.1413}': replaces one value of the base description.
  void apply_set(YAML::Node base, const YAML::Node& key, const YAML::Node& value,
                 const std::string& display, const fs::path& dir, const std::string& base_file) {
    const std::string path = key.Scalar();
    std::vector<std::string> parts;
    std::stringstream ss(path);
    for (std::string p; std::getline(ss, p, '.');) parts.push_back(p);
    const std::string shown = "set." + path;
    if (parts.empty() ||
        std::any_of(parts.begin(), parts.end(), [](const auto& p) { return p.empty(); })) {
      reader_.error(key, "", shown, "expected a dotted path such as chains.NAME.links.7.d");
      return;
    }
    YAML::Node node = base;
    for (std::size_t i = 0; i < parts.size(); ++i) {
      const bool last = i + 1 == parts.size();
      const std::string walked = fmt::format(
          "{}", fmt::join(parts.begin(), parts.begin() + static_cast<long>(i) + 1, "."));
      if (node.IsSequence()) {
        const auto index = detail::parse_number(parts[i]);
        if (!index || *index < 0 || *index != std::floor(*index) || *index >= node.size()) {
          reader_.error(key, "", shown,
                        fmt::format("'{}' is a list of {} items in {}; expected an index 0..{}",
                                    walked.substr(0, walked.rfind('.')), node.size(), base_file,
                                    node.size() - 1));
          return;
        }
        const auto at = static_cast<std::size_t>(*index);
        if (last) {
          node[at] = value;
          origins_.add(node[at], display, dir);
          return;
        }
        node.reset(node[at]);
      } else if (node.IsMap()) {
        if (last) {
          node[parts[i]] = value;
          origins_.add(node[parts[i]], display, dir);
          return;
        }
        if (!node[parts[i]]) {
          std::vector<std::string> keys;
          for (const auto& kv : node) keys.push_back(kv.first.Scalar());
          reader_.error(key, "", shown,
                        "no key '" + walked + "' in " + base_file + did_you_mean(parts[i], keys));
          return;
        }
        node.reset(node[parts[i]]);
      } else {
        reader_.error(key, "", shown,
                      "'" + walked.substr(0, walked.rfind('.')) + "' in " + base_file +
                          " is a single value; expected a path into maps and lists");
        return;
      }
    }
  }

  // yaml-cpp keeps duplicate keys, but lookups see only the first: report them.
  void check_duplicate_keys(const YAML::Node& n) {
    if (n.IsSequence())
      for (const auto& item : n) check_duplicate_keys(item);
    if (!n.IsMap()) return;
    std::map<std::string, SourceLocation> seen;
    for (const auto& kv : n) {
      const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : "";
      if (auto it = seen.find(key); it != seen.end())
        reader_.error(kv.first, "", key,
                      "duplicate key (first defined at " + it->second.str() + ")");
      else
        seen[key] = reader_.location(kv.first);
      check_duplicate_keys(kv.second);
    }
  }

  // --- reading -----------------------------------------------------------------------------
  void read(const YAML::Node& root) {
    reader_.check_keys(root, kTopKeys, "", "");
    name_ = reader_.string(root, "robot", "", "", true).value_or("robot");
    root_name_ = reader_.string(root, "root", "", "", false).value_or("root");
    density_ =
        reader_.positive(root, "density", "", "", false, "a density", "kg/m^3").value_or(1000.0);
    add_link(root_name_);
    const std::size_t errors_before_tree = diags_.items().size();
    read_link_declarations(root["links"]);
    read_chains(root["chains"]);
    read_joints(root["joints"]);
    resolve_joint_parents();
    check_tree();
    if (diags_.items().size() != errors_before_tree) return;  // the rest needs a sound tree
    for (const auto& l : links_) old_link_names_.push_back(l.name);
    order_tree();
    read_link_properties();
    read_frames(root["frames"]);
    read_cameras(root["cameras"]);
    read_skin(root["skin"]);
  }

  int add_link(const std::string& name) {
    if (auto it = link_index_.find(name); it != link_index_.end()) return it->second;
    links_.push_back({});
    links_.back().name = name;
    link_index_[name] = static_cast<int>(links_.size()) - 1;
    return static_cast<int>(links_.size()) - 1;
  }

  std::vector<std::string> link_names() const {
    std::vector<std::string> out;
    for (const auto& l : links_) out.push_back(l.name);
    return out;
  }

  void read_link_declarations(const YAML::Node& links) {
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

  // Sets `child`'s parent joint, or reports a second parent.
  bool attach(int child, int joint, const YAML::Node& at, const std::string& item,
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

  int add_joint(JointBuild jb) {
    if (jb.joint.type != JointType::Fixed) jb.joint.dof = num_dofs_++;
    joint_index_[jb.joint.name] = static_cast<int>(joints_.size());
    joints_.push_back(std::move(jb));
    return static_cast<int>(joints_.size()) - 1;
  }

  // A fixed link `name` under `parent` at `pose` (chain frames after shared joints, chain tips).
  int add_fixed_link(const std::string& name, int parent, const Eigen::Isometry3d& pose,
                     const std::string& source, const YAML::Node& at, const std::string& key) {
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

  void read_chains(const YAML::Node& chains) {
    if (!chains) return;
    if (!reader_.expect_map(chains, "", "chains", "a map of chain names to DH chains")) return;
    for (const auto& kv : chains) read_chain(kv.first.Scalar(), kv.first, kv.second);
  }

  void read_chain(const std::string& name, const YAML::Node& key, const YAML::Node& node) {
    const std::string item = "chain '" + name + "'";
    if (!reader_.expect_map(node, item, "", "a map with 'links' (and 'base', 'H0', 'HN', 'tip')"))
      return;
    reader_.check_keys(node, kChainKeys, item, "");
    ChainInfo info;
    info.name = name;
    int cur = 0;
    if (const auto base = reader_.string(node, "base", item, "", false)) {
      if (auto it = link_index_.find(*base); it != link_index_.end()) {
        cur = it->second;
      } else {
        reader_.error(node["base"], item, "base",
                      "unknown link " + in_quotes(*base) +
                          "; expected the root, a link under 'links' or a link of an earlier "
                          "chain" +
                          did_you_mean(*base, link_names()));
        return;
      }
    }
    info.base_link = cur;
    const auto h0 = reader_.pose(node, "H0", item, "");
    const auto hn = reader_.pose(node, "HN", item, "");
    if (!h0 || !hn) return;
    Eigen::Isometry3d x = *h0;  // pose of the chain's current frame in link `cur`
    const YAML::Node links = node["links"];
    if (!links) {
      reader_.error(key, item, "links", "missing required key (expected a list of DH links)");
      return;
    }
    if (!links.IsSequence()) {
      reader_.error(links, item, "links", "expected a list of DH links, got " + describe(links));
      return;
    }
    for (std::size_t i = 0; i < links.size(); ++i) {
      const YAML::Node e = links[i];
      const std::string prefix = fmt::format("links[{}].", i);
      if (!reader_.expect_map(e, item, prefix.substr(0, prefix.size() - 1),
                              "a DH link {joint, a, d, alpha_deg, offset_deg, limits_deg}"))
        return;
      reader_.check_keys(e, kDhKeys, item, prefix);
      const auto joint = reader_.string(e, "joint", item, prefix, true);
      const auto a = reader_.number(e, "a", item, prefix, false, "m");
      const auto d = reader_.number(e, "d", item, prefix, false, "m");
      const auto alpha = reader_.number(e, "alpha_deg", item, prefix, false, "deg");
      const auto offset = reader_.number(e, "offset_deg", item, prefix, false, "deg");
      const auto limits = read_limits(e, "limits_deg", item, prefix, kDeg, "deg");
      const auto link_name = reader_.string(e, "link", item, prefix, false);
      if (!joint || !limits || (e["a"] && !a) || (e["d"] && !d) || (e["alpha_deg"] && !alpha) ||
          (e["offset_deg"] && !offset))
        return;
      const Eigen::Isometry3d post =
          dh_post(a.value_or(0), d.value_or(0), alpha.value_or(0) * kDeg);
      const double off = offset.value_or(0) * kDeg;
      if (auto it = joint_index_.find(*joint); it != joint_index_.end()) {
        // A joint shared with an earlier chain (the iCub torso): same q, possibly different
        // DH parameters after it. Valid only if the frame before it is the same.
        const JointBuild& shared = joints_[it->second];
        const Joint& sj = shared.joint;
        const std::string where = prefix + "joint";
        if (sj.type != JointType::Revolute || sj.parent_link != cur || !near(sj.pre, x) ||
            (sj.axis - Eigen::Vector3d::UnitZ()).norm() > 1e-12) {
          const auto [dp, dr] = sj.parent_link == cur ? distance(sj.pre, x) : std::pair{0.0, 0.0};
          reader_.error(e["joint"], item, where,
                        "joint " + in_quotes(*joint) + " is shared with " + shared.source +
                            " but the frame before it differs" +
                            (sj.parent_link == cur
                                 ? fmt::format(" (by {:.4g} m and {:.4g} deg)", dp, dr / kDeg)
                                 : " (it follows another link)") +
                            "; expected a chain whose links before a shared joint are the same");
          return;
        }
        if (std::abs(sj.lower - (*limits)[0]) > 1e-9 || std::abs(sj.upper - (*limits)[1]) > 1e-9) {
          reader_.error(e["limits_deg"], item, prefix + "limits_deg",
                        fmt::format("joint '{}' is shared with {} but its limits differ; expected "
                                    "[{:.6g}, {:.6g}] as there",
                                    *joint, shared.source, sj.lower / kDeg, sj.upper / kDeg));
          return;
        }
        // T = F·Rz(q+off_A)·post_A · [post_A⁻¹·Rz(off_B − off_A)·post_B] = F·Rz(q+off_B)·post_B
        const Eigen::Isometry3d rel = sj.post.inverse() * rot_z(off - sj.offset) * post;
        const int shared_child = sj.child_link;
        info.joints.push_back(*joint);
        // Reuse a frame an earlier chain already made for the same DH parameters.
        int existing = -1;
        for (const auto& other : joints_)
          if (other.joint.type == JointType::Fixed && other.joint.parent_link == shared_child &&
              near(other.joint.pre, rel) &&
              (!link_name || links_[other.joint.child_link].name == *link_name))
            existing = other.joint.child_link;
        if (near(rel, Eigen::Isometry3d::Identity()) && !link_name) existing = shared_child;
        if (existing >= 0) {
          cur = existing;
        } else {
          cur = add_fixed_link(link_name.value_or(fmt::format("{}_{}", name, i)), shared_child, rel,
                               item, e, prefix + "link");
        }
        x.setIdentity();
        continue;
      }
      JointBuild jb;
      jb.joint.name = *joint;
      jb.joint.type = JointType::Revolute;
      jb.joint.parent_link = cur;
      jb.joint.pre = x;
      jb.joint.offset = off;
      jb.joint.post = post;
      jb.joint.lower = (*limits)[0];
      jb.joint.upper = (*limits)[1];
      jb.source = item;
      jb.at = e["joint"];
      const int child = add_link(link_name.value_or(fmt::format("{}_{}", name, i)));
      jb.joint.child_link = child;
      if (!attach(child, static_cast<int>(joints_.size()), e["link"] ? e["link"] : e["joint"], item,
                  prefix + (e["link"] ? "link" : "joint")))
        return;
      add_joint(std::move(jb));
      info.joints.push_back(*joint);
      cur = child;
      x.setIdentity();
    }
    info.tip_frame = reader_.string(node, "tip", item, "", false).value_or(name + "_tip");
    chain_tips_.push_back({info.tip_frame, cur, x * *hn, node["tip"] ? node["tip"] : key, item});
    chains_.push_back(std::move(info));
  }

  // [min, max] (scaled by `unit_scale`), min <= max.
  std::optional<Eigen::Vector2d> read_limits(const YAML::Node& map, const std::string& key,
                                             const std::string& item, const std::string& prefix,
                                             double unit_scale, const std::string& unit) {
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

  void read_joints(const YAML::Node& joints) {
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

  void resolve_joint_parents() {
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

  // Every link reaches the root through its parents: report detached links and cycles.
  void check_tree() {
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

  // Reindexes links depth-first from the root so that parents come first; joint i becomes the
  // parent joint of link i + 1.
  void order_tree() {
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
    for (std::size_t i = 0; i < link_order.size(); ++i)
      new_link[link_order[i]] = static_cast<int>(i);
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
    for (std::size_t i = 0; i < links_.size(); ++i)
      link_index_[links_[i].name] = static_cast<int>(i);
    built_links_.resize(links_.size());
    for (std::size_t i = 0; i < links_.size(); ++i) {
      built_links_[i].name = links_[i].name;
      built_links_[i].parent_joint = links_[i].parent_joint;
      built_links_[i].parent_link = i == 0 ? -1 : joints_[links_[i].parent_joint].joint.parent_link;
    }
  }

  // --- link properties ---------------------------------------------------------------------
  void read_link_properties() {
    for (std::size_t i = 0; i < links_.size(); ++i) {
      if (!links_[i].declared) continue;
      const std::string item = "link '" + links_[i].name + "'";
      const YAML::Node n = links_[i].decl;
      Link& link = built_links_[i];
      if (n.IsNull()) continue;  // a declared link without properties
      if (!reader_.expect_map(n, item, "", "a map of link properties (collision, visual, mass)"))
        continue;
      reader_.check_keys(n, kLinkKeys, item, "");
      link.collision = read_geometries(n, "collision", item);
      link.visual = n["visual"] ? read_geometries(n, "visual", item) : link.collision;
      const auto density = reader_.positive(n, "density", item, "", false, "a density", "kg/m^3");
      const auto mass = reader_.positive(n, "mass", item, "", false, "a mass", "kg");
      if (n["mass"] && !mass) continue;
      const auto com = reader_.numbers(n, "com", item, "", false, 3, "m");
      const auto inertia = reader_.numbers(n, "inertia", item, "", false, 6, "kg m^2");
      if ((n["inertia"] || n["com"]) && !n["mass"]) {
        reader_.error(n[n["inertia"] ? "inertia" : "com"], item, n["inertia"] ? "inertia" : "com",
                      "given without 'mass'; expected 'mass' [kg] as well");
        continue;
      }
      const bool has_mesh =
          std::any_of(link.collision.begin(), link.collision.end(),
                      [](const Geometry& g) { return g.type == GeometryType::Mesh; });
      if (!mass) {
        if (has_mesh) {
          reader_.error(n["collision"], item, "mass",
                        "cannot compute the mass of mesh geometry; expected 'mass' [kg]");
          continue;
        }
        link.inertial = inertial_from_geometry(link.collision, density.value_or(density_));
        continue;
      }
      Inertial in;
      double vol = 0;
      for (const auto& g : link.collision) vol += volume(g);
      if (vol > 0) in = inertial_from_geometry(link.collision, *mass / vol);
      in.mass = *mass;
      if (com) in.com = *com;
      if (inertia) {
        const auto& v = *inertia;  // ixx, iyy, izz, ixy, ixz, iyz
        in.inertia << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(in.inertia);
        if (eig.eigenvalues().minCoeff() < 0) {
          reader_.error(n["inertia"], item, "inertia",
                        "not a physical inertia (not positive semi-definite); expected [ixx, iyy, "
                        "izz, ixy, ixz, iyz] about the centre of mass [kg m^2]");
          continue;
        }
      }
      link.inertial = in;
    }
  }

  std::vector<Geometry> read_geometries(const YAML::Node& link, const std::string& key,
                                        const std::string& item) {
    std::vector<Geometry> out;
    const YAML::Node list = link[key];
    if (!list) return out;
    if (!list.IsSequence()) {
      reader_.error(list, item, key, "expected a list of shapes, got " + describe(list));
      return out;
    }
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string path = fmt::format("{}[{}]", key, i);
      if (auto g = read_geometry(list[i], item, path)) out.push_back(std::move(*g));
    }
    return out;
  }

  std::optional<Geometry> read_geometry(const YAML::Node& n, const std::string& item,
                                        const std::string& path) {
    if (!reader_.expect_map(n, item, path, "a shape {type: sphere|box|cylinder|capsule|mesh, ...}"))
      return std::nullopt;
    const std::string prefix = path + ".";
    const auto type = reader_.string(n, "type", item, prefix, true);
    if (!type) return std::nullopt;
    const auto t = std::find(kGeometryTypes.begin(), kGeometryTypes.end(), *type);
    if (t == kGeometryTypes.end()) {
      reader_.error(n["type"], item, prefix + "type",
                    "unknown geometry type " + in_quotes(*type) +
                        did_you_mean(*type, kGeometryTypes) +
                        "; expected one of: " + join_names(kGeometryTypes));
      return std::nullopt;
    }
    Geometry g;
    g.type = static_cast<GeometryType>(t - kGeometryTypes.begin());
    std::vector<std::string> keys = {"type", "origin"};
    bool ok = true;
    const auto need = [&](const auto& v) {
      if (!v) ok = false;
      return v;
    };
    switch (g.type) {
      case GeometryType::Sphere:
        keys.push_back("radius");
        g.radius =
            need(reader_.positive(n, "radius", item, prefix, true, "a radius", "m")).value_or(0);
        break;
      case GeometryType::Box: {
        keys.push_back("size");
        const auto s = need(reader_.numbers(n, "size", item, prefix, true, 3, "m"));
        if (s && s->minCoeff() <= 0) {
          reader_.error(n["size"], item, prefix + "size",
                        "expected 3 extents > 0 [m], got a non-positive extent");
          ok = false;
        } else if (s) {
          g.size = *s;
        }
        break;
      }
      case GeometryType::Cylinder:
      case GeometryType::Capsule: {
        keys.insert(keys.end(), {"radius", "length", "from", "to"});
        g.radius =
            need(reader_.positive(n, "radius", item, prefix, true, "a radius", "m")).value_or(0);
        if (n["from"] || n["to"]) {
          // Along a segment: handy for limbs between two joint centres.
          const auto from = need(reader_.numbers(n, "from", item, prefix, true, 3, "m"));
          const auto to = need(reader_.numbers(n, "to", item, prefix, true, 3, "m"));
          if (n["length"] || n["origin"]) {
            reader_.error(n, item, path,
                          "expected either 'from'/'to' or 'length'/'origin', got both");
            return std::nullopt;
          }
          if (from && to) {
            const Eigen::Vector3d axis = *to - *from;
            g.length = axis.norm();
            if (g.length <= 0) {
              reader_.error(n["to"], item, prefix + "to", "expected 'to' different from 'from'");
              return std::nullopt;
            }
            g.origin.translation() = 0.5 * (*from + *to);
            g.origin.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis)
                                    .toRotationMatrix();
          }
        } else {
          g.length =
              need(reader_.positive(n, "length", item, prefix, true, "a length", "m")).value_or(0);
        }
        break;
      }
      case GeometryType::Mesh: {
        keys.insert(keys.end(), {"file", "scale"});
        const auto file = need(reader_.string(n, "file", item, prefix, true));
        if (file) {
          const fs::path p = (origins_.directory(n["file"]) / *file).lexically_normal();
          std::error_code ec;
          if (!fs::exists(p, ec)) {
            reader_.error(n["file"], item, prefix + "file",
                          "mesh file " + in_quotes(*file) + " does not exist (resolved to '" +
                              p.string() + "')");
            ok = false;
          } else if (std::ifstream in(p, std::ios::binary); !in || !fs::is_regular_file(p, ec)) {
            reader_.error(n["file"], item, prefix + "file",
                          "mesh file " + in_quotes(*file) + " cannot be read (resolved to '" +
                              p.string() + "'); expected a readable regular file");
            ok = false;
          } else {
            g.mesh_file = p.string();
          }
        }
        if (const YAML::Node s = n["scale"]; s && s.IsScalar()) {
          const auto v = need(reader_.positive(n, "scale", item, prefix, false, "a scale", "1"));
          if (v) g.mesh_scale.setConstant(*v);
        } else if (s) {
          const auto v = need(reader_.numbers(n, "scale", item, prefix, false, 3));
          if (v && v->minCoeff() <= 0) {
            reader_.error(s, item, prefix + "scale", "expected scale factors > 0");
            ok = false;
          } else if (v) {
            g.mesh_scale = *v;
          }
        }
        break;
      }
    }
    reader_.check_keys(n, keys, item, prefix);
    if (!n["from"]) {
      if (const auto origin = reader_.pose(n, "origin", item, prefix))
        g.origin = *origin;
      else
        ok = false;
    }
    if (!ok) return std::nullopt;
    return g;
  }

  // --- frames, cameras, skin -----------------------------------------------------------------
  std::optional<int> find_link(const YAML::Node& map, const std::string& key,
                               const std::string& item, bool required) {
    const auto name = reader_.string(map, key, item, "", required);
    if (!name) return std::nullopt;
    if (auto it = link_index_.find(*name); it != link_index_.end()) return it->second;
    reader_.error(map[key], item, key,
                  "unknown link " + in_quotes(*name) + did_you_mean(*name, link_names()));
    return std::nullopt;
  }

  void add_frame(Frame f, const YAML::Node& at, const std::string& item) {
    for (const auto& other : frames_)
      if (other.name == f.name) {
        reader_.error(at, item, "",
                      "a frame of this name already exists; expected unique frame names");
        return;
      }
    frames_.push_back(std::move(f));
  }

  void read_frames(const YAML::Node& frames) {
    for (const auto& tip : chain_tips_) {
      const int link = link_index_.at(old_link_names_.at(tip.link));
      add_frame({tip.name, link, tip.pose}, tip.at, tip.item);
    }
    if (!frames) return;
    if (!reader_.expect_map(frames, "", "frames", "a map of frame names to {link, origin}")) return;
    for (const auto& kv : frames) {
      const std::string item = "frame '" + kv.first.Scalar() + "'";
      if (!reader_.expect_map(kv.second, item, "", "a map with 'link' and 'origin'")) continue;
      reader_.check_keys(kv.second, kFrameKeys, item, "");
      const auto link = find_link(kv.second, "link", item, true);
      const auto pose = reader_.pose(kv.second, "origin", item, "");
      if (link && pose) add_frame({kv.first.Scalar(), *link, *pose}, kv.first, item);
    }
  }

  void read_cameras(const YAML::Node& cameras) {
    if (!cameras) return;
    if (!reader_.expect_map(cameras, "", "cameras", "a map of camera names to cameras")) return;
    for (const auto& kv : cameras) {
      const std::string item = "camera '" + kv.first.Scalar() + "'";
      const YAML::Node n = kv.second;
      if (!reader_.expect_map(n, item, "", "a map with 'link' or 'frame', 'fx', 'fy', ..."))
        continue;
      reader_.check_keys(n, kCameraKeys, item, "");
      Camera c;
      c.name = kv.first.Scalar();
      bool ok = true;
      const auto origin = reader_.pose(n, "origin", item, "");
      if (!origin) ok = false;
      if (n["frame"] && n["link"]) {
        reader_.error(n, item, "frame", "expected either 'link' or 'frame', got both");
        ok = false;
      } else if (n["frame"]) {
        const auto f = reader_.string(n, "frame", item, "", true);
        const auto it = std::find_if(frames_.begin(), frames_.end(),
                                     [&](const Frame& fr) { return f && fr.name == *f; });
        if (!f) {
          ok = false;
        } else if (it == frames_.end()) {
          std::vector<std::string> names;
          for (const auto& fr : frames_) names.push_back(fr.name);
          reader_.error(n["frame"], item, "frame",
                        "unknown frame " + in_quotes(*f) + did_you_mean(*f, names));
          ok = false;
        } else if (origin) {
          c.link = it->link;
          c.pose = it->pose * *origin;
        }
      } else if (const auto link = find_link(n, "link", item, true)) {
        c.link = *link;
        if (origin) c.pose = *origin;
      } else {
        ok = false;
      }
      const auto fx = reader_.positive(n, "fx", item, "", true, "a focal length", "px");
      const auto fy = reader_.positive(n, "fy", item, "", true, "a focal length", "px");
      const auto w = reader_.integer(n, "width", item, "", true, 1);
      const auto h = reader_.integer(n, "height", item, "", true, 1);
      const auto cx = reader_.number(n, "cx", item, "", false, "px");
      const auto cy = reader_.number(n, "cy", item, "", false, "px");
      const auto near_clip =
          reader_.positive(n, "near", item, "", false, "a clipping distance", "m");
      const auto far_clip = reader_.positive(n, "far", item, "", false, "a clipping distance", "m");
      if (!fx || !fy || !w || !h || (n["cx"] && !cx) || (n["cy"] && !cy) ||
          (n["near"] && !near_clip) || (n["far"] && !far_clip))
        ok = false;
      if (!ok) continue;
      c.fx = *fx;
      c.fy = *fy;
      c.width = static_cast<int>(*w);
      c.height = static_cast<int>(*h);
      c.cx = cx.value_or(0.5 * c.width);
      c.cy = cy.value_or(0.5 * c.height);
      c.near = near_clip.value_or(0.01);
      c.far = far_clip.value_or(100.0);
      if (c.far <= c.near) {
        reader_.error(n["far"] ? n["far"] : n, item, "far",
                      fmt::format("far {} <= near {}; expected far > near [m]", c.far, c.near));
        continue;
      }
      cameras_.push_back(std::move(c));
    }
  }

  void read_skin(const YAML::Node& skin) {
    if (!skin) return;
    if (!reader_.expect_map(skin, "", "skin", "a map of body-part names to skin patches")) return;
    for (const auto& kv : skin) {
      const std::string item = "skin patch '" + kv.first.Scalar() + "'";
      const YAML::Node n = kv.second;
      if (!reader_.expect_map(n, item, "", "a map with 'link', 'surface' and its parameters"))
        continue;
      SkinPatch p;
      p.body_part = kv.first.Scalar();
      const auto link = find_link(n, "link", item, true);
      const auto surface = reader_.string(n, "surface", item, "", true);
      const auto origin = reader_.pose(n, "origin", item, "");
      if (!surface) continue;
      if (std::find(kSurfaces.begin(), kSurfaces.end(), *surface) == kSurfaces.end()) {
        reader_.error(n["surface"], item, "surface",
                      "unknown surface " + in_quotes(*surface) + did_you_mean(*surface, kSurfaces) +
                          "; expected one of: " + join_names(kSurfaces));
        continue;
      }
      p.surface = *surface;
      const bool cylinder = *surface == "cylinder";
      reader_.check_keys(n, cylinder ? kCylinderSkinKeys : kBoxFaceSkinKeys, item, "");
      bool ok = link && origin;
      const auto put = [&](const std::string& key, std::optional<double> v, bool required) {
        if (v)
          p.params[key] = *v;
        else if (required || n[key])
          ok = false;
      };
      const auto spacing = reader_.positive(n, "spacing", item, "", true, "a spacing", "m");
      put("spacing", spacing, true);
      const auto group = reader_.integer(n, "group_size", item, "", false, 1);
      put("group_size", group ? std::optional<double>(static_cast<double>(*group)) : std::nullopt,
          false);
      if (cylinder) {
        put("radius", reader_.positive(n, "radius", item, "", true, "a radius", "m"), true);
        const auto z0 = reader_.number(n, "z_min", item, "", true, "m");
        const auto z1 = reader_.number(n, "z_max", item, "", true, "m");
        put("z_min", z0, true);
        put("z_max", z1, true);
        if (z0 && z1 && *z0 >= *z1) {
          reader_.error(n["z_max"], item, "z_max",
                        fmt::format("z_max {} <= z_min {}; expected z_min < z_max [m]",
                                    n["z_max"].Scalar(), n["z_min"].Scalar()));
          ok = false;
        }
        const auto a0 = reader_.number(n, "angle_min_deg", item, "", false, "deg");
        const auto a1 = reader_.number(n, "angle_max_deg", item, "", false, "deg");
        put("angle_min_deg", a0.value_or(-180.0), false);
        put("angle_max_deg", a1.value_or(180.0), false);
        if ((n["angle_min_deg"] && !a0) || (n["angle_max_deg"] && !a1)) ok = false;
        const double span = a1.value_or(180.0) - a0.value_or(-180.0);
        if (ok && (span <= 0 || span > 360)) {
          reader_.error(n["angle_max_deg"] ? n["angle_max_deg"] : n, item, "angle_max_deg",
                        fmt::format("the angle range [{}, {}] deg is empty or wider than a turn; "
                                    "expected angle_min_deg < angle_max_deg <= angle_min_deg + 360",
                                    a0.value_or(-180.0), a1.value_or(180.0)));
          ok = false;
        }
      } else {
        put("size_x", reader_.positive(n, "size_x", item, "", true, "a size", "m"), true);
        put("size_y", reader_.positive(n, "size_y", item, "", true, "a size", "m"), true);
      }
      if (!ok) continue;
      p.link = *link;
      p.origin = *origin;
      skin_patches_.push_back(std::move(p));
    }
  }

  // --- building ------------------------------------------------------------------------------
  RobotModel build() {
    std::vector<Joint> joints;
    for (auto& jb : joints_) joints.push_back(std::move(jb.joint));
    for (auto& c : chains_) c.base_link = link_index_.at(old_link_names_.at(c.base_link));
    return RobotModel(name_, std::move(built_links_), std::move(joints), std::move(frames_),
                      std::move(cameras_), std::move(skin_patches_), std::move(chains_));
  }

  struct ChainTip {
    std::string name;
    int link;  // pre-ordering index
    Eigen::Isometry3d pose;
    YAML::Node at;
    std::string item;
  };

  Diagnostics diags_;
  NodeOrigins origins_;
  YamlReader reader_;
  std::string name_, root_name_;
  double density_ = 1000.0;
  std::vector<LinkBuild> links_;
  std::map<std::string, int> link_index_;
  std::vector<JointBuild> joints_;
  std::map<std::string, int> joint_index_;
  int num_dofs_ = 0;
  std::vector<ChainInfo> chains_;
  std::vector<ChainTip> chain_tips_;
  std::vector<std::string> old_link_names_;
  std::set<std::string> unattached_ok_;  // children of joints that failed to load
  std::vector<Link> built_links_;
  std::vector<Frame> frames_;
  std::vector<Camera> cameras_;
  std::vector<SkinPatch> skin_patches_;
};

}  // namespace

RobotModel parse_robot_model(const std::string& text, const std::string& display_name,
                             const fs::path& base_dir) {
  Loader loader;
  return loader.load(text, display_name, base_dir);
}

RobotModel load_robot_model(const fs::path& file) {
  bool ok = false;
  const std::string text = read_text(file, ok);
  if (!ok)
    throw InputError("cannot read robot description '" + file.string() +
                     "'; expected a readable YAML file");
  return parse_robot_model(text, file.string(), file.parent_path());
}

}  // namespace somasim::robot
