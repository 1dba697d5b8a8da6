// Colour maps: OpenCV look-up tables, applied to values quantised to 256 levels.
#include "somasim/figures/colormap.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "colormap_detail.hpp"

namespace somasim::figures {
namespace detail {

std::uint8_t quantise(double t) {
  if (!(t > 0)) return 0;  // also NaN (callers handle NaN before)
  if (t >= 1) return 255;
  return static_cast<std::uint8_t>(std::lround(t * 255.0));
}

cv::Mat apply_colormap(const cv::Mat& levels, Colormap map) {
  cv::Mat out;
  if (map == Colormap::kGray) {
    cv::cvtColor(levels, out, cv::COLOR_GRAY2BGR);
    return out;
  }
  int cv_map = cv::COLORMAP_VIRIDIS;
  switch (map) {
    case Colormap::kViridis:
      cv_map = cv::COLORMAP_VIRIDIS;
      break;
    case Colormap::kPlasma:
      cv_map = cv::COLORMAP_PLASMA;
      break;
    case Colormap::kInferno:
      cv_map = cv::COLORMAP_INFERNO;
      break;
    case Colormap::kMagma:
      cv_map = cv::COLORMAP_MAGMA;
      break;
    case Colormap::kCividis:
      cv_map = cv::COLORMAP_CIVIDIS;
      break;
    case Colormap::kTurbo:
      cv_map = cv::COLORMAP_TURBO;
      break;
    case Colormap::kJet:
      cv_map = cv::COLORMAP_JET;
      break;
    case Colormap::kGray:
      break;
  }
  cv::applyColorMap(levels, out, cv_map);
  return out;
}

}  // namespace detail

Color colormap_color(Colormap map, double t) {
  cv::Mat level(1, 1, CV_8UC1, cv::Scalar(detail::quantise(t)));
  const cv::Vec3b c = detail::apply_colormap(level, map).at<cv::Vec3b>(0, 0);
  return Color{c[2], c[1], c[0]};
}

}  // namespace somasim::figures
