#pragma once
// Private drawing layer of somasim_figures: a vector canvas over cairo with text laid out by
// Pango. Coordinates are pixels of the figure, x to the right and y downwards; pixel (c, r)
// covers [c, c + 1) x [r, r + 1). Everything drawn is recorded, so one drawing gives the PNG's
// pixels and the SVG's vectors. Cairo and Pango live only in core/figures/src.
#include <array>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "somasim/figures/figure.hpp"

namespace somasim::figures {

/// The recorded vector drawing of a figure (opaque outside the library).
class Drawing;

namespace detail {

inline constexpr Color kBlack{0, 0, 0};
inline constexpr Color kWhite{255, 255, 255};
inline constexpr Color kGridGrey{225, 225, 225};
inline constexpr Color kDarkGrey{70, 70, 70};

/// A point in figure pixels.
struct Point {
  double x = 0, y = 0;
};

/// An axis-aligned rectangle in figure pixels.
struct Rect {
  double x = 0, y = 0, width = 0, height = 0;
  bool contains(Point p) const {
    return p.x >= x && p.x < x + width && p.y >= y && p.y < y + height;
  }
};

/// Text sizes [px of the font's em], times the spec's font_scale.
struct Fonts {
  double scale = 1.0;
  double tick() const { return 14.0 * scale; }
  double label() const { return 16.0 * scale; }
  double title() const { return 18.0 * scale; }
  double legend() const { return 14.0 * scale; }
};

enum class HAlign { kLeft, kCenter, kRight };
enum class VAlign { kTop, kMiddle, kBottom };
enum class Weight { kNormal, kBold };

/// Size {width, height} [px] of the box `text` is aligned by (its logical extents: ascent to
/// descent, advance width), in the sans-serif face at `size_px`.
struct TextSize {
  double width = 0, height = 0;
};
TextSize text_size(const std::string& text, double size_px, Weight weight = Weight::kNormal);

/// A figure being drawn: starts white, `width` x `height` px.
class Canvas {
 public:
  Canvas(int width, int height);
  ~Canvas();
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }

  /// Fills the rectangle with `color` at opacity `alpha`.
  void fill_rect(Rect r, Color color, double alpha = 1.0);
  /// A 1 px outline along the inside of the pixels bounding `r`'s edges (crisp frame).
  void frame_rect(Rect r, Color color);
  /// A crisp 1 px line between pixel centres of integer pixels (a) and (b).
  void pixel_line(std::array<int, 2> a, std::array<int, 2> b, Color color);
  /// Polyline through points (NaN breaks it), round joins and caps, dashed or dotted.
  void polyline(const std::vector<Point>& pts, Color color, double width_px, LineStyle style,
                double alpha = 1.0);
  /// Marker of diameter size_px centred at p (white outline for contrast when `outline`).
  void marker(Point p, Marker marker, double size_px, Color color, bool outline = false);
  /// Text aligned at `anchor` by its box (text_size); vertical = rotated 90 degrees
  /// counter-clockwise (reads bottom to top; the box is then height x width). Invalid UTF-8 is
  /// drawn with replacement characters.
  void text(const std::string& text, Point anchor, HAlign h, VAlign v, double size_px, Color color,
            Weight weight = Weight::kNormal, bool vertical = false);
  /// Paints an RGB image with its top-left corner at pixel (x, y), pixel for pixel.
  void image(const Image& image, int x, int y);
  /// Replays another figure's drawing (or paints its image when it has none) at (x, y).
  void figure(const Figure& figure, int x, int y);

  /// Restricts drawing to `r` until the matching pop_clip().
  void push_clip(Rect r);
  void pop_clip();

  /// Ends drawing: the figure with its pixels and its recorded vectors.
  Figure finish(std::vector<AxesFrame> axes);

 private:
  struct State;
  int width_ = 0, height_ = 0;
  std::unique_ptr<State> state_;
};

/// The largest side of a figure or image cairo can draw [px].
inline constexpr int kMaxFigurePx = 32767;

/// Throws InputError "<what>: figure size W x H px is too small; expected 200 x 150 to
/// 32767 x 32767" (or "too large").
void check_figure_size(const char* what, int width, int height);

}  // namespace detail
}  // namespace somasim::figures
