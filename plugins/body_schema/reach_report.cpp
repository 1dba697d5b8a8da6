#include "reach_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "sample_stats.hpp"
#include "somasim/atomic_file.hpp"
#include "somasim/error.hpp"
#include "somasim/figures/compose.hpp"
#include "somasim/figures/figure.hpp"
#include "somasim/figures/line_plot.hpp"

namespace somasim::plugins {
namespace {

using Field = double FrameErrors::*;

}  // namespace

ReachReport::ReachReport(int open_loop_frames, int closed_loop_frames)
    : open_frames_(open_loop_frames), closed_frames_(closed_loop_frames) {}

void ReachReport::add(const MovementId& id, int frame, const FrameErrors& errors) {
  rows_.push_back({id, frame, errors});
}

nlohmann::json ReachReport::metrics() const {
  nlohmann::json m;
  const int end_open = open_frames_, end_closed = open_frames_ + closed_frames_;
  auto values = [&](Field f, int frame) {
    std::vector<double> v;
    for (const Row& r : rows_)
      if (r.frame == frame) v.push_back(r.e.*f);
    return v;
  };
  auto put = [&](const std::string& key, Field f, int frame) {
    const MeanSd s = mean_sd(values(f, frame));
    m[key] = s.n > 0 ? nlohmann::json(s.mean) : nlohmann::json(nullptr);
    m[key + "_sd"] = s.n > 0 ? nlohmann::json(s.sd) : nlohmann::json(nullptr);
  };
  m["reach_movements"] = completed_;
  m["reach_movements_at_frame_" + std::to_string(end_open)] =
      static_cast<int>(values(&FrameErrors::estimation_mm, end_open).size());
  put("estimation_error_mm", &FrameErrors::estimation_mm, end_open);
  put("estimation_error_deg", &FrameErrors::estimation_deg, end_open);
  put("estimation_error_nominal_mm", &FrameErrors::nominal_mm, end_open);
  put("estimation_error_nominal_deg", &FrameErrors::nominal_deg, end_open);
  put("estimation_error_final_mm", &FrameErrors::estimation_mm, end_closed);
  put("estimation_error_final_deg", &FrameErrors::estimation_deg, end_closed);
  put("reaching_error_open_loop_mm", &FrameErrors::reaching_mm, end_open);
  put("reaching_error_open_loop_deg", &FrameErrors::reaching_deg, end_open);
  put("reaching_error_closed_loop_mm", &FrameErrors::reaching_mm, end_closed);
  put("reaching_error_closed_loop_deg", &FrameErrors::reaching_deg, end_closed);
  put("reaching_error_estimated_closed_loop_mm", &FrameErrors::reaching_est_mm, end_closed);
  put("reaching_error_estimated_closed_loop_deg", &FrameErrors::reaching_est_deg, end_closed);
  auto ratio = [&](const std::string& key, const std::string& num, const std::string& den) {
    const bool ok = m[num].is_number() && m[den].is_number() && m[den].get<double>() > 0;
    m[key] =
        ok ? nlohmann::json(m[num].get<double>() / m[den].get<double>()) : nlohmann::json(nullptr);
  };
  ratio("estimation_gain_position", "estimation_error_nominal_mm", "estimation_error_mm");
  ratio("estimation_gain_orientation", "estimation_error_nominal_deg", "estimation_error_deg");
  ratio("closed_loop_gain_position", "reaching_error_open_loop_mm",
        "reaching_error_closed_loop_mm");
  ratio("closed_loop_gain_orientation", "reaching_error_open_loop_deg",
        "reaching_error_closed_loop_deg");
  return m;
}

void ReachReport::write_csv(const std::filesystem::path& file) const {
  std::ostringstream out;
  out << "movement,target,start,repetition,frame,estimation error [mm],estimation error [deg],"
         "nominal error [mm],nominal error [deg],reaching error [mm],reaching error [deg],"
         "estimated reaching error [mm],estimated reaching error [deg]\n";
  for (const Row& r : rows_)
    out << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{}\n", r.id.movement, r.id.target,
                       r.id.start, r.id.repetition, r.frame, r.e.estimation_mm, r.e.estimation_deg,
                       r.e.nominal_mm, r.e.nominal_deg, r.e.reaching_mm, r.e.reaching_deg,
                       r.e.reaching_est_mm, r.e.reaching_est_deg);
  try {
    write_file_atomically(file, out.str());
  } catch (const std::runtime_error& e) {
    throw RunError(fmt::format("reach_controller: {}", e.what()));
  }
}

