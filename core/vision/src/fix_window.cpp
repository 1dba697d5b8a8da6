#include "somasim/vision/fix_window.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "somasim/error.hpp"

namespace somasim::vision {

FixWindow::FixWindow(int capacity) : capacity_(capacity) {
  if (capacity < 2)
    throw InputError(fmt::format("a fix window holds at least 2 fixes, got {}", capacity));
}

void FixWindow::add(double time_s, const Eigen::Vector3d& position_m, double radius_m) {
  if (!fixes_.empty() && time_s < fixes_.back().time_s)
    throw std::logic_error("FixWindow::add: fixes must come in time order");
  fixes_.push_back({time_s, {position_m.x(), position_m.y(), position_m.z(), radius_m}});
  if (size() > capacity_) fixes_.pop_front();
}

Eigen::Vector4d FixWindow::slope() const {
  if (fixes_.size() < 2) return Eigen::Vector4d::Zero();
  double mean_t = 0.0;
  Eigen::Vector4d mean = Eigen::Vector4d::Zero();
  for (const Fix& f : fixes_) {
    mean_t += f.time_s;
    mean += f.position_radius;
  }
  mean_t /= static_cast<double>(fixes_.size());
  mean /= static_cast<double>(fixes_.size());
  double var_t = 0.0;
  Eigen::Vector4d cov = Eigen::Vector4d::Zero();
  for (const Fix& f : fixes_) {
    const double dt = f.time_s - mean_t;
    var_t += dt * dt;
    cov += dt * (f.position_radius - mean);
  }
  return var_t > 0.0 ? Eigen::Vector4d(cov / var_t) : Eigen::Vector4d::Zero();
}

Eigen::Vector3d FixWindow::velocity() const {
  return slope().head<3>();
}

double FixWindow::radius_rate() const {
  double mean_radius = 0.0;
  for (const Fix& f : fixes_) mean_radius += f.position_radius.w();
  if (fixes_.empty() || mean_radius <= 0.0) return 0.0;
  mean_radius /= static_cast<double>(fixes_.size());
  return std::abs(slope().w()) / mean_radius;
}

}  // namespace somasim::vision
