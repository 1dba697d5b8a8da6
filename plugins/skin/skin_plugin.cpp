#include "skin_plugin.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "skin_figure.hpp"
#include "somasim/diagnostics.hpp"
#include "somasim/figures/figure.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/skin/layout_file.hpp"

namespace somasim::plugins {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (start <= s.size()) {
    const auto comma = s.find(',', start);
    const std::string item =
        trim(s.substr(start, comma == std::string::npos ? comma : comma - start));
    if (!item.empty()) items.push_back(item);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return items;
}

}  // namespace

template <class V>
void SkinPlugin::Config::visit(V& v) {
  v.block(robot);
  v.field("parts", parts)
      .doc("body parts with skin (names of the robot's skin patches); empty = all");
  v.field("spacing", spacing)
      .unit("m")
      .range(0.0, 1.0)
      .doc("distance between neighbouring physical taxels; 0 = each patch's own");
  v.field("group_size", group_size)
      .range(0, 10000)
      .doc("physical taxels per virtual taxel (module); 0 = each patch's own");
  v.field("layout_files", layout_files)
      .doc(
          "'part=file, ...': layouts read from files instead of generated (somasim's format, "
          "somasim/skin/layout_file.hpp, or the iCub's skinGui positions files), relative to "
          "the experiment file");
  v.field("contact_radius", contact_radius)
      .unit("m")
      .range(1e-4, 1.0)
      .doc("taxels within this distance of a contact point respond");
  v.field("pressure_model", pressure_model)
      .doc(
          "shared: normal force / taxels in the radius; kernel: force x "
          "exp(-d^2 / (2 sigma^2)), sigma = contact_radius / 2");
  v.field("pressure_threshold", pressure_threshold)
      .unit("N")
      .at_least(0.0)
      .doc("a taxel is active when its pressure (force per taxel) exceeds this");
  v.field("min_taxels", min_taxels)
      .at_least(0)
      .doc("a contact event needs MORE than this many active physical taxels on a part");
  v.field("release_s", release_s)
      .unit("s")
      .at_least(0.0)
      .doc("a contact episode ends after this long without active taxels on the part");
  v.field("figure", figure).doc("draw figures/skin_layout.png at the end");
}

template <class V>
void SkinPlugin::Ports::visit(V& v) {
  v.port("link_poses", link_poses,
         "poses of all robot links (root frame); empty = the robot at q = 0");
  v.port("contacts", contacts_in, "contact points; those on skin links press taxels");
  v.port("taxels", taxels,
         "one part per body part: virtual taxel ids, poses in the root frame (this "
         "tick) and in the link frame");
  v.port("contacts", contacts,
         "one event per part and contact episode, with the touched virtual "
         "taxels; events older than 2 s are pruned");
  v.port("pressures", pressures,
         "per virtual taxel (order of 'taxels'): peak pressure of its physical "
         "taxels [N]");
}

PluginSpec SkinPlugin::spec() {
  return make_plugin_spec<Config, Ports>(
      "skin",
      "Artificial skin: taxel layouts on the robot's skin patches (generated or from "
      "files), grouped into virtual taxels (modules); contact points -> taxel pressures "
      "-> one contact event per body part and contact episode (pressure over threshold "
      "on more than min_taxels taxels); virtual taxel poses in the root frame.");
}

