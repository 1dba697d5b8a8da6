#include "presentation_plan.hpp"

#include "somasim/random_directions.hpp"

namespace somasim::plugins {

std::optional<PlannedObject> plan_presentation(PresentationMotion motion,
                                               const Eigen::Vector3d& taxel,
                                               const Eigen::Vector3d& normal,
                                               const PresentationGeometry& g, std::mt19937_64& rng,
                                               const PathCheck& clear, int attempts) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector3d target = taxel + g.size * normal;
  const bool receding = motion == PresentationMotion::kReceding;
  const double lo = receding ? g.receding_start_min : g.distance_min;
  const double hi = receding ? g.receding_start_max : g.distance_max;
  Eigen::Vector3d dir;
  double distance = 0.0;
  for (int attempt = 0;; ++attempt) {
    if (attempt == attempts) return std::nullopt;
    dir = sample_direction_in_cone(normal, g.cone_rad, rng);
    distance = lo + unit(rng) * (hi - lo);
    const Eigen::Vector3d start = target + distance * dir;
    const Eigen::Vector3d end = motion == PresentationMotion::kApproach ? target
                                : receding ? start + g.distance_max * dir
                                           : start;
    if (clear(start, end)) break;
  }
  PlannedObject out;
  out.start = target + distance * dir;
  out.speed = g.speed_min + unit(rng) * (g.speed_max - g.speed_min);
  switch (motion) {
    case PresentationMotion::kApproach:
      out.velocity = -out.speed * dir;
      out.travel = distance / out.speed;
      out.lifetime = out.travel + g.linger;
      break;
    case PresentationMotion::kStatic:
      out.speed = 0.0;
      out.lifetime = g.static_duration;
      break;
    case PresentationMotion::kReceding:
      out.velocity = out.speed * dir;
      out.lifetime = g.distance_max / out.speed;
      break;
  }
  return out;
}

}  // namespace somasim::plugins
