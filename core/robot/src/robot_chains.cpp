// Robot description loader: DH chains.

#include "robot_loader_internal.hpp"

namespace somasim::robot::detail {

namespace {

const std::vector<std::string> kChainKeys = {"base", "H0", "HN", "tip", "links"};
const std::vector<std::string> kDhKeys = {"joint",      "a",          "d",   "alpha_deg",
                                          "offset_deg", "limits_deg", "link"};

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

}  // namespace

void RobotLoader::read_chains(const YAML::Node& chains) {
  if (!chains) return;
  if (!reader_.expect_map(chains, "", "chains", "a map of chain names to DH chains")) return;
  for (const auto& kv : chains) read_chain(kv.first.Scalar(), kv.first, kv.second);
}

void RobotLoader::read_chain(const std::string& name, const YAML::Node& key,
                             const YAML::Node& node) {
  const std::string item = "chain '" + name + "'";
  if (!reader_.expect_map(node, item, "", "a map with 'links' (and 'base', 'H0', 'HN', 'tip')"))
    return;
  reader_.check_keys(node, kChainKeys, item, "");
  if (!node["links"] && node["tip"]) {  // along the tree: resolved once the model is built
    tree_chains_.push_back({name, key, node});
    return;
  }
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
    const Eigen::Isometry3d post = dh_post(a.value_or(0), d.value_or(0), alpha.value_or(0) * kDeg);
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
        reader_.error(
            e["joint"], item, where,
            "joint " + in_quotes(*joint) + " is shared with " + shared.source +
                " but the frame before it differs" +
                (sj.parent_link == cur ? fmt::format(" (by {:.4g} m and {:.4g} deg)", dp, dr / kDeg)
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

std::vector<ChainInfo> RobotLoader::tree_chains(const RobotModel& model) {
  std::vector<ChainInfo> out;
  for (const TreeChain& tc : tree_chains_) {
    const std::string item = "chain '" + tc.name + "'";
    reader_.check_keys(tc.node, {"base", "tip"}, item, "");
    const std::string base = reader_.string(tc.node, "base", item, "", false).value_or(root_name_);
    const auto tip = reader_.string(tc.node, "tip", item, "", true);
    if (!tip) continue;
    if (model.find_chain(tc.name) || std::any_of(out.begin(), out.end(), [&](const ChainInfo& c) {
          return c.name == tc.name;
        })) {
      reader_.error(tc.key, item, "", "a chain of this name already exists");
      continue;
    }
    const int base_link = model.find_link(base);
    if (base_link < 0) {
      reader_.error(tc.node["base"], item, "base", "unknown link " + in_quotes(base));
      continue;
    }
    int tip_link = -1;
    if (const int f = model.find_frame(*tip); f >= 0)
      tip_link = model.frames()[static_cast<std::size_t>(f)].link;
    else
      tip_link = model.find_link(*tip);
    if (tip_link < 0) {
      reader_.error(tc.node["tip"], item, "tip",
                    "unknown frame or link " + in_quotes(*tip) + "; expected a frame or a link");
      continue;
    }
    ChainInfo info{tc.name, base_link, *tip, {}};
    int l = tip_link;
    for (; l != base_link && l > 0; l = model.link(l).parent_link) {
      const Joint& j = model.joint(model.link(l).parent_joint);
      if (j.type != JointType::Fixed) info.joints.insert(info.joints.begin(), j.name);
    }
    if (l != base_link) {
      reader_.error(tc.node["tip"], item, "tip",
                    in_quotes(*tip) + " is not below the base link " + in_quotes(base) +
                        "; expected a tip on the tree below the base");
      continue;
    }
    out.push_back(std::move(info));
  }
  diags_.throw_if_any();
  return out;
}

}  // namespace somasim::robot::detail
