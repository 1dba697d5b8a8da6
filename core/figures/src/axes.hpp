#pragma once
// Private: axes layout (margins from text sizes), ticks, frame, grid and axis labels.
#include <optional>
#include <string>
#include <vector>

#include "canvas.hpp"
#include "somasim/figures/figure.hpp"

namespace somasim::figures::detail {

inline constexpr int kTickLen = 5;  // [px] outward tick marks
inline constexpr int kPad = 10;     // [px] outer padding / gaps between text blocks

struct AxisTicks {
  std::vector<double> values;
  double step = 1;
  std::vector<std::string> labels;
};

/// Nice ticks for an axis `length_px` long (denser on longer axes).
AxisTicks make_x_ticks(Range r, int length_px);
AxisTicks make_y_ticks(Range r, int length_px);

/// Widest label, label height [px] at font size `size_px`.
int max_label_width(const AxisTicks& t, double size_px);
int label_height(double size_px);

/// [lo, hi] padded by `pad_frac` of the span; a degenerate or missing extent gets a sensible
/// range. lo/hi are the finite data extent (lo > hi means no data).
Range padded_range(double lo, double hi, double pad_frac);

/// Throws InputError "<what>: <axis> range [lo, hi] is invalid; expected finite lo < hi".
void check_range(const char* what, const char* axis, Range r);

/// Light grid lines at the ticks (inside the plot area only).
void draw_grid(Canvas& canvas, const AxesFrame& f, const AxisTicks& xt, const AxisTicks& yt);

/// What draw_axes writes around the plot area.
struct AxesText {
  std::string x_label;  ///< empty: none
  std::string y_label;  ///< empty: none
  bool x_tick_labels = true;
  double y_label_center_x = 0;  ///< column of the (vertical) y label's centre
};

/// Black frame, outward ticks, tick labels and axis labels.
void draw_axes(Canvas& canvas, const AxesFrame& f, const AxisTicks& xt, const AxisTicks& yt,
               const AxesText& text, const Fonts& fonts);

/// Centred title at the top of the figure; returns the row below it.
int draw_title(Canvas& canvas, const std::string& title, const Fonts& fonts);
/// Height the title occupies (0 margin rows when empty; includes padding).
int title_height(const std::string& title, const Fonts& fonts);

/// Pixel position of a data point.
inline Point px(const AxesFrame& f, double x, double y) {
  const auto p = f.to_pixel(x, y);
  return {p[0], p[1]};
}

/// Appends points every ~10 px strictly between a and b (at most max_points - 1; none when a is
/// not finite), so that legend placement (kBest) sees whole segments, not only their ends.
void densify(Point a, Point b, int max_points, std::vector<Point>& out);

/// Whether any of points[first...] lies in the plot area (edges included).
bool any_inside(const AxesFrame& f, const std::vector<Point>& points, std::size_t first = 0);

/// The plot area.
inline Rect plot_rect(const AxesFrame& f) {
  return {static_cast<double>(f.left), static_cast<double>(f.top), static_cast<double>(f.width),
          static_cast<double>(f.height)};
}

}  // namespace somasim::figures::detail

namespace somasim::figures::detail {

/// Margin widths [px] around the plot area for the given texts.
int left_margin(const AxisTicks& yt, bool has_y_label, const Fonts& fonts);
int bottom_margin(bool has_x_tick_labels, bool has_x_label, const Fonts& fonts);
/// Column of the vertical y label's centre.
double y_label_center(const Fonts& fonts);

}  // namespace somasim::figures::detail