void SkinPlugin::configure(NodeContext& ctx) {
  config_ = read_config<Config>(ctx);
  bind_ports(ctx, ports_);
  model_ = robot::experiment_robot(ctx, config_.robot);
  response_params_.contact_radius = config_.contact_radius;
  response_params_.model = config_.pressure_model;
  response_params_.pressure_threshold = config_.pressure_threshold;
  response_params_.min_taxels = config_.min_taxels;
  response_params_.release_s = config_.release_s;

  select_parts(ctx);
  load_layouts(ctx);
  parts_on_link_.assign(static_cast<std::size_t>(model_->num_links()), {});
  for (std::size_t k = 0; k < parts_.size(); ++k) {
    Part& p = parts_[k];
    p.response = std::make_unique<skin::PartResponse>(p.layout, response_params_);
    parts_on_link_[static_cast<std::size_t>(p.layout.link)].push_back(static_cast<int>(k));
    ctx.log().info("skin '{}' on link '{}': {} taxels, {} virtual", p.layout.body_part,
                   model_->link(p.layout.link).name, p.layout.size(),
                   p.layout.virtual_taxels.size());
  }
  robot::RobotData data(*model_);
  robot::forward_kinematics(*model_, data, Eigen::VectorXd::Zero(model_->num_dofs()));
  rest_poses_ = data.link_poses;

  link_poses_ = &ports_.link_poses.get();
  contacts_ = ports_.contacts_in.get();
  taxels_ = &ports_.taxels.get();
  events_ = &ports_.contacts.get();
  pressures_ = &ports_.pressures.get();
  init_outputs();
  update_poses(rest_poses_);
}

void SkinPlugin::select_parts(NodeContext& ctx) {
  std::vector<std::string> available;
  for (const auto& patch : model_->skin_patches()) available.push_back(patch.body_part);
  const auto find_patch = [&](const std::string& name) -> const robot::SkinPatch* {
    for (const auto& patch : model_->skin_patches())
      if (patch.body_part == name) return &patch;
    config_error(ctx, config_, config_.parts,
                 "unknown body part '" + name + "'" + did_you_mean(name, available) + "; robot '" +
                     model_->name() +
                     "' has skin on: " + (available.empty() ? "nothing" : join_names(available)));
  };
  std::vector<std::string> names = config_.parts;
  if (names.empty()) names = available;
  for (const auto& name : names) {
    for (const auto& p : parts_)
      if (p.patch->body_part == name)
        config_error(ctx, config_, config_.parts, "body part '" + name + "' twice");
    Part part;
    part.patch = find_patch(name);
    parts_.push_back(std::move(part));
  }
  if (parts_.empty())
    config_error(ctx, config_, config_.robot.name,
                 "robot '" + model_->name() + "' has no skin patches");
}

void SkinPlugin::load_layouts(NodeContext& ctx) {
  skin::LayoutOptions options;
  options.spacing = config_.spacing;
  options.group_size = config_.group_size;
  std::map<std::string, std::string> files;
  for (const auto& item : split_list(config_.layout_files)) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || trim(item.substr(0, eq)).empty() ||
        trim(item.substr(eq + 1)).empty())
      config_error(ctx, config_, config_.layout_files,
                   "expected 'part=file' items separated by commas, got '" + item + "'");
    const std::string part = trim(item.substr(0, eq));
    bool selected = false;
    std::vector<std::string> names;
    for (const auto& p : parts_) {
      names.push_back(p.patch->body_part);
      selected = selected || p.patch->body_part == part;
    }
    if (!selected)
      config_error(ctx, config_, config_.layout_files,
                   "body part '" + part + "' has no skin in this node" + did_you_mean(part, names) +
                       "; parts: " + join_names(names));
    const std::string file = trim(item.substr(eq + 1));
    const std::filesystem::path path = ctx.resolve_input_path(file);
    if (const std::string why = input_file_problem(path); !why.empty())
      config_error(ctx, config_, config_.layout_files, "layout file '" + file + "' " + why);
    files[part] = path.string();
  }
  for (auto& p : parts_) {
    const auto it = files.find(p.patch->body_part);
    try {
      p.layout = it != files.end()
                     ? skin::load_layout_file(it->second, p.patch->body_part, p.patch->link)
                     : skin::generate_layout(*p.patch, options);
    } catch (const InputError& e) {
      if (it != files.end()) config_error(ctx, config_, config_.layout_files, e.what());
      config_error(ctx, config_, config_.spacing, e.what());
    }
  }
}