namespace {

// Mean and mean ± sd curves per frame in [first, last] of (frame, value) samples.
std::vector<figures::Series> band(const std::vector<std::pair<int, double>>& samples, int first,
                                  int last, const std::string& label, figures::Color colour,
                                  figures::LineStyle style) {
  std::map<int, std::vector<double>> by_frame;
  for (const auto& [frame, v] : samples)
    if (frame >= first && frame <= last) by_frame[frame].push_back(v);
  figures::Series mean, low, high;
  for (const auto& [frame, v] : by_frame) {
    const MeanSd s = mean_sd(v);
    mean.x.push_back(frame), low.x.push_back(frame), high.x.push_back(frame);
    mean.y.push_back(s.mean), low.y.push_back(s.mean - s.sd), high.y.push_back(s.mean + s.sd);
  }
  mean.label = label;
  mean.color = low.color = high.color = colour;
  mean.style = style;
  low.style = high.style = figures::LineStyle::kDotted;
  low.width_px = high.width_px = 1.0;
  return {mean, low, high};
}

}  // namespace

void ReachReport::write_figures(const std::filesystem::path& estimation,
                                const std::filesystem::path& reaching,
                                const std::filesystem::path& closed_loop,
                                const std::string& title) const {
  const int end = open_frames_ + closed_frames_;
  auto samples = [&](Field f) {
    std::vector<std::pair<int, double>> s;
    for (const Row& r : rows_) s.emplace_back(r.frame, r.e.*f);
    return s;
  };
  const figures::Color blue{31, 119, 180}, red{214, 39, 40}, black{20, 20, 20}, green{44, 160, 44};
  using figures::LineStyle;
  auto panel = [&](const std::string& panel_title, const std::string& y_label, int first,
                   const std::vector<std::vector<figures::Series>>& bands) {
    figures::LinePlotSpec p;
    p.title = panel_title;
    p.x_label = "camera frame (one per image pair)";
    p.y_label = y_label;
    for (const auto& b : bands) p.series.insert(p.series.end(), b.begin(), b.end());
    figures::RefLine end_of_open_loop;
    end_of_open_loop.value = static_cast<double>(open_frames_);
    end_of_open_loop.label = "end of open loop";
    p.vlines.push_back(end_of_open_loop);
    p.x_range = figures::Range{static_cast<double>(first), static_cast<double>(end)};
    p.width = 760;
    p.height = 440;
    return figures::render_line_plot(p);
  };
  auto pair = [&](const std::string& what, int first, Field mm_a, Field deg_a,
                  const std::string& label_a, figures::Color colour_a, Field mm_b, Field deg_b,
                  const std::string& label_b, figures::Color colour_b) {
    auto bands = [&](Field a, Field b) {
      return std::vector<std::vector<figures::Series>>{
          band(samples(a), first, end, label_a, colour_a, LineStyle::kSolid),
          band(samples(b), first, end, label_b, colour_b, LineStyle::kDashed)};
    };
    return figures::compose_row(
        {panel("Position", "position error [mm]", first, bands(mm_a, mm_b)),
         panel("Orientation", "orientation error [°]", first, bands(deg_a, deg_b))},
        16,
        fmt::format("{} over {} movements, {} (lines: mean; dotted: mean ± 1 sd)", what, completed_,
                    title));
  };
  figures::save_figure(
      pair("Hand pose estimation error", 1, &FrameErrors::estimation_mm,
           &FrameErrors::estimation_deg, "with adaptation", blue, &FrameErrors::nominal_mm,
           &FrameErrors::nominal_deg, "nominal model", red),
      estimation);
  figures::save_figure(
      pair("Reaching error", 1, &FrameErrors::reaching_mm, &FrameErrors::reaching_deg, "real",
           black, &FrameErrors::reaching_est_mm, &FrameErrors::reaching_est_deg, "estimated",
           green),
      reaching);
  const int first_close = std::max(1, open_frames_ - 10);
  figures::save_figure(
      pair("Reaching error in closed loop", first_close, &FrameErrors::reaching_mm,
           &FrameErrors::reaching_deg, "real", black, &FrameErrors::reaching_est_mm,
           &FrameErrors::reaching_est_deg, "estimated", green),
      closed_loop);
}

}  // namespace somasim::plugins
