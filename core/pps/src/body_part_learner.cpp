#include "somasim/pps/body_part_learner.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "somasim/error.hpp"

namespace somasim::pps {

BodyPartLearner::BodyPartLearner(std::string body_part, std::vector<TaxelInfo> taxels,
                                 const LearnerParams& params)
    : body_part_(std::move(body_part)),
      params_(params),
      taxels_(std::move(taxels)),
      buffer_(params.buffer),
      rf_(params.rf) {
  if (const std::string e = params_.grid.validate(); !e.empty())
    throw InputError("PPS learner '" + body_part_ + "': invalid grid: " + e);
  if (const std::string e = params_.parzen.validate(); !e.empty())
    throw InputError("PPS learner '" + body_part_ + "': invalid Parzen spec: " + e);
  const bool distance_only = params_.model == PpsModel::kDistanceOnly;
  map_grid_ = distance_only ? distance_only_grid(params_.grid) : params_.grid;
  query_ttc_ = distance_only_query_ttc(map_grid_, params_.parzen);
  maps_.reserve(taxels_.size());
  for (std::size_t k = 0; k < taxels_.size(); ++k) maps_.emplace_back(map_grid_, params_.parzen);
  touched_.assign(taxels_.size(), 0);
  scratch_poses_.resize(taxels_.size());
  contact_.resize(taxels_.size());
}

namespace {

// Believed root <- link transform of a part, fitted to its taxels (link vs root positions).
Eigen::Isometry3d fit_root_from_link(std::span<const TaxelInfo> taxels,
                                     std::span<const TaxelPose> taxels_root) {
  Eigen::Matrix3Xd link(3, static_cast<Eigen::Index>(taxels.size()));
  Eigen::Matrix3Xd root(3, link.cols());
  for (std::size_t k = 0; k < taxels.size(); ++k) {
    link.col(static_cast<Eigen::Index>(k)) = taxels[k].pose_link.position;
    root.col(static_cast<Eigen::Index>(k)) = taxels_root[k].position;
  }
  return Eigen::Isometry3d(Eigen::umeyama(link, root, false));
}

}  // namespace

// The perceived stimulus at time t [s]: interpolated between the buffered samples around t,
// carried along its velocity beyond the first or last one.
Stimulus BodyPartLearner::perceived_at(double t) const {
  const auto& samples = buffer_.samples();
  const StimulusSample* before = nullptr;
  const StimulusSample* after = nullptr;
  for (const StimulusSample& s : samples) {
    if (s.time <= t) before = &s;
    if (s.time >= t && !after) after = &s;
  }
  if (before && after && after->time > before->time) {
    const double w = (t - before->time) / (after->time - before->time);
    Stimulus out = before->stimulus;
    out.position = (1.0 - w) * before->stimulus.position + w * after->stimulus.position;
    out.velocity = (1.0 - w) * before->stimulus.velocity + w * after->stimulus.velocity;
    return out;
  }
  const StimulusSample& nearest = before ? *before : *after;
  Stimulus out = nearest.stimulus;
  out.position += out.velocity * (t - nearest.time);
  return out;
}

void BodyPartLearner::record_contact_offset(std::span<const TaxelPose> taxels_root,
                                            std::span<const int> touched_ids, double touch_time_s,
                                            const std::optional<SkinTouch>& touch) {
  if (taxels_root.size() != taxels_.size() || buffer_.empty()) return;
  std::vector<std::size_t> touched;
  std::vector<Eigen::Vector3d> touched_link;
  for (const int id : touched_ids)
    if (const int k = index_of(id); k >= 0) {
      touched.push_back(static_cast<std::size_t>(k));
      touched_link.push_back(taxels_[static_cast<std::size_t>(k)].pose_link.position);
    }
  if (touched.empty()) return;
  const auto record = [&](std::size_t k, const Stimulus& perceived, double skin_d) {
    const TaxelFrameStimulus local = to_taxel_frame(taxels_root[k], perceived);
    contact_.add(k, compute_d_ttc(local.p, local.v, params_.ttc).d - skin_d);
  };
  if (!touch) {  // the contact taken at the taxel centres, at the touch
    for (const std::size_t k : touched) record(k, perceived_at(touch_time_s), 0.0);
    return;
  }
  const std::size_t k =
      touched[static_cast<std::size_t>(nearest_point(touched_link, touch->point_link))];
  // What the skin itself tells (link frame, free of kinematic error): a stimulus of the
  // perceived radius resting on the skin at the centre of pressure; before the touch, it was
  // where the perceived path says, relative to the touch — the path carried into the link
  // frame by the believed link pose (fitted to the taxels), so the error's offset cancels.
  const Eigen::Isometry3d link_from_root =
      (taxels_.size() >= 3 ? fit_root_from_link(taxels_, taxels_root)
                           : Eigen::Isometry3d::Identity())
          .inverse();
  const Stimulus at_touch = perceived_at(touch_time_s);
  const Eigen::Vector3d resting_at_touch = touch->point_link + at_touch.radius * touch->normal_link;
  const Eigen::Vector3d path_at_touch = link_from_root * at_touch.position;
  const TaxelPose& taxel = taxels_[k].pose_link;
  const auto resting_at = [&](double t) {  // link frame
    const Stimulus seen = perceived_at(t);
    Stimulus resting = seen;
    resting.position = resting_at_touch + link_from_root * seen.position - path_at_touch;
    resting.velocity = link_from_root.linear() * seen.velocity;
    return to_taxel_frame(taxel, resting);
  };
  // Back along the path to where it was kOffsetClearance outside the taxel (buffered samples,
  // then linear between the last one out and the next).
  const auto& samples = buffer_.samples();
  double later_t = touch_time_s, later_h = resting_at(touch_time_s).p.z();
  double found_t = std::numeric_limits<double>::quiet_NaN();
  for (auto it = samples.rbegin(); it != samples.rend(); ++it) {
    if (it->time >= touch_time_s) continue;
    const double h = resting_at(it->time).p.z();
    if (h >= kOffsetClearance) {
      found_t = it->time + (later_t - it->time) * (h - kOffsetClearance) / (h - later_h);
      break;
    }
    later_t = it->time;
    later_h = h;
  }
  if (std::isnan(found_t)) return;  // the buffered path never was that far out
  const TaxelFrameStimulus on_skin = resting_at(found_t);
  record(k, perceived_at(found_t), compute_d_ttc(on_skin.p, on_skin.v, params_.ttc).d);
}

std::optional<double> BodyPartLearner::contact_offset(int k) const {
  const auto kk = static_cast<std::size_t>(k);
  return contact_.estimate(kk, params_.contact);
}

int BodyPartLearner::index_of(int id) const {
  for (std::size_t k = 0; k < taxels_.size(); ++k)
    if (taxels_[k].id == id) return static_cast<int>(k);
  return -1;
}

LearningStats BodyPartLearner::on_contact(const Eigen::Isometry3d& root_from_link,
                                          std::span<const int> touched_ids) {
  const Eigen::Matrix3d r = root_from_link.linear();
  const Eigen::Vector3d t = root_from_link.translation();
  for (std::size_t k = 0; k < taxels_.size(); ++k) {
    scratch_poses_[k].position = r * taxels_[k].pose_link.position + t;
    scratch_poses_[k].normal = r * taxels_[k].pose_link.normal;
  }
  return on_contact(std::span<const TaxelPose>(scratch_poses_), touched_ids);
}

LearningStats BodyPartLearner::on_contact(std::span<const TaxelPose> taxels_root,
                                          std::span<const int> touched_ids) {
  if (taxels_root.size() != taxels_.size())
    throw InputError("PPS learner '" + body_part_ + "': contact event gives " +
                     std::to_string(taxels_root.size()) + " taxel poses, expected " +
                     std::to_string(taxels_.size()) + " (one per taxel of the body part)");
  LearningStats st;
  st.buffered_samples = buffer_.size();
  std::fill(touched_.begin(), touched_.end(), std::uint8_t{0});
  for (const int id : touched_ids) {
    const int k = index_of(id);
    if (k >= 0 && !touched_[static_cast<std::size_t>(k)]) {
      touched_[static_cast<std::size_t>(k)] = 1;
      ++st.touched_taxels;
    }
  }
  const auto& samples = buffer_.samples();
  const GridSpec& grid = map_grid_;
  const TtcDefinition ttc_def = params_.ttc;
  const bool distance_only = params_.model == PpsModel::kDistanceOnly;
  if (!samples.empty()) {
    for (std::size_t k = 0; k < taxels_.size(); ++k) {
      const Eigen::Matrix3d rt = taxel_rotation(taxels_root[k].normal).transpose();
      const Eigen::Vector3d origin = taxels_root[k].position;
      const bool positive = touched_[k] != 0;
      TaxelMap& map = maps_[k];
      bool changed = false;
      for (const StimulusSample& s : samples) {
        Eigen::Vector3d p = rt * (s.stimulus.position - origin);
        p.z() -= s.stimulus.radius;
        if (!rf_.contains(p)) continue;
        ++st.in_rf;
        const Eigen::Vector3d v = rt * s.stimulus.velocity;
        DTtc dt = compute_d_ttc(p, v, ttc_def);
        if (distance_only) {  // D only: TTC neither needed nor binned
          dt.ttc = query_ttc_;
          dt.valid = true;
        }
        if (!dt.valid) {
          ++st.invalid_ttc;
          continue;
        }
        int i = 0, j = 0;
        if (!grid.bin_of(dt.d, dt.ttc, i, j)) {
          ++st.out_of_range;
          continue;
        }
        map.add_to_bin(grid.index(i, j), positive);
        changed = true;
        ++(positive ? st.positives : st.negatives);
        if (dt.d < 0.0) ++st.behind_skin;
      }
      if (changed) map.refresh();
    }
  }
  buffer_.clear();
  totals_.buffered_samples += st.buffered_samples;
  totals_.touched_taxels += st.touched_taxels;
  totals_.in_rf += st.in_rf;
  totals_.invalid_ttc += st.invalid_ttc;
  totals_.out_of_range += st.out_of_range;
  totals_.positives += st.positives;
  totals_.negatives += st.negatives;
  totals_.behind_skin += st.behind_skin;
  return st;
}

double BodyPartLearner::activation(int k, const TaxelPose& taxel_root, const Stimulus& s) const {
  const TaxelFrameStimulus ts = to_taxel_frame(taxel_root, s);
  if (!rf_.contains(ts.p)) return 0.0;
  const TaxelMap& map = maps_.at(static_cast<std::size_t>(k));
  if (params_.model == PpsModel::kDistanceOnly) {
    const double n = ts.p.norm();
    return map.activation(ts.p.z() < 0.0 ? -n : n, query_ttc_);
  }
  const DTtc dt = compute_d_ttc(ts.p, ts.v, params_.ttc);
  if (!dt.valid) return 0.0;
  return map.activation(dt.d, dt.ttc);
}

}  // namespace somasim::pps
