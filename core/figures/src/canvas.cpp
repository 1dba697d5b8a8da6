#include "canvas.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <sstream>

#include <fmt/format.h>

#include <cairo.h>
#include <glib.h>
#include <pango/pangocairo.h>

#include "drawing.hpp"
#include "somasim/error.hpp"

namespace somasim::figures::detail {
namespace {

bool finite(Point p) {
  return std::isfinite(p.x) && std::isfinite(p.y);
}

void set_color(cairo_t* cr, Color c, double alpha = 1.0) {
  cairo_set_source_rgba(cr, c.r / 255.0, c.g / 255.0, c.b / 255.0, alpha);
}

/// Font options that make text metrics independent of the surface drawn on (no hinting), so a
/// layout measured here has the same size on the recording, the image and the SVG surface.
cairo_font_options_t* unhinted_options() {
  thread_local struct Options {
    cairo_font_options_t* ptr = cairo_font_options_create();
    Options() {
      cairo_font_options_set_hint_style(ptr, CAIRO_HINT_STYLE_NONE);
      cairo_font_options_set_hint_metrics(ptr, CAIRO_HINT_METRICS_OFF);
      cairo_font_options_set_antialias(ptr, CAIRO_ANTIALIAS_GRAY);
    }
    ~Options() { cairo_font_options_destroy(ptr); }
  } options;
  return options.ptr;
}

struct LayoutDeleter {
  void operator()(PangoLayout* l) const { g_object_unref(l); }
};
using LayoutPtr = std::unique_ptr<PangoLayout, LayoutDeleter>;

std::string valid_utf8(const std::string& text) {
  if (g_utf8_validate(text.data(), static_cast<gssize>(text.size()), nullptr)) return text;
  gchar* fixed = g_utf8_make_valid(text.data(), static_cast<gssize>(text.size()));
  std::string out(fixed);
  g_free(fixed);
  return out;
}

/// A one-line layout of `text` in the sans-serif face, for drawing on `cr`.
LayoutPtr make_layout(cairo_t* cr, const std::string& text, double size_px, Weight weight) {
  LayoutPtr layout(pango_cairo_create_layout(cr));
  pango_cairo_context_set_font_options(pango_layout_get_context(layout.get()), unhinted_options());
  pango_layout_context_changed(layout.get());
  PangoFontDescription* font = pango_font_description_from_string("Sans");
  pango_font_description_set_absolute_size(font, size_px * PANGO_SCALE);
  pango_font_description_set_weight(
      font, weight == Weight::kBold ? PANGO_WEIGHT_BOLD : PANGO_WEIGHT_NORMAL);
  pango_layout_set_font_description(layout.get(), font);
  pango_font_description_free(font);
  const std::string utf8 = valid_utf8(text);
  pango_layout_set_text(layout.get(), utf8.data(), static_cast<int>(utf8.size()));
  return layout;
}

/// Logical extents [px] of a layout: x, y of the box's corner relative to the layout's origin.
Rect logical_box(PangoLayout* layout) {
  PangoRectangle logical;
  pango_layout_get_extents(layout, nullptr, &logical);
  return {static_cast<double>(logical.x) / PANGO_SCALE,
          static_cast<double>(logical.y) / PANGO_SCALE,
          static_cast<double>(logical.width) / PANGO_SCALE,
          static_cast<double>(logical.height) / PANGO_SCALE};
}

/// A cairo context on a 1 x 1 image, per thread, for measuring text.
cairo_t* measuring_context() {
  thread_local struct Measure {
    cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_A8, 1, 1);
    cairo_t* cr = cairo_create(surface);
    ~Measure() {
      cairo_destroy(cr);
      cairo_surface_destroy(surface);
    }
  } measure;
  return measure.cr;
}

/// Clips segment a-b to `r` (Liang-Barsky); false when nothing of it is inside.
bool clip_segment(Point& a, Point& b, const Rect& r) {
  double t0 = 0, t1 = 1;
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {a.x - r.x, r.x + r.width - a.x, a.y - r.y, r.y + r.height - a.y};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0) {
      if (q[i] < 0) return false;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0)
      t0 = std::max(t0, t);
    else
      t1 = std::min(t1, t);
    if (t0 > t1) return false;
  }
  const Point start{a.x + t0 * dx, a.y + t0 * dy}, end{a.x + t1 * dx, a.y + t1 * dy};
  a = start;
  b = end;
  return true;
}

