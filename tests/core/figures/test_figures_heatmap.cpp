#include <cmath>

#include <gtest/gtest.h>

#include "somasim/error.hpp"
#include "somasim/figures/heatmap.hpp"
#include "temp_png.hpp"

namespace fig = somasim::figures;
using fig::test::TempDir;

namespace {

/// Data coordinates of the centre of the pixel that contains data point (x, y).
std::array<double, 2> pixel_centre_data(const fig::AxesFrame& f, double x, double y) {
  const auto p = f.to_pixel(x, y);
  const double cx = std::floor(p[0]) + 0.5, cy = std::floor(p[1]) + 0.5;
  return {f.x.lo + (cx - f.left) / f.width * (f.x.hi - f.x.lo),
          f.y.lo + (f.top + f.height - cy) / f.height * (f.y.hi - f.y.lo)};
}

fig::Color pixel_at(const fig::Figure& g, double x, double y) {
  const auto p = g.axes.at(0).to_pixel(x, y);
  return g.image.at(static_cast<int>(std::floor(p[0])), static_cast<int>(std::floor(p[1])));
}

/// 2 x 11 samples over x in [0, 10]: value = x / 10 (a gradient along x).
fig::HeatmapSpec x_gradient() {
  fig::HeatmapSpec s;
  s.grid.rows = 2;
  s.grid.cols = 11;
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 11; ++c) s.grid.values.push_back(c / 10.0);
  s.x_min = 0;
  s.x_max = 10;
  s.y_min = 0;
  s.y_max = 3;
  s.title = "gradient";
  s.x_label = "D [cm]";
  s.y_label = "TTC [s]";
  s.colorbar_label = "activation";
  return s;
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const somasim::InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

}  // namespace

TEST(Heatmap, DefaultSizeAndAxesFrameInsideTheImage) {
  const auto g = fig::render_heatmap(x_gradient());
  EXPECT_EQ(g.image.width, 900);
  EXPECT_EQ(g.image.height, 600);
  ASSERT_EQ(g.axes.size(), 1u);
  const auto& f = g.axes[0];
  EXPECT_GT(f.left, 40);                  // room for tick labels and the y label
  EXPECT_GT(f.top, 20);                   // room for the title
  EXPECT_LT(f.left + f.width, 900 - 80);  // room for the colour bar
  EXPECT_LT(f.top + f.height, 600 - 40);  // room for tick labels and the x label
  EXPECT_EQ(f.x, (fig::Range{0, 10}));
  EXPECT_EQ(f.y, (fig::Range{0, 3}));
}

TEST(Heatmap, GradientAlongXHasTheColourOfTheValueAtEachDataPoint) {
  const auto g = fig::render_heatmap(x_gradient());
  for (double x : {0.7, 2.5, 5.0, 7.5, 9.3}) {
    const auto c = pixel_centre_data(g.axes[0], x, 1.5);
    EXPECT_EQ(pixel_at(g, x, 1.5), fig::colormap_color(fig::Colormap::kViridis, c[0] / 10))
        << "x = " << x;
  }
  // Low values dark, high values bright (viridis: purple -> yellow).
  const auto lo = pixel_at(g, 0.2, 1.5), hi = pixel_at(g, 9.8, 1.5);
  EXPECT_LT(lo.r + lo.g, hi.r + hi.g);
}

TEST(Heatmap, RowZeroIsAtTheBottomAndYGrowsUpwards) {
  fig::HeatmapSpec s = x_gradient();
  s.layout = fig::GridLayout::kCells;
  s.resampling = fig::Resampling::kNearest;
  s.colormap = fig::Colormap::kJet;
  // 2 x 2 cells: bottom row {0, 1/3}, top row {2/3, 1}.
  s.grid = fig::Grid::row_major(2, 2, {0.0, 1.0 / 3, 2.0 / 3, 1.0});
  const auto g = fig::render_heatmap(s);
  const auto jet = [](double t) { return fig::colormap_color(fig::Colormap::kJet, t); };
  EXPECT_EQ(pixel_at(g, 2.5, 0.75), jet(0.0));      // bottom-left cell
  EXPECT_EQ(pixel_at(g, 7.5, 0.75), jet(1.0 / 3));  // bottom-right
  EXPECT_EQ(pixel_at(g, 2.5, 2.25), jet(2.0 / 3));  // top-left
  EXPECT_EQ(pixel_at(g, 7.5, 2.25), jet(1.0));      // top-right
  EXPECT_EQ(jet(1.0), (fig::Color{128, 0, 0}));     // dark red: really the top of jet
}

TEST(Heatmap, EigenMatrixRowsRunAlongY) {
  Eigen::MatrixXd m(2, 2);
  m << 0.0, 1.0 / 3, 2.0 / 3, 1.0;
  const fig::Grid g = fig::Grid::from_matrix(m);
  EXPECT_EQ(g.rows, 2);
  EXPECT_EQ(g.cols, 2);
  EXPECT_EQ(g.values, (std::vector<double>{0.0, 1.0 / 3, 2.0 / 3, 1.0}));
}

TEST(Heatmap, AutoValueRangeSpansTheFiniteValuesAndNanIsGrey) {
  fig::HeatmapSpec s = x_gradient();
  s.layout = fig::GridLayout::kCells;
  s.resampling = fig::Resampling::kNearest;
  s.grid = fig::Grid::row_major(1, 3, {10.0, std::nan(""), 20.0});
  s.value_range.reset();
  const auto g = fig::render_heatmap(s);
  EXPECT_EQ(pixel_at(g, 1.5, 1.5), fig::colormap_color(fig::Colormap::kViridis, 0.0));
  EXPECT_EQ(pixel_at(g, 5.0, 1.5), (fig::Color{225, 225, 225}));
  EXPECT_EQ(pixel_at(g, 8.5, 1.5), fig::colormap_color(fig::Colormap::kViridis, 1.0));
}

