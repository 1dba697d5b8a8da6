#include "presentation_trace.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <fmt/format.h>

#include "somasim/figures/line_plot.hpp"

namespace somasim::plugins {
namespace {
/// "left_forearm" -> "left forearm".
std::string human(std::string name) {
  std::replace(name.begin(), name.end(), '_', ' ');
  return name;
}
}  // namespace

void PresentationTrace::add_sample(double t, const std::vector<double>& distances,
                                   const std::vector<double>& activations, double speed) {
  time_s.push_back(t);
  for (double d : distances) distance_m.push_back(static_cast<float>(d));
  for (double a : activations) activation.push_back(static_cast<float>(a));
  controller_speed.push_back(speed);
}

void draw_presentation_figure(const PresentationTrace& trace, const PresentationRecord& record,
                              double threshold, int taxels, const std::filesystem::path& file) {
  namespace fig = somasim::figures;
  const std::size_t n = trace.taxel_ids.size(), samples = trace.time_s.size();
  // The most activated taxels (ties: the nearest one first).
  std::vector<double> peak(n, 0.0), nearest(n, INFINITY);
  for (std::size_t s = 0; s < samples; ++s)
    for (std::size_t k = 0; k < n; ++k) {
      peak[k] = std::max(peak[k], static_cast<double>(trace.activation[s * n + k]));
      const double d = trace.distance_m[s * n + k];
      if (std::isfinite(d)) nearest[k] = std::min(nearest[k], d);
    }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return peak[a] != peak[b] ? peak[a] > peak[b] : nearest[a] < nearest[b];
  });
  // The taxel of the first trigger comes first.
  const auto trig =
      std::find(trace.taxel_ids.begin(), trace.taxel_ids.end(), record.trigger_taxel_id);
  if (trig != trace.taxel_ids.end()) {
    const auto k = static_cast<std::size_t>(trig - trace.taxel_ids.begin());
    order.erase(std::find(order.begin(), order.end(), k));
    order.insert(order.begin(), k);
  }
  order.resize(std::min<std::size_t>(order.size(), static_cast<std::size_t>(taxels)));

  fig::LinePlotSpec distance, activation, speed;
  distance.y_label = "distance to the skin [cm]";
  activation.y_label = "PPS activation";
  activation.y_range = fig::Range{0.0, 1.05};
  fig::RefLine threshold_line;
  threshold_line.value = threshold;
  threshold_line.label = fmt::format("threshold {:.2f}", threshold);
  activation.hlines.push_back(threshold_line);
  speed.y_label = "arm speed [m/s]";
  for (std::size_t k : order) {
    fig::Series d, a;
    d.label = a.label =
        fmt::format("taxel {}{}", trace.taxel_ids[k],
                    trace.taxel_ids[k] == record.trigger_taxel_id ? " (trigger)" : "");
    for (std::size_t s = 0; s < samples; ++s) {
      d.x.push_back(trace.time_s[s] - record.start_s);
      d.y.push_back(100.0 * trace.distance_m[s * n + k]);
      a.y.push_back(trace.activation[s * n + k]);
    }
    a.x = d.x;
    distance.series.push_back(std::move(d));
    activation.series.push_back(std::move(a));
  }
  distance.hlines.push_back({0.0, "skin", fig::Color{90, 90, 90}, fig::LineStyle::kDotted});
  fig::Series v;
  v.label = "controller";
  v.color = fig::Color{0, 0, 0};
  for (std::size_t s = 0; s < samples; ++s) {
    v.x.push_back(trace.time_s[s] - record.start_s);
    v.y.push_back(trace.controller_speed[s]);
  }
  double top = 0.12;
  for (double x : v.y)
    if (std::isfinite(x)) top = std::max(top, 1.1 * x);
  speed.series.push_back(std::move(v));
  speed.y_range = fig::Range{0.0, top};
  for (auto* p : {&distance, &activation, &speed}) {
    if (record.triggered)
      p->vlines.push_back({record.trigger_time_s - record.start_s,
                           p == &distance ? "first trigger" : "", fig::Color{214, 39, 40}});
    if (record.skin_contact)
      p->vlines.push_back({record.contact_time_s - record.start_s,
                           p == &distance ? "skin contact" : "", fig::Color{148, 103, 189},
                           fig::LineStyle::kDotted});
  }
  fig::StackedPlotSpec spec;
  spec.title = fmt::format("Presentation {}: {} {} aimed at taxel {} of the {}", record.id,
                           motion_name(record.motion), record.shape, record.taxel_id,
                           human(record.body_part));
  spec.x_label = "time since presentation [s]";
  spec.panels = {distance, activation, speed};
  fig::save_figure(fig::render_stacked(spec), file);
}

}  // namespace somasim::plugins
