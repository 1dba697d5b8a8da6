#include "somasim/control/link_clearance.hpp"

#include <algorithm>
#include <cmath>

namespace somasim::control {

std::vector<LinkCapsule> link_capsules(const robot::RobotModel& model, int link) {
  std::vector<LinkCapsule> out;
  const auto& shapes = model.link(link).collision;
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    const robot::Geometry& g = shapes[i];
    LinkCapsule c;
    c.link = link;
    c.shape = static_cast<int>(i);
    Eigen::Vector3d half = Eigen::Vector3d::Zero();  // half segment, shape frame
    switch (g.type) {
      case robot::GeometryType::Sphere:
        c.radius = g.radius;
        break;
      case robot::GeometryType::Cylinder:  // same length, rounded rims
        c.radius = g.radius;
        half = Eigen::Vector3d(0, 0, std::max(0.0, 0.5 * g.length - g.radius));
        break;
      case robot::GeometryType::Capsule:
        c.radius = g.radius;
        half = Eigen::Vector3d(0, 0, 0.5 * g.length);
        break;
      case robot::GeometryType::Box: {
        int longest = 0;
        g.size.maxCoeff(&longest);
        const int i1 = (longest + 1) % 3, i2 = (longest + 2) % 3;
        c.radius = 0.5 * std::hypot(g.size[i1], g.size[i2]);
        half[longest] = 0.5 * g.size[longest];
        break;
      }
      case robot::GeometryType::Mesh:
        continue;
    }
    c.a = g.origin * (-half);
    c.b = g.origin * half;
    out.push_back(c);
  }
  return out;
}

double segment_distance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                        const Eigen::Vector3d& q0, const Eigen::Vector3d& q1) {
  // Closest points of two segments (Ericson, Real-Time Collision Detection, 5.1.9).
  const Eigen::Vector3d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  constexpr double kEps = 1e-15;
  double s = 0.0, t = 0.0;
  if (a <= kEps && e <= kEps) return r.norm();
  if (a <= kEps) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= kEps) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > kEps ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return ((p0 + s * d1) - (q0 + t * d2)).norm();
}

LinkClearance::LinkClearance(const robot::RobotModel& model, const std::vector<int>& group_a,
                             const std::vector<int>& group_b, std::vector<Ignored> ignored)
    : ignored_(std::move(ignored)) {
  for (int l : group_a)
    for (const auto& c : link_capsules(model, l)) a_.push_back(c);
  for (int l : group_b)
    for (const auto& c : link_capsules(model, l)) b_.push_back(c);
}

ClearanceResult LinkClearance::check(const std::vector<Eigen::Isometry3d>& link_poses) const {
  ClearanceResult best;
  for (const auto& ca : a_) {
    const Eigen::Isometry3d& ta = link_poses[static_cast<std::size_t>(ca.link)];
    const Eigen::Vector3d a0 = ta * ca.a, a1 = ta * ca.b;
    for (const auto& cb : b_) {
      const bool skip = std::any_of(ignored_.begin(), ignored_.end(), [&](const Ignored& i) {
        return i.link_a == ca.link && (i.shape_a < 0 || i.shape_a == ca.shape) &&
               i.link_b == cb.link;
      });
      if (skip) continue;
      const Eigen::Isometry3d& tb = link_poses[static_cast<std::size_t>(cb.link)];
      const double d = segment_distance(a0, a1, tb * cb.a, tb * cb.b) - ca.radius - cb.radius;
      if (d < best.distance) best = {d, ca.link, cb.link, ca.shape, cb.shape};
    }
  }
  return best;
}

}  // namespace somasim::control
