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

PresentedBody presented_body(ObjectShape shape, bool corner, const Eigen::Vector3d& n, double size,
                             double cylinder_half_height) {
  PresentedBody b;
  if (shape == ObjectShape::kCylinder) {
    // The axis (local z) across the normal: the round side faces the taxel.
    const Eigen::Vector3d axis = n.unitOrthogonal();
    b.rotation.col(0) = n;
    b.rotation.col(1) = axis.cross(n);
    b.rotation.col(2) = axis;
    b.size = Eigen::Vector3d(size, cylinder_half_height, 0);
  } else if (corner) {
    // The cube's corner (+1, +1, +1)·size points at the taxel.
    b.rotation = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::Ones().normalized(), -n)
                     .toRotationMatrix();
    b.size = Eigen::Vector3d::Constant(size);
  } else {
    // A cube's face (its local +z) faces the taxel.
    b.rotation = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), n).toRotationMatrix();
    b.size = shape == ObjectShape::kSphere ? Eigen::Vector3d(size, 0, 0)
                                           : Eigen::Vector3d::Constant(size);
  }
  return b;
}

const char* shape_name(ObjectShape shape) {
  switch (shape) {
    case ObjectShape::kBox:
      return "box";
    case ObjectShape::kCylinder:
      return "cylinder";
    case ObjectShape::kMesh:
      return "mesh";
    default:
      return "sphere";
  }
}

}  // namespace somasim::plugins
