#include "pps_learner.hpp"

#include <algorithm>
#include <cmath>

#include "landscape_figure.hpp"
#include "learner_params.hpp"
#include "somasim/diagnostics.hpp"
#include "somasim/pps/learned_state.hpp"
#include "somasim/pps/map_io.hpp"
#include "somasim/pps/offset_estimate.hpp"
#include "somasim/pps/offset_ridge.hpp"

namespace somasim::plugins {

PluginSpec PpsLearner::spec() {
  PluginSpec s("pps_learner",
               "Peripersonal-space learner (Roncone et al. 2016): per taxel (D, TTC) counts "
               "learned from buffered stimuli at skin contacts; Parzen-smoothed activations.");
  s.add_string("body_part")
      .defaults(std::string("taxel"))
      .describe("the skin part (a name in the 'taxels' input) whose taxels learn");
  declare_learner_params(s);
  s.add_bool("learn").defaults(true).describe("learn from contact events (false: only evaluate)");
  s.add_string("load")
      .defaults(std::string(""))
      .describe("learned-state file to start from (somasim JSON); relative to the experiment");
  s.add_string("save")
      .defaults(std::string("pps_map.json"))
      .describe("file name of the learned state written into the run folder ('' = none)");
  s.add_list("figure_taxels")
      .defaults(std::vector<double>{})
      .describe("taxel ids whose landscapes are drawn (empty: the first four)");
  s.add_list("snapshot_events")
      .defaults(std::vector<double>{})
      .describe("also draw the landscapes after these many events (e.g. [1, 4] as in Fig 9)");
  s.add_int("min_samples")
      .defaults(std::int64_t{50})
      .at_least(0)
      .describe("taxels with fewer learned samples are left out of offset statistics");
  s.input<Stimulus>("stimulus", "perceived stimulus (root frame), sampled at this node's rate");
  s.input<SkinTaxels>("taxels", "taxel poses in the root frame");
  s.input<ContactEvents>("contacts", "skin contact events (unwired: no learning)", true);
  s.output<TaxelValues>("activations", "activation in [0, 1] of each taxel of the part");
  s.output<double>("max_activation", "largest activation of the part");
  return s;
}

void PpsLearner::configure(NodeContext& ctx) {
  params_ = read_learner_params(ctx);
  body_part_ = ctx.param<std::string>("body_part");
  learn_ = ctx.param<bool>("learn");
  save_name_ = ctx.param<std::string>("save");
  min_samples_ = ctx.param<int>("min_samples");
  figure_taxels_ = ctx.param<std::vector<double>>("figure_taxels");
  for (double e : ctx.param<std::vector<double>>("snapshot_events"))
    snapshot_after_.push_back(static_cast<std::size_t>(e));
  stimulus_ = &ctx.input<Stimulus>("stimulus");
  skin_ = &ctx.input<SkinTaxels>("taxels");
  contacts_ = ctx.is_wired("contacts") ? &ctx.input<ContactEvents>("contacts") : nullptr;
  activations_ = &ctx.output<TaxelValues>("activations");
  max_activation_ = &ctx.output<double>("max_activation");
  if (const std::string load = ctx.param<std::string>("load"); !load.empty()) {
    load_path_ = ctx.resolve_input_path(load).string();
    pps::LoadExpectations expect;
    expect.body_part = body_part_;
    expect.model = params_.model;
    const pps::LearnedState state = pps::load_learned_state(load_path_, expect);
    learner_ = std::make_unique<pps::BodyPartLearner>(pps::make_learner(state, params_));
  }
}

const SkinPart* PpsLearner::find_part(NodeContext& ctx) const {
  for (const auto& p : skin_->parts)
    if (p.name == body_part_) return &p;
  std::vector<std::string> names;
  for (const auto& p : skin_->parts) names.push_back(p.name);
  ctx.param_error("body_part", "no skin part '" + body_part_ + "' in the 'taxels' input" +
                                   did_you_mean(body_part_, names) +
                                   "; parts: " + join_names(names));
}

void PpsLearner::create_learner(NodeContext& ctx, const SkinPart& part) {
  if (learner_) {
    if (learner_->taxels().size() != part.taxel_ids.size())
      throw InputError(load_path_ + ": " + std::to_string(learner_->taxels().size()) +
                       " taxels, but body part '" + body_part_ + "' has " +
                       std::to_string(part.taxel_ids.size()) + " on the skin");
  } else {
    std::vector<pps::TaxelInfo> taxels;
    for (std::size_t k = 0; k < part.taxel_ids.size(); ++k) {
      pps::TaxelInfo t;
      t.id = part.taxel_ids[k];
      const bool has_link = part.positions_link.size() == part.taxel_ids.size();
      t.pose_link.position = has_link ? part.positions_link[k] : part.positions[k];
      t.pose_link.normal = has_link ? part.normals_link[k] : part.normals[k];
      taxels.push_back(t);
    }
    learner_ = std::make_unique<pps::BodyPartLearner>(body_part_, std::move(taxels), params_);
  }
  activations_->labels.clear();
  for (int id : part.taxel_ids)
    activations_->labels.push_back(body_part_ + "/" + std::to_string(id));
  activations_->values.assign(part.taxel_ids.size(), 0.0);
  poses_.resize(part.taxel_ids.size());
  ctx.log().info("{} taxels on '{}'", part.taxel_ids.size(), body_part_);
}

void PpsLearner::step(NodeContext& ctx) {
  const SkinPart* part = find_part(ctx);
  if (!learner_ || poses_.empty()) create_learner(ctx, *part);
  for (std::size_t k = 0; k < poses_.size(); ++k) {
    poses_[k].position = part->positions[k];
    poses_[k].normal = part->normals[k];
  }
  const double now = ctx.time_s();
  // Contacts first, with the samples buffered up to them; the current sample belongs to the
  // approach that ended with the contact only if it is not later than the contact.
  bool have_new_event = false;
  double first_event_time = now;
  if (contacts_)
    for (const auto& e : contacts_->recent)
      if (e.id > last_event_id_ && e.body_part == body_part_) {
        have_new_event = true;
        first_event_time = std::min(first_event_time, e.time_s);
      }
  const bool sample_after_contact = have_new_event && now > first_event_time;
  const auto push_current = [&] {
    learner_->push_stimulus({now, {stimulus_->position, stimulus_->velocity, stimulus_->radius}});
  };
  if (stimulus_->present && !sample_after_contact) push_current();
  if (contacts_) learn_from_events(ctx);
  if (stimulus_->present && sample_after_contact) push_current();
  if (!stimulus_->present) learner_->buffer().update(now);
  update_activations();
}

void PpsLearner::learn_from_events(NodeContext& ctx) {
  for (const auto& e : contacts_->recent) {
    if (e.id <= last_event_id_) continue;
    last_event_id_ = e.id;
    if (e.body_part != body_part_ || !learn_) continue;
    touched_.assign(e.touched_taxels.begin(), e.touched_taxels.end());
    learner_->on_contact(poses_, touched_);
    ++events_;
    if (std::find(snapshot_after_.begin(), snapshot_after_.end(), events_) != snapshot_after_.end())
      draw_landscapes(ctx, *learner_, figure_taxels_,
                      "after_" + std::to_string(events_) + "_events");
  }
}

void PpsLearner::update_activations() {
  double max_a = 0.0;
  const pps::Stimulus s{stimulus_->position, stimulus_->velocity, stimulus_->radius};
  for (std::size_t k = 0; k < poses_.size(); ++k) {
    const double a =
        stimulus_->present ? learner_->activation(static_cast<int>(k), poses_[k], s) : 0.0;
    activations_->values[k] = a;
    max_a = std::max(max_a, a);
  }
  *max_activation_ = max_a;
}

void PpsLearner::finish(NodeContext& ctx) {
  if (!learner_) return;
  report(ctx);
  if (!save_name_.empty())
    pps::save_learned_state(pps::learned_state(*learner_), ctx.output_path(save_name_).string());
  draw_landscapes(ctx, *learner_, figure_taxels_, "");
}

void PpsLearner::report(NodeContext& ctx) {
  const pps::LearningStats& t = learner_->totals();
  const std::size_t counted = t.positives + t.negatives;
  ctx.report_metric("events", events_);
  ctx.report_metric("samples", counted);
  ctx.report_metric("positive_samples", t.positives);
  ctx.report_metric("negative_samples", t.negatives);
  ctx.report_metric("negative_d_share",
                    counted ? static_cast<double>(t.behind_skin) / counted : 0.0);
  // Offsets per taxel with enough samples: the paper's Fig 8 regression (offset_estimate_m)
  // and the ridge-end estimator (offset_ridge_m); the part's offsets are their means.
  nlohmann::json per_taxel = nlohmann::json::object();
  double sum = 0.0, sum_ridge = 0.0;
  int n = 0, n_ridge = 0;
  const auto opt_json = [](const std::optional<double>& v) {
    return v ? nlohmann::json(*v) : nlohmann::json();
  };
  const bool distance_only = params_.model == pps::PpsModel::kDistanceOnly;
  for (std::size_t k = 0; k < learner_->maps().size(); ++k) {
    auto& map = learner_->maps()[k];
    if (map.stale()) map.refresh();
    std::uint64_t samples = 0;
    for (std::size_t i = 0; i < map.pos().size(); ++i) samples += map.pos()[i] + map.neg()[i];
    // Fig 8 needs a TTC axis: undefined for the distance-only model.
    const auto offset = distance_only ? std::nullopt : pps::estimate_offset(map);
    const auto ridge = pps::estimate_offset_ridge(map);
    const std::string id = std::to_string(learner_->taxels()[k].id);
    per_taxel[id] = {{"samples", samples},
                     {"offset_estimate_m", opt_json(offset)},
                     {"offset_ridge_m", opt_json(ridge)}};
    if (samples < static_cast<std::uint64_t>(min_samples_)) continue;
    if (offset) {
      sum += *offset;
      ++n;
    }
    if (ridge) {
      sum_ridge += *ridge;
      ++n_ridge;
    }
  }
  ctx.report_metric("offset_estimate_m", n ? nlohmann::json(sum / n) : nlohmann::json());
  ctx.report_metric("offset_ridge_m",
                    n_ridge ? nlohmann::json(sum_ridge / n_ridge) : nlohmann::json());
  ctx.report_metric("taxels", per_taxel);
}

}  // namespace somasim::plugins
