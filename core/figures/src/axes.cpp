#include "axes.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "somasim/error.hpp"
#include "somasim/figures/ticks.hpp"

namespace somasim::figures::detail {
namespace {

AxisTicks make_ticks(Range r, int max_ticks) {
  AxisTicks t;
  t.step = nice_step(r.lo, r.hi, max_ticks);
  t.values = nice_ticks(r.lo, r.hi, max_ticks);
  for (double v : t.values) t.labels.push_back(format_tick(v, t.step));
  return t;
}

}  // namespace

AxisTicks make_x_ticks(Range r, int length_px) {
  return make_ticks(r, std::clamp(length_px / 75 + 1, 3, 10));
}
AxisTicks make_y_ticks(Range r, int length_px) {
  return make_ticks(r, std::clamp(length_px / 40 + 1, 3, 9));
}

int max_label_width(const AxisTicks& t, double scale) {
  int w = 0;
  for (const auto& s : t.labels) w = std::max(w, text_size(s, scale).width);
  return w;
}

int label_height(double scale) {
  return text_size("0", scale).height;
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

void draw_grid(cv::Mat& img, const AxesFrame& f, const AxisTicks& xt, const AxisTicks& yt) {
  const cv::Scalar c = bgr(kGridGrey);
  for (double v : xt.values) {
    const int x = static_cast<int>(std::floor(px(f, v, f.y.lo).x));
    if (x > f.left && x < f.left + f.width - 1)
      cv::line(img, {x, f.top}, {x, f.top + f.height - 1}, c, 1);
  }
  for (double v : yt.values) {
    const int y = static_cast<int>(std::floor(px(f, f.x.lo, v).y));
    if (y > f.top && y < f.top + f.height - 1)
      cv::line(img, {f.left, y}, {f.left + f.width - 1, y}, c, 1);
  }
}

void draw_axes(cv::Mat& img, const AxesFrame& f, const AxisTicks& xt, const AxisTicks& yt,
               const AxesText& text, const Fonts& fonts) {
  const cv::Scalar black = bgr(kBlack);
  const int l = f.left - 1, r = f.left + f.width, t = f.top - 1, b = f.top + f.height;
  cv::rectangle(img, {l, t}, {r, b}, black, 1);
  const int th = label_height(fonts.tick());
  for (std::size_t i = 0; i < xt.values.size(); ++i) {
    const int x = std::clamp(static_cast<int>(std::floor(px(f, xt.values[i], f.y.lo).x)), l, r);
    cv::line(img, {x, b}, {x, b + kTickLen}, black, 1);
    if (text.x_tick_labels)
      put_text(img, xt.labels[i], {x + 0.5, b + kTickLen + 6.0}, HAlign::kCenter, VAlign::kTop,
               fonts.tick(), kBlack);
  }
  for (std::size_t i = 0; i < yt.values.size(); ++i) {
    const int y = std::clamp(static_cast<int>(std::floor(px(f, f.x.lo, yt.values[i]).y)), t, b);
    cv::line(img, {l - kTickLen, y}, {l, y}, black, 1);
    put_text(img, yt.labels[i], {l - kTickLen - 5.0, y + 0.5}, HAlign::kRight, VAlign::kMiddle,
             fonts.tick(), kBlack);
  }
  if (!text.x_label.empty() && text.x_tick_labels)
    put_text(img, text.x_label, {f.left + f.width / 2.0, b + kTickLen + 6.0 + th + 12.0},
             HAlign::kCenter, VAlign::kTop, fonts.label(), kBlack);
  if (!text.y_label.empty())
    put_text(img, text.y_label, {text.y_label_center_x, f.top + f.height / 2.0}, HAlign::kCenter,
             VAlign::kMiddle, fonts.label(), kBlack, 1, /*vertical=*/true);
}

int title_height(const std::string& title, const Fonts& fonts) {
  if (title.empty()) return 14;
  return 14 + text_size(title, fonts.title(), 2).height + 18;
}

int draw_title(cv::Mat& img, const std::string& title, const Fonts& fonts) {
  if (!title.empty()) {
    // Shrink a title too long for the figure rather than clipping it.
    double scale = fonts.title();
    const int w = text_size(title, scale, 2).width;
    if (w > img.cols - 2 * kPad) scale *= static_cast<double>(img.cols - 2 * kPad) / w;
    put_text(img, title, {img.cols / 2.0, 14.0}, HAlign::kCenter, VAlign::kTop, scale, kBlack, 2);
  }
  return title_height(title, fonts);
}

}  // namespace somasim::figures::detail

namespace somasim::figures::detail {

int left_margin(const AxisTicks& yt, bool has_y_label, const Fonts& fonts) {
  int m = kPad + max_label_width(yt, fonts.tick()) + 5 + kTickLen + 1;
  if (has_y_label) m += label_height(fonts.label()) + 6 + kPad;
  return m;
}

int bottom_margin(bool has_x_tick_labels, bool has_x_label, const Fonts& fonts) {
  int m = 1 + kTickLen;
  if (has_x_tick_labels) m += 6 + label_height(fonts.tick()) + 6;
  if (has_x_label && has_x_tick_labels) m += 6 + label_height(fonts.label()) * 3 / 2;
  return m + kPad;
}

double y_label_center(const Fonts& fonts) {
  return kPad + 3 + label_height(fonts.label()) / 2.0;
}

}  // namespace somasim::figures::detail
