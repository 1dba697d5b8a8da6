#include "particle_comparison.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "sample_stats.hpp"
#include "somasim/figures/compose.hpp"
#include "somasim/figures/figure.hpp"
#include "somasim/figures/line_plot.hpp"
#include "somasim/rng.hpp"

namespace somasim::plugins {
namespace {

nlohmann::json number_or_null(double x) {
  return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr);
}

}  // namespace

ParticleComparison::ParticleComparison(const std::vector<int>& sizes, int dims,
                                       const body_schema::NoiseSchedule& schedule,
                                       const body_schema::KdeOptions& kde, std::uint64_t seed,
                                       double reinflate_factor)
    : reinflate_factor_(reinflate_factor) {
  for (std::size_t k = 0; k < sizes.size(); ++k) {
    filters_.push_back(std::make_unique<body_schema::OffsetParticleFilter>(
        dims, sizes[k], schedule, splitmix64(seed + 1 + k), kde));
    records_.push_back({sizes[k], {}, {}, {}});
  }
}

void ParticleComparison::reset() {
  for (auto& f : filters_) f->reset();
}

void ParticleComparison::step(const ScoreFn& score) {
  for (std::size_t k = 0; k < filters_.size(); ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    body_schema::OffsetParticleFilter& f = *filters_[k];
    f.predict();
    const body_schema::FilterUpdate u = f.update(score(f.particles()));
    if (!(u.best_likelihood > 0.0)) f.inflate_sigma(reinflate_factor_);
    records_[k].step_ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
}

std::vector<Eigen::VectorXd> ParticleComparison::estimates() const {
  std::vector<Eigen::VectorXd> out;
  for (const auto& f : filters_) out.push_back(f->estimate());
  return out;
}

void ParticleComparison::record_error(std::size_t k, double error_mm, double error_deg) {
  records_[k].error_mm.push_back(error_mm);
  records_[k].error_deg.push_back(error_deg);
}

nlohmann::json particle_metrics(const std::vector<SizeRecord>& records) {
  nlohmann::json m;
  for (const SizeRecord& r : records) {
    const std::string key = fmt::format("particles_{}_", r.particles);
    const MeanSd mm = mean_sd(r.error_mm), deg = mean_sd(r.error_deg);
    m[key + "estimation_error_mm"] = number_or_null(mm.mean);
    m[key + "estimation_error_mm_sd"] = number_or_null(mm.sd);
    m[key + "estimation_error_deg"] = number_or_null(deg.mean);
    m[key + "estimation_error_deg_sd"] = number_or_null(deg.sd);
    m[key + "step_ms"] = number_or_null(median(r.step_ms));
  }
  return m;
}

void write_particle_figure(const std::vector<SizeRecord>& records,
                           const std::filesystem::path& file) {
  std::vector<SizeRecord> sorted = records;
  std::sort(sorted.begin(), sorted.end(),
            [](const SizeRecord& a, const SizeRecord& b) { return a.particles < b.particles; });
  auto panel = [&](const std::string& title, const std::string& y_label,
                   const std::function<std::vector<double>(const SizeRecord&)>& values,
                   bool with_sd) {
    figures::Series mean, low, high;
    for (const SizeRecord& r : sorted) {
      const MeanSd s = mean_sd(values(r));
      const double x = std::log10(static_cast<double>(r.particles));
      mean.x.push_back(x), low.x.push_back(x), high.x.push_back(x);
      mean.y.push_back(s.mean), low.y.push_back(s.mean - s.sd), high.y.push_back(s.mean + s.sd);
    }
    mean.label = "mean";
    mean.marker = figures::Marker::kCircle;
    low.style = high.style = figures::LineStyle::kDotted;
    low.width_px = high.width_px = 1.0;
    low.color = high.color = mean.color = figures::Color{31, 119, 180};
    if (with_sd) low.label = "mean ± 1 sd";
    figures::LinePlotSpec p;
    p.title = title;
    p.x_label = "number of particles, log10 M";
    p.y_label = y_label;
    p.series = {mean};
    if (with_sd) p.series.insert(p.series.end(), {low, high});
    p.width = 520;
    p.height = 400;
    return figures::render_line_plot(p);
  };
  const auto step_ms = [](const SizeRecord& r) { return std::vector<double>{median(r.step_ms)}; };
  figures::save_figure(
      figures::compose_row(
          {panel(
               "Position", "position error [mm]", [](const SizeRecord& r) { return r.error_mm; },
               true),
           panel(
               "Orientation", "orientation error [°]",
               [](const SizeRecord& r) { return r.error_deg; }, true),
           panel("Cost", "time per filter step, median [ms]", step_ms, false)},
          12,
          "Body schema estimation error and cost against the number of particles (same "
          "movements and images)"),
      file);
}

}  // namespace somasim::plugins
