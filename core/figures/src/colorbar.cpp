#include "colorbar.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "axes.hpp"
#include "colormap_detail.hpp"

namespace somasim::figures::detail {

int colorbar_total_width(Range values, int bar_height, const std::string& label,
                         const Fonts& fonts) {
  const AxisTicks t = make_y_ticks(values, bar_height);
  int w = kColorbarGap + kColorbarWidth + kTickLen + 5 + max_label_width(t, fonts.tick());
  if (!label.empty()) w += kPad + label_height(fonts.label()) + 6;
  return w + kPad;
}

void draw_colorbar(Canvas& canvas, Rect bar, Colormap map, Range values, const std::string& label,
                   const Fonts& fonts) {
  const int bx = static_cast<int>(bar.x), by = static_cast<int>(bar.y);
  const int bw = static_cast<int>(bar.width), bh = static_cast<int>(bar.height);
  Image strip{bw, bh, std::vector<std::uint8_t>(static_cast<std::size_t>(bw) * bh * 3)};
  for (int r = 0; r < bh; ++r) {
    const Color c = level_color(map, quantise(1.0 - (r + 0.5) / bh));
    for (int x = 0; x < bw; ++x) {
      const std::size_t i = 3 * (static_cast<std::size_t>(r) * bw + x);
      strip.rgb[i] = c.r;
      strip.rgb[i + 1] = c.g;
      strip.rgb[i + 2] = c.b;
    }
  }
  canvas.image(strip, bx, by);
  AxesFrame f{bx, by, bw, bh, Range{0, 1}, values};
  const AxisTicks t = make_y_ticks(values, bh);
  canvas.frame_rect({bar.x - 1, bar.y - 1, bar.width + 2, bar.height + 2}, kBlack);
  const int right = bx + bw;
  int max_w = 0;
  for (std::size_t i = 0; i < t.values.size(); ++i) {
    const int y =
        std::clamp(static_cast<int>(std::floor(px(f, 0, t.values[i]).y)), by - 1, by + bh);
    canvas.pixel_line({right, y}, {right + kTickLen, y}, kBlack);
    canvas.text(t.labels[i], {right + kTickLen + 5.0, y + 0.5}, HAlign::kLeft, VAlign::kMiddle,
                fonts.tick(), kBlack);
    max_w =
        std::max(max_w, static_cast<int>(std::ceil(text_size(t.labels[i], fonts.tick()).width)));
  }
  if (!label.empty())
    canvas.text(label,
                {right + kTickLen + 5.0 + max_w + kPad + label_height(fonts.label()) / 2.0,
                 bar.y + bar.height / 2.0},
                HAlign::kCenter, VAlign::kMiddle, fonts.label(), kBlack, Weight::kNormal, true);
}

}  // namespace somasim::figures::detail
