#include "legend.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "axes.hpp"

namespace somasim::figures::detail {

void draw_legend(Canvas& canvas, const AxesFrame& f, const std::vector<LegendEntry>& all,
                 LegendPosition pos, const Fonts& fonts, const std::vector<Point>& data_px) {
  std::vector<LegendEntry> entries;
  for (const auto& e : all)
    if (!e.label.empty()) entries.push_back(e);
  if (entries.empty() || pos == LegendPosition::kNone) return;

  const double size = fonts.legend();
  const int lh = label_height(size);
  const int row_h = std::max(lh + 4, 20);
  const int sample_w = 34, pad = 8, inset = 8;
  int text_w = 0;
  for (const auto& e : entries)
    text_w = std::max(text_w, static_cast<int>(std::ceil(text_size(e.label, size).width)));
  const int box_w = pad + sample_w + 8 + text_w + pad;
  const int box_h = pad / 2 + row_h * static_cast<int>(entries.size()) + pad / 2;

  const std::array<LegendPosition, 4> corners = {
      LegendPosition::kTopRight, LegendPosition::kTopLeft, LegendPosition::kBottomRight,
      LegendPosition::kBottomLeft};
  auto rect_at = [&](LegendPosition p) {
    const bool right = p == LegendPosition::kTopRight || p == LegendPosition::kBottomRight;
    const bool top = p == LegendPosition::kTopRight || p == LegendPosition::kTopLeft;
    const int x = right ? f.left + f.width - inset - box_w : f.left + inset;
    const int y = top ? f.top + inset : f.top + f.height - inset - box_h;
    return Rect{static_cast<double>(x), static_cast<double>(y), static_cast<double>(box_w),
                static_cast<double>(box_h)};
  };
  if (pos == LegendPosition::kBest) {
    pos = LegendPosition::kTopRight;
    std::size_t best = static_cast<std::size_t>(-1);
    for (auto c : corners) {
      const Rect r = rect_at(c);
      std::size_t n = 0;
      for (const auto& p : data_px)
        if (std::isfinite(p.x) && std::isfinite(p.y) && r.contains(p)) ++n;
      if (n < best) {
        best = n;
        pos = c;
      }
    }
  }
  const Rect box = rect_at(pos);
  canvas.fill_rect(box, kWhite, 0.85);
  canvas.frame_rect(box, Color{160, 160, 160});
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const auto& e = entries[i];
    const double cy = box.y + pad / 2.0 + row_h * (static_cast<double>(i) + 0.5);
    const double x0 = box.x + pad, x1 = x0 + sample_w;
    if (e.line) {
      if (e.halo)
        canvas.polyline({{x0, cy}, {x1, cy}}, kWhite, e.width_px + 2.5, LineStyle::kSolid);
      canvas.polyline({{x0, cy}, {x1, cy}}, e.color, e.width_px, e.style);
    }
    if (e.marker) canvas.marker({(x0 + x1) / 2, cy}, *e.marker, e.marker_px, e.color, e.halo);
    canvas.text(e.label, {x1 + 8, cy}, HAlign::kLeft, VAlign::kMiddle, size, kBlack);
  }
}

}  // namespace somasim::figures::detail
