#include "somasim/pps/contact_evidence.hpp"

#include <algorithm>
#include <cmath>

namespace somasim::pps {

void ContactEvidenceLog::resize(std::size_t taxels) {
  values_.assign(taxels, {});
  sum_.assign(taxels, 0.0);
  count_.assign(taxels, 0);
}

void ContactEvidenceLog::add(std::size_t k, double d) {
  values_[k].push_back(d);
  sum_[k] += d;
  ++count_[k];
}

void ContactEvidenceLog::restore(std::size_t k, double sum, std::uint32_t count) {
  values_[k].clear();
  sum_[k] = sum;
  count_[k] = count;
}

ContactEvidenceLog::Robust ContactEvidenceLog::evaluate(std::size_t k,
                                                        const ContactEstimateSpec& spec) const {
  const auto min_events = static_cast<std::size_t>(std::max(spec.min_events, 1));
  if (count_[k] == 0) return {ContactEvidence::kNone, 0.0};
  const std::vector<double>& v = values_[k];
  if (v.size() != count_[k]) {  // restored: only the mean is known
    if (count_[k] < min_events) return {ContactEvidence::kTooFew, 0.0};
    return {ContactEvidence::kEstimated, sum_[k] / count_[k]};
  }
  std::vector<double> sorted = v;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t n = sorted.size();
  const double median = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
  double inlier_sum = 0.0;
  std::size_t inliers = 0;
  for (const double d : sorted)
    if (std::abs(d - median) <= spec.agreement_m) {
      inlier_sum += d;
      ++inliers;
    }
  if (inliers < min_events) return {ContactEvidence::kTooFew, 0.0};
  if (2 * inliers <= n) return {ContactEvidence::kDisagreeing, 0.0};
  return {ContactEvidence::kEstimated, inlier_sum / static_cast<double>(inliers)};
}

ContactEvidence ContactEvidenceLog::state(std::size_t k, const ContactEstimateSpec& spec) const {
  return evaluate(k, spec).state;
}

std::optional<double> ContactEvidenceLog::estimate(std::size_t k,
                                                   const ContactEstimateSpec& spec) const {
  const Robust r = evaluate(k, spec);
  if (r.state != ContactEvidence::kEstimated) return std::nullopt;
  return r.value;
}

}  // namespace somasim::pps
