#pragma once
/// @file
/// Basic types of somasim_figures: colours, ranges, RGB images, axes frames and rendered figures.
///
/// Every plot function renders a `Figure`: its pixels, the placement of its axes (so that callers
/// and tests can map data coordinates to pixels) and its vector drawing, which `save_figure`
/// writes as a PNG and an SVG beside it. Drawing is done by cairo, text laid out by Pango in the
/// system's sans-serif face (DejaVu Sans on Debian): any UTF-8 text ("°", "σ", "Δ").
#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace somasim::figures {

/// 8-bit sRGB colour.
struct Color {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Color&) const = default;
};

/// A closed interval [lo, hi] in data units.
struct Range {
  double lo = 0.0;
  double hi = 1.0;
  bool operator==(const Range&) const = default;
};

/// How a line is stroked.
enum class LineStyle { kSolid, kDashed, kDotted };

/// Marker shapes for points.
enum class Marker { kCircle, kSquare, kTriangle, kDiamond, kCross, kPlus };

/// Where a legend box goes inside its axes; kBest picks the corner covering the fewest data points.
enum class LegendPosition { kBest, kTopRight, kTopLeft, kBottomRight, kBottomLeft, kNone };

/// Default qualitative palette (matplotlib "tab10"); series without a colour cycle through it.
const std::vector<Color>& palette();

/// Row-major 8-bit RGB image: pixel (x, y) is at rgb[3 * (y * width + x) + {0, 1, 2}].
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;

  /// Colour of pixel (x = column, y = row from the top). Precondition: inside the image.
  Color at(int x, int y) const {
    const std::size_t i = 3 * (static_cast<std::size_t>(y) * width + x);
    return Color{rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

/// Placement of one axes (plot area) in a figure, in pixels, with its data ranges.
/// The plot area covers pixel columns [left, left + width) and rows [top, top + height);
/// x grows to the right and y grows upwards.
struct AxesFrame {
  int left = 0, top = 0, width = 0, height = 0;  ///< [px]
  Range x;                                       ///< data range shown along x
  Range y;                                       ///< data range shown along y

  /// Continuous pixel position {column, row} of data point (x, y); pixel (c, r) covers
  /// [c, c + 1) x [r, r + 1), so floor() of the result is the pixel containing the point.
  std::array<double, 2> to_pixel(double px, double py) const {
    return {left + (px - x.lo) / (x.hi - x.lo) * width,
            top + height - (py - y.lo) / (y.hi - y.lo) * height};
  }
};

/// The recorded vector drawing of a figure (opaque: written by save_figure and save_svg).
class Drawing;

/// A rendered figure: the image, its axes (one per panel, top to bottom / left to right) and the
/// vector drawing the image was rasterised from (null for a figure made from pixels only).
struct Figure {
  Image image;
  std::vector<AxesFrame> axes;
  std::shared_ptr<const Drawing> drawing;
};

/// Writes `image` as a PNG file (deterministic bytes for identical pixels). Throws
/// somasim::InputError when the image is empty or the file cannot be written.
void save_png(const Image& image, const std::filesystem::path& path);

/// Writes the figure's vector drawing as an SVG file (text as glyph outlines, heatmap cells as
/// an embedded image); identical drawings give identical bytes. Throws somasim::InputError when
/// the figure has no drawing or the file cannot be written.
void save_svg(const Figure& figure, const std::filesystem::path& path);

/// Writes `png_path` and, when the figure has a vector drawing, the SVG of the same name beside
/// it (`x.png` -> `x.svg`). Throws somasim::InputError as save_png and save_svg.
void save_figure(const Figure& figure, const std::filesystem::path& png_path);

/// Reads a PNG (or any format OpenCV decodes) as RGB. Throws somasim::InputError when the file
/// is missing or cannot be decoded.
Image load_png(const std::filesystem::path& path);

}  // namespace somasim::figures
