#include "somasim/pps/stimulus.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace somasim::pps {

Eigen::Matrix3d taxel_rotation(const Eigen::Vector3d& normal) {
  const Eigen::Vector3d z = normal.normalized();
  const Eigen::Vector3d a = z.cwiseAbs();
  Eigen::Vector3d ref = Eigen::Vector3d::UnitX();
  if (a.y() < a.x() && a.y() <= a.z())
    ref = Eigen::Vector3d::UnitY();
  else if (a.z() < a.x() && a.z() < a.y())
    ref = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d x = (ref - ref.dot(z) * z).normalized();
  Eigen::Matrix3d r;
  r.col(0) = x;
  r.col(1) = z.cross(x);
  r.col(2) = z;
  return r;
}

TaxelFrameStimulus to_taxel_frame(const TaxelPose& taxel, const Stimulus& s) {
  const Eigen::Matrix3d r = taxel_rotation(taxel.normal);
  TaxelFrameStimulus out;
  out.p = r.transpose() * (s.position - taxel.position);
  out.p.z() -= s.radius;
  out.v = r.transpose() * s.velocity;  // a direction: rotation only
  return out;
}

double time_since_outside(std::span<const TaxelPose> taxels, const Stimulus& s, double clearance,
                          double max_s) {
  double back = 0.0;
  for (const TaxelPose& taxel : taxels) {
    const TaxelFrameStimulus local = to_taxel_frame(taxel, s);
    if (local.p.z() < clearance && local.v.z() < 0.0)
      back = std::max(back, (clearance - local.p.z()) / -local.v.z());
  }
  return std::min(back, max_s);
}

int nearest_point(std::span<const Eigen::Vector3d> points, const Eigen::Vector3d& target) {
  int best = -1;
  double best_d2 = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double d2 = (points[i] - target).squaredNorm();
    if (best < 0 || d2 < best_d2) {
      best = static_cast<int>(i);
      best_d2 = d2;
    }
  }
  return best;
}

DTtc compute_d_ttc(const Eigen::Vector3d& p, const Eigen::Vector3d& v, TtcDefinition def) {
  DTtc out;
  const double n2 = p.squaredNorm();
  const double n = std::sqrt(n2);
  out.d = p.z() < 0.0 ? -n : n;
  if (def == TtcDefinition::kSigned) {
    const double pv = p.dot(v);
    if (pv < 0.0) {
      out.ttc = -n2 / pv;
      out.valid = true;
    }
  } else {
    const double speed = v.norm();
    if (speed > 0.0) {
      out.ttc = n / speed;
      out.valid = true;
    }
  }
  return out;
}

}  // namespace somasim::pps
