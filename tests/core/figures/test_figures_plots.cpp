#include <cmath>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "somasim/error.hpp"
#include "somasim/figures/compose.hpp"
#include "somasim/figures/image_grid.hpp"
#include "somasim/figures/line_plot.hpp"
#include "somasim/figures/scatter.hpp"
#include "temp_png.hpp"

namespace fig = somasim::figures;
using fig::test::TempDir;

namespace {

fig::Color pixel_at(const fig::Figure& g, std::size_t axes, double x, double y) {
  const auto p = g.axes.at(axes).to_pixel(x, y);
  return g.image.at(static_cast<int>(std::floor(p[0])), static_cast<int>(std::floor(p[1])));
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const somasim::InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

fig::LinePlotSpec flat_plot() {
  fig::LinePlotSpec s;
  s.title = "activation";
  s.x_label = "time [s]";
  s.y_label = "activation";
  s.series.push_back({{0, 1, 2, 3, 4}, {0.5, 0.5, 0.5, 0.5, 0.5}, "taxel 3"});
  s.series.back().width_px = 4;
  s.y_range = fig::Range{0, 1};
  return s;
}

const fig::Color kWhite{255, 255, 255};

}  // namespace

TEST(LinePlot, SeriesIsDrawnInThePaletteColourAtItsDataPoints) {
  const auto g = fig::render_line_plot(flat_plot());
  EXPECT_EQ(g.image.width, 900);
  EXPECT_EQ(g.image.height, 600);
  ASSERT_EQ(g.axes.size(), 1u);
  EXPECT_EQ(g.axes[0].x, (fig::Range{0, 4}));  // data extent
  EXPECT_EQ(g.axes[0].y, (fig::Range{0, 1}));  // fixed
  for (double x : {0.5, 1.7, 3.3}) EXPECT_EQ(pixel_at(g, 0, x, 0.5), fig::palette()[0]) << x;
  EXPECT_EQ(pixel_at(g, 0, 2.3, 0.7), kWhite);  // background away from the line and grid
}

TEST(LinePlot, NanBreaksTheLine) {
  fig::LinePlotSpec s = flat_plot();
  s.series[0].y[2] = std::nan("");
  s.grid = false;
  const auto g = fig::render_line_plot(s);
  EXPECT_EQ(pixel_at(g, 0, 0.5, 0.5), fig::palette()[0]);
  EXPECT_EQ(pixel_at(g, 0, 2.0, 0.5), kWhite);
}

TEST(LinePlot, DashedThresholdHasDashesAndGaps) {
  fig::LinePlotSpec s = flat_plot();
  s.grid = false;
  s.legend = fig::LegendPosition::kNone;
  s.hlines.push_back({0.25, "threshold", fig::Color{200, 0, 0}});
  const auto g = fig::render_line_plot(s);
  const auto& f = g.axes[0];
  const int row = static_cast<int>(std::floor(f.to_pixel(0, 0.25)[1]));
  int red = 0, white = 0;
  for (int x = f.left + 2; x < f.left + f.width - 2; ++x) {
    const auto c = g.image.at(x, row);
    red += c == fig::Color{200, 0, 0};
    white += c == kWhite;
  }
  EXPECT_GT(red, f.width / 4);
  EXPECT_GT(white, f.width / 8);
}

TEST(LinePlot, AutoYRangeIncludesTheReferenceLinesAndIsPadded) {
  fig::LinePlotSpec s = flat_plot();
  s.y_range.reset();
  s.series[0].y = {0.0, 0.1, 0.2, 0.3, 0.2};
  s.hlines.push_back({0.8, "threshold"});
  const auto g = fig::render_line_plot(s);
  EXPECT_NEAR(g.axes[0].y.lo, -0.04, 1e-12);
  EXPECT_NEAR(g.axes[0].y.hi, 0.84, 1e-12);
}

TEST(LinePlot, MismatchedSeriesThrows) {
  fig::LinePlotSpec s = flat_plot();
  s.series.push_back({{0, 1, 2}, {0, 1}, "a"});
  EXPECT_EQ(message_of([&] { fig::render_line_plot(s); }),
            "line plot: series 'a' has 3 x values but 2 y values");
  s = flat_plot();
  s.y_range = fig::Range{1, 0};
  EXPECT_EQ(message_of([&] { fig::render_line_plot(s); }),
            "line plot: y range [1, 0] is invalid; expected finite lo < hi");
}

TEST(LinePlot, SameInputGivesIdenticalBytes) {
  TempDir dir;
  fig::LinePlotSpec s = flat_plot();
  s.hlines.push_back({0.25, "threshold"});
  s.title = "Activation of taxel 3 (°, σ, Δ)";
  fig::save_figure(fig::render_line_plot(s), dir.path() / "a.png");
  fig::save_figure(fig::render_line_plot(s), dir.path() / "b.png");
  for (const char* ext : {".png", ".svg"})
    EXPECT_EQ(fig::test::read_bytes(dir.path() / (std::string("a") + ext)),
              fig::test::read_bytes(dir.path() / (std::string("b") + ext)))
        << ext;
}

TEST(Stacked, PanelsShareTheXAxisAndStackTopToBottom) {
  fig::StackedPlotSpec st;
  st.title = "approach";
  st.x_label = "time [s]";
  for (int i = 0; i < 3; ++i) {
    fig::LinePlotSpec p = flat_plot();
    p.title = "panel " + std::to_string(i);
    p.series[0].x = {0.0, 2.0 + i};  // different extents: the shared range is the union
    p.series[0].y = {0.5, 0.5};
    st.panels.push_back(p);
  }
  const auto g = fig::render_stacked(st);
  ASSERT_EQ(g.axes.size(), 3u);
  EXPECT_EQ(g.image.width, 900);
  EXPECT_GT(g.image.height, 3 * st.panel_height);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(g.axes[i].left, g.axes[0].left);
    EXPECT_EQ(g.axes[i].width, g.axes[0].width);
    EXPECT_EQ(g.axes[i].height, st.panel_height);
    EXPECT_EQ(g.axes[i].x, (fig::Range{0, 4}));
    if (i > 0) {
      EXPECT_GT(g.axes[i].top, g.axes[i - 1].top + g.axes[i - 1].height);
    }
    EXPECT_EQ(pixel_at(g, i, 1.0, 0.5), fig::palette()[0]) << i;
  }
  EXPECT_LT(g.axes[2].top + g.axes[2].height, g.image.height - 30);  // x labels below
}

