// Heatmap: resampled grid, colour bar, bin-edge grid and overlays.
#include "somasim/figures/heatmap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "axes.hpp"
#include "canvas.hpp"
#include "colorbar.hpp"
#include "colormap_detail.hpp"
#include "legend.hpp"
#include "somasim/error.hpp"

namespace somasim::figures {

Grid Grid::from_matrix(const Eigen::MatrixXd& m) {
  Grid g{static_cast<int>(m.rows()), static_cast<int>(m.cols()), {}};
  g.values.reserve(static_cast<std::size_t>(m.size()));
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c) g.values.push_back(m(r, c));
  return g;
}

namespace {
using namespace detail;

constexpr Color kMissing{225, 225, 225};
const Color kOverlay[] = {{220, 20, 60}, {255, 255, 255}, {255, 140, 0}, {255, 0, 255}};

void validate(const HeatmapSpec& s) {
  const Grid& g = s.grid;
  std::ostringstream os;
  if (g.rows <= 0 || g.cols <= 0 || g.values.empty()) {
    os << "heatmap: grid is empty (" << g.rows << " rows x " << g.cols << " cols, "
       << g.values.size() << " values); expected at least one value";
    throw InputError(os.str());
  }
  if (g.values.size() != static_cast<std::size_t>(g.rows) * g.cols) {
    os << "heatmap: grid has " << g.values.size() << " values but rows x cols = " << g.rows << " x "
       << g.cols << " = " << static_cast<std::size_t>(g.rows) * g.cols;
    throw InputError(os.str());
  }
  if (s.layout == GridLayout::kSamples && (g.rows < 2 || g.cols < 2)) {
    os << "heatmap: a kSamples grid needs at least 2 rows and 2 cols, got " << g.rows << " x "
       << g.cols << " (use GridLayout::kCells for bins)";
    throw InputError(os.str());
  }
  check_range("heatmap", "x", {s.x_min, s.x_max});
  check_range("heatmap", "y", {s.y_min, s.y_max});
  if (s.value_range) check_range("heatmap", "value", *s.value_range);
  for (const auto& l : s.lines)
    if (l.x.size() != l.y.size()) {
      os << "heatmap: line '" << l.label << "' has " << l.x.size() << " x values but " << l.y.size()
         << " y values";
      throw InputError(os.str());
    }
  for (const auto& p : s.points)
    if (p.x.size() != p.y.size()) {
      os << "heatmap: points '" << p.label << "' have " << p.x.size() << " x values but "
         << p.y.size() << " y values";
      throw InputError(os.str());
    }
  check_figure_size("heatmap", s.width, s.height);
}

Range value_range(const HeatmapSpec& s) {
  if (s.value_range) return *s.value_range;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double v : s.grid.values)
    if (std::isfinite(v)) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  if (!(lo <= hi)) return {0, 1};
  if (lo == hi) return {lo - 0.5, hi + 0.5};
  return {lo, hi};
}

/// Fractional grid index of data coordinate v along an axis of n values over [a, b].
double frac_index(double v, double a, double b, int n, GridLayout layout) {
  const double u = (v - a) / (b - a);
  return layout == GridLayout::kSamples ? u * (n - 1) : u * n - 0.5;
}

double sample(const Grid& g, double fr, double fc, Resampling mode) {
  const auto at = [&](int r, int c) { return g.values[static_cast<std::size_t>(r) * g.cols + c]; };
  fr = std::clamp(fr, 0.0, g.rows - 1.0);
  fc = std::clamp(fc, 0.0, g.cols - 1.0);
  const int nr = static_cast<int>(std::lround(fr)), nc = static_cast<int>(std::lround(fc));
  if (mode == Resampling::kNearest) return at(nr, nc);
  const int r0 = static_cast<int>(std::floor(fr)), c0 = static_cast<int>(std::floor(fc));
  const int r1 = std::min(r0 + 1, g.rows - 1), c1 = std::min(c0 + 1, g.cols - 1);
  const double tr = fr - r0, tc = fc - c0;
  const double v00 = at(r0, c0), v01 = at(r0, c1), v10 = at(r1, c0), v11 = at(r1, c1);
  if (!std::isfinite(v00) || !std::isfinite(v01) || !std::isfinite(v10) || !std::isfinite(v11))
    return at(nr, nc);
  return (1 - tr) * ((1 - tc) * v00 + tc * v01) + tr * ((1 - tc) * v10 + tc * v11);
}

