#include "somasim/skin/skin_response.hpp"

#include <algorithm>
#include <cmath>

namespace somasim::skin {

PartResponse::PartResponse(const SkinLayout& layout, const ResponseParams& params)
    : layout_(layout),
      params_(params),
      pressure_(layout.size(), 0.0),
      over_(layout.size(), false),
      fired_(layout.size(), false) {
  scratch_.reserve(layout.size());
}

void PartResponse::clear() {
  std::fill(pressure_.begin(), pressure_.end(), 0.0);
}

int PartResponse::add_contact(const Eigen::Vector3d& point_link, double normal_force) {
  const double r2 = params_.contact_radius * params_.contact_radius;
  scratch_.clear();
  for (std::size_t i = 0; i < layout_.size(); ++i)
    if ((layout_.positions[i] - point_link).squaredNorm() <= r2)
      scratch_.push_back(static_cast<int>(i));
  if (scratch_.empty() || !(normal_force > 0)) return static_cast<int>(scratch_.size());
  if (params_.model == PressureModel::kShared) {
    const double share = normal_force / static_cast<double>(scratch_.size());
    for (int i : scratch_) pressure_[static_cast<std::size_t>(i)] += share;
  } else {
    const double sigma = 0.5 * params_.contact_radius;
    const double k = -0.5 / (sigma * sigma);
    for (int i : scratch_) {
      const double d2 = (layout_.positions[static_cast<std::size_t>(i)] - point_link).squaredNorm();
      pressure_[static_cast<std::size_t>(i)] += normal_force * std::exp(k * d2);
    }
  }
  return static_cast<int>(scratch_.size());
}

std::optional<TouchOnset> PartResponse::update(double now_s) {
  int count = 0;
  for (std::size_t i = 0; i < pressure_.size(); ++i) {
    over_[i] = pressure_[i] > params_.pressure_threshold;
    count += over_[i] ? 1 : 0;
  }
  if (count > 0) last_active_s_ = now_s;
  if (in_episode_ && count == 0 && now_s - last_active_s_ >= params_.release_s - 1e-12)
    in_episode_ = false;
  std::optional<TouchOnset> onset;
  if (!in_episode_ && count > params_.min_taxels) {
    in_episode_ = true;
    TouchOnset t;
    t.physical_count = count;
    std::vector<bool> touched(layout_.virtual_taxels.size(), false);
    Eigen::Vector3d weighted_position = Eigen::Vector3d::Zero();
    Eigen::Vector3d weighted_normal = Eigen::Vector3d::Zero();
    double total = 0.0;
    for (std::size_t i = 0; i < over_.size(); ++i) {
      if (!over_[i]) continue;
      touched[static_cast<std::size_t>(layout_.module[i])] = true;
      weighted_position += pressure_[i] * layout_.positions[i];
      weighted_normal += pressure_[i] * layout_.normals[i];
      total += pressure_[i];
    }
    t.centre_link = weighted_position / total;  // total > threshold * count > 0
    if (weighted_normal.norm() > 1e-12) t.normal_link = weighted_normal.normalized();
    for (std::size_t v = 0; v < touched.size(); ++v)
      if (touched[v]) t.virtual_ids.push_back(layout_.virtual_taxels[v].id);
    std::sort(t.virtual_ids.begin(), t.virtual_ids.end());
    onset = std::move(t);
  }
  if (in_episode_)
    for (std::size_t i = 0; i < over_.size(); ++i)
      if (over_[i]) fired_[i] = true;
  return onset;
}

double PartResponse::virtual_pressure(std::size_t v) const {
  double peak = 0.0;
  for (int i : layout_.virtual_taxels[v].members)
    peak = std::max(peak, pressure_[static_cast<std::size_t>(i)]);
  return peak;
}

}  // namespace somasim::skin