TEST(Stacked, NoPanelsThrows) {
  EXPECT_EQ(message_of([] { fig::render_stacked(fig::StackedPlotSpec{}); }),
            "stacked plot: no panels; expected at least one");
}

TEST(Scatter, GroupsByCategoryInAscendingOrder) {
  const auto groups =
      fig::group_by_category({1, 2, 3, 4}, {5, 6, 7, 8}, {7, 3, 7, 3}, {"three", "seven"});
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(groups[0].label, "three");
  EXPECT_EQ(groups[0].x, (std::vector<double>{2, 4}));
  EXPECT_EQ(groups[1].label, "seven");
  EXPECT_EQ(groups[1].y, (std::vector<double>{5, 7}));
  EXPECT_EQ(message_of([] {
              fig::group_by_category({1}, {1, 2}, {0});
            }),
            "scatter: group_by_category got 1 x, 2 y and 1 category values; expected equal sizes");
}

TEST(Scatter, MarkersInCategoryColoursAndEqualAspect) {
  fig::ScatterSpec s;
  s.title = "layout";
  s.x_label = "x [mm]";
  s.y_label = "y [mm]";
  s.groups = fig::group_by_category({0, 10, 20, 30}, {0, 5, 0, 5}, {0, 1, 0, 1}, {"a", "b"});
  s.equal_aspect = true;
  s.legend = fig::LegendPosition::kNone;
  const auto g = fig::render_scatter(s);
  const auto& f = g.axes.at(0);
  EXPECT_NEAR((f.x.hi - f.x.lo) / f.width, (f.y.hi - f.y.lo) / f.height, 1e-9);
  EXPECT_EQ(pixel_at(g, 0, 10, 5), fig::palette()[1]);
  EXPECT_EQ(pixel_at(g, 0, 20, 0), fig::palette()[0]);
  s.groups[0].y.pop_back();
  EXPECT_EQ(message_of([&] { fig::render_scatter(s); }),
            "scatter: group 'a' has 2 x values but 1 y values");
}

