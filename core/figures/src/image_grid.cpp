// A grid of images with column titles and row labels.
#include "somasim/figures/image_grid.hpp"

#include <fmt/format.h>

#include "axes.hpp"
#include "canvas.hpp"
#include "somasim/error.hpp"

namespace somasim::figures {

Figure render_image_grid(const ImageGridSpec& s) {
  using namespace detail;
  if (s.rows.empty() || s.rows.front().empty())
    throw InputError("image grid: no images; expected at least one row with one image");
  const int w = s.rows.front().front().width, h = s.rows.front().front().height;
  std::size_t cols = 0;
  for (std::size_t r = 0; r < s.rows.size(); ++r) {
    cols = std::max(cols, s.rows[r].size());
    for (std::size_t c = 0; c < s.rows[r].size(); ++c) {
      const Image& im = s.rows[r][c];
      if (im.width != w || im.height != h || w <= 0 || h <= 0 ||
          im.rgb.size() != static_cast<std::size_t>(w) * h * 3)
        throw InputError(
            fmt::format("image grid: image ({}, {}) is {} x {} px; expected every image {} x {} px",
                        r, c, im.width, im.height, w, h));
    }
  }
  if (s.gap_px < 0) throw InputError("image grid: gap_px is negative");
  const Fonts fonts{s.font_scale};
  const int gap = s.gap_px;
  const int top = s.title.empty() ? 0 : title_height(s.title, fonts) - gap;
  const int header = s.column_titles.empty() ? 0 : label_height(fonts.tick()) + 4;
  const int width = static_cast<int>(cols) * (w + gap) + gap;
  const int height = top + header + static_cast<int>(s.rows.size()) * (h + gap) + gap;
  Canvas canvas(width, height);
  draw_title(canvas, s.title, fonts);
  for (std::size_t c = 0; c < cols && c < s.column_titles.size(); ++c)
    canvas.text(s.column_titles[c], {gap + static_cast<double>(c) * (w + gap) + 2, top + 2.0},
                HAlign::kLeft, VAlign::kTop, fonts.tick(), kBlack);
  for (std::size_t r = 0; r < s.rows.size(); ++r) {
    const int y = top + header + gap + static_cast<int>(r) * (h + gap);
    for (std::size_t c = 0; c < s.rows[r].size(); ++c)
      canvas.image(s.rows[r][c], gap + static_cast<int>(c) * (w + gap), y);
    if (r < s.row_labels.size() && !s.row_labels[r].empty()) {
      // White on a translucent dark box: readable on any image.
      const TextSize t = text_size(s.row_labels[r], fonts.tick());
      canvas.fill_rect(
          {static_cast<double>(gap), static_cast<double>(y), t.width + 8, t.height + 4}, kBlack,
          0.55);
      canvas.text(s.row_labels[r], {gap + 4.0, y + 2.0}, HAlign::kLeft, VAlign::kTop, fonts.tick(),
                  kWhite);
    }
  }
  return canvas.finish({});
}

}  // namespace somasim::figures
