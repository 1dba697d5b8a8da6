#include "learner_report.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <unordered_map>

#include "somasim/pps/offset_estimate.hpp"
#include "somasim/pps/offset_floor.hpp"
#include "somasim/pps/offset_ridge.hpp"

namespace somasim::plugins {

namespace {

const char* evidence_name(pps::ContactEvidence e) {
  switch (e) {
    case pps::ContactEvidence::kEstimated:
      return "estimated";
    case pps::ContactEvidence::kTooFew:
      return "too_few";
    case pps::ContactEvidence::kDisagreeing:
      return "disagreeing";
    default:
      return "none";
  }
}

using nlohmann::json;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

json opt_json(const std::optional<double>& v) {
  return v ? json(*v) : json();
}

// Mean and largest value of a stream of numbers; null json when empty.
struct Summary {
  double sum = 0.0;
  double max = 0.0;
  std::size_t n = 0;
  void add(double v) {
    sum += v;
    max = n ? std::max(max, v) : v;
    ++n;
  }
  json mean_json() const { return n ? json(sum / static_cast<double>(n)) : json(); }
  json max_json() const { return n ? json(max) : json(); }
};

// Estimates of one estimator over a set of taxels, and their errors where the truth is known.
struct EstimatorStats {
  Summary estimate;      // estimates of taxels with enough samples
  Summary error;         // |estimate - truth| where both are defined
  Summary bias;          // estimate - truth where both are defined (signed)
  std::size_t none = 0;  // taxels with enough samples and a finite truth but no estimate

  void add(const std::optional<double>& e, double truth) {
    if (e) estimate.add(*e);
    if (!std::isfinite(truth)) return;
    if (e) {
      error.add(std::abs(*e - truth));
      bias.add(*e - truth);
    } else
      ++none;
  }
};

// Offset statistics of a set of taxels (one part, or all parts).
struct OffsetStats {
  EstimatorStats contact, floor, ridge, paper;
  Summary truth;              // true offsets of taxels with enough samples
  std::size_t evaluated = 0;  // taxels with enough samples and a finite true offset
  std::size_t counted = 0;    // taxels with enough samples

