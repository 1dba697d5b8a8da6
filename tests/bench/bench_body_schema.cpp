// The body-schema filter step (issue targets: M = 200 in both eyes <= 100 ms and <= 1.3x the
// bare render + read-back of the same hypotheses; M = 2000 <= 1 s): observation (colour
// segmentation of both eye images), prediction, hypothesis rendering and scoring, update.
// The bare floor is the same hypotheses drawn and read back by a GL HypothesisRenderer with no
// extraction, measured in the same loop so that both see the same machine load. software = 1:
// the filter's tiles drawn by the CPU rasterizer (scorer option `rasterizer: software`) against
// the same GL floor. egl = 1: GL through EGL (a hardware EGL device where the machine has one,
// SOMASIM_EGL_PLATFORM) for both the filter and the floor, instead of OSMesa.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <random>

#include "../core/body_schema/real_arm_views.hpp"
#include "somasim/body_schema/hypothesis_scorer.hpp"
#include "somasim/body_schema/observation.hpp"
#include "somasim/body_schema/oriented_edges.hpp"
#include "somasim/body_schema/particle_filter.hpp"

namespace {

using namespace somasim;
using namespace somasim::body_schema;
namespace support = somasim::body_schema::testing;

void BM_FilterStepOverBareRender(benchmark::State& state) {
  const int particles = static_cast<int>(state.range(0));
  const int workers = static_cast<int>(state.range(1));
  const render::RenderBackend backend =
      state.range(3) != 0 ? render::RenderBackend::kEgl : render::RenderBackend::kOsmesa;
  const Eigen::VectorXd q = support::hand_before_eyes();
  const support::RealEyes eyes = support::look(q, backend);
  const ArmHypothesisModel arm = arm_hypothesis_model(*support::icub(), {"r_hand"}, 8);
  ScorerOptions options;
  options.rasterizer =
      state.range(2) != 0 ? render::Rasterizer::kSoftware : render::Rasterizer::kGl;
  HypothesisScorer scorer(support::icub(), arm, support::arm_dofs(), workers, options, backend);
  render::HypothesisRenderer bare(arm.meshes, workers, backend);
  NoiseSchedule schedule = noise_schedule_preset("paper");
  schedule.jump_fraction = 0.1;  // as configs/body_schema_reaching.yaml
  schedule.jump_sigma_deg = 1.5;
  OffsetParticleFilter filter(7, particles, schedule, 1);
  render::HypothesisBatchOptions floor_options;
  floor_options.extract = false;
  floor_options.margin_px = ScorerOptions{}.margin_px;
  using Clock = std::chrono::steady_clock;
  double step_s = 0.0, floor_s = 0.0;
  for (auto _ : state) {
    const Clock::time_point t0 = Clock::now();
    std::vector<cv::Mat> masks;
    for (const cv::Mat& rgb : eyes.rgb) masks.push_back(segment_colour(rgb, HsvRange{}));
    filter.predict();
    benchmark::DoNotOptimize(
        filter.update(scorer.score(q, filter.particles(), eyes.cameras, masks)));
    const Clock::time_point t1 = Clock::now();
    render::HypothesisBatch batch;
    batch.meshes = {0};
    batch.cameras = eyes.cameras;
    for (Eigen::Index m = 0; m < filter.particles().cols(); ++m)
      batch.hypotheses.push_back(scorer.link_poses(q, filter.particles().col(m)));
    const Clock::time_point t2 = Clock::now();
    benchmark::DoNotOptimize(bare.render(batch, floor_options));
    const Clock::time_point t3 = Clock::now();
    const double s = std::chrono::duration<double>(t1 - t0).count();
    step_s += s;
    floor_s += std::chrono::duration<double>(t3 - t2).count();
    state.SetIterationTime(s);
    if (filter.sigma_deg() < 1.0) filter.reset();  // keep the particles spread as in a movement
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["step_ms"] = 1e3 * step_s / n;
  state.counters["bare_render_ms"] = 1e3 * floor_s / n;
  state.counters["ratio"] = floor_s > 0.0 ? step_s / floor_s : 0.0;
  state.counters["kinematics_ms"] = scorer.timing().kinematics_ms;
  state.counters["compare_ms"] = scorer.timing().compare_ms;
}
BENCHMARK(BM_FilterStepOverBareRender)
    ->ArgNames({"M", "workers", "software", "egl"})
    ->Args({200, 1, 0, 0})
    ->Args({200, 2, 0, 0})
    ->Args({2000, 2, 0, 0})
    ->Args({200, 2, 1, 0})
    ->Args({2000, 2, 1, 0})
    ->Args({200, 2, 0, 1})
    ->Args({2000, 2, 0, 1})
    ->Args({200, 2, 1, 1})
    ->Args({2000, 2, 1, 1})
    ->Args({2000, 8, 0, 1})
    ->Args({2000, 8, 1, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime();

// One edge scoring of M = 200 particles spread 2 deg about the truth, both eyes, the CPU
// rasterizer on 2 workers and the oriented chamfer (w = 40 px), as body_schema_edges.yaml: the
// outer contour only (inner 0), with the inner contours (inner 1) or with their creases too
// (inner 2), side by side.
void BM_EdgeScoring(benchmark::State& state) {
  const bool inner = state.range(0) != 0;
  const Eigen::VectorXd q = support::hand_before_eyes();
  const support::RealEyes eyes = support::look(q);
  std::vector<cv::Mat> observations;
  for (const cv::Mat& rgb : eyes.rgb) observations.push_back(oriented_edge_map(rgb));
  ScorerOptions options;
  options.kind = LikelihoodKind::kEdges;
  options.edge_lambda = 25.0 / 255.0;
  options.edge_orientation_weight = 40.0;
  options.rasterizer = render::Rasterizer::kSoftware;
  options.inner_contours = inner;
  options.crease_contours = state.range(0) == 2;
  HypothesisScorer scorer(support::icub(),
                          arm_hypothesis_model(*support::icub(), {"r_hand"}, 8, inner),
                          support::arm_dofs(), 2, options);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 2.0);
  Eigen::MatrixXd particles(7, 200);
  for (Eigen::Index m = 0; m < particles.cols(); ++m)
    for (Eigen::Index j = 0; j < 7; ++j)
      particles(j, m) = support::true_offsets_deg()[j] + noise(rng);
  double render_ms = 0.0, compare_ms = 0.0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(scorer.score(q, particles, eyes.cameras, observations));
    render_ms += scorer.timing().render_ms;
    compare_ms += scorer.timing().compare_ms;
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["render_ms"] = render_ms / n;
  state.counters["compare_ms"] = compare_ms / n;
}
BENCHMARK(BM_EdgeScoring)->ArgName("inner")->DenseRange(0, 2)->Unit(benchmark::kMillisecond);

// The estimate's KDE (the argmax of ω_i + α/M Σ_m ω_m K(β_i, β_m)) over M particles spread as a
// filter's mid-movement cloud (7 offsets, σ 2°): what the exhaustive O(M²) estimate costs as M
// grows, and the screened one (KdeOptions: S = 512 draws, 2 × 64 candidates scored exactly).
// `same_pick` is 1 where the screened pick is the exhaustive one, `score_ratio` the screened
// pick's exact score over the best.
// Weights uniform at random (no relation to position: the screen's hardest case) or, `peaked`,
// a Gaussian likelihood of width 2° around a point 1.5° from the cloud's centre (as images give).
Eigen::MatrixXd kde_cloud(int m, bool peaked, Eigen::VectorXd& weights) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, 2.0);
  Eigen::MatrixXd p(7, m);
  for (Eigen::Index k = 0; k < p.size(); ++k) p.data()[k] = noise(rng);
  weights =
      Eigen::VectorXd::NullaryExpr(m, [&] { return std::uniform_real_distribution<>(0, 1)(rng); });
  if (peaked) {
    const Eigen::VectorXd truth = Eigen::VectorXd::Constant(7, 1.5 / std::sqrt(7.0));
    for (int i = 0; i < m; ++i) weights[i] = std::exp(-0.125 * (p.col(i) - truth).squaredNorm());
  }
  weights /= weights.sum();
  return p;
}

void BM_KdeArgmax(benchmark::State& state) {
  Eigen::VectorXd w;
  const Eigen::MatrixXd p = kde_cloud(static_cast<int>(state.range(0)), state.range(3) != 0, w);
  const auto threads = static_cast<int>(state.range(1));
  KdeOptions exhaustive;
  exhaustive.exact_max_particles = std::numeric_limits<int>::max();
  KdeOptions kde = exhaustive;
  if (state.range(2) != 0) kde.exact_max_particles = 1;
  for (auto _ : state) benchmark::DoNotOptimize(kde_argmax(p, w, kde, threads));
  if (state.range(2) != 0) {
    const int pick = kde_argmax(p, w, kde, threads);
    const int best = kde_argmax(p, w, exhaustive, threads);
    state.counters["same_pick"] = pick == best ? 1.0 : 0.0;
    state.counters["score_ratio"] = kde_score(p, w, kde, pick) / kde_score(p, w, kde, best);
  }
}
BENCHMARK(BM_KdeArgmax)
    ->ArgNames({"M", "threads", "screened", "peaked"})
    ->Args({200, 1, 0, 0})
    ->Args({2000, 1, 0, 0})
    ->Args({2000, 2, 0, 0})
    ->Args({2000, 1, 1, 0})
    ->Args({10000, 1, 0, 0})
    ->Args({10000, 2, 0, 0})
    ->Args({10000, 1, 1, 0})
    ->Args({10000, 2, 1, 0})
    ->Args({10000, 1, 1, 1})
    ->Args({10000, 2, 1, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