TEST(Compose, RowPlacesFiguresSideBySide) {
  const auto a = fig::render_line_plot(flat_plot());
  fig::LinePlotSpec small = flat_plot();
  small.width = 400;
  small.height = 300;
  const auto b = fig::render_line_plot(small);
  const auto row = fig::compose_row({a, b}, 10);
  EXPECT_EQ(row.image.width, 900 + 10 + 400);
  EXPECT_EQ(row.image.height, 600);
  ASSERT_EQ(row.axes.size(), 2u);
  EXPECT_EQ(row.axes[0].left, a.axes[0].left);
  EXPECT_EQ(row.axes[1].left, b.axes[0].left + 910);
  EXPECT_EQ(row.axes[1].top, b.axes[0].top);
  for (int y : {0, 100, 299})
    for (int x : {0, 123, 399}) EXPECT_EQ(row.image.at(910 + x, y), b.image.at(x, y));
  EXPECT_EQ(row.image.at(905, 10), kWhite);    // the gap
  EXPECT_EQ(row.image.at(1000, 450), kWhite);  // below the shorter figure
  EXPECT_EQ(pixel_at(row, 1, 1.0, 0.5), fig::palette()[0]);

  const auto col = fig::compose_column({a, b}, 0, "both");
  EXPECT_EQ(col.image.width, 900);
  EXPECT_GT(col.image.height, 900);
  EXPECT_EQ(message_of([] { fig::compose_row({}); }), "compose_row: no figures to compose");
}

TEST(Legend, OnlyWhatIsDrawnInsideTheAxesGetsAnEntry) {
  // A series wholly outside the shown x range adds nothing to the figure: not even a legend line.
  fig::LinePlotSpec s = flat_plot();
  s.x_range = fig::Range{0, 4};
  const auto without = fig::render_line_plot(s);
  s.series.push_back({{10, 11}, {0.2, 0.3}, "outside the axes"});
  const auto with = fig::render_line_plot(s);
  EXPECT_EQ(with.image.rgb, without.image.rgb);

  fig::ScatterSpec sc;
  sc.groups.push_back({{0, 1}, {0, 1}, "seen"});
  sc.x_range = fig::Range{-1, 2};
  sc.y_range = fig::Range{-1, 2};
  const auto seen = fig::render_scatter(sc);
  sc.groups.push_back({{5, 6}, {5, 6}, "not seen"});
  EXPECT_EQ(fig::render_scatter(sc).image.rgb, seen.image.rgb);
}

TEST(Text, AnyUtf8IsDrawnAndInvalidBytesDoNotStopAFigure) {
  fig::LinePlotSpec s = flat_plot();
  const auto plain = fig::render_line_plot(s);
  s.title = "Orientation error [°] of σ-points, Δt = 5 ms";
  const auto unicode = fig::render_line_plot(s);
  EXPECT_NE(unicode.image.rgb, plain.image.rgb);
  s.title = std::string("bad bytes \xff\xfe here");
  EXPECT_NO_THROW(fig::render_line_plot(s));
  s.title = std::string(2000, 'W');  // shrunk to the figure's width, never clipped or thrown
  EXPECT_NO_THROW(fig::render_line_plot(s));
}

TEST(Compose, KeepsTheVectorDrawingOfItsPanels) {
  TempDir dir;
  const auto row = fig::compose_row(
      {fig::render_line_plot(flat_plot()), fig::render_line_plot(flat_plot())}, 10, "Two panels");
  ASSERT_NE(row.drawing, nullptr);
  fig::save_figure(row, dir.path() / "row.png");
  const std::string svg = fig::test::read_bytes(dir.path() / "row.svg");
  EXPECT_NE(svg.find("width=\"1810\""), std::string::npos);
  EXPECT_EQ(svg.find("<image"), std::string::npos);  // lines and text stay vectors

  // A figure made from pixels only composes too, and has no SVG to write.
  fig::Figure pixels{fig::render_line_plot(flat_plot()).image, {}, nullptr};
  const auto mixed = fig::compose_row({pixels}, 0);
  EXPECT_EQ(mixed.image.rgb, pixels.image.rgb);
  EXPECT_THROW(fig::save_svg(pixels, dir.path() / "p.svg"), somasim::InputError);
  fig::save_figure(pixels, dir.path() / "p.png");
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "p.png"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "p.svg"));
}