  void add(const std::optional<double>& c, const std::optional<double>& f,
           const std::optional<double>& r, const std::optional<double>& p, double t) {
    ++counted;
    contact.add(c, t);
    floor.add(f, t);
    ridge.add(r, t);
    paper.add(p, t);
    if (!std::isfinite(t)) return;
    truth.add(t);
    ++evaluated;
  }
};

std::uint64_t sample_count(const pps::TaxelMap& map) {
  std::uint64_t n = 0;
  for (std::size_t i = 0; i < map.pos().size(); ++i) n += map.pos()[i] + map.neg()[i];
  return n;
}

json sample_metrics(const pps::LearningStats& t) {
  const std::size_t counted = t.positives + t.negatives;
  return {{"samples", counted},
          {"positive_samples", t.positives},
          {"negative_samples", t.negatives},
          {"negative_d_share",
           counted ? static_cast<double>(t.behind_skin) / static_cast<double>(counted) : 0.0}};
}

}  // namespace

void report_learning(NodeContext& ctx, std::vector<LearnerPart>& parts, int min_samples,
                     const TaxelValues* true_offsets, const std::vector<OffsetGroup>& groups) {
  std::vector<OffsetStats> group_stats(groups.size());
  std::unordered_map<std::string, double> truth_by_label;
  if (true_offsets)
    for (std::size_t i = 0; i < true_offsets->labels.size() && i < true_offsets->values.size(); ++i)
      truth_by_label[true_offsets->labels[i]] = true_offsets->values[i];
  const bool single = parts.size() == 1;
  std::size_t events = 0;
  pps::LearningStats totals;
  OffsetStats all;
  json per_taxel = json::object(), per_part = json::object();
  json mean_contact = json::object(), mean_floor = json::object(), mean_ridge = json::object(),
       mean_paper = json::object(), mean_truth = json::object();
  // Touched taxels whose contact evidence gives no estimate, by reason.
  std::size_t too_few = 0, disagreeing = 0;
  for (LearnerPart& part : parts) {
    if (!part.learner) continue;
    pps::BodyPartLearner& learner = *part.learner;
    const bool distance_only = learner.params().model == pps::PpsModel::kDistanceOnly;
    OffsetStats stats;
    for (std::size_t k = 0; k < learner.maps().size(); ++k) {
      pps::TaxelMap& map = learner.maps()[k];
      if (map.stale()) map.refresh();
      const std::uint64_t samples = sample_count(map);
      const bool counted = samples >= static_cast<std::uint64_t>(min_samples);
      // Estimates only for taxels with enough samples (Fig 8 evaluates the activation on a
      // grid: the costliest part of the report). Fig 8 needs a TTC axis: none for the
      // distance-only model.
      std::optional<double> contact, floor, ridge, paper;
      if (counted) {
        contact = learner.contact_offset(static_cast<int>(k));
        floor = pps::estimate_offset_floor(map);
        ridge = pps::estimate_offset_ridge(map);
        if (!distance_only) paper = pps::estimate_offset(map);
      }
      const std::string id = std::to_string(learner.taxels()[k].id);
      const std::string label = part.name + "/" + id;
      double truth = kNaN;
      if (const auto it = truth_by_label.find(label); it != truth_by_label.end())
        truth = it->second;
      const pps::ContactEvidence evidence = learner.contact_evidence(static_cast<int>(k));
      too_few += evidence == pps::ContactEvidence::kTooFew ? 1 : 0;
      disagreeing += evidence == pps::ContactEvidence::kDisagreeing ? 1 : 0;
      json& t = per_taxel[single ? id : label];
      t = {{"samples", samples},
           {"contacts", learner.contact_count(static_cast<int>(k))},
           {"contact_evidence", evidence_name(evidence)},
           {"offset_contact_m", opt_json(contact)},
           {"offset_floor_m", opt_json(floor)},
           {"offset_ridge_m", opt_json(ridge)},
           {"offset_estimate_m", opt_json(paper)}};
      if (true_offsets) t["true_offset_m"] = std::isfinite(truth) ? json(truth) : json();
      if (!counted) continue;
      stats.add(contact, floor, ridge, paper, truth);
      all.add(contact, floor, ridge, paper, truth);
      for (std::size_t g = 0; g < groups.size(); ++g)
        if (groups[g].contains(part.name, learner.taxels()[k].pose_link.normal))
          group_stats[g].add(contact, floor, ridge, paper, truth);
    }
    const pps::LearningStats& t = learner.totals();
    json p = sample_metrics(t);
    p["events"] = part.events;
    p["taxels"] = learner.taxels().size();
    if (true_offsets) {
      p["offset_taxels_evaluated"] = stats.evaluated;
      p["offset_error_max_m"] = stats.contact.error.max_json();
      p["offset_error_mean_m"] = stats.contact.error.mean_json();
      p["offset_error_max_floor_m"] = stats.floor.error.max_json();
      p["offset_error_mean_floor_m"] = stats.floor.error.mean_json();
      p["offset_error_max_contact_m"] = stats.contact.error.max_json();
      p["offset_error_mean_contact_m"] = stats.contact.error.mean_json();
      p["offset_error_max_ridge_m"] = stats.ridge.error.max_json();
      p["offset_error_mean_ridge_m"] = stats.ridge.error.mean_json();
      p["offset_error_max_paper_m"] = stats.paper.error.max_json();
      p["offset_error_mean_paper_m"] = stats.paper.error.mean_json();
    }
    per_part[part.name] = std::move(p);
    mean_contact[part.name] = stats.contact.estimate.mean_json();
    mean_floor[part.name] = stats.floor.estimate.mean_json();
    mean_ridge[part.name] = stats.ridge.estimate.mean_json();
    mean_paper[part.name] = stats.paper.estimate.mean_json();
    mean_truth[part.name] = stats.truth.mean_json();
    events += part.events;
    totals.positives += t.positives;
    totals.negatives += t.negatives;
    totals.behind_skin += t.behind_skin;
  }
  ctx.report_metric("events", events);
  ctx.report_metric("contact_estimates_withheld",
                    json{{"too_few", too_few}, {"disagreeing", disagreeing}});
  const json sums = sample_metrics(totals);
  for (const char* key : {"samples", "positive_samples", "negative_samples", "negative_d_share"})
    ctx.report_metric(key, sums[key]);
  // Means over every taxel with enough samples (all parts): the paper's Fig 8 regression, the
  // ridge end and the floor, under their original keys.
  ctx.report_metric("offset_estimate_m", all.paper.estimate.mean_json());
  ctx.report_metric("offset_ridge_m", all.ridge.estimate.mean_json());
  ctx.report_metric("offset_floor_m", all.floor.estimate.mean_json());
  ctx.report_metric("offset_contact_m", all.contact.estimate.mean_json());
  // Per part; the estimator that holds for errors of either sign (the contact estimator: the
  // map-based ones cannot tell the sign of a sideways offset) is the unsuffixed key.
  ctx.report_metric("offset_mean_m", mean_contact);
  ctx.report_metric("offset_mean_contact_m", mean_contact);
  ctx.report_metric("offset_mean_floor_m", mean_floor);
  ctx.report_metric("offset_mean_ridge_m", mean_ridge);
  ctx.report_metric("offset_mean_paper_m", mean_paper);
  if (true_offsets) {
    ctx.report_metric("true_offset_mean_m", mean_truth);
    ctx.report_metric("offset_error_max_m", all.contact.error.max_json());
    ctx.report_metric("offset_error_mean_m", all.contact.error.mean_json());
    ctx.report_metric("offset_error_max_floor_m", all.floor.error.max_json());
    ctx.report_metric("offset_error_mean_floor_m", all.floor.error.mean_json());
    ctx.report_metric("offset_error_max_contact_m", all.contact.error.max_json());
    ctx.report_metric("offset_error_mean_contact_m", all.contact.error.mean_json());
    ctx.report_metric("offset_error_max_ridge_m", all.ridge.error.max_json());
    ctx.report_metric("offset_error_mean_ridge_m", all.ridge.error.mean_json());
    ctx.report_metric("offset_error_max_paper_m", all.paper.error.max_json());
    ctx.report_metric("offset_error_mean_paper_m", all.paper.error.mean_json());
    ctx.report_metric("offset_taxels_evaluated", all.evaluated);
    ctx.report_metric("offset_taxels_without_estimate", json{{"contact", all.contact.none},
                                                             {"floor", all.floor.none},
                                                             {"ridge", all.ridge.none},
                                                             {"paper", all.paper.none}});
  }
  if (!groups.empty()) {
    json by_group = json::object();
    for (std::size_t g = 0; g < groups.size(); ++g) {
      const OffsetStats& s = group_stats[g];
      json j = {{"taxels", s.counted},
                {"offset_mean_m", s.contact.estimate.mean_json()},
                {"offset_mean_paper_m", s.paper.estimate.mean_json()}};
      if (true_offsets) {
        j["true_offset_mean_m"] = s.truth.mean_json();
        j["offset_error_max_m"] = s.contact.error.max_json();
        j["offset_error_mean_m"] = s.contact.error.mean_json();
        // The group's offset (the mean over its taxels, the paper's Fig 8 figure) minus the
        // true one, over the taxels with both.
        j["group_offset_error_m"] = s.contact.bias.mean_json();
        j["offset_taxels_evaluated"] = s.evaluated;
      }
      by_group[groups[g].name] = std::move(j);
    }
    ctx.report_metric("offset_groups", by_group);
  }
  ctx.report_metric("per_part", per_part);
  ctx.report_metric("taxels", per_taxel);
}

}  // namespace somasim::plugins
