#pragma once
/// @file
/// From contact points to taxel pressures and contact events of one skin part.
///
/// Pressure model (per contact point, normal force F [N], taxels within `contact_radius` of the
/// point, distance d):
///   - shared: each of the n taxels in the radius gets F / n (the force shared evenly);
///   - kernel: each gets F · exp(-d² / (2 σ²)), σ = contact_radius / 2.
/// Pressures of several contact points add up. "Pressure" is thus a force per taxel [N].
///
/// Contact events (as in Roncone et al. 2016, Learning peripersonal space representation through
/// artificial skin for avoidance and reaching with whole body surface): a part is touched when more
/// than `min_taxels` physical taxels are over `pressure_threshold`. One event per contact episode:
/// it fires at the first touched update, and the episode lasts until no taxel of the part has been
/// over threshold for `release_s` (so a persistent or bouncing contact does not fire again).
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "somasim/name_table.hpp"
#include "somasim/skin/skin_layout.hpp"

namespace somasim::skin {

enum class PressureModel { kShared, kKernel };
inline constexpr NamedValue<PressureModel> kPressureModelNames[] = {
    {PressureModel::kShared, "shared"}, {PressureModel::kKernel, "kernel"}};
/// "shared", "kernel".
constexpr std::span<const NamedValue<PressureModel>> name_table(PressureModel) {
  return kPressureModelNames;
}

struct ResponseParams {
  double contact_radius = 0.01;  ///< taxels within this distance of a contact respond [m]
  PressureModel model = PressureModel::kShared;
  double pressure_threshold = 0.01;  ///< [N per taxel]
  int min_taxels = 2;                ///< an event needs MORE than this many taxels over threshold
  double release_s = 0.1;            ///< quiet time that ends an episode [s]
};

/// Onset of a contact episode on a part.
struct TouchOnset {
  std::vector<int> virtual_ids;  ///< virtual taxels with a member over threshold (ascending)
  int physical_count = 0;        ///< physical taxels over threshold
  /// Centre of pressure [m, link frame]: the pressure-weighted mean position of the physical
  /// taxels over threshold (what the robot's skin can tell about where it was touched).
  Eigen::Vector3d centre_link = Eigen::Vector3d::Zero();
  /// Pressure-weighted mean outward normal of those taxels (unit, link frame).
  Eigen::Vector3d normal_link = Eigen::Vector3d::UnitZ();
};

/// Pressures and episode state of one part. Usage per update: clear(); add_contact() for each
/// contact point on the part; then update(now).
class PartResponse {
 public:
  PartResponse(const SkinLayout& layout, const ResponseParams& params);

  void clear();
  /// Adds the pressure of a contact at `point_link` [m, link frame] with normal force [N].
  /// Returns the number of taxels in the radius.
  int add_contact(const Eigen::Vector3d& point_link, double normal_force);
  /// Evaluates thresholds at time `now_s`; returns the onset when a new episode starts.
  std::optional<TouchOnset> update(double now_s);

  const std::vector<double>& pressures() const { return pressure_; }  ///< per physical taxel
  /// Peak member pressure of virtual taxel `v` (index into layout.virtual_taxels).
  double virtual_pressure(std::size_t v) const;
  /// Taxels over threshold at the last update.
  const std::vector<bool>& over_threshold() const { return over_; }
  bool in_episode() const { return in_episode_; }
  /// Physical taxels that were over threshold at any time during an episode (figures, metrics).
  const std::vector<bool>& fired() const { return fired_; }

 private:
  const SkinLayout& layout_;
  ResponseParams params_;
  std::vector<double> pressure_;
  std::vector<bool> over_, fired_;
  std::vector<int> scratch_;
  bool in_episode_ = false;
  double last_active_s_ = 0.0;
};

}  // namespace somasim::skin
