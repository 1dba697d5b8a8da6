#include "canvas.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "somasim/error.hpp"

namespace somasim::figures::detail {
namespace {
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr int kShift = 4;  // sub-pixel bits for cv drawing
constexpr double kOne = 1 << kShift;

cv::Point fixed(cv::Point2d p) {
  return cv::Point(static_cast<int>(std::lround(p.x * kOne)),
                   static_cast<int>(std::lround(p.y * kOne)));
}
bool finite(cv::Point2d p) {
  return std::isfinite(p.x) && std::isfinite(p.y);
}

void segment(cv::Mat& img, cv::Point2d a, cv::Point2d b, Color c, double w) {
  // Pixel centres are at integer + 0.5 in our convention and at integers in OpenCV's.
  cv::line(img, fixed(a - cv::Point2d(0.5, 0.5)), fixed(b - cv::Point2d(0.5, 0.5)), bgr(c),
           std::max(1, static_cast<int>(std::lround(w))), cv::LINE_AA, kShift);
}
}  // namespace

cv::Size text_size(const std::string& text, double scale, int thickness) {
  int baseline = 0;
  return cv::getTextSize(text, kFont, scale, thickness, &baseline);
}

void put_text(cv::Mat& img, const std::string& text, cv::Point2d anchor, HAlign h, VAlign v,
              double scale, Color color, int thickness, bool vertical) {
  if (text.empty()) return;
  int baseline = 0;
  const cv::Size sz = cv::getTextSize(text, kFont, scale, thickness, &baseline);
  const int pad = 2 + thickness;
  cv::Mat mask = cv::Mat::zeros(sz.height + baseline + 2 * pad, sz.width + 2 * pad, CV_8UC1);
  cv::putText(mask, text, cv::Point(pad, pad + sz.height), kFont, scale, cv::Scalar(255), thickness,
              cv::LINE_AA);
  // Alignment box (cap height) inside the mask, before rotation.
  double box_w = sz.width, box_h = sz.height, off_x = pad, off_y = pad;
  if (vertical) {
    cv::rotate(mask, mask, cv::ROTATE_90_COUNTERCLOCKWISE);
    // After rotation the cap box spans columns [pad, pad + h) and rows [pad, pad + w).
    off_x = pad;
    off_y = pad;
    std::swap(box_w, box_h);
  }
  double x0 = anchor.x, y0 = anchor.y;
  if (h == HAlign::kCenter) x0 -= box_w / 2;
  if (h == HAlign::kRight) x0 -= box_w;
  if (v == VAlign::kMiddle) y0 -= box_h / 2;
  if (v == VAlign::kBottom) y0 -= box_h;
  const int ox = static_cast<int>(std::lround(x0 - off_x));
  const int oy = static_cast<int>(std::lround(y0 - off_y));
  for (int r = 0; r < mask.rows; ++r) {
    const int y = oy + r;
    if (y < 0 || y >= img.rows) continue;
    const auto* m = mask.ptr<std::uint8_t>(r);
    auto* p = img.ptr<cv::Vec3b>(y);
    for (int c = 0; c < mask.cols; ++c) {
      const int x = ox + c;
      if (x < 0 || x >= img.cols || m[c] == 0) continue;
      const double a = m[c] / 255.0;
      cv::Vec3b& px = p[x];
      px[0] = static_cast<std::uint8_t>(std::lround(px[0] * (1 - a) + color.b * a));
      px[1] = static_cast<std::uint8_t>(std::lround(px[1] * (1 - a) + color.g * a));
      px[2] = static_cast<std::uint8_t>(std::lround(px[2] * (1 - a) + color.r * a));
    }
  }
}

void draw_polyline(cv::Mat& img, const std::vector<cv::Point2d>& pts, Color color, double width_px,
                   LineStyle style) {
  // Round caps add about half the width at each dash end: lengthen the gaps accordingly.
  const double w = std::max(2.0, width_px);
  const double on = style == LineStyle::kDashed ? 3.5 * w : 0.5;
  const double off = style == LineStyle::kDashed ? 3.0 * w + width_px + 1 : 2.0 * w + width_px;
  double phase = 0;  // distance travelled along the current dash cycle
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const cv::Point2d a = pts[i - 1], b = pts[i];
    if (!finite(a) || !finite(b)) {
      phase = 0;
      continue;
    }
    if (style == LineStyle::kSolid) {
      segment(img, a, b, color, width_px);
      continue;
    }
    const double len = cv::norm(b - a);
    if (len == 0) continue;
    const cv::Point2d dir = (b - a) / len;
    double t = 0;
    while (t < len) {
      const double cycle = on + off;
      const double in_cycle = std::fmod(phase, cycle);
      if (in_cycle < on) {
        const double run = std::min(on - in_cycle, len - t);
        if (style == LineStyle::kDotted) {
          cv::circle(img, fixed(a + dir * t - cv::Point2d(0.5, 0.5)),
                     static_cast<int>(std::lround(std::max(1.0, width_px / 2) * kOne)), bgr(color),
                     cv::FILLED, cv::LINE_AA, kShift);
          const double skip = on + off - in_cycle;
          t += skip;
          phase += skip;
          continue;
        }
        segment(img, a + dir * t, a + dir * (t + run), color, width_px);
        t += run;
        phase += run;
      } else {
        const double run = std::min(cycle - in_cycle, len - t);
        t += run;
        phase += run;
      }
    }
  }
}

