#include "learner_report.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <unordered_map>

#include "somasim/pps/offset_estimate.hpp"
#include "somasim/pps/offset_ridge.hpp"

namespace somasim::plugins {

namespace {

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
  json mean_json() const { return n ? json(sum / n) : json(); }
  json max_json() const { return n ? json(max) : json(); }
};

// Offset statistics of a set of taxels (one part, or all parts).
struct OffsetStats {
  Summary ridge, paper, truth;       // estimates and true offsets of taxels with enough samples
  Summary error_ridge, error_paper;  // |estimate - truth| where both are defined
  std::size_t evaluated = 0;         // taxels with enough samples and a finite true offset
  std::size_t no_ridge = 0, no_paper = 0;  // ... of which without that estimate

  void add(const std::optional<double>& r, const std::optional<double>& p, double t) {
    if (r) ridge.add(*r);
    if (p) paper.add(*p);
    if (!std::isfinite(t)) return;
    truth.add(t);
    ++evaluated;
    if (r)
      error_ridge.add(std::abs(*r - t));
    else
      ++no_ridge;
    if (p)
      error_paper.add(std::abs(*p - t));
    else
      ++no_paper;
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
          {"negative_d_share", counted ? static_cast<double>(t.behind_skin) / counted : 0.0}};
}

}  // namespace

void report_learning(NodeContext& ctx, std::vector<LearnerPart>& parts, int min_samples,
                     const TaxelValues* true_offsets) {
  std::unordered_map<std::string, double> truth_by_label;
  if (true_offsets)
    for (std::size_t i = 0; i < true_offsets->labels.size() && i < true_offsets->values.size(); ++i)
      truth_by_label[true_offsets->labels[i]] = true_offsets->values[i];
  const bool single = parts.size() == 1;
  std::size_t events = 0;
  pps::LearningStats totals;
  OffsetStats all;
  json per_taxel = json::object(), per_part = json::object();
  json mean_ridge = json::object(), mean_paper = json::object(), mean_truth = json::object();
  for (LearnerPart& part : parts) {
    if (!part.learner) continue;
    pps::BodyPartLearner& learner = *part.learner;
    const bool distance_only = learner.params().model == pps::PpsModel::kDistanceOnly;
    OffsetStats stats;
    for (std::size_t k = 0; k < learner.maps().size(); ++k) {
      pps::TaxelMap& map = learner.maps()[k];
      if (map.stale()) map.refresh();
      const std::uint64_t samples = sample_count(map);
      // Fig 8 needs a TTC axis: undefined for the distance-only model.
      const auto paper = distance_only ? std::nullopt : pps::estimate_offset(map);
      const auto ridge = pps::estimate_offset_ridge(map);
      const std::string id = std::to_string(learner.taxels()[k].id);
      const std::string label = part.name + "/" + id;
      double truth = kNaN;
      if (const auto it = truth_by_label.find(label); it != truth_by_label.end())
        truth = it->second;
      json& t = per_taxel[single ? id : label];
      t = {{"samples", samples},
           {"offset_estimate_m", opt_json(paper)},
           {"offset_ridge_m", opt_json(ridge)}};
      if (true_offsets) t["true_offset_m"] = std::isfinite(truth) ? json(truth) : json();
      if (samples < static_cast<std::uint64_t>(min_samples)) continue;
      stats.add(ridge, paper, truth);
      all.add(ridge, paper, truth);
    }
    const pps::LearningStats& t = learner.totals();
    json p = sample_metrics(t);
    p["events"] = part.events;
    p["taxels"] = learner.taxels().size();
    if (true_offsets) {
      p["offset_taxels_evaluated"] = stats.evaluated;
      p["offset_error_max_m"] = stats.error_ridge.max_json();
      p["offset_error_max_paper_m"] = stats.error_paper.max_json();
    }
    per_part[part.name] = std::move(p);
    mean_ridge[part.name] = stats.ridge.mean_json();
    mean_paper[part.name] = stats.paper.mean_json();
    mean_truth[part.name] = stats.truth.mean_json();
    events += part.events;
    totals.positives += t.positives;
    totals.negatives += t.negatives;
    totals.behind_skin += t.behind_skin;
  }
  ctx.report_metric("events", events);
  const json sums = sample_metrics(totals);
  for (const char* key : {"samples", "positive_samples", "negative_samples", "negative_d_share"})
    ctx.report_metric(key, sums[key]);
  // Means over every taxel with enough samples (all parts): the paper's Fig 8 regression and
  // the ridge-end estimator, under their original keys.
  ctx.report_metric("offset_estimate_m", all.paper.mean_json());
  ctx.report_metric("offset_ridge_m", all.ridge.mean_json());
  ctx.report_metric("offset_mean_m", mean_ridge);
  ctx.report_metric("offset_mean_paper_m", mean_paper);
  if (true_offsets) {
    ctx.report_metric("true_offset_mean_m", mean_truth);
    ctx.report_metric("offset_error_max_m", all.error_ridge.max_json());
    ctx.report_metric("offset_error_mean_m", all.error_ridge.mean_json());
    ctx.report_metric("offset_error_max_paper_m", all.error_paper.max_json());
    ctx.report_metric("offset_error_mean_paper_m", all.error_paper.mean_json());
    ctx.report_metric("offset_taxels_evaluated", all.evaluated);
    ctx.report_metric("offset_taxels_without_estimate",
                      json{{"ridge", all.no_ridge}, {"paper", all.no_paper}});
  }
  ctx.report_metric("per_part", per_part);
  ctx.report_metric("taxels", per_taxel);
}

}  // namespace somasim::plugins
