// The summary figure of a sweep: one metric against one swept value, mean ± sd over seeds.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "somasim/diagnostics.hpp"
#include "somasim/error.hpp"
#include "somasim/figures/line_plot.hpp"
#include "somasim/sweep/collect.hpp"
#include "somasim/sweep/labels.hpp"
#include "somasim/yaml_text.hpp"

namespace somasim::sweep {

namespace {

std::size_t column(const SweepTable& t, const std::string& name) {
  return static_cast<std::size_t>(std::find(t.header.begin(), t.header.end(), name) -
                                  t.header.begin());
}

struct MeanSd {
  double mean = 0, sd = 0;
};

MeanSd mean_sd(const std::vector<double>& v) {
  MeanSd s;
  for (double x : v) s.mean += x;
  s.mean /= static_cast<double>(v.size());
  if (v.size() > 1) {
    for (double x : v) s.sd += (x - s.mean) * (x - s.mean);
    s.sd = std::sqrt(s.sd / static_cast<double>(v.size() - 1));  // sample sd over seeds
  }
  return s;
}

}  // namespace

int draw_summary(const SweepTable& table, const std::string& metric, const std::string& against,
                 const std::filesystem::path& png, const std::string& against_label) {
  const std::size_t status_col = column(table, "status");
  std::vector<std::string> metrics(table.header.begin() + static_cast<long>(status_col) + 1,
                                   table.header.end());
  const std::size_t m_col = column(table, metric);
  if (m_col <= status_col || m_col >= table.header.size())
    throw InputError("--metric '" + metric + "': no run of this sweep reports it" +
                     did_you_mean(metric, metrics) + "; metrics: " + join_names(metrics));
  if (std::find(table.axes.begin(), table.axes.end(), against) == table.axes.end())
    throw InputError("--against '" + against + "': not an axis of this sweep" +
                     did_you_mean(against, table.axes) +
                     "; expected one of: " + join_names(table.axes));
  const std::size_t x_col = column(table, against);
  // Non-numeric axis values are drawn at their position among the axis's values.
  std::vector<std::string> x_texts;
  for (const auto& row : table.rows)
    if (std::find(x_texts.begin(), x_texts.end(), row[x_col]) == x_texts.end())
      x_texts.push_back(row[x_col]);
  const bool numeric_x = std::all_of(x_texts.begin(), x_texts.end(), [](const std::string& s) {
    const auto v = parse_double(s);
    return v && std::isfinite(*v);
  });
  std::map<std::string, std::map<double, std::vector<double>>> groups;  // others -> x -> values
  for (const auto& row : table.rows) {
    const auto y = parse_double(row[m_col]);
    if (row[status_col] != "completed" || !y || !std::isfinite(*y)) continue;
    const double x =
        numeric_x ? *parse_double(row[x_col])
                  : static_cast<double>(std::find(x_texts.begin(), x_texts.end(), row[x_col]) -
                                        x_texts.begin());
    std::string others;
    for (const auto& a : table.axes)
      if (a != against)
        others += fmt::format("{}{} = {}", others.empty() ? "" : ", ",
                              a.substr(a.rfind('.') == std::string::npos ? 0 : a.rfind('.') + 1),
                              row[column(table, a)]);
    groups[others][x].push_back(*y);
  }
  if (groups.empty())
    throw InputError("--metric '" + metric + "': no completed run has a number for it");
  std::size_t most_seeds = 0;
  for (const auto& [others, by_x] : groups)
    for (const auto& [x, ys] : by_x) most_seeds = std::max(most_seeds, ys.size());
  const std::string x_words =
      against_label.empty() ? parameter_label(against, "", "") : against_label;
  const std::size_t dot = against.rfind('.');
  figures::LinePlotSpec plot;
  std::string title =
      fmt::format("{} against the swept {}: mean ± 1 sd over {} seed{}", metric_label(metric),
                  dot == std::string::npos ? against : against.substr(dot + 1), most_seeds,
                  most_seeds == 1 ? "" : "s");
  title[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(title[0])));
  plot.title = title;
  plot.x_label = numeric_x ? x_words : x_words + " (value index)";
  plot.y_label = metric_label(metric);
  int points = 0;
  std::size_t colour = 0;
  for (const auto& [others, by_x] : groups) {
    const figures::Color c = figures::palette()[colour++ % figures::palette().size()];
    figures::Series mean, low, high;
    for (const auto& [x, ys] : by_x) {
      const MeanSd s = mean_sd(ys);
      mean.x.push_back(x), low.x.push_back(x), high.x.push_back(x);
      mean.y.push_back(s.mean), low.y.push_back(s.mean - s.sd), high.y.push_back(s.mean + s.sd);
      ++points;
    }
    mean.label = others.empty() ? "mean" : others;
    mean.marker = figures::Marker::kCircle;
    low.style = high.style = figures::LineStyle::kDotted;
    low.width_px = high.width_px = 1.0;
    low.color = high.color = mean.color = c;
    if (groups.size() == 1) low.label = "mean ± 1 sd";
    plot.series.insert(plot.series.end(), {mean, low, high});
  }
  figures::save_figure(figures::render_line_plot(plot), png);
  return points;
}

}  // namespace somasim::sweep