void SkinPlugin::init_outputs() {
  taxels_->parts.clear();
  pressures_->labels.clear();
  for (const auto& p : parts_) {
    SkinPart out;
    out.name = p.layout.body_part;
    out.link = model_->link(p.layout.link).name;
    for (std::size_t v = 0; v < p.layout.virtual_taxels.size(); ++v) {
      out.taxel_ids.push_back(p.layout.virtual_taxels[v].id);
      out.positions_link.push_back(p.layout.virtual_position(v));
      out.normals_link.push_back(p.layout.virtual_normal(v));
      pressures_->labels.push_back(out.name + "/" + std::to_string(out.taxel_ids.back()));
    }
    out.positions = out.positions_link;
    out.normals = out.normals_link;
    taxels_->parts.push_back(std::move(out));
  }
  pressures_->values.assign(pressures_->labels.size(), 0.0);
}

void SkinPlugin::update_poses(const std::vector<Eigen::Isometry3d>& poses) {
  for (std::size_t k = 0; k < parts_.size(); ++k) {
    SkinPart& out = taxels_->parts[k];
    Part& part = parts_[k];
    const Eigen::Isometry3d& pose = poses[static_cast<std::size_t>(part.layout.link)];
    // A link that has not moved (a posed robot) leaves its taxels where they are.
    if (part.posed && pose.matrix() == part.posed_at.matrix()) continue;
    part.posed = true;
    part.posed_at = pose;
    for (std::size_t v = 0; v < out.taxel_ids.size(); ++v) {
      out.positions[v] = pose * out.positions_link[v];
      out.normals[v] = pose.linear() * out.normals_link[v];
    }
  }
}

void SkinPlugin::apply_contacts(const Contacts& contacts,
                                const std::vector<Eigen::Isometry3d>& poses) {
  const auto press = [&](int link, const Eigen::Vector3d& point_link, double force, double t) {
    if (link < 0 || link >= static_cast<int>(parts_on_link_.size())) return;
    for (int k : parts_on_link_[static_cast<std::size_t>(link)]) {
      Part& part = parts_[static_cast<std::size_t>(k)];
      part.pressed = true;
      part.response->add_contact(point_link, force);
      if (!(part.step_first_touch <= t)) part.step_first_touch = t;  // (NaN: the first)
    }
  };
  // A world faster than the skin keeps a history: take every point since the last step, so
  // that brief impacts between two skin samples still press the taxels.
  const bool use_history = !contacts.recent.empty();
  const std::vector<Contact>& points = use_history ? contacts.recent : contacts.points;
  // Forces are averaged over the world steps since the last skin step (the taxels integrate).
  int steps = 1;
  if (use_history) {
    double previous = last_contact_time_;
    steps = 0;
    for (const Contact& c : points)
      if (c.time_s > last_contact_time_ && c.time_s != previous) {
        ++steps;
        previous = c.time_s;
      }
    steps = std::max(steps, 1);
  }
  double newest = last_contact_time_;
  for (const Contact& c : points) {
    if (use_history && c.time_s <= last_contact_time_) continue;
    newest = std::max(newest, c.time_s);
    const double force = c.normal_force / steps;
    if (!std::isfinite(c.normal_force) || !c.point.allFinite() || !c.point_in_a.allFinite())
      throw RunError(fmt::format("input 'contacts': non-finite contact (links {} / {}, force {})",
                                 c.link_a, c.link_b, c.normal_force));
    press(c.link_a, c.point_in_a, force, c.time_s);
    if (c.link_b >= 0 && c.link_b < static_cast<int>(poses.size()))
      press(c.link_b, poses[static_cast<std::size_t>(c.link_b)].inverse() * c.point, force,
            c.time_s);
  }
  last_contact_time_ = newest;
}

