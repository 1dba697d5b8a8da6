// Colour maps: OpenCV's look-up tables, applied to values quantised to 256 levels.
#include "somasim/figures/colormap.hpp"

#include <array>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "colormap_detail.hpp"

namespace somasim::figures {
namespace detail {
namespace {

using Table = std::array<Color, 256>;

int opencv_map(Colormap map) {
  switch (map) {
    case Colormap::kPlasma:
      return cv::COLORMAP_PLASMA;
    case Colormap::kInferno:
      return cv::COLORMAP_INFERNO;
    case Colormap::kMagma:
      return cv::COLORMAP_MAGMA;
    case Colormap::kCividis:
      return cv::COLORMAP_CIVIDIS;
    case Colormap::kTurbo:
      return cv::COLORMAP_TURBO;
    case Colormap::kJet:
      return cv::COLORMAP_JET;
    case Colormap::kViridis:
    case Colormap::kGray:
      break;
  }
  return cv::COLORMAP_VIRIDIS;
}

Table make_table(Colormap map) {
  cv::Mat levels(1, 256, CV_8UC1);
  for (int i = 0; i < 256; ++i) levels.at<std::uint8_t>(0, i) = static_cast<std::uint8_t>(i);
  cv::Mat bgr;
  if (map == Colormap::kGray)
    cv::cvtColor(levels, bgr, cv::COLOR_GRAY2BGR);
  else
    cv::applyColorMap(levels, bgr, opencv_map(map));
  Table t;
  for (int i = 0; i < 256; ++i) {
    const cv::Vec3b c = bgr.at<cv::Vec3b>(0, i);
    t[static_cast<std::size_t>(i)] = Color{c[2], c[1], c[0]};
  }
  return t;
}

const Table& table(Colormap map) {
  static const std::array<Table, 8> kTables = {
      make_table(Colormap::kViridis), make_table(Colormap::kPlasma),
      make_table(Colormap::kInferno), make_table(Colormap::kMagma),
      make_table(Colormap::kCividis), make_table(Colormap::kTurbo),
      make_table(Colormap::kJet),     make_table(Colormap::kGray)};
  return kTables[static_cast<std::size_t>(map)];
}

}  // namespace

std::uint8_t quantise(double t) {
  if (!(t > 0)) return 0;  // also NaN (callers handle NaN before)
  if (t >= 1) return 255;
  return static_cast<std::uint8_t>(std::lround(t * 255.0));
}

Color level_color(Colormap map, std::uint8_t level) {
  return table(map)[level];
}

}  // namespace detail

Color colormap_color(Colormap map, double t) {
  return detail::level_color(map, detail::quantise(t));
}

}  // namespace somasim::figures
