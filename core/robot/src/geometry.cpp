#include "somasim/robot/geometry.hpp"

#include <cmath>

namespace somasim::robot {

std::string_view geometry_type_name(GeometryType type) {
  switch (type) {
    case GeometryType::Sphere:
      return "sphere";
    case GeometryType::Box:
      return "box";
    case GeometryType::Cylinder:
      return "cylinder";
    case GeometryType::Capsule:
      return "capsule";
    case GeometryType::Mesh:
      return "mesh";
  }
  return "?";
}

double volume(const Geometry& g) {
  const double r = g.radius;
  switch (g.type) {
    case GeometryType::Sphere:
      return 4.0 / 3.0 * M_PI * r * r * r;
    case GeometryType::Box:
      return g.size.prod();
    case GeometryType::Cylinder:
      return M_PI * r * r * g.length;
    case GeometryType::Capsule:
      return M_PI * r * r * g.length + 4.0 / 3.0 * M_PI * r * r * r;
    case GeometryType::Mesh:
      return 0.0;
  }
  return 0.0;
}

namespace {

// Inertia of one shape about its own centre, in the shape frame.
Eigen::Matrix3d shape_inertia(const Geometry& g, double mass) {
  const double r2 = g.radius * g.radius;
  const double h = g.length;
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  switch (g.type) {
    case GeometryType::Sphere:
      d.setConstant(0.4 * mass * r2);
      break;
    case GeometryType::Box: {
      const Eigen::Vector3d s2 = g.size.cwiseProduct(g.size);
      d = mass / 12.0 * Eigen::Vector3d(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y());
      break;
    }
    case GeometryType::Cylinder:
      d.x() = d.y() = mass * (3.0 * r2 + h * h) / 12.0;
      d.z() = 0.5 * mass * r2;
      break;
    case GeometryType::Capsule: {
      // Cylinder plus two hemispheres (each: com 3r/8 from its flat face, 83/320 m r² about it).
      const double vc = M_PI * r2 * h;
      const double vs = 4.0 / 3.0 * M_PI * r2 * g.radius;
      const double mc = mass * vc / (vc + vs);
      const double mh = 0.5 * (mass - mc);
      const double arm = 0.5 * h + 3.0 / 8.0 * g.radius;
      d.x() = d.y() = mc * (3.0 * r2 + h * h) / 12.0 + 2.0 * mh * (83.0 / 320.0 * r2 + arm * arm);
      d.z() = 0.5 * mc * r2 + 2.0 * 0.4 * mh * r2;
      break;
    }
    case GeometryType::Mesh:
      break;
  }
  return d.asDiagonal();
}

}  // namespace

Inertial inertial_from_geometry(const std::vector<Geometry>& shapes, double density) {
  Inertial out;
  for (const auto& g : shapes) {
    const double m = density * volume(g);
    if (m <= 0) continue;
    out.com += m * g.origin.translation();
    out.mass += m;
  }
  if (out.mass <= 0) return Inertial{};
  out.com /= out.mass;
  for (const auto& g : shapes) {
    const double m = density * volume(g);
    if (m <= 0) continue;
    const Eigen::Matrix3d R = g.origin.linear();
    const Eigen::Vector3d p = g.origin.translation() - out.com;
    // Parallel-axis theorem: I + m (|p|² I − p pᵀ).
    out.inertia += R * shape_inertia(g, m) * R.transpose() +
                   m * (p.squaredNorm() * Eigen::Matrix3d::Identity() - p * p.transpose());
  }
  return out;
}

}  // namespace somasim::robot