void draw_marker(cv::Mat& img, cv::Point2d p, Marker marker, double size_px, Color color,
                 bool outline) {
  if (!finite(p)) return;
  const cv::Point2d c = p - cv::Point2d(0.5, 0.5);
  const double r = size_px / 2;
  const cv::Scalar col = bgr(color);
  auto poly = [&](const std::vector<cv::Point2d>& v) {
    std::vector<cv::Point> q;
    for (auto& x : v) q.push_back(fixed(c + x));
    if (outline) cv::polylines(img, q, true, bgr(kWhite), 3, cv::LINE_AA, kShift);
    cv::fillConvexPoly(img, q, col, cv::LINE_AA, kShift);
  };
  switch (marker) {
    case Marker::kCircle:
      if (outline)
        cv::circle(img, fixed(c), static_cast<int>(std::lround((r + 1) * kOne)), bgr(kWhite),
                   cv::FILLED, cv::LINE_AA, kShift);
      cv::circle(img, fixed(c), static_cast<int>(std::lround(r * kOne)), col, cv::FILLED,
                 cv::LINE_AA, kShift);
      break;
    case Marker::kSquare:
      poly({{-r, -r}, {r, -r}, {r, r}, {-r, r}});
      break;
    case Marker::kTriangle:
      poly({{0, -r * 1.15}, {r * 1.1, r * 0.75}, {-r * 1.1, r * 0.75}});
      break;
    case Marker::kDiamond:
      poly({{0, -r * 1.2}, {r, 0}, {0, r * 1.2}, {-r, 0}});
      break;
    case Marker::kCross:
    case Marker::kPlus: {
      const double k = marker == Marker::kCross ? r * 0.75 : r;
      const std::array<cv::Point2d, 4> ends =
          marker == Marker::kCross
              ? std::array<cv::Point2d, 4>{cv::Point2d{-k, -k}, {k, k}, {-k, k}, {k, -k}}
              : std::array<cv::Point2d, 4>{cv::Point2d{-k, 0}, {k, 0}, {0, -k}, {0, k}};
      const int w = std::max(2, static_cast<int>(std::lround(size_px / 4)));
      for (int i = 0; i < 4; i += 2) {
        if (outline)
          cv::line(img, fixed(c + ends[i]), fixed(c + ends[i + 1]), bgr(kWhite), w + 2, cv::LINE_AA,
                   kShift);
      }
      for (int i = 0; i < 4; i += 2)
        cv::line(img, fixed(c + ends[i]), fixed(c + ends[i + 1]), col, w, cv::LINE_AA, kShift);
      break;
    }
  }
}

void blend_rect(cv::Mat& img, cv::Rect r, Color color, double alpha) {
  r &= cv::Rect(0, 0, img.cols, img.rows);
  if (r.empty()) return;
  cv::Mat roi = img(r);
  cv::Mat fill(roi.size(), roi.type(), bgr(color));
  cv::addWeighted(fill, alpha, roi, 1 - alpha, 0, roi);
}

Image to_image(const cv::Mat& m) {
  Image out;
  out.width = m.cols;
  out.height = m.rows;
  out.rgb.resize(static_cast<std::size_t>(m.cols) * m.rows * 3);
  for (int y = 0; y < m.rows; ++y) {
    const auto* p = m.ptr<cv::Vec3b>(y);
    for (int x = 0; x < m.cols; ++x) {
      const std::size_t i = 3 * (static_cast<std::size_t>(y) * m.cols + x);
      out.rgb[i] = p[x][2];
      out.rgb[i + 1] = p[x][1];
      out.rgb[i + 2] = p[x][0];
    }
  }
  return out;
}

cv::Mat to_mat(const Image& image) {
  cv::Mat m(image.height, image.width, CV_8UC3);
  for (int y = 0; y < image.height; ++y) {
    auto* p = m.ptr<cv::Vec3b>(y);
    for (int x = 0; x < image.width; ++x) {
      const Color c = image.at(x, y);
      p[x] = cv::Vec3b(c.b, c.g, c.r);
    }
  }
  return m;
}

void check_figure_size(const char* what, int width, int height) {
  if (width < 200 || height < 150) {
    std::ostringstream os;
    os << what << ": figure size " << width << " x " << height
       << " px is too small; expected at least 200 x 150";
    throw InputError(os.str());
  }
}

}  // namespace somasim::figures::detail