void set_dash(cairo_t* cr, LineStyle style, double width_px) {
  const double w = std::max(1.0, width_px);
  if (style == LineStyle::kDashed) {
    // Butt caps: dashes are exactly as long as drawn.
    const double dashes[] = {3.5 * std::max(2.0, w), 2.5 * std::max(2.0, w) + 1};
    cairo_set_dash(cr, dashes, 2, 0);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
  } else if (style == LineStyle::kDotted) {
    // Zero-length dashes with round caps are dots of the line's width (at least 1.6 px, so that
    // thin dotted lines stay visible).
    const double dot = std::max(1.6, width_px);
    const double dashes[] = {0.0, 2.2 * dot};
    cairo_set_dash(cr, dashes, 2, 0);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    cairo_set_line_width(cr, dot);
  } else {
    cairo_set_dash(cr, nullptr, 0, 0);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  }
}

}  // namespace

TextSize text_size(const std::string& text, double size_px, Weight weight) {
  if (text.empty()) return {0, 0};
  const LayoutPtr layout = make_layout(measuring_context(), text, size_px, weight);
  const Rect box = logical_box(layout.get());
  return {box.width, box.height};
}

struct Canvas::State {
  cairo_surface_t* surface = nullptr;
  cairo_t* cr = nullptr;
};

Canvas::Canvas(int width, int height) : width_(width), height_(height), state_(new State) {
  const cairo_rectangle_t extents{0, 0, static_cast<double>(width), static_cast<double>(height)};
  state_->surface = cairo_recording_surface_create(CAIRO_CONTENT_COLOR_ALPHA, &extents);
  state_->cr = cairo_create(state_->surface);
  cairo_set_line_join(state_->cr, CAIRO_LINE_JOIN_ROUND);
  fill_rect({0, 0, static_cast<double>(width), static_cast<double>(height)}, kWhite);
}

Canvas::~Canvas() {
  if (state_->cr) cairo_destroy(state_->cr);
  if (state_->surface) cairo_surface_destroy(state_->surface);
}

void Canvas::fill_rect(Rect r, Color color, double alpha) {
  cairo_t* cr = state_->cr;
  cairo_rectangle(cr, r.x, r.y, r.width, r.height);
  set_color(cr, color, alpha);
  cairo_fill(cr);
}

void Canvas::frame_rect(Rect r, Color color) {
  cairo_t* cr = state_->cr;
  cairo_set_dash(cr, nullptr, 0, 0);
  cairo_set_line_width(cr, 1.0);
  cairo_rectangle(cr, r.x + 0.5, r.y + 0.5, r.width - 1, r.height - 1);
  set_color(cr, color);
  cairo_stroke(cr);
}

void Canvas::pixel_line(std::array<int, 2> a, std::array<int, 2> b, Color color) {
  cairo_t* cr = state_->cr;
  cairo_set_dash(cr, nullptr, 0, 0);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_SQUARE);
  cairo_set_line_width(cr, 1.0);
  cairo_move_to(cr, a[0] + 0.5, a[1] + 0.5);
  cairo_line_to(cr, b[0] + 0.5, b[1] + 0.5);
  set_color(cr, color);
  cairo_stroke(cr);
}

