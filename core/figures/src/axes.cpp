#include "axes.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "somasim/error.hpp"
#include "somasim/figures/ticks.hpp"

namespace somasim::figures::detail {
namespace {

AxisTicks make_ticks(Range r, int max_ticks) {
  AxisTicks t;
  t.step = nice_step(r.lo, r.hi, max_ticks);
  t.values = nice_ticks(r.lo, r.hi, max_ticks);
  for (double v : t.values) {
    // Typeset negative numbers with a minus sign, not a hyphen.
    std::string label = format_tick(v, t.step);
    if (!label.empty() && label[0] == '-') label.replace(0, 1, "\u2212");
    t.labels.push_back(std::move(label));
  }
  return t;
}

}  // namespace

AxisTicks make_x_ticks(Range r, int length_px) {
  return make_ticks(r, std::clamp(length_px / 75 + 1, 3, 10));
}
AxisTicks make_y_ticks(Range r, int length_px) {
  return make_ticks(r, std::clamp(length_px / 40 + 1, 3, 9));
}

int max_label_width(const AxisTicks& t, double size_px) {
  double w = 0;
  for (const auto& s : t.labels) w = std::max(w, text_size(s, size_px).width);
  return static_cast<int>(std::ceil(w));
}

int label_height(double size_px) {
  return static_cast<int>(std::ceil(text_size("0", size_px).height));
}

Range padded_range(double lo, double hi, double pad_frac) {
  if (!(lo <= hi)) return {0.0, 1.0};
  if (hi - lo <= 1e-12 * std::max(1.0, std::fabs(lo))) {
    const double half = lo == 0 ? 1.0 : 0.1 * std::fabs(lo);
    return {lo - half, hi + half};
  }
  const double pad = (hi - lo) * pad_frac;
  return {lo - pad, hi + pad};
}

void check_range(const char* what, const char* axis, Range r) {
  if (!std::isfinite(r.lo) || !std::isfinite(r.hi) || !(r.lo < r.hi)) {
    std::ostringstream os;
    os << what << ": " << axis << " range [" << r.lo << ", " << r.hi
       << "] is invalid; expected finite lo < hi";
    throw InputError(os.str());
  }
}

void draw_grid(Canvas& canvas, const AxesFrame& f, const AxisTicks& xt, const AxisTicks& yt) {
  for (double v : xt.values) {
    const int x = static_cast<int>(std::floor(px(f, v, f.y.lo).x));
    if (x > f.left && x < f.left + f.width - 1)
      canvas.pixel_line({x, f.top}, {x, f.top + f.height - 1}, kGridGrey);
  }
  for (double v : yt.values) {
    const int y = static_cast<int>(std::floor(px(f, f.x.lo, v).y));
    if (y > f.top && y < f.top + f.height - 1)
      canvas.pixel_line({f.left, y}, {f.left + f.width - 1, y}, kGridGrey);
  }
}

void draw_axes(Canvas& canvas, const AxesFrame& f, const AxisTicks& xt, const AxisTicks& yt,
               const AxesText& text, const Fonts& fonts) {
  const int l = f.left - 1, r = f.left + f.width, t = f.top - 1, b = f.top + f.height;
  canvas.frame_rect({static_cast<double>(l), static_cast<double>(t), r - l + 1.0, b - t + 1.0},
                    kBlack);
  const int th = label_height(fonts.tick());
  for (std::size_t i = 0; i < xt.values.size(); ++i) {
    const int x = std::clamp(static_cast<int>(std::floor(px(f, xt.values[i], f.y.lo).x)), l, r);
    canvas.pixel_line({x, b}, {x, b + kTickLen}, kBlack);
    if (text.x_tick_labels)
      canvas.text(xt.labels[i], {x + 0.5, b + kTickLen + 4.0}, HAlign::kCenter, VAlign::kTop,
                  fonts.tick(), kBlack);
  }
  for (std::size_t i = 0; i < yt.values.size(); ++i) {
    const int y = std::clamp(static_cast<int>(std::floor(px(f, f.x.lo, yt.values[i]).y)), t, b);
    canvas.pixel_line({l - kTickLen, y}, {l, y}, kBlack);
    canvas.text(yt.labels[i], {l - kTickLen - 5.0, y + 0.5}, HAlign::kRight, VAlign::kMiddle,
                fonts.tick(), kBlack);
  }
  if (!text.x_label.empty() && text.x_tick_labels)
    canvas.text(text.x_label, {f.left + f.width / 2.0, b + kTickLen + 4.0 + th + 6.0},
                HAlign::kCenter, VAlign::kTop, fonts.label(), kBlack);
  if (!text.y_label.empty())
    canvas.text(text.y_label, {text.y_label_center_x, f.top + f.height / 2.0}, HAlign::kCenter,
                VAlign::kMiddle, fonts.label(), kBlack, Weight::kNormal, /*vertical=*/true);
}

void densify(Point a, Point b, int max_points, std::vector<Point>& out) {
  if (!std::isfinite(a.x) || !std::isfinite(a.y)) return;
  const int n = static_cast<int>(
      std::min(static_cast<double>(max_points), std::hypot(b.x - a.x, b.y - a.y) / 10));
  for (int k = 1; k < n; ++k) {
    const double t = static_cast<double>(k) / n;
    out.push_back({a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t});
  }
}

bool any_inside(const AxesFrame& f, const std::vector<Point>& points, std::size_t first) {
  for (std::size_t i = first; i < points.size(); ++i) {
    const Point& p = points[i];
    if (p.x >= f.left && p.x <= f.left + f.width && p.y >= f.top && p.y <= f.top + f.height)
      return true;
  }
  return false;
}

int title_height(const std::string& title, const Fonts& fonts) {
  if (title.empty()) return 14;
  return 10 + static_cast<int>(std::ceil(text_size(title, fonts.title(), Weight::kBold).height)) +
         12;
}

int draw_title(Canvas& canvas, const std::string& title, const Fonts& fonts) {
  if (!title.empty()) {
    // Shrink a title too long for the figure rather than clipping it.
    double size = fonts.title();
    const double w = text_size(title, size, Weight::kBold).width;
    if (w > canvas.width() - 2 * kPad) size *= (canvas.width() - 2 * kPad) / w;
    canvas.text(title, {canvas.width() / 2.0, 10.0}, HAlign::kCenter, VAlign::kTop, size, kBlack,
                Weight::kBold);
  }
  return title_height(title, fonts);
}

}  // namespace somasim::figures::detail

namespace somasim::figures::detail {

int left_margin(const AxisTicks& yt, bool has_y_label, const Fonts& fonts) {
  int m = kPad + max_label_width(yt, fonts.tick()) + 5 + kTickLen + 1;
  if (has_y_label) m += label_height(fonts.label()) + 6;
  return m;
}

int bottom_margin(bool has_x_tick_labels, bool has_x_label, const Fonts& fonts) {
  int m = 1 + kTickLen;
  if (has_x_tick_labels) m += 4 + label_height(fonts.tick());
  if (has_x_label && has_x_tick_labels) m += 6 + label_height(fonts.label());
  return m + kPad;
}

double y_label_center(const Fonts& fonts) {
  return kPad + label_height(fonts.label()) / 2.0;
}

}  // namespace somasim::figures::detail
