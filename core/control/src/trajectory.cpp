#include "somasim/control/trajectory.hpp"

#include <algorithm>

#include "somasim/diagnostics.hpp"
#include "somasim/error.hpp"

namespace somasim::control {

Profile parse_profile(const std::string& name) {
  if (const auto profile = parse_enum<Profile>(name)) return *profile;
  throw InputError("unknown trajectory profile '" + name +
                   "'; expected 'linear' or 'minimum_jerk'" +
                   did_you_mean(name, enum_names<Profile>()));
}

ProfileSample sample_profile(Profile profile, double tau) {
  tau = std::clamp(tau, 0.0, 1.0);
  if (profile == Profile::kLinear) return {tau, 1.0};
  const double t2 = tau * tau, t3 = t2 * tau;
  return {t3 * (10.0 - 15.0 * tau + 6.0 * t2), 30.0 * t2 * (1.0 - 2.0 * tau + t2)};
}

JointTrajectory::JointTrajectory(Profile profile, double t0, Eigen::VectorXd start,
                                 std::vector<Waypoint> waypoints)
    : profile_(profile), t0_(t0), start_(std::move(start)), waypoints_(std::move(waypoints)) {
  double t = t0_;
  for (std::size_t i = 0; i < waypoints_.size(); ++i) {
    const Waypoint& w = waypoints_[i];
    if (w.position.size() != start_.size())
      throw InputError("trajectory waypoint " + std::to_string(i) + ": expected " +
                       std::to_string(start_.size()) + " joint values, got " +
                       std::to_string(w.position.size()));
    if (!(w.duration_s > 0.0))
      throw InputError("trajectory waypoint " + std::to_string(i) +
                       ": expected a positive duration, got " + std::to_string(w.duration_s));
    t += w.duration_s;
    end_times_.push_back(t);
  }
}

int JointTrajectory::segment_at(double t) const {
  const auto it = std::upper_bound(end_times_.begin(), end_times_.end(), t);
  return static_cast<int>(it - end_times_.begin());
}

void JointTrajectory::sample(double t, Eigen::Ref<Eigen::VectorXd> position,
                             Eigen::Ref<Eigen::VectorXd> velocity) const {
  SOMASIM_CHECK(position.size() == start_.size() && velocity.size() == start_.size(),
                "trajectory sample size");
  if (t < t0_ || waypoints_.empty()) {
    position = t < t0_ || waypoints_.empty() ? start_ : final_position();
    velocity.setZero();
    return;
  }
  const int k = segment_at(t);
  if (k >= num_waypoints()) {
    position = final_position();
    velocity.setZero();
    return;
  }
  const Eigen::VectorXd& from = k == 0 ? start_ : waypoints_[k - 1].position;
  const Waypoint& to = waypoints_[k];
  const double begin = end_times_[k] - to.duration_s;
  const ProfileSample p = sample_profile(profile_, (t - begin) / to.duration_s);
  position = from + p.s * (to.position - from);
  velocity = (p.ds / to.duration_s) * (to.position - from);
}

}  // namespace somasim::control