TEST(Determinism, FiguresDrawnOnOtherThreadsGiveTheSameBytes) {
  TempDir dir;
  fig::LinePlotSpec s = flat_plot();
  s.title = "Distance to the skin [cm] against time";
  fig::save_figure(fig::render_line_plot(s), dir.path() / "main.png");
  std::vector<std::thread> threads;
  for (int i = 0; i < 3; ++i)
    threads.emplace_back([&, i] {
      fig::save_figure(fig::render_line_plot(s), dir.path() / ("t" + std::to_string(i) + ".png"));
    });
  for (auto& t : threads) t.join();
  for (int i = 0; i < 3; ++i)
    for (const char* ext : {".png", ".svg"})
      EXPECT_EQ(fig::test::read_bytes(dir.path() / ("t" + std::to_string(i) + ext)),
                fig::test::read_bytes(dir.path() / (std::string("main") + ext)))
          << i << ext;
}

TEST(ImageGrid, ImagesKeepTheirPixelsAndSizesMustAgree) {
  fig::Image red{20, 10, std::vector<std::uint8_t>(20 * 10 * 3, 0)};
  for (std::size_t i = 0; i < red.rgb.size(); i += 3) red.rgb[i] = 200;
  fig::ImageGridSpec s;
  s.column_titles = {"left_eye", "right_eye"};
  s.rows = {{red, red}, {red, red}};
  const auto g = fig::render_image_grid(s);
  ASSERT_NE(g.drawing, nullptr);
  // Bottom-right image: its bottom-right pixel, 4 px from the figure's corner.
  EXPECT_EQ(g.image.at(g.image.width - 5, g.image.height - 5), (fig::Color{200, 0, 0}));
  s.rows[1][1].width = 19;
  EXPECT_EQ(message_of([&] { fig::render_image_grid(s); }),
            "image grid: image (1, 1) is 19 x 10 px; expected every image 20 x 10 px");
  EXPECT_EQ(message_of([] { fig::render_image_grid({}); }),
            "image grid: no images; expected at least one row with one image");
}

TEST(Robustness, PointsFarOffOrNotFiniteNeverSpoilTheRest) {
  // A point 1e7 plot heights away: its segment leaves the axes at the top, nothing wraps around.
  fig::LinePlotSpec s = flat_plot();
  s.series = {{{0, 1}, {0.5, 1e7}, "steep"}};
  s.x_range = fig::Range{0, 1};
  s.grid = false;
  const auto g2 = fig::render_line_plot(s);
  for (double x : {0.3, 0.55, 0.93})
    for (double y : {0.1, 0.33, 0.53, 0.9})
      EXPECT_EQ(pixel_at(g2, 0, x, y), kWhite) << x << ", " << y;
  // An annotated point at NaN: skipped, and the axes, legend and title are still drawn.
  fig::ScatterSpec sc;
  sc.title = "Title";
  sc.groups.push_back({{0, 1, NAN}, {0, 1, 2}, "points"});
  sc.groups.back().annotations = {"a", "b", "c"};
  const auto with_nan = fig::render_scatter(sc);
  sc.groups.back().annotations = {"a", "b", ""};
  EXPECT_EQ(with_nan.image.rgb, fig::render_scatter(sc).image.rgb);
  // Figures larger than cairo can draw are refused, not crashed on.
  s.width = 40000;
  EXPECT_EQ(message_of([&] { fig::render_line_plot(s); }),
            "line plot: figure size 40000 x 600 px is too large; expected 200 x 150 to 32767 x "
            "32767");
}
