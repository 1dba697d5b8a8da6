#pragma once
// Private drawing primitives of somasim_figures (OpenCV lives only in core/figures/src).
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "somasim/figures/figure.hpp"

namespace somasim::figures::detail {

inline cv::Scalar bgr(Color c) {
  return cv::Scalar(c.b, c.g, c.r);
}
inline constexpr Color kBlack{0, 0, 0};
inline constexpr Color kWhite{255, 255, 255};
inline constexpr Color kGridGrey{225, 225, 225};
inline constexpr Color kDarkGrey{70, 70, 70};

/// Text sizes: Hershey simplex scale for ~12-17 px glyphs, times the spec's font_scale.
struct Fonts {
  double scale = 1.0;
  double tick() const { return 0.55 * scale; }
  double label() const { return 0.65 * scale; }
  double title() const { return 0.75 * scale; }
  double legend() const { return 0.55 * scale; }
};

enum class HAlign { kLeft, kCenter, kRight };
enum class VAlign { kTop, kMiddle, kBottom };

/// Size {width, height} of the box used to align `text` (cap height; descenders hang below).
cv::Size text_size(const std::string& text, double scale, int thickness = 1);

/// Draws anti-aliased text aligned at `anchor`; vertical = rotated 90 degrees counter-clockwise
/// (reads bottom to top; the box is then height x width).
void put_text(cv::Mat& img, const std::string& text, cv::Point2d anchor, HAlign h, VAlign v,
              double scale, Color color, int thickness = 1, bool vertical = false);

/// Anti-aliased polyline through pixel points (NaN breaks it), with dash pattern.
void draw_polyline(cv::Mat& img, const std::vector<cv::Point2d>& pts, Color color, double width_px,
                   LineStyle style);

/// Marker of diameter size_px centred at p (white outline for contrast when `outline`).
void draw_marker(cv::Mat& img, cv::Point2d p, Marker marker, double size_px, Color color,
                 bool outline = false);

/// Blends `color` over the rectangle with opacity alpha.
void blend_rect(cv::Mat& img, cv::Rect r, Color color, double alpha);

/// Converts a BGR 8UC3 Mat to an Image and back.
Image to_image(const cv::Mat& bgr_mat);
cv::Mat to_mat(const Image& image);

/// Throws InputError "<what>: figure size W x H px is too small; expected at least 200 x 150".
void check_figure_size(const char* what, int width, int height);

}  // namespace somasim::figures::detail
