// Composition of figures into one image.
#include "somasim/figures/compose.hpp"

#include <algorithm>

#include "axes.hpp"
#include "canvas.hpp"
#include "somasim/error.hpp"

namespace somasim::figures {
namespace {
using namespace detail;

Figure compose(const std::vector<Figure>& panels, int gap, const std::string& title,
               double font_scale, bool row) {
  const char* what = row ? "compose_row" : "compose_column";
  if (panels.empty()) throw InputError(std::string(what) + ": no figures to compose");
  if (gap < 0) throw InputError(std::string(what) + ": gap_px is negative");
  int w = 0, h = 0;
  for (std::size_t i = 0; i < panels.size(); ++i) {
    const Image& im = panels[i].image;
    if (im.width <= 0 || im.height <= 0 ||
        im.rgb.size() != static_cast<std::size_t>(im.width) * im.height * 3)
      throw InputError(std::string(what) + ": figure " + std::to_string(i) + " has an empty image");
    if (row) {
      w += im.width + (i ? gap : 0);
      h = std::max(h, im.height);
    } else {
      h += im.height + (i ? gap : 0);
      w = std::max(w, im.width);
    }
  }
  const Fonts fonts{font_scale};
  const int top = title.empty() ? 0 : title_height(title, fonts);
  Canvas canvas(w, h + top);
  std::vector<AxesFrame> axes;
  int x = 0, y = top;
  for (const auto& p : panels) {
    canvas.figure(p, x, y);
    for (AxesFrame f : p.axes) {
      f.left += x;
      f.top += y;
      axes.push_back(f);
    }
    if (row)
      x += p.image.width + gap;
    else
      y += p.image.height + gap;
  }
  draw_title(canvas, title, fonts);
  return canvas.finish(std::move(axes));
}

}  // namespace

Figure compose_row(const std::vector<Figure>& panels, int gap_px, const std::string& title,
                   double font_scale) {
  return compose(panels, gap_px, title, font_scale, true);
}

Figure compose_column(const std::vector<Figure>& panels, int gap_px, const std::string& title,
                      double font_scale) {
  return compose(panels, gap_px, title, font_scale, false);
}

}  // namespace somasim::figures
