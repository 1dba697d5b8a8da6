// Line plots and stacked panels sharing the x axis.
#include "somasim/figures/line_plot.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "axes.hpp"
#include "canvas.hpp"
#include "legend.hpp"
#include "somasim/error.hpp"

namespace somasim::figures {
namespace {
using namespace detail;

constexpr double kInf = std::numeric_limits<double>::infinity();

void validate_panel(const char* what, const LinePlotSpec& p) {
  for (const auto& s : p.series)
    if (s.x.size() != s.y.size()) {
      std::ostringstream os;
      os << what << ": series '" << s.label << "' has " << s.x.size() << " x values but "
         << s.y.size() << " y values";
      throw InputError(os.str());
    }
  if (p.y_range) check_range(what, "y", *p.y_range);
}

void extend(double v, double& lo, double& hi) {
  if (std::isfinite(v)) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
}

Range x_extent(const std::vector<const LinePlotSpec*>& panels) {
  double lo = kInf, hi = -kInf;
  for (const auto* p : panels) {
    for (const auto& s : p->series)
      for (std::size_t i = 0; i < s.x.size(); ++i)
        if (std::isfinite(s.y[i])) extend(s.x[i], lo, hi);
    for (const auto& v : p->vlines) extend(v.value, lo, hi);
  }
  if (!(lo <= hi)) return {0, 1};
  if (hi - lo <= 1e-12 * std::max(1.0, std::fabs(lo))) return padded_range(lo, hi, 0.05);
  return {lo, hi};
}

Range y_extent(const LinePlotSpec& p, Range xr) {
  if (p.y_range) return *p.y_range;
  double lo = kInf, hi = -kInf;
  for (const auto& s : p.series)
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (s.x[i] >= xr.lo && s.x[i] <= xr.hi) extend(s.y[i], lo, hi);
  for (const auto& h : p.hlines) extend(h.value, lo, hi);
  return padded_range(lo, hi, 0.05);
}

struct PanelLayout {
  const LinePlotSpec* spec;
  Range yr;
  AxisTicks yt;
  int top = 0, height = 0;
};

void draw_panel(Canvas& canvas, const AxesFrame& f, const PanelLayout& pl, const AxisTicks& xt,
                const AxesText& text, const Fonts& fonts) {
  const LinePlotSpec& p = *pl.spec;
  if (p.grid) draw_grid(canvas, f, xt, pl.yt);
  canvas.push_clip(plot_rect(f));
  std::vector<LegendEntry> legend, ref_legend;  // series first, then reference lines
  std::vector<Point> data_px;
  const double left = f.left, right = f.left + f.width, top = f.top, bottom = f.top + f.height;
  const Color ref_default{70, 70, 70};
  for (const auto& h : p.hlines) {
    const Color c = h.color.value_or(ref_default);
    const double y = px(f, f.x.lo, h.value).y;
    canvas.polyline({{left, y}, {right, y}}, c, h.width_px, h.style);
    if (y >= top && y <= bottom)
      ref_legend.push_back({h.label, c, true, h.style, h.width_px, std::nullopt, 8, false});
    for (int x = 0; x <= f.width; x += 8) data_px.push_back({left + x, y});
  }
  for (const auto& v : p.vlines) {
    const Color c = v.color.value_or(ref_default);
    const double x = px(f, v.value, f.y.lo).x;
    canvas.polyline({{x, top}, {x, bottom}}, c, v.width_px, v.style);
    if (x >= left && x <= right)
      ref_legend.push_back({v.label, c, true, v.style, v.width_px, std::nullopt, 8, false});
    for (int y = 0; y <= f.height; y += 8) data_px.push_back({x, top + y});
  }
  std::size_t next = 0;
  for (const auto& s : p.series) {
    const Color c = s.color.value_or(palette()[next++ % palette().size()]);
    std::vector<Point> pts;
    pts.reserve(s.x.size());
    Point prev{NAN, NAN};
    const std::size_t first = data_px.size();
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      const Point q = px(f, s.x[i], s.y[i]);
      pts.push_back(q);
      if (std::isfinite(q.x) && std::isfinite(q.y)) {
        densify(prev, q, 50, data_px);
        data_px.push_back(q);
      }
      prev = q;
    }
    const bool visible = any_inside(f, data_px, first);
    canvas.polyline(pts, c, s.width_px, s.style);
    if (s.marker)
      for (const auto& q : pts) canvas.marker(q, *s.marker, 4 + 2 * s.width_px, c);
    // Only what can be seen gets a legend entry.
    if (visible)
      legend.push_back({s.label, c, true, s.style, s.width_px, s.marker, 4 + 2 * s.width_px});
  }
  canvas.pop_clip();
  legend.insert(legend.end(), ref_legend.begin(), ref_legend.end());
  draw_axes(canvas, f, xt, pl.yt, text, fonts);
  draw_legend(canvas, f, legend, p.legend, fonts, data_px);
}

Figure render_panels(const char* what, const std::string& title, const std::string& x_label,
                     std::optional<Range> x_range, const std::vector<const LinePlotSpec*>& panels,
                     int width, int height, int panel_height, double font_scale) {
  if (panels.empty()) throw InputError(std::string(what) + ": no panels; expected at least one");
  for (const auto* p : panels) validate_panel(what, *p);
  if (x_range) check_range(what, "x", *x_range);
  const Fonts fonts{font_scale};
  const Range xr = x_range.value_or(x_extent(panels));

  const int top = title_height(title, fonts);
  const int bottom = bottom_margin(true, !x_label.empty(), fonts);
  const int panel_title_h = label_height(fonts.label()) + 8;
  const int gap = 16;
  // Panel heights: single plot fills the figure; stacked panels have panel_height each.
  std::vector<PanelLayout> layout;
  int y = top;
  for (std::size_t i = 0; i < panels.size(); ++i) {
    const bool stacked = panels.size() > 1 || panel_height > 0;
    if (i > 0) y += gap;
    if (stacked && !panels[i]->title.empty()) y += panel_title_h;
    PanelLayout pl{panels[i], {}, {}, y, 0};
    pl.height = stacked ? panel_height : height - top - bottom;
    y += pl.height;
    layout.push_back(pl);
  }
  const int fig_h = panel_height > 0 ? y + bottom : height;
  if (layout.back().height < 50)
    throw InputError(std::string(what) + ": figure " + std::to_string(width) + " x " +
                     std::to_string(fig_h) + " px leaves no room for the plot; enlarge it");
  int left = 0;
  for (auto& pl : layout) {
    pl.yr = y_extent(*pl.spec, xr);
    check_range(what, "y", pl.yr);
    pl.yt = make_y_ticks(pl.yr, pl.height);
    left = std::max(left, left_margin(pl.yt, !pl.spec->y_label.empty(), fonts));
  }
  int plot_w = width - left - 2 * kPad;
  AxisTicks xt = make_x_ticks(xr, plot_w);
  const int half_last =
      static_cast<int>(std::ceil(text_size(xt.labels.back(), fonts.tick()).width / 2));
  plot_w = width - left - std::max(2 * kPad, half_last + kPad);
  if (plot_w < 50)
    throw InputError(std::string(what) + ": figure width " + std::to_string(width) +
                     " px leaves no room for the plot; enlarge it");
  xt = make_x_ticks(xr, plot_w);

  Canvas canvas(width, fig_h);
  std::vector<AxesFrame> axes;
  for (std::size_t i = 0; i < layout.size(); ++i) {
    const PanelLayout& pl = layout[i];
    const AxesFrame f{left, pl.top, plot_w, pl.height, xr, pl.yr};
    const bool last = i + 1 == layout.size();
    AxesText text{last ? x_label : "", pl.spec->y_label, last, y_label_center(fonts)};
    draw_panel(canvas, f, pl, xt, text, fonts);
    if (layout.size() > 1 || panel_height > 0)
      canvas.text(pl.spec->title, {static_cast<double>(left), pl.top - 5.0}, HAlign::kLeft,
                  VAlign::kBottom, fonts.label(), kBlack);
    axes.push_back(f);
  }
  draw_title(canvas, title, fonts);
  return canvas.finish(std::move(axes));
}

}  // namespace

Figure render_line_plot(const LinePlotSpec& spec) {
  check_figure_size("line plot", spec.width, spec.height);
  return render_panels("line plot", spec.title, spec.x_label, spec.x_range, {&spec}, spec.width,
                       spec.height, 0, spec.font_scale);
}

Figure render_stacked(const StackedPlotSpec& spec) {
  check_figure_size("stacked plot", spec.width, std::max(150, spec.panel_height));
  if (spec.panel_height < 50)
    throw InputError("stacked plot: panel_height is " + std::to_string(spec.panel_height) +
                     " px; expected at least 50");
  std::vector<const LinePlotSpec*> panels;
  for (const auto& p : spec.panels) panels.push_back(&p);
  return render_panels("stacked plot", spec.title, spec.x_label, spec.x_range, panels, spec.width,
                       0, spec.panel_height, spec.font_scale);
}

}  // namespace somasim::figures
