#include "somasim/vision/fix_window.hpp"

#include <stdexcept>

#include <fmt/format.h>

#include "somasim/error.hpp"

namespace somasim::vision {

FixWindow::FixWindow(int capacity) : capacity_(capacity) {
  if (capacity < 2)
    throw InputError(fmt::format("a fix window holds at least 2 fixes, got {}", capacity));
}

void FixWindow::add(double time_s, const Eigen::Vector3d& position_m) {
  if (!fixes_.empty() && time_s < fixes_.back().time_s)
    throw std::logic_error("FixWindow::add: fixes must come in time order");
  fixes_.push_back({time_s, position_m});
  if (size() > capacity_) fixes_.pop_front();
}

Eigen::Vector3d FixWindow::velocity() const {
  if (fixes_.size() < 2) return Eigen::Vector3d::Zero();
  double mean_t = 0.0;
  Eigen::Vector3d mean_p = Eigen::Vector3d::Zero();
  for (const Fix& f : fixes_) {
    mean_t += f.time_s;
    mean_p += f.position_m;
  }
  mean_t /= static_cast<double>(fixes_.size());
  mean_p /= static_cast<double>(fixes_.size());
  double var_t = 0.0;
  Eigen::Vector3d cov = Eigen::Vector3d::Zero();
  for (const Fix& f : fixes_) {
    const double dt = f.time_s - mean_t;
    var_t += dt * dt;
    cov += dt * (f.position_m - mean_p);
  }
  return var_t > 0.0 ? Eigen::Vector3d(cov / var_t) : Eigen::Vector3d::Zero();
}

}  // namespace somasim::vision
