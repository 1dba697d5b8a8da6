// Scatter plots with categories.
#include "somasim/figures/scatter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "axes.hpp"
#include "canvas.hpp"
#include "legend.hpp"
#include "somasim/error.hpp"

namespace somasim::figures {
namespace {
using namespace detail;

void validate(const ScatterSpec& s) {
  for (const auto& g : s.groups) {
    std::ostringstream os;
    if (g.x.size() != g.y.size()) {
      os << "scatter: group '" << g.label << "' has " << g.x.size() << " x values but "
         << g.y.size() << " y values";
      throw InputError(os.str());
    }
    if (!g.annotations.empty() && g.annotations.size() != g.x.size()) {
      os << "scatter: group '" << g.label << "' has " << g.annotations.size() << " annotations but "
         << g.x.size() << " points";
      throw InputError(os.str());
    }
  }
  if (s.x_range) check_range("scatter", "x", *s.x_range);
  if (s.y_range) check_range("scatter", "y", *s.y_range);
  check_figure_size("scatter", s.width, s.height);
}

Range extent(const ScatterSpec& s, bool along_x) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& g : s.groups)
    for (std::size_t i = 0; i < g.x.size(); ++i)
      if (std::isfinite(g.x[i]) && std::isfinite(g.y[i])) {
        const double v = along_x ? g.x[i] : g.y[i];
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
  return padded_range(lo, hi, 0.05);
}

/// Widens the range with fewer data units per pixel so both axes have the same scale.
void equalise(Range& xr, Range& yr, int w, int h) {
  const double ux = (xr.hi - xr.lo) / w, uy = (yr.hi - yr.lo) / h;
  if (ux < uy) {
    const double half = uy * w / 2, mid = (xr.lo + xr.hi) / 2;
    xr = {mid - half, mid + half};
  } else {
    const double half = ux * h / 2, mid = (yr.lo + yr.hi) / 2;
    yr = {mid - half, mid + half};
  }
}

}  // namespace

std::vector<ScatterGroup> group_by_category(const std::vector<double>& x,
                                            const std::vector<double>& y,
                                            const std::vector<int>& category,
                                            const std::vector<std::string>& labels) {
  if (x.size() != y.size() || x.size() != category.size()) {
    std::ostringstream os;
    os << "scatter: group_by_category got " << x.size() << " x, " << y.size() << " y and "
       << category.size() << " category values; expected equal sizes";
    throw InputError(os.str());
  }
  std::map<int, ScatterGroup> groups;
  for (std::size_t i = 0; i < x.size(); ++i) {
    auto& g = groups[category[i]];
    g.x.push_back(x[i]);
    g.y.push_back(y[i]);
  }
  std::vector<ScatterGroup> out;
  std::size_t k = 0;
  for (auto& [cat, g] : groups) {
    g.label = k < labels.size() ? labels[k] : std::to_string(cat);
    out.push_back(std::move(g));
    ++k;
  }
  return out;
}

Figure render_scatter(const ScatterSpec& s) {
  validate(s);
  const Fonts fonts{s.font_scale};
  Range xr = s.x_range.value_or(extent(s, true));
  Range yr = s.y_range.value_or(extent(s, false));

  const int top = title_height(s.title, fonts);
  const int bottom = bottom_margin(true, !s.x_label.empty(), fonts);
  const int plot_h = s.height - top - bottom;
  AxisTicks yt, xt;
  int left = 0, plot_w = 0;
  for (int pass = 0; pass < 2; ++pass) {
    yt = make_y_ticks(yr, plot_h);
    left = left_margin(yt, !s.y_label.empty(), fonts);
    plot_w = s.width - left - 3 * kPad;
    if (plot_w < 50 || plot_h < 50)
      throw InputError("scatter: figure " + std::to_string(s.width) + " x " +
                       std::to_string(s.height) + " px leaves no room for the plot; enlarge it");
    if (s.equal_aspect) equalise(xr, yr, plot_w, plot_h);
  }
  yt = make_y_ticks(yr, plot_h);
  xt = make_x_ticks(xr, plot_w);
  const AxesFrame f{left, top, plot_w, plot_h, xr, yr};

  Canvas canvas(s.width, s.height);
  if (s.grid) draw_grid(canvas, f, xt, yt);
  canvas.push_clip(plot_rect(f));
  std::vector<LegendEntry> legend;
  std::vector<Point> data_px;
  std::size_t next = 0;
  for (const auto& g : s.groups) {
    const Color c = g.color.value_or(palette()[next++ % palette().size()]);
    const std::size_t first = data_px.size();
    for (std::size_t i = 0; i < g.x.size(); ++i) {
      const Point q = px(f, g.x[i], g.y[i]);
      canvas.marker(q, g.marker, g.size_px, c);
      data_px.push_back(q);
    }
    // Only what can be seen gets a legend entry.
    if (any_inside(f, data_px, first))
      legend.push_back({g.label, c, false, LineStyle::kSolid, 0, g.marker, g.size_px});
  }
  for (const auto& g : s.groups)
    for (std::size_t i = 0; i < g.annotations.size(); ++i) {
      const Point q = px(f, g.x[i], g.y[i]);
      canvas.text(g.annotations[i], {q.x + g.size_px / 2 + 2, q.y - g.size_px / 2 + 2},
                  HAlign::kLeft, VAlign::kBottom, fonts.tick() * 0.8, kDarkGrey);
    }
  canvas.pop_clip();
  draw_axes(canvas, f, xt, yt, AxesText{s.x_label, s.y_label, true, y_label_center(fonts)}, fonts);
  draw_legend(canvas, f, legend, s.legend, fonts, data_px);
  draw_title(canvas, s.title, fonts);
  return canvas.finish({f});
}

}  // namespace somasim::figures
