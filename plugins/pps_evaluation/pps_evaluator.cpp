#include "pps_evaluator.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <fmt/format.h>

#include "evaluation_report.hpp"
#include "somasim/diagnostics.hpp"

namespace somasim::plugins {

namespace {

const char* shape_name(ObjectShape s) {
  switch (s) {
    case ObjectShape::kSphere:
      return "sphere";
    case ObjectShape::kBox:
      return "box";
    case ObjectShape::kCylinder:
      return "cylinder";
    case ObjectShape::kMesh:
      break;
  }
  return "unknown";
}

std::string velocity_port(int i) {
  return "velocity_" + std::to_string(i + 1);
}

}  // namespace

template <class V>
void PpsEvaluator::Config::visit(V& v) {
  v.field("threshold", threshold)
      .range(0, 1)
      .doc("activation threshold of a trigger (the controllers' threshold)");
  v.field("trigger_hold_s", trigger_hold_s)
      .unit("s")
      .range(0, 10)
      .doc(
          "a trigger counts once the activation has stayed above the threshold this long (the "
          "controllers' trigger_hold_s)");
  v.field("trigger_at_once_above", trigger_at_once_above)
      .range(0, 1)
      .doc(
          "an activation above this counts at once, without the hold (the controllers' "
          "trigger_at_once_above)");
  v.field("velocity_parts", velocity_parts)
      .doc(
          "space-separated skin parts, the i-th is the part whose controller's velocity is "
          "wired to velocity_i (e.g. 'left_forearm right_palm'); '-' skips an input");
  v.field("figure_presentations", figure_presentations)
      .max_size(100)
      .at_least(1)
      .doc("ids of the presentations drawn as Fig 10/11-style figures");
  v.field("figure_taxels", figure_taxels)
      .range(1, 20)
      .doc("the most activated taxels drawn per figure");
  v.field("csv", csv).doc("per-presentation table written into the run folder ('' = none)");
}

template <class V>
void PpsEvaluator::Ports::visit(V& v) {
  v.port("presentation", presentation, "the object presented now (e.g. object_thrower)");
  v.port("objects", objects, "object states from the world (ground truth)");
  v.port("taxels", taxels, "true taxel poses (root frame), e.g. skin.taxels");
  v.port("contacts", contacts, "skin contact events");
  v.port("activations", activations,
         "PPS activations, labelled 'part/id' (one or several parts); "
         "unlabelled: the values of the aimed part only");
  v.port("world_contacts", world_contacts, "the world's contacts: object-robot contact anywhere");
  v.port("spawns", spawns,
         "the stimulus source's spawn requests: object shapes and sizes for "
         "exact distances (unwired: bounding spheres, a lower bound)");
  for (int i = 0; i < kVelocityInputs; ++i)
    v.port(velocity_port(i), velocity[static_cast<std::size_t>(i)],
           "commanded velocity of a controller [m/s] (see velocity_parts)");
}

PluginSpec PpsEvaluator::spec() {
  return make_plugin_spec<Config, Ports>(
      "pps_evaluator",
      "Scores PPS avoidance / reaching against the ground truth: per presented object, "
      "whether the aimed skin part's activations crossed the threshold, the true "
      "object-to-skin distances at the trigger and at the closest, skin and object "
      "contacts; rates, distance summaries, a CSV row per presentation and figures.");
}

void PpsEvaluator::configure(NodeContext& ctx) {
  config_ = read_config<Config>(ctx);
  aimed_trigger_ = pps::HeldTrigger(config_.trigger_hold_s);
  other_trigger_ = pps::HeldTrigger(config_.trigger_hold_s);
  bind_ports(ctx, ports_);
  csv_name_ = config_.csv.name;
  if (!csv_name_.empty()) csv_path_ = config_.csv.path;
  for (const std::string& p : config_.velocity_parts) velocity_parts_.push_back(p == "-" ? "" : p);
  if (velocity_parts_.size() > static_cast<std::size_t>(kVelocityInputs))
    config_error(ctx, config_, config_.velocity_parts,
                 fmt::format("{} parts named, but there are only {} velocity "
                             "inputs (velocity_1 .. velocity_{})",
                             velocity_parts_.size(), kVelocityInputs, kVelocityInputs));
  velocity_parts_.resize(kVelocityInputs);
  for (int i = 0; i < kVelocityInputs; ++i) {
    const auto& velocity = ports_.velocity[static_cast<std::size_t>(i)];
    const bool wired = velocity.wired();
    const auto& part = velocity_parts_[static_cast<std::size_t>(i)];
    if (wired && part.empty())
      config_error(ctx, config_, config_.velocity_parts,
                   "input '" + velocity_port(i) + "' is wired, but no part is named for it");
    if (!wired && !part.empty())
      config_error(
          ctx, config_, config_.velocity_parts,
          "part '" + part + "' is named for input '" + velocity_port(i) + "', which is not wired");
    velocities_.push_back(velocity.get());
  }
  presentation_ = &ports_.presentation.get();
  objects_ = &ports_.objects.get();
  taxels_ = &ports_.taxels.get();
  contacts_ = &ports_.contacts.get();
  activations_ = &ports_.activations.get();
  world_contacts_ = ports_.world_contacts.get();
  spawns_ = ports_.spawns.get();
}

const SkinPart* PpsEvaluator::find_part(NodeContext& ctx, const std::string& name) const {
  for (const auto& p : taxels_->parts)
    if (p.name == name) return &p;
  if (taxels_->parts.empty()) return nullptr;  // the skin has not reported yet
  std::vector<std::string> names;
  for (const auto& p : taxels_->parts) names.push_back(p.name);
  throw RunError(ctx.node_name() + ": presentation " + std::to_string(presentation_->id) +
                 " aims at skin part '" + name + "', which is not in the 'taxels' input" +
                 did_you_mean(name, names) + "; parts: " + join_names(names));
}

robot::ObjectGeometry PpsEvaluator::geometry_of(const std::string& object,
                                                std::size_t index) const {
  robot::ObjectGeometry g;
  if (const auto it = geometries_.find(object); it != geometries_.end()) g = it->second;
  if (index < objects_->radius.size()) g.bounding_radius = objects_->radius[index];
  return g;
}

PresentationRecord* PpsEvaluator::record_at(double t) {
  for (auto it = records_.rbegin(); it != records_.rend(); ++it)
    if (it->covers(t)) return &*it;
  return nullptr;
}

void PpsEvaluator::follow_presentation(NodeContext& ctx) {
  const Presentation& p = *presentation_;
  const double now = ctx.time_s();
  if (!records_.empty() && records_.back().open() && (p.id != records_.back().id || !p.active))
    records_.back().end_s = now;
  if (p.id == 0 || !p.active || (!records_.empty() && records_.back().id == p.id)) return;
  PresentationRecord r;
  r.id = p.id;
  r.motion = p.motion;
  r.object = p.object;
  r.body_part = p.body_part;
  r.taxel_id = p.taxel_id;
  r.speed = p.speed;
  r.sight = p.sight;
  r.start_s = p.start_time_s;
  record_of_object_[r.object] = records_.size();
  aimed_trigger_.reset();
  other_trigger_.reset();
  records_.push_back(std::move(r));
  if (std::find(config_.figure_presentations.begin(), config_.figure_presentations.end(),
                static_cast<double>(p.id)) != config_.figure_presentations.end())
    traces_[p.id].id = p.id;
}

void PpsEvaluator::observe(NodeContext& ctx, PresentationRecord& r) {
  const SkinPart* part = find_part(ctx, r.body_part);
  if (!part) return;
  // The object in the world (indices are stable: removed objects keep their slot).
  std::size_t at = objects_->names.size();
  for (std::size_t i = 0; i < objects_->names.size(); ++i)
    if (objects_->names[i] == r.object) at = i;
  const bool present =
      at < objects_->present.size() && objects_->present[at] && at < objects_->poses.size();
  distances_.assign(part->positions.size(), PresentationRecord::kNaN);
  double nearest = PresentationRecord::kNaN;
  if (present) {
    const robot::ObjectGeometry g = geometry_of(r.object, at);
    const Eigen::Isometry3d& pose = objects_->poses[at];
    if (!r.seen) r.shape = shape_name(g.shape);
    r.seen = true;
    for (std::size_t k = 0; k < part->positions.size(); ++k) {
      distances_[k] = robot::surface_distance(g, pose, part->positions[k]);
      if (!(distances_[k] >= nearest)) nearest = distances_[k];
    }
    double any = nearest;
    for (const auto& other : taxels_->parts) {
      if (&other == part) continue;
      for (const auto& x : other.positions)
        any = std::min(any, robot::surface_distance(g, pose, x));
    }
    if (!(r.min_distance_m <= nearest)) r.min_distance_m = nearest;
    if (!(r.min_distance_any_part_m <= any)) r.min_distance_any_part_m = any;
  }

  // Activations of the aimed part, and whether another part's crossed the threshold.
  const auto a = part_activations_[r.body_part].select(*activations_, *part, ctx.node_name());
  double peak = 0.0;
  std::size_t peak_at = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (a[k] > peak) {
      peak = a[k];
      peak_at = k;
    }
  r.max_activation = std::max(r.max_activation, peak);
  const bool aimed_above = present && peak > config_.threshold;
  if (aimed_trigger_.update(ctx.time_s(), aimed_above,
                            aimed_above && peak > config_.trigger_at_once_above) &&
      !r.triggered) {
    r.triggered = true;
    r.trigger_time_s = ctx.time_s();
    r.trigger_distance_m = nearest;
    r.trigger_taxel_id = part->taxel_ids[peak_at];
  }
  const std::string prefix = r.body_part + "/";
  double other_peak = 0.0;
  for (std::size_t i = 0; present && i < activations_->labels.size(); ++i)
    if (!activations_->labels[i].starts_with(prefix))
      other_peak = std::max(other_peak, activations_->values[i]);
  const bool other_above = other_peak > config_.threshold;
  if (other_trigger_.update(ctx.time_s(), other_above,
                            other_above && other_peak > config_.trigger_at_once_above))
    r.triggered_other_part = true;

  double speed = PresentationRecord::kNaN;
  for (std::size_t i = 0; i < velocities_.size(); ++i)
    if (velocities_[i] && velocity_parts_[i] == r.body_part) speed = velocities_[i]->norm();
  if (std::isfinite(speed)) r.max_speed = std::max(r.max_speed, speed);

  if (const auto it = traces_.find(r.id); it != traces_.end()) {
    PresentationTrace& t = it->second;
    if (t.taxel_ids.empty()) t.taxel_ids = part->taxel_ids;
    std::vector<double> act(a.begin(), a.end());
    act.resize(part->taxel_ids.size(), 0.0);  // nothing computed yet: zeros
    t.add_sample(ctx.time_s(), distances_, act, speed);
  }
}

void PpsEvaluator::attribute_contacts() {
  for (const auto& e : contacts_->recent) {
    if (e.id <= last_event_id_) continue;
    last_event_id_ = e.id;
    PresentationRecord* r = record_at(e.time_s);
    if (!r) continue;
    r->skin_contact_any = true;
    if (e.body_part == r->body_part && !r->skin_contact) {
      r->skin_contact = true;
      r->contact_time_s = e.time_s;
    }
  }
  if (!world_contacts_) return;
  double newest = last_world_contact_s_;
  for (const auto& c : world_contacts_->recent) {
    if (c.time_s <= last_world_contact_s_) continue;
    newest = std::max(newest, c.time_s);
    const int object = c.object_a >= 0 ? c.object_a : c.object_b;
    const int link = c.object_a >= 0 ? c.link_b : c.link_a;
    if (object < 0 || link < 0 || static_cast<std::size_t>(object) >= objects_->names.size())
      continue;
    const auto it = record_of_object_.find(objects_->names[static_cast<std::size_t>(object)]);
    if (it != record_of_object_.end()) records_[it->second].object_contact = true;
  }
  last_world_contact_s_ = newest;
}

void PpsEvaluator::step(NodeContext& ctx) {
  if (spawns_)
    for (const auto& s : spawns_->recent)
      if (!geometries_.contains(s.name))
        geometries_[s.name] = robot::ObjectGeometry{s.shape, s.size, 0};
  follow_presentation(ctx);
  if (!records_.empty() && records_.back().open()) observe(ctx, records_.back());
  attribute_contacts();
}

void PpsEvaluator::finish(NodeContext& ctx) {
  const nlohmann::json metrics = evaluation_metrics(records_);
  for (const auto& [key, value] : metrics.items()) ctx.report_metric(key, value);
  ctx.report_metric("threshold", config_.threshold);
  if (!csv_name_.empty()) write_presentations_csv(csv_path_, records_);
  for (const auto& [id, trace] : traces_) {
    if (trace.time_s.empty()) continue;
    const auto it = std::find_if(records_.begin(), records_.end(),
                                 [&id = id](const PresentationRecord& r) { return r.id == id; });
    draw_presentation_figure(trace, *it, config_.threshold, config_.figure_taxels,
                             ctx.figure_path(fmt::format("presentation_{}_{}_{}.png", id,
                                                         motion_name(it->motion), it->body_part)));
  }
}

}  // namespace somasim::plugins
