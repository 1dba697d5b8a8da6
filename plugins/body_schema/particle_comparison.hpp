#pragma once
// The paper's particle study (Table 2, Figs 9–10): further filters of other sizes M run in the
// body_schema_filter node on the same images and encoder readings as its main filter (so all
// sizes see the same movements and the same visual feedback). Per size: the estimation error at
// the evaluated frame of every movement, and the wall time of a filter step.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <vector>

#include <nlohmann/json.hpp>

#include "somasim/body_schema/hypothesis_scorer.hpp"
#include "somasim/body_schema/particle_filter.hpp"

namespace somasim::plugins {

/// Errors and step times of one filter size.
struct SizeRecord {
  int particles = 0;
  std::vector<double> error_mm, error_deg;  ///< estimation error at the evaluated frame
  std::vector<double> step_ms;              ///< wall time of each step [ms]
};

class ParticleComparison {
 public:
  /// One filter per size (>= 1 each), seeded from `seed` and its index; a frame whose
  /// likelihoods are all 0 multiplies a filter's σ_s by `reinflate_factor`.
  ParticleComparison(const std::vector<int>& sizes, int dims,
                     const body_schema::NoiseSchedule& schedule, const body_schema::KdeOptions& kde,
                     std::uint64_t seed, double reinflate_factor);

  bool empty() const { return filters_.empty(); }
  void reset();  ///< a new movement
  /// Likelihoods of all particles (columns, [deg]) on this frame's images.
  using ScoreFn = std::function<std::vector<double>(const Eigen::MatrixXd& particles_deg)>;
  /// One frame of every compared filter: predict, `score`, update.
  void step(const ScoreFn& score);
  /// The estimates β̂ [deg] of the compared filters, in the order of the sizes.
  std::vector<Eigen::VectorXd> estimates() const;
  /// Records the estimation error of compared filter `k` at the evaluated frame.
  void record_error(std::size_t k, double error_mm, double error_deg);
  const std::vector<SizeRecord>& records() const { return records_; }

 private:
  std::vector<std::unique_ptr<body_schema::OffsetParticleFilter>> filters_;
  std::vector<SizeRecord> records_;
  double reinflate_factor_;  // σ_s multiplier after a frame no particle explained
};

/// Metrics per size ("particles_<M>_estimation_error_mm", "_deg", their "_sd",
/// "particles_<M>_step_ms" (median)) for `records` (the main filter's included).
nlohmann::json particle_metrics(const std::vector<SizeRecord>& records);
/// figures/...: estimation error (mm, deg; mean ± sd) and step time against M, log-scaled M.
void write_particle_figure(const std::vector<SizeRecord>& records,
                           const std::filesystem::path& file);

}  // namespace somasim::plugins
