// Benchmarks of somasim_pps: activation queries and one learning event (4,000 taxels, 80
// buffered samples), each against a naive same-run baseline.
#include <cmath>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>
#include <Eigen/Geometry>

#include "somasim/pps/body_part_learner.hpp"

using namespace somasim::pps;

namespace {

TaxelMap random_map() {
  std::mt19937 rng(1);
  std::uniform_int_distribution<int> c(0, 50);
  std::vector<TaxelMap::Count> pos(32), neg(32);
  for (int k = 0; k < 32; ++k) {
    pos[k] = c(rng);
    neg[k] = c(rng);
  }
  return TaxelMap(GridSpec::code(), ParzenSpec::code(), pos, neg);
}

std::vector<Eigen::Vector2d> random_queries() {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> d(-0.1, 0.2), t(0.0, 1.2);
  std::vector<Eigen::Vector2d> q(4096);
  for (auto& x : q) x = Eigen::Vector2d(d(rng), t(rng));
  return q;
}

void BM_ActivationFast(benchmark::State& state) {
  const TaxelMap m = random_map();
  const auto q = random_queries();
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& x = q[i++ & 4095];
    benchmark::DoNotOptimize(m.activation(x.x(), x.y()));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ActivationFast);

void BM_ActivationNaive32Exp(benchmark::State& state) {
  const TaxelMap m = random_map();
  const auto q = random_queries();
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& x = q[i++ & 4095];
    benchmark::DoNotOptimize(m.activation_naive(x.x(), x.y()));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ActivationNaive32Exp);

constexpr int kTaxels = 4000;
constexpr int kSamples = 80;

std::vector<TaxelInfo> patch() {
  // A 0.2 m x 0.2 m skin patch with slightly tilted normals (link frame).
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.1, 0.1), tilt(-0.3, 0.3);
  std::vector<TaxelInfo> t(kTaxels);
  for (int k = 0; k < kTaxels; ++k)
    t[k] = TaxelInfo{k, TaxelPose{Eigen::Vector3d(u(rng), u(rng), 0.0),
                                  Eigen::Vector3d(tilt(rng), tilt(rng), 1.0).normalized()}};
  return t;
}

std::vector<StimulusSample> trajectory() {
  // Approach from 0.25 m above the patch to contact in 4 s (80 samples at 50 ms).
  std::vector<StimulusSample> s(kSamples);
  for (int i = 0; i < kSamples; ++i) {
    const double z = 0.25 - 0.25 * (i + 1) / kSamples;
    s[i] = StimulusSample{0.05 * i, Stimulus{Eigen::Vector3d(0.01, -0.02, z + 0.02),
                                             Eigen::Vector3d(0, 0, -0.0625), 0.02}};
  }
  return s;
}

void BM_LearningEvent(benchmark::State& state) {
  BodyPartLearner l("patch", patch(), LearnerParams::code());
  const auto traj = trajectory();
  const std::vector<int> touched = {0, 1, 2};
  const Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  std::size_t counted = 0;
  for (auto _ : state) {
    state.PauseTiming();
    for (const auto& s : traj) l.push_stimulus(s);
    state.ResumeTiming();
    const LearningStats st = l.on_contact(pose, touched);
    counted = st.positives + st.negatives;
  }
  state.counters["samples_counted"] = static_cast<double>(counted);
}
BENCHMARK(BM_LearningEvent)->Unit(benchmark::kMillisecond);

// Naive baseline: an Eigen::Isometry3d per taxel, inverse transform per sample, a heap-allocated
// per-sample record, the RF test with tan() each time, and a normaliser refresh per sample.
void BM_LearningEventNaive(benchmark::State& state) {
  const auto taxels = patch();
  const auto traj = trajectory();
  const ReceptiveField rf = ReceptiveField::code();
  std::vector<TaxelMap> maps(kTaxels, TaxelMap(GridSpec::code(), ParzenSpec::code()));
  std::size_t counted = 0;
  for (auto _ : state) {
    counted = 0;
    for (int k = 0; k < kTaxels; ++k) {
      Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
      frame.linear() = taxel_rotation(taxels[k].pose_link.normal);
      frame.translation() = taxels[k].pose_link.position;
      const Eigen::Isometry3d inv = frame.inverse();
      const bool positive = k < 3;
      for (const auto& s : traj) {
        std::vector<Eigen::Vector3d> pv;  // allocation per sample
        pv.push_back(inv * s.stimulus.position - Eigen::Vector3d(0, 0, s.stimulus.radius));
        pv.push_back(inv.linear() * s.stimulus.velocity);
        if (!in_receptive_field(pv[0], rf)) continue;
        const DTtc dt = compute_d_ttc(pv[0], pv[1], TtcDefinition::kSigned);
        if (dt.valid && maps[k].add_sample(dt.d, dt.ttc, positive)) ++counted;
      }
    }
  }
  state.counters["samples_counted"] = static_cast<double>(counted);
}
BENCHMARK(BM_LearningEventNaive)->Unit(benchmark::kMillisecond);

}  // namespace
