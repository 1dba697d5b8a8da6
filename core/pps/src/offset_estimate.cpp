#include "somasim/pps/offset_estimate.hpp"

#include <cmath>

#include <Eigen/Eigenvalues>

namespace somasim::pps {

std::optional<RegressionLine> fit_activation_line(const TaxelMap& map, const OffsetOptions& opt) {
  const GridSpec& g = map.grid();
  if (opt.n_d < 2 || opt.n_ttc < 2) return std::nullopt;
  double sw = 0, sx = 0, sy = 0;
  double sxx = 0, sxy = 0, syy = 0;
  for (int a = 0; a < opt.n_d; ++a) {
    const double x = static_cast<double>(a) / (opt.n_d - 1);
    const double d = a + 1 == opt.n_d ? g.d_max : g.d_min + x * (g.d_max - g.d_min);
    for (int b = 0; b < opt.n_ttc; ++b) {
      const double y = static_cast<double>(b) / (opt.n_ttc - 1);
      const double t = b + 1 == opt.n_ttc ? g.ttc_max : g.ttc_min + y * (g.ttc_max - g.ttc_min);
      const double w = map.activation(d, t);
      if (w <= 0.0 || w < opt.min_activation) continue;
      sw += w;
      sx += w * x;
      sy += w * y;
      sxx += w * x * x;
      sxy += w * x * y;
      syy += w * y * y;
    }
  }
  if (!(sw > 0.0)) return std::nullopt;
  const double mx = sx / sw, my = sy / sw;
  Eigen::Matrix2d c;
  c(0, 0) = sxx / sw - mx * mx;
  c(0, 1) = c(1, 0) = sxy / sw - mx * my;
  c(1, 1) = syy / sw - my * my;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(c);
  const Eigen::Vector2d ev = es.eigenvalues();  // ascending
  if (!(ev(1) > 0.0) || ev(1) - ev(0) <= 1e-9 * ev(1)) return std::nullopt;
  const Eigen::Vector2d dir = es.eigenvectors().col(1);
  RegressionLine line;
  line.centre = {g.d_min + mx * (g.d_max - g.d_min), g.ttc_min + my * (g.ttc_max - g.ttc_min)};
  line.direction = Eigen::Vector2d(dir.x() * (g.d_max - g.d_min), dir.y() * (g.ttc_max - g.ttc_min))
                       .normalized();
  return line;
}

std::optional<double> estimate_offset(const TaxelMap& map, const OffsetOptions& opt) {
  const auto line = fit_activation_line(map, opt);
  if (!line || std::abs(line->direction.y()) < 1e-9 * line->direction.norm()) return std::nullopt;
  // D where the line meets TTC = 0 (the same point in scaled or unscaled axes).
  return line->centre.x() - line->centre.y() * line->direction.x() / line->direction.y();
}

}  // namespace somasim::pps
