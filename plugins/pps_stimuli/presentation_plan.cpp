#include "presentation_plan.hpp"

#include <stdexcept>

#include <Eigen/Eigenvalues>

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

Eigen::Vector3d part_long_axis(const std::vector<Eigen::Vector3d>& taxel_positions) {
  if (taxel_positions.size() < 2) return Eigen::Vector3d::Zero();
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : taxel_positions) mean += p;
  mean /= static_cast<double>(taxel_positions.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& p : taxel_positions) scatter += (p - mean) * (p - mean).transpose();
  if (scatter.trace() <= 0.0) return Eigen::Vector3d::Zero();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
  return solver.eigenvectors().col(2).normalized();  // eigenvalues ascend
}

namespace {

// A unit axis across the normal `n`, laid as `mode` says relative to `long_axis`.
Eigen::Vector3d cylinder_axis_across(const Eigen::Vector3d& n, CylinderAxis mode,
                                     const Eigen::Vector3d& long_axis) {
  // A long axis within ~6 deg of the normal says nothing about the plane across it.
  constexpr double kMinSine = 0.1;
  if (mode != CylinderAxis::kAny) {
    const Eigen::Vector3d along = long_axis - long_axis.dot(n) * n;
    if (along.norm() > kMinSine)
      return mode == CylinderAxis::kAlongPart ? along.normalized() : n.cross(along).normalized();
  }
  return n.unitOrthogonal();
}

}  // namespace

PresentedBody presented_body(ObjectShape shape, bool corner, const Eigen::Vector3d& n, double size,
                             double cylinder_half_height, CylinderAxis axis_mode,
                             const Eigen::Vector3d& long_axis) {
  PresentedBody b;
  if (shape == ObjectShape::kCylinder) {
    // The axis (local z) across the normal: the round side faces the taxel.
    const Eigen::Vector3d axis = cylinder_axis_across(n, axis_mode, long_axis);
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