TEST(Heatmap, OverlayLineIsDrawnInItsColourOverTheMap) {
  fig::HeatmapSpec s = x_gradient();
  s.lines.push_back({{1, 9}, {1.5, 1.5}, "regression", fig::Color{255, 0, 0}, 4});
  s.points.push_back({{5}, {2.5}, "sample", fig::Color{255, 255, 255}, fig::Marker::kSquare, 12});
  const auto g = fig::render_heatmap(s);
  EXPECT_EQ(pixel_at(g, 5.0, 1.5), (fig::Color{255, 0, 0}));
  EXPECT_EQ(pixel_at(g, 5.0, 2.5), (fig::Color{255, 255, 255}));
  // Away from the overlays the map is untouched.
  const auto c = pixel_centre_data(g.axes[0], 5.0, 0.4);
  EXPECT_EQ(pixel_at(g, 5.0, 0.4), fig::colormap_color(fig::Colormap::kViridis, c[0] / 10));
}

TEST(Heatmap, WritesADecodablePngOfTheRenderedPixels) {
  TempDir dir;
  const auto g = fig::render_heatmap(x_gradient());
  const auto path = dir.path() / "map.png";
  fig::save_figure(g, path);
  ASSERT_TRUE(std::filesystem::exists(path));
  // The vector drawing beside it.
  const std::string svg = fig::test::read_bytes(dir.path() / "map.svg");
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("width=\"900\""), std::string::npos);
  EXPECT_NE(svg.find("<image"), std::string::npos);  // the cells, embedded
  const fig::Image back = fig::load_png(path);
  EXPECT_EQ(back.width, 900);
  EXPECT_EQ(back.height, 600);
  EXPECT_EQ(back.rgb, g.image.rgb);
  // White background in the corner.
  EXPECT_EQ(back.at(1, 598), (fig::Color{255, 255, 255}));
}

TEST(Heatmap, SameInputGivesIdenticalBytes) {
  TempDir dir;
  fig::HeatmapSpec s = x_gradient();
  s.lines.push_back({{0, 10}, {0, 3}, "line"});
  s.x_edges = {0, 2.5, 5, 7.5, 10};
  s.title = "Activation over distance and time to contact";
  fig::save_figure(fig::render_heatmap(s), dir.path() / "a.png");
  fig::save_figure(fig::render_heatmap(s), dir.path() / "b.png");
  for (const char* ext : {".png", ".svg"}) {
    const auto a = fig::test::read_bytes(dir.path() / (std::string("a") + ext));
    EXPECT_FALSE(a.empty());
    EXPECT_EQ(a, fig::test::read_bytes(dir.path() / (std::string("b") + ext))) << ext;
  }
}

TEST(Heatmap, MismatchedGridSizeThrows) {
  fig::HeatmapSpec s = x_gradient();
  s.grid = fig::Grid::row_major(3, 4, std::vector<double>(10, 0.5));
  EXPECT_EQ(message_of([&] { fig::render_heatmap(s); }),
            "heatmap: grid has 10 values but rows x cols = 3 x 4 = 12");
}

TEST(Heatmap, EmptyGridThrows) {
  fig::HeatmapSpec s = x_gradient();
  s.grid = {};
  EXPECT_EQ(message_of([&] { fig::render_heatmap(s); }),
            "heatmap: grid is empty (0 rows x 0 cols, 0 values); expected at least one value");
}

TEST(Heatmap, SamplesNeedTwoPerAxis) {
  fig::HeatmapSpec s = x_gradient();
  s.grid = fig::Grid::row_major(1, 3, {0, 1, 2});
  EXPECT_EQ(message_of([&] { fig::render_heatmap(s); }),
            "heatmap: a kSamples grid needs at least 2 rows and 2 cols, got 1 x 3 (use "
            "GridLayout::kCells for bins)");
}

TEST(Heatmap, InvalidRangeAndOverlayThrow) {
  fig::HeatmapSpec s = x_gradient();
  s.x_max = s.x_min;
  EXPECT_EQ(message_of([&] { fig::render_heatmap(s); }),
            "heatmap: x range [0, 0] is invalid; expected finite lo < hi");
  s = x_gradient();
  s.lines.push_back({{0, 1, 2}, {0, 1}, "fit"});
  EXPECT_EQ(message_of([&] { fig::render_heatmap(s); }),
            "heatmap: line 'fit' has 3 x values but 2 y values");
  s = x_gradient();
  s.width = 100;
  EXPECT_EQ(message_of([&] { fig::render_heatmap(s); }),
            "heatmap: figure size 100 x 600 px is too small; expected 200 x 150 to 32767 x 32767");
}

TEST(SavePng, UnwritablePathThrows) {
  const auto g = fig::render_heatmap(x_gradient());
  EXPECT_EQ(message_of([&] { fig::save_figure(g, "/nonexistent_somasim_dir/map.png"); }),
            "cannot write PNG file '/nonexistent_somasim_dir/map.png': directory "
            "'/nonexistent_somasim_dir' does not exist");
  EXPECT_EQ(message_of([&] { fig::save_png(fig::Image{}, "x.png"); }),
            "cannot write PNG file 'x.png': the image is empty or its pixel buffer does not "
            "match its size");
}

TEST(LoadPng, MissingFileThrows) {
  EXPECT_EQ(message_of([&] { fig::load_png("/nonexistent_somasim_dir/map.png"); }),
            "cannot read image '/nonexistent_somasim_dir/map.png': no such file");
}
