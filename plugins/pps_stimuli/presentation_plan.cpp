#include "presentation_plan.hpp"

#include "somasim/error.hpp"
#include "somasim/random_directions.hpp"

namespace somasim::plugins {

PlannedObject plan_presentation(PresentationMotion motion, const Eigen::Vector3d& taxel,
                                const Eigen::Vector3d& normal, const PresentationGeometry& g,
                                std::mt19937_64& rng,
                                const std::function<bool(const Eigen::Vector3d&)>& clear,
                                const std::string& part) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector3d target = taxel + g.size * normal;
  const bool receding = motion == PresentationMotion::kReceding;
  const double lo = receding ? g.receding_start_min : g.distance_min;
  const double hi = receding ? g.receding_start_max : g.distance_max;
  Eigen::Vector3d dir;
  double distance = 0.0;
  for (int attempt = 0;; ++attempt) {
    dir = sample_direction_in_cone(normal, g.cone_rad, rng);
    distance = lo + unit(rng) * (hi - lo);
    if (clear(target + distance * dir)) break;
    if (attempt == 100)
      throw RunError(std::string("no start point clear of the robot for a ") + motion_name(motion) +
                     " object aimed at '" + part + "' (raise '" +
                     (receding ? "receding_start_min" : "distance_min") + "' or lower 'cone_deg')");
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