void fill_plot(Canvas& canvas, const AxesFrame& f, const HeatmapSpec& s, Range vr) {
  Image cells{f.width, f.height,
              std::vector<std::uint8_t>(static_cast<std::size_t>(f.width) * f.height * 3)};
  std::vector<double> fc(f.width);
  for (int c = 0; c < f.width; ++c) {
    const double x = f.x.lo + (c + 0.5) / f.width * (f.x.hi - f.x.lo);
    fc[c] = frac_index(x, s.x_min, s.x_max, s.grid.cols, s.layout);
  }
  for (int r = 0; r < f.height; ++r) {
    const double y = f.y.hi - (r + 0.5) / f.height * (f.y.hi - f.y.lo);
    const double fr = frac_index(y, s.y_min, s.y_max, s.grid.rows, s.layout);
    for (int c = 0; c < f.width; ++c) {
      const double v = sample(s.grid, fr, fc[c], s.resampling);
      const Color col = std::isnan(v)
                            ? kMissing
                            : level_color(s.colormap, quantise((v - vr.lo) / (vr.hi - vr.lo)));
      const std::size_t i = 3 * (static_cast<std::size_t>(r) * f.width + c);
      cells.rgb[i] = col.r;
      cells.rgb[i + 1] = col.g;
      cells.rgb[i + 2] = col.b;
    }
  }
  canvas.image(cells, f.left, f.top);
}

void draw_edges(Canvas& canvas, const AxesFrame& f, const HeatmapSpec& s) {
  const double top = f.top, bottom = f.top + f.height, left = f.left, right = f.left + f.width;
  for (double e : s.x_edges) {
    const double x = px(f, e, f.y.lo).x;
    if (x >= left + 0.5 && x <= right - 0.5)
      canvas.polyline({{x, top}, {x, bottom}}, kWhite, 1, LineStyle::kSolid, 0.55);
  }
  for (double e : s.y_edges) {
    const double y = px(f, f.x.lo, e).y;
    if (y >= top + 0.5 && y <= bottom - 0.5)
      canvas.polyline({{left, y}, {right, y}}, kWhite, 1, LineStyle::kSolid, 0.55);
  }
}

}  // namespace

Figure render_heatmap(const HeatmapSpec& s) {
  validate(s);
  const Fonts fonts{s.font_scale};
  const Range vr = value_range(s);
  const Range xr{s.x_min, s.x_max}, yr{s.y_min, s.y_max};

  const int top = title_height(s.title, fonts);
  const int bottom = bottom_margin(true, !s.x_label.empty(), fonts);
  const int plot_h = s.height - top - bottom;
  const AxisTicks yt = make_y_ticks(yr, plot_h);
  const int left = left_margin(yt, !s.y_label.empty(), fonts);
  const int right = colorbar_total_width(vr, plot_h, s.colorbar_label, fonts);
  const int plot_w = s.width - left - right;
  if (plot_w < 50 || plot_h < 50)
    throw InputError("heatmap: figure " + std::to_string(s.width) + " x " +
                     std::to_string(s.height) + " px leaves no room for the plot; enlarge it");
  const AxisTicks xt = make_x_ticks(xr, plot_w);
  const AxesFrame frame{left, top, plot_w, plot_h, xr, yr};

  Canvas canvas(s.width, s.height);
  fill_plot(canvas, frame, s, vr);
  canvas.push_clip(plot_rect(frame));
  draw_edges(canvas, frame, s);

  // Overlays, clipped to the plot area.
  std::vector<LegendEntry> legend;
  std::vector<Point> data_px;
  std::size_t next = 0;
  for (const auto& l : s.lines) {
    const Color c = l.color.value_or(kOverlay[next++ % std::size(kOverlay)]);
    std::vector<Point> pts;
    const std::size_t first = data_px.size();
    for (std::size_t i = 0; i < l.x.size(); ++i) {
      const Point p = px(frame, l.x[i], l.y[i]);
      pts.push_back(p);
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
      if (i > 0) densify(px(frame, l.x[i - 1], l.y[i - 1]), p, 200, data_px);
      data_px.push_back(p);
    }
    canvas.polyline(pts, kWhite, l.width_px + 2.5, LineStyle::kSolid);
    canvas.polyline(pts, c, l.width_px, l.style);
    // Only what can be seen gets a legend entry.
    if (any_inside(frame, data_px, first))
      legend.push_back({l.label, c, true, l.style, l.width_px, std::nullopt, 8, true});
  }
  for (const auto& p : s.points) {
    const Color c = p.color.value_or(kOverlay[next++ % std::size(kOverlay)]);
    const std::size_t first = data_px.size();
    for (std::size_t i = 0; i < p.x.size(); ++i) {
      const Point q = px(frame, p.x[i], p.y[i]);
      canvas.marker(q, p.marker, p.size_px, c, true);
      data_px.push_back(q);
    }
    if (any_inside(frame, data_px, first))
      legend.push_back({p.label, c, false, LineStyle::kSolid, 0, p.marker, p.size_px, true});
  }

  canvas.pop_clip();
  AxesText text{s.x_label, s.y_label, true, y_label_center(fonts)};
  draw_axes(canvas, frame, xt, yt, text, fonts);
  draw_colorbar(
      canvas,
      {static_cast<double>(frame.left + frame.width + kColorbarGap), static_cast<double>(frame.top),
       static_cast<double>(kColorbarWidth), static_cast<double>(plot_h)},
      s.colormap, vr, s.colorbar_label, fonts);
  draw_legend(canvas, frame, legend, s.legend, fonts, data_px);
  draw_title(canvas, s.title, fonts);
  return canvas.finish({frame});
}

}  // namespace somasim::figures