void Canvas::polyline(const std::vector<Point>& pts, Color color, double width_px, LineStyle style,
                      double alpha) {
  cairo_t* cr = state_->cr;
  cairo_set_line_width(cr, width_px);
  set_dash(cr, style, width_px);
  set_color(cr, color, alpha);
  // Segments are clipped to the figure (with a margin) in double precision: cairo's fixed-point
  // coordinates wrap beyond about 8e6 px, which would draw far-off points as stray lines.
  const double margin = 100 + width_px;
  const Rect bounds{-margin, -margin, width_ + 2 * margin, height_ + 2 * margin};
  bool drawing = false;
  Point last{NAN, NAN};  // where the current path ends
  for (std::size_t i = 1; i < pts.size(); ++i) {
    Point a = pts[i - 1], b = pts[i];
    if (!finite(a) || !finite(b) || !clip_segment(a, b, bounds)) {
      if (drawing) cairo_stroke(cr);
      drawing = false;
      continue;
    }
    if (!drawing || a.x != last.x || a.y != last.y) {
      if (drawing) cairo_stroke(cr);
      cairo_move_to(cr, a.x, a.y);
      drawing = true;
    }
    cairo_line_to(cr, b.x, b.y);
    last = b;
  }
  if (drawing) cairo_stroke(cr);
}

void Canvas::marker(Point p, Marker marker, double size_px, Color color, bool outline) {
  if (!finite(p)) return;
  cairo_t* cr = state_->cr;
  const double r = size_px / 2;
  cairo_set_dash(cr, nullptr, 0, 0);
  auto poly = [&](std::initializer_list<Point> v) {
    bool first = true;
    for (const Point& q : v) {
      if (first)
        cairo_move_to(cr, p.x + q.x, p.y + q.y);
      else
        cairo_line_to(cr, p.x + q.x, p.y + q.y);
      first = false;
    }
    cairo_close_path(cr);
  };
  auto fill_shape = [&](const auto& shape) {
    if (outline) {
      shape();
      cairo_set_line_width(cr, 2.0);
      set_color(cr, kWhite);
      cairo_stroke(cr);
    }
    shape();
    set_color(cr, color);
    cairo_fill(cr);
  };
  switch (marker) {
    case Marker::kCircle:
      fill_shape([&] {
        cairo_new_sub_path(cr);
        cairo_arc(cr, p.x, p.y, r, 0, 2 * M_PI);
      });
      break;
    case Marker::kSquare:
      fill_shape([&] { poly({{-r, -r}, {r, -r}, {r, r}, {-r, r}}); });
      break;
    case Marker::kTriangle:
      fill_shape([&] { poly({{0, -r * 1.15}, {r * 1.1, r * 0.75}, {-r * 1.1, r * 0.75}}); });
      break;
    case Marker::kDiamond:
      fill_shape([&] { poly({{0, -r * 1.2}, {r, 0}, {0, r * 1.2}, {-r, 0}}); });
      break;
    case Marker::kCross:
    case Marker::kPlus: {
      const double k = marker == Marker::kCross ? r * 0.75 : r;
      const std::array<Point, 4> ends =
          marker == Marker::kCross ? std::array<Point, 4>{Point{-k, -k}, {k, k}, {-k, k}, {k, -k}}
                                   : std::array<Point, 4>{Point{-k, 0}, {k, 0}, {0, -k}, {0, k}};
      const double w = std::max(2.0, std::round(size_px / 4));
      cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
      auto strokes = [&](Color c, double width) {
        for (int i = 0; i < 4; i += 2) {
          cairo_move_to(cr, p.x + ends[i].x, p.y + ends[i].y);
          cairo_line_to(cr, p.x + ends[i + 1].x, p.y + ends[i + 1].y);
        }
        cairo_set_line_width(cr, width);
        set_color(cr, c);
        cairo_stroke(cr);
      };
      if (outline) strokes(kWhite, w + 2);
      strokes(color, w);
      break;
    }
  }
}

void Canvas::text(const std::string& text, Point anchor, HAlign h, VAlign v, double size_px,
                  Color color, Weight weight, bool vertical) {
  if (text.empty() || !finite(anchor)) return;
  cairo_t* cr = state_->cr;
  cairo_save(cr);
  cairo_translate(cr, anchor.x, anchor.y);
  if (vertical) cairo_rotate(cr, -M_PI / 2);
  const LayoutPtr layout = make_layout(cr, text, size_px, weight);
  const Rect box = logical_box(layout.get());
  // In the text's own frame (rotated for vertical text: its x runs up the figure, its y to the
  // right) the anchor is a point of its box.
  const HAlign along = vertical ? (v == VAlign::kTop      ? HAlign::kRight
                                   : v == VAlign::kBottom ? HAlign::kLeft
                                                          : HAlign::kCenter)
                                : h;
  const VAlign across = vertical ? (h == HAlign::kLeft    ? VAlign::kTop
                                    : h == HAlign::kRight ? VAlign::kBottom
                                                          : VAlign::kMiddle)
                                 : v;
  double x = -box.x, y = -box.y;
  if (along == HAlign::kCenter) x -= box.width / 2;
  if (along == HAlign::kRight) x -= box.width;
  if (across == VAlign::kMiddle) y -= box.height / 2;
  if (across == VAlign::kBottom) y -= box.height;
  cairo_move_to(cr, x, y);
  set_color(cr, color);
  pango_cairo_show_layout(cr, layout.get());
  cairo_restore(cr);
}