void SkinPlugin::step(NodeContext& ctx) {
  const auto& poses = link_poses_->poses.empty() ? rest_poses_ : link_poses_->poses;
  if (poses.size() != static_cast<std::size_t>(model_->num_links()))
    throw RunError(fmt::format("input 'link_poses': expected {} link poses (robot '{}'), got {}",
                               model_->num_links(), model_->name(), poses.size()));
  update_poses(poses);
  for (auto& p : parts_) {
    // Pressures are all zero unless a contact pressed the part in the previous step.
    if (p.pressed) p.response->clear();
    p.pressed_before = p.pressed;
    p.pressed = false;
    p.step_first_touch = std::numeric_limits<double>::quiet_NaN();
  }
  if (contacts_) apply_contacts(*contacts_, poses);
  for (auto& p : parts_) {
    if (!p.pressed)
      p.episode_first_touch = std::numeric_limits<double>::quiet_NaN();
    else if (!p.pressed_before || std::isnan(p.episode_first_touch))
      p.episode_first_touch = p.step_first_touch;
  }

  const double now = ctx.time_s();
  std::size_t out = 0;
  for (auto& p : parts_) {
    if (auto onset = p.response->update(now)) {
      ContactEvent e;
      e.id = next_event_id_++;
      e.time_s = now;
      e.first_touch_s = std::min(p.episode_first_touch, now);  // NaN stays NaN
      e.body_part = p.layout.body_part;
      e.contact_point_link = onset->centre_link;
      e.contact_normal_link = onset->normal_link;
      e.touched_taxels = std::move(onset->virtual_ids);
      p.touched_virtual.insert(e.touched_taxels.begin(), e.touched_taxels.end());
      ++p.events;
      ctx.log().debug("contact on '{}' at t = {:.3f} s: {} taxels, virtual {}", e.body_part, now,
                      onset->physical_count, fmt::join(e.touched_taxels, " "));
      events_->recent.push_back(std::move(e));
    }
    // Untouched now and at the previous step: its virtual pressures are (still) all zero.
    if (!p.pressed && !p.pressed_before) {
      out += p.layout.virtual_taxels.size();
      continue;
    }
    for (std::size_t v = 0; v < p.layout.virtual_taxels.size(); ++v)
      pressures_->values[out++] = p.response->virtual_pressure(v);
  }
  auto& recent = events_->recent;
  recent.erase(std::remove_if(recent.begin(), recent.end(),
                              [&](const ContactEvent& e) {
                                return e.time_s < now - keep_events_s_ &&
                                       e.id + 1 != next_event_id_;
                              }),
               recent.end());
}

void SkinPlugin::finish(NodeContext& ctx) {
  if (!model_) return;
  report(ctx);
  if (!config_.figure || parts_.empty()) return;
  std::vector<SkinFigurePanel> panels;
  for (const auto& p : parts_)
    panels.push_back({p.patch, &p.layout, p.response->fired(), p.touched_virtual, p.events});
  figures::save_figure(render_skin_layout(panels), ctx.figure_path("skin_layout.png"));
}

void SkinPlugin::report(NodeContext& ctx) {
  nlohmann::json events = nlohmann::json::object(), fired = nlohmann::json::object(),
                 taxels = nlohmann::json::object();
  std::size_t total = 0;
  for (const auto& p : parts_) {
    const std::string& name = p.layout.body_part;
    events[name] = p.events;
    total += p.events;
    const auto& f = p.response->fired();
    fired[name] = {
        {"physical", std::count(f.begin(), f.end(), true)},
        {"virtual", std::vector<int>(p.touched_virtual.begin(), p.touched_virtual.end())}};
    taxels[name] = {{"physical", p.layout.size()}, {"virtual", p.layout.virtual_taxels.size()}};
  }
  ctx.report_metric("events_per_part", events);
  ctx.report_metric("events_total", total);
  ctx.report_metric("taxels_fired", fired);
  ctx.report_metric("taxels", taxels);
}

}  // namespace somasim::plugins
