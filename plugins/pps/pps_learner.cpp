#include "pps_learner.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "landscape_figure.hpp"
#include "learner_params.hpp"
#include "learner_report.hpp"
#include "somasim/diagnostics.hpp"
#include "somasim/pps/ini_export.hpp"
#include "somasim/pps/learned_file.hpp"
#include "somasim/pps/learned_state.hpp"

namespace somasim::plugins {

template <class V>
void PpsLearner::Config::visit(V& v) {
  v.field("body_part", body_part)
      .doc(
          "the skin part(s) whose taxels learn: one or several space-separated names in the "
          "'taxels' input, e.g. \"left_forearm right_palm\" (one learner per part)");
  v.block(learning);
  v.field("learn", learn).doc("learn from contact events (false: only evaluate)");
  v.field("load", load)
      .doc(
          "learned-state file to start from, relative to the experiment: somasim JSON (holding "
          "every body part), or the iCub's taxels2D_*.ini (sections named as the body parts; "
          "(D, TTC) counts only, taxel geometry taken from the 'taxels' input by id)");
  v.field("save", save)
      .doc(
          "file name of the learned state written into the run folder, all parts in one file: "
          "*.json (somasim) or *.ini (the iCub's taxels2D format, d_ttc model only) ('' = none)");
  v.field("figure_taxels", figure_taxels)
      .max_size(100)
      .doc(
          "taxel ids whose landscapes are drawn, in every part that has them (empty: the first "
          "four of each part; for the snapshots, the first four touched so far)");
  v.field("snapshot_events", snapshot_events)
      .max_size(100)
      .doc(
          "also draw a part's landscapes after it learned from these many events (e.g. [1, 4] "
          "as in Fig 9); a drawn taxel without positive samples yet is named in the log");
  v.field("min_samples", min_samples)
      .at_least(0)
      .doc("taxels with fewer learned samples are left out of offset statistics");
  v.field("offset_groups", offset_groups)
      .doc(
          "taxel groups whose offsets are also reported together (metric offset_groups), e.g. "
          "\"inner_forearm: left_forearm +z, palm: right_palm\": a body part, optionally only "
          "the taxels whose outward normal points along +x/-x/+y/-y/+z/-z of its link frame");
}

void PpsLearner::Config::validate(ConfigChecks& checks) const {
  checks.require(!body_part.empty(), body_part, "is empty, expected one or more skin parts");
  for (auto it = body_part.begin(); it != body_part.end(); ++it)
    checks.require(std::find(body_part.begin(), it, *it) == it, body_part,
                   "lists '" + *it + "' twice");
}

template <class V>
void PpsLearner::Ports::visit(V& v) {
  v.port("stimulus", stimulus, "perceived stimulus (root frame), sampled at this node's rate");
  v.port("taxels", taxels, "taxel poses in the root frame");
  v.port("contacts", contacts, "skin contact events (unwired: no learning)");
  v.port("true_offsets", true_offsets,
         "the offset [m] each taxel should show, by label \"part/id\" (NaN: "
         "unknown), for the offset_error_* metrics");
  v.port("activations", activations,
         "activation in [0, 1] of each taxel, parts concatenated in the order of "
         "body_part, labels \"part/id\"");
  v.port("max_activation", max_activation, "largest activation over all parts");
}

PluginSpec PpsLearner::spec() {
  return make_plugin_spec<Config, Ports>(
      "pps_learner",
      "Peripersonal-space learner (Roncone et al. 2016): per taxel (D, TTC) counts "
      "learned from buffered stimuli at skin contacts; Parzen-smoothed activations.");
}

void PpsLearner::configure(NodeContext& ctx) {
  config_ = read_config<Config>(ctx);
  bind_ports(ctx, ports_);
  params_ = config_.learning.to_params();
  parse_body_parts();
  save_name_ = config_.save.name;
  if (!save_name_.empty()) save_path_ = config_.save.path;
  if (!save_name_.empty() && pps::is_ini_learned_file(save_name_) &&
      params_.model != pps::PpsModel::kDTtc)
    config_error(ctx, config_, config_.save,
                 "an .ini file holds (D, TTC) maps; this learner's model is " +
                     std::string(pps::to_string(params_.model)) + " (save as .json)");
  try {
    std::vector<std::string> names;
    for (const LearnerPart& p : parts_) names.push_back(p.name);
    offset_groups_ = parse_offset_groups(config_.offset_groups, names);
  } catch (const InputError& e) {
    config_error(ctx, config_, config_.offset_groups, e.what());
  }
  for (double e : config_.snapshot_events) snapshot_after_.push_back(static_cast<std::size_t>(e));
  stimulus_ = &ports_.stimulus.get();
  skin_ = &ports_.taxels.get();
  contacts_ = ports_.contacts.get();
  true_offsets_ = ports_.true_offsets.get();
  activations_ = &ports_.activations.get();
  max_activation_ = &ports_.max_activation.get();
  if (config_.load.given()) this->load(ctx, config_.load.path);
}

void PpsLearner::parse_body_parts() {
  // Duplicates and an empty list are refused by Config::validate().
  for (const std::string& name : config_.body_part) parts_.emplace_back().name = name;
}

void PpsLearner::load(NodeContext& ctx, const std::filesystem::path& file) {
  load_path_ = file.string();
  pps::PartsExpectations expect;
  for (const LearnerPart& p : parts_) expect.body_parts.push_back(p.name);
  expect.model = params_.model;
  pps::LearnedFile loaded;
  try {
    loaded = pps::load_learned_file(load_path_, expect, params_.parzen);
  } catch (const InputError& e) {
    config_error(ctx, config_, config_.load,
                 e.what());  // the file's own message, located at the parameter
  }
  for (std::size_t i = 0; i < parts_.size(); ++i) {
    if (loaded.has_geometry)
      parts_[i].learner =
          std::make_unique<pps::BodyPartLearner>(pps::make_learner(loaded.parts[i], params_));
    else
      parts_[i].needs_geometry = std::make_unique<pps::LearnedState>(std::move(loaded.parts[i]));
  }
}

// A learner from a file without geometry: its taxels in the input's order, posed as the input's.
void PpsLearner::add_geometry(LearnerPart& p, const SkinPart& part) {
  pps::LearnedState& st = *p.needs_geometry;
  const std::size_t n = part.taxel_ids.size();
  const bool has_link = part.positions_link.size() == n && part.normals_link.size() == n;
  std::vector<pps::LearnedTaxel> ordered;
  for (std::size_t k = 0; k < n; ++k) {
    const auto it = std::find_if(st.taxels.begin(), st.taxels.end(),
                                 [&](const auto& t) { return t.id == part.taxel_ids[k]; });
    if (it == st.taxels.end())
      throw InputError(load_path_ + ": body part \"" + p.name + "\" has no taxel " +
                       std::to_string(part.taxel_ids[k]) +
                       ", expected every taxel id of the 'taxels' input");
    ordered.push_back(*it);
    ordered.back().pose_link.position = has_link ? part.positions_link[k] : part.positions[k];
    ordered.back().pose_link.normal = has_link ? part.normals_link[k] : part.normals[k];
  }
  if (ordered.size() != st.taxels.size())
    throw InputError(load_path_ + ": body part \"" + p.name + "\" has " +
                     std::to_string(st.taxels.size()) + " taxels, expected " + std::to_string(n) +
                     " (the 'taxels' input's count)");
  st.taxels = std::move(ordered);
  p.learner = std::make_unique<pps::BodyPartLearner>(pps::make_learner(st, params_));
  p.needs_geometry.reset();
}

// First step: finds each part in the 'taxels' input, checks a loaded learner against it (or
// creates the learner from its taxels), and lays out the activations output.
void PpsLearner::bind_parts(NodeContext& ctx) {
  activations_->labels.clear();
  std::size_t total = 0;
  for (LearnerPart& p : parts_) {
    const SkinPart& part = input_part(ctx, p);
    const std::size_t n = part.taxel_ids.size();
    if (p.needs_geometry) add_geometry(p, part);
    if (p.learner) {
      const auto& taxels = p.learner->taxels();
      if (taxels.size() != n)
        throw InputError(load_path_ + ": body part \"" + p.name + "\" has " +
                         std::to_string(taxels.size()) + " taxels, expected " + std::to_string(n) +
                         " (the 'taxels' input's count)");
      for (std::size_t k = 0; k < n; ++k)
        if (taxels[k].id != part.taxel_ids[k])
          throw InputError(load_path_ + ": body part \"" + p.name + "\": taxel " +
                           std::to_string(k) + " has id " + std::to_string(taxels[k].id) +
                           ", expected " + std::to_string(part.taxel_ids[k]) +
                           " (the 'taxels' input's order)");
    } else {
      const bool has_link = part.positions_link.size() == n && part.normals_link.size() == n;
      std::vector<pps::TaxelInfo> taxels(n);
      for (std::size_t k = 0; k < n; ++k) {
        taxels[k].id = part.taxel_ids[k];
        taxels[k].pose_link.position = has_link ? part.positions_link[k] : part.positions[k];
        taxels[k].pose_link.normal = has_link ? part.normals_link[k] : part.normals[k];
      }
      p.learner = std::make_unique<pps::BodyPartLearner>(p.name, std::move(taxels), params_);
    }
    p.first = total;
    total += n;
    p.poses.resize(n);
    for (int id : part.taxel_ids) activations_->labels.push_back(p.name + "/" + std::to_string(id));
    ctx.log().info("{} taxels on '{}'", n, p.name);
  }
  activations_->values.assign(total, 0.0);
  check_figure_taxels(ctx);
  bound_ = true;
}

void PpsLearner::check_figure_taxels(NodeContext& ctx) const {
  for (double id : config_.figure_taxels) {
    bool found = false;
    for (const LearnerPart& p : parts_)
      found = found || p.learner->index_of(static_cast<int>(id)) >= 0;
    if (!found) {
      std::string names;
      for (const LearnerPart& p : parts_) names += (names.empty() ? "" : " ") + p.name;
      config_error(ctx, config_, config_.figure_taxels,
                   "taxel id " + std::to_string(static_cast<int>(id)) +
                       " is on none of the parts (" + names + ")");
    }
  }
}

// The part's entry in the 'taxels' input: the cached index if it still names the part (no
// allocation, no search), else found again by name.
const SkinPart& PpsLearner::input_part(NodeContext& ctx, LearnerPart& p) const {
  const auto& parts = skin_->parts;
  if (p.input_index >= parts.size() || parts[p.input_index].name != p.name) {
    p.input_index = parts.size();
    for (std::size_t i = 0; i < parts.size(); ++i)
      if (parts[i].name == p.name) p.input_index = i;
    if (p.input_index == parts.size()) {
      std::vector<std::string> names;
      for (const auto& q : parts) names.push_back(q.name);
      config_error(ctx, config_, config_.body_part,
                   "no skin part '" + p.name + "' in the 'taxels' input" +
                       did_you_mean(p.name, names) + "; parts: " + join_names(names));
    }
  }
  const SkinPart& part = parts[p.input_index];
  if (bound_) {
    const std::size_t n = p.poses.size();
    if (part.positions.size() != n || part.normals.size() != n)
      throw RunError("pps_learner: skin part '" + p.name + "' now has " +
                     std::to_string(part.positions.size()) + " taxel positions and " +
                     std::to_string(part.normals.size()) + " normals, expected " +
                     std::to_string(n));
  } else if (part.positions.size() != part.taxel_ids.size() ||
             part.normals.size() != part.taxel_ids.size()) {
    throw RunError("pps_learner: skin part '" + p.name + "' has " +
                   std::to_string(part.taxel_ids.size()) + " taxel ids but " +
                   std::to_string(part.positions.size()) + " positions and " +
                   std::to_string(part.normals.size()) + " normals");
  }
  return part;
}

void PpsLearner::step(NodeContext& ctx) {
  if (!bound_) bind_parts(ctx);
  for (LearnerPart& p : parts_) {
    const SkinPart& part = input_part(ctx, p);
    for (std::size_t k = 0; k < p.poses.size(); ++k) {
      p.poses[k].position = part.positions[k];
      p.poses[k].normal = part.normals[k];
    }
    p.event_before_now = false;
  }
  const double now = ctx.time_s();
  // Contacts first, with the samples buffered up to them; the current sample belongs to the
  // approach that ended with a part's contact only if it is not later than the contact.
  if (contacts_)
    for (const auto& e : contacts_->recent)
      if (e.id > last_event_id_ && e.time_s < now)
        for (LearnerPart& p : parts_)
          if (e.body_part == p.name) p.event_before_now = true;
  const pps::StimulusSample sample{now,
                                   {stimulus_->position, stimulus_->velocity, stimulus_->radius}};
  if (stimulus_->present)
    for (LearnerPart& p : parts_)
      if (!p.event_before_now) p.learner->push_stimulus(sample);
  if (contacts_) learn_from_events(ctx);
  for (LearnerPart& p : parts_) {
    if (!stimulus_->present)
      p.learner->buffer().update(now);
    else if (p.event_before_now)
      p.learner->push_stimulus(sample);
  }
  update_activations();
}

void PpsLearner::learn_from_events(NodeContext& ctx) {
  for (const auto& e : contacts_->recent) {
    if (e.id <= last_event_id_) continue;
    last_event_id_ = e.id;
    if (!config_.learn) continue;
    for (LearnerPart& p : parts_) {
      if (e.body_part != p.name) continue;
      // The contact estimator: where the stimulus was perceived when it touched (before the
      // buffer is spent on the maps).
      std::optional<pps::SkinTouch> touch;
      if (e.contact_point_link.allFinite() && e.contact_normal_link.allFinite())
        touch = pps::SkinTouch{e.contact_point_link, e.contact_normal_link};
      p.learner->record_contact_offset(p.poses, e.touched_taxels,
                                       std::isnan(e.first_touch_s) ? e.time_s : e.first_touch_s,
                                       touch);
      p.learner->on_contact(p.poses, e.touched_taxels);
      ++p.events;
      if (std::find(snapshot_after_.begin(), snapshot_after_.end(), p.events) !=
          snapshot_after_.end())
        draw_landscapes(ctx, *p.learner, snapshot_taxels(ctx, p),
                        "after_" + std::to_string(p.events) + "_events");
    }
  }
}

// Fig 9 snapshots show one-shot learning: by default the (first four) taxels touched so far; a
// listed taxel that has no positive sample yet is drawn blank, and the log says why.
std::vector<double> PpsLearner::snapshot_taxels(NodeContext& ctx, const LearnerPart& p) const {
  const pps::BodyPartLearner& learner = *p.learner;
  std::vector<double> ids = config_.figure_taxels;
  if (ids.empty())
    for (std::size_t k = 0; k < learner.taxels().size() && ids.size() < kSnapshotTaxels; ++k)
      if (learner.contact_count(static_cast<int>(k)) > 0) ids.push_back(learner.taxels()[k].id);
  for (double id : ids) {
    const int k = learner.index_of(static_cast<int>(id));
    if (k < 0) continue;
    const auto& pos = learner.maps()[static_cast<std::size_t>(k)].pos();
    if (std::all_of(pos.begin(), pos.end(), [](auto c) { return c == 0; }))
      ctx.log().info(
          "{}: the landscape of {}/{} after {} events is blank: no positive sample yet "
          "(the taxel has not been touched)",
          ctx.node_name(), p.name, static_cast<int>(id), p.events);
  }
  return ids;
}

void PpsLearner::update_activations() {
  double max_a = 0.0;
  const pps::Stimulus s{stimulus_->position, stimulus_->velocity, stimulus_->radius};
  double* out = activations_->values.data();
  for (const LearnerPart& p : parts_) {
    for (std::size_t k = 0; k < p.poses.size(); ++k) {
      const double a =
          stimulus_->present ? p.learner->activation(static_cast<int>(k), p.poses[k], s) : 0.0;
      out[p.first + k] = a;
      max_a = std::max(max_a, a);
    }
  }
  *max_activation_ = max_a;
}

void PpsLearner::finish(NodeContext& ctx) {
  if (!bound_) return;
  report_learning(ctx, parts_, config_.min_samples, true_offsets_, offset_groups_);
  if (!save_name_.empty()) {
    std::vector<pps::LearnedState> states;
    for (const LearnerPart& p : parts_) states.push_back(pps::learned_state(*p.learner));
    pps::save_learned_file(states, save_path_.string());
  }
  for (LearnerPart& p : parts_)
    draw_landscapes(ctx, *p.learner, config_.figure_taxels, "", true_offsets_);
}

}  // namespace somasim::plugins