void Canvas::image(const Image& image, int x, int y) {
  if (image.width <= 0 || image.height <= 0) return;
  cairo_surface_t* src = cairo_image_surface_create(CAIRO_FORMAT_RGB24, image.width, image.height);
  if (const cairo_status_t status = cairo_surface_status(src); status != CAIRO_STATUS_SUCCESS) {
    cairo_surface_destroy(src);
    throw InputError(fmt::format("figure: a {} x {} px image cannot be drawn ({})", image.width,
                                 image.height, cairo_status_to_string(status)));
  }
  cairo_surface_flush(src);
  unsigned char* data = cairo_image_surface_get_data(src);
  const int stride = cairo_image_surface_get_stride(src);
  for (int r = 0; r < image.height; ++r) {
    auto* row = reinterpret_cast<std::uint32_t*>(data + static_cast<std::ptrdiff_t>(r) * stride);
    for (int c = 0; c < image.width; ++c) {
      const Color px = image.at(c, r);
      row[c] = (std::uint32_t{px.r} << 16) | (std::uint32_t{px.g} << 8) | px.b;
    }
  }
  cairo_surface_mark_dirty(src);
  cairo_t* cr = state_->cr;
  cairo_save(cr);
  cairo_set_source_surface(cr, src, x, y);
  cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
  cairo_rectangle(cr, x, y, image.width, image.height);
  cairo_fill(cr);
  cairo_restore(cr);
  cairo_surface_destroy(src);
}

void Canvas::figure(const Figure& figure, int x, int y) {
  if (!figure.drawing) {
    image(figure.image, x, y);
    return;
  }
  cairo_t* cr = state_->cr;
  const std::lock_guard lock(figure.drawing->mutex());
  cairo_save(cr);
  cairo_set_source_surface(cr, figure.drawing->surface(), x, y);
  cairo_rectangle(cr, x, y, figure.image.width, figure.image.height);
  cairo_fill(cr);
  cairo_restore(cr);
}

void Canvas::push_clip(Rect r) {
  cairo_save(state_->cr);
  cairo_rectangle(state_->cr, r.x, r.y, r.width, r.height);
  cairo_clip(state_->cr);
}

void Canvas::pop_clip() {
  cairo_restore(state_->cr);
}

Figure Canvas::finish(std::vector<AxesFrame> axes) {
  if (const cairo_status_t status = cairo_status(state_->cr); status != CAIRO_STATUS_SUCCESS)
    throw RunError(std::string("figure: drawing failed: ") + cairo_status_to_string(status));
  cairo_destroy(state_->cr);
  state_->cr = nullptr;
  auto drawing = std::make_shared<Drawing>(state_->surface, width_, height_);
  state_->surface = nullptr;  // owned by the drawing now
  Figure out;
  out.image = drawing->rasterise();
  out.axes = std::move(axes);
  out.drawing = std::move(drawing);
  return out;
}

void check_figure_size(const char* what, int width, int height) {
  if (width < 200 || height < 150 || width > kMaxFigurePx || height > kMaxFigurePx) {
    std::ostringstream os;
    os << what << ": figure size " << width << " x " << height << " px is too "
       << (width < 200 || height < 150 ? "small" : "large") << "; expected 200 x 150 to "
       << kMaxFigurePx << " x " << kMaxFigurePx;
    throw InputError(os.str());
  }
}

}  // namespace somasim::figures::detail
