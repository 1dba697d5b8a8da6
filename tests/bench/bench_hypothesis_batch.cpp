// One batch of 200 forearm + hand hypotheses in both eyes (320 x 240, iCub intrinsics) through
// HypothesisRenderer with W = 1 and 2 workers, beside baselines in the same run (and the
// software rasterizer beside GL, BM_SoftwareOverGl; occluders beside none, BM_OccludersOverPlain):
//   - the bare floor: the same geometry, tiles and single read-back per worker with no
//     silhouette or contour extraction (HypothesisBatchOptions::extract = false); the issue's
//     target is a batch <= 1.3 x this floor and <= 50 ms;
//   - one full SceneRenderer render + id read-back per hypothesis and eye.
// egl = 1: the same through EGL (a hardware EGL device where the machine has one,
// SOMASIM_EGL_PLATFORM) instead of OSMesa.
// llvmpipe's own threads per context: set LP_NUM_THREADS in the environment of the run.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>

#include "somasim/render/context.hpp"
#include "somasim/render/hypothesis_batch.hpp"
#include "somasim/render/scene_renderer.hpp"

using namespace somasim::render;

namespace {

constexpr int kHypotheses = 200;

Camera eye(const std::string& name, double y) {
  Camera c;
  c.name = name;
  c.intrinsics = {320, 240, 257.34, 257.34, 160.0, 120.0, 0.02, 5.0};
  Eigen::Matrix3d r;
  r.col(0) = -Eigen::Vector3d::UnitY();
  r.col(1) = -Eigen::Vector3d::UnitZ();
  r.col(2) = Eigen::Vector3d::UnitX();
  c.pose_root.linear() = r;
  c.pose_root.translation() = Eigen::Vector3d(0.0, y, 0.0);
  return c;
}

// Forearm cylinder, palm box, thumb box and two finger cylinders: 232 triangles.
std::vector<TriangleMesh> arm_meshes() {
  return {tessellate_cylinder(0.025, 0.16, 16), tessellate_box(Eigen::Vector3d(0.07, 0.025, 0.08)),
          tessellate_box(Eigen::Vector3d(0.015, 0.015, 0.04)), tessellate_cylinder(0.008, 0.05, 8),
          tessellate_cylinder(0.008, 0.05, 8)};
}

HypothesisBatch arm_batch() {
  HypothesisBatch batch;
  batch.meshes = {0, 1, 2, 3, 4};
  batch.cameras = {eye("left_eye", 0.034), eye("right_eye", -0.034)};
  for (int k = 0; k < kHypotheses; ++k) {
    // Joint-offset-like perturbations of a forearm held 0.35 m in front of the eyes.
    const double a = 0.05 * std::sin(0.37 * k), b = 0.05 * std::cos(0.23 * k);
    Eigen::Isometry3d forearm = Eigen::Isometry3d::Identity();
    forearm.translation() = Eigen::Vector3d(0.35, 0.02 + 0.2 * a, -0.05 + 0.2 * b);
    forearm.linear() = (Eigen::AngleAxisd(0.9 + a, Eigen::Vector3d::UnitY()) *
                        Eigen::AngleAxisd(-0.4 + b, Eigen::Vector3d::UnitX()))
                           .toRotationMatrix();
    Eigen::Isometry3d hand = forearm;
    hand.translate(Eigen::Vector3d(0.0, 0.0, 0.12));
    hand.rotate(Eigen::AngleAxisd(3.0 * a, Eigen::Vector3d::UnitX()));
    Eigen::Isometry3d thumb = hand, finger1 = hand, finger2 = hand;
    thumb.translate(Eigen::Vector3d(0.04, 0.0, 0.0));
    thumb.rotate(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY()));
    finger1.translate(Eigen::Vector3d(-0.02, 0.0, 0.065));
    finger2.translate(Eigen::Vector3d(0.015, 0.0, 0.065));
    batch.hypotheses.push_back({forearm, hand, thumb, finger1, finger2});
  }
  return batch;
}

RenderBackend backend_arg(std::int64_t egl) {
  return egl != 0 ? RenderBackend::kEgl : RenderBackend::kOsmesa;
}

void BM_HypothesisBatch(benchmark::State& state) {
  HypothesisRenderer renderer(arm_meshes(), static_cast<int>(state.range(0)),
                              backend_arg(state.range(2)));
  const HypothesisBatch batch = arm_batch();
  HypothesisBatchOptions options;
  options.contour = state.range(1) != 0;
  for (auto _ : state) benchmark::DoNotOptimize(renderer.render(batch, options));
  const HypothesisBatchResult result = renderer.render(batch, options);
  state.counters["hypotheses/s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * kHypotheses, benchmark::Counter::kIsRate);
  state.counters["views/s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * kHypotheses * 2, benchmark::Counter::kIsRate);
  state.counters["roi_w"] = result.cameras[0].roi.width;
  state.counters["roi_h"] = result.cameras[0].roi.height;
}
BENCHMARK(BM_HypothesisBatch)
    ->ArgNames({"workers", "contour", "egl"})
    ->Args({1, 0, 0})
    ->Args({1, 1, 0})
    ->Args({2, 0, 0})
    ->Args({2, 1, 0})
    ->Args({2, 0, 1})
    ->Args({2, 1, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Bare floor: the same batch drawn and read back, nothing extracted (every tile left empty).
void BM_HypothesisBatchBareFloor(benchmark::State& state) {
  HypothesisRenderer renderer(arm_meshes(), static_cast<int>(state.range(0)),
                              backend_arg(state.range(1)));
  const HypothesisBatch batch = arm_batch();
  HypothesisBatchOptions options;
  options.extract = false;
  for (auto _ : state) benchmark::DoNotOptimize(renderer.render(batch, options));
  state.counters["hypotheses/s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * kHypotheses, benchmark::Counter::kIsRate);
  state.counters["views/s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * kHypotheses * 2, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_HypothesisBatchBareFloor)
    ->ArgNames({"workers", "egl"})
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({2, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The batch and its bare floor in alternation, on the same renderer: each iteration times one
// batch with extraction (the benchmark's time) and one without; counters floor_ms and ratio =
// batch / floor (sums over all iterations), so that the machine's load falls on both alike.
void BM_HypothesisBatchOverFloor(benchmark::State& state) {
  HypothesisRenderer renderer(arm_meshes(), static_cast<int>(state.range(0)));
  const HypothesisBatch batch = arm_batch();
  HypothesisBatchOptions options, floor;
  options.contour = state.range(1) != 0;
  floor.extract = false;
  using Clock = std::chrono::steady_clock;
  double batch_s = 0.0, floor_s = 0.0;
  for (auto _ : state) {
    const Clock::time_point t0 = Clock::now();
    benchmark::DoNotOptimize(renderer.render(batch, floor));
    const Clock::time_point t1 = Clock::now();
    benchmark::DoNotOptimize(renderer.render(batch, options));
    const Clock::time_point t2 = Clock::now();
    floor_s += std::chrono::duration<double>(t1 - t0).count();
    const double s = std::chrono::duration<double>(t2 - t1).count();
    batch_s += s;
    state.SetIterationTime(s);
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["batch_ms"] = 1e3 * batch_s / n;
  state.counters["floor_ms"] = 1e3 * floor_s / n;
  state.counters["ratio"] = floor_s > 0.0 ? batch_s / floor_s : 0.0;
}
BENCHMARK(BM_HypothesisBatchOverFloor)
    ->ArgNames({"workers", "contour"})
    ->Args({1, 0})
    ->Args({1, 1})
    ->Args({2, 0})
    ->Args({2, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime();

// Times `baseline()` then `measured()` in every iteration, `measured` being the benchmark's
// (manual) time; counters <baseline_name>_ms, <measured_name>_ms and ratio = measured / baseline
// (sums over all iterations).
template <class Baseline, class Measured>
void in_alternation(benchmark::State& state, const std::string& baseline_name, Baseline&& baseline,
                    const std::string& measured_name, Measured&& measured) {
  using Clock = std::chrono::steady_clock;
  double baseline_s = 0.0, measured_s = 0.0;
  for (auto _ : state) {
    const Clock::time_point t0 = Clock::now();
    benchmark::DoNotOptimize(baseline());
    const Clock::time_point t1 = Clock::now();
    benchmark::DoNotOptimize(measured());
    const Clock::time_point t2 = Clock::now();
    baseline_s += std::chrono::duration<double>(t1 - t0).count();
    const double s = std::chrono::duration<double>(t2 - t1).count();
    measured_s += s;
    state.SetIterationTime(s);
  }
  const double n = static_cast<double>(state.iterations());
  state.counters[baseline_name + "_ms"] = 1e3 * baseline_s / n;
  state.counters[measured_name + "_ms"] = 1e3 * measured_s / n;
  state.counters["ratio"] = baseline_s > 0.0 ? measured_s / baseline_s : 0.0;
}

// The software rasterizer against GL (the baseline) in alternation, same batch and worker count:
// each iteration times one GL batch and one software batch (the benchmark's time); counters
// gl_ms, software_ms and ratio = software / GL (sums over all iterations).
void BM_SoftwareOverGl(benchmark::State& state) {
  const int workers = static_cast<int>(state.range(0));
  HypothesisRenderer gl(arm_meshes(), workers);
  HypothesisRenderer software(arm_meshes(), workers, RenderBackend::kOsmesa, Rasterizer::kSoftware);
  const HypothesisBatch batch = arm_batch();
  HypothesisBatchOptions options;
  options.contour = state.range(1) != 0;
  in_alternation(
      state, "gl", [&] { return gl.render(batch, options); }, "software",
      [&] { return software.render(batch, options); });
}
BENCHMARK(BM_SoftwareOverGl)
    ->ArgNames({"workers", "contour"})
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({2, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime();

// Occluders against none (the baseline) in alternation on the software rasterizer with inner
// contours (as body_schema_edges.yaml draws): the same batch with the other hand (a palm box
// and a forearm cylinder, 2 occluder meshes) posed across the hypotheses' forearms, nearer the
// eyes. Counters plain_ms, occluded_ms and ratio = occluded / plain (sums over all iterations).
void BM_OccludersOverPlain(benchmark::State& state) {
  std::vector<TriangleMesh> meshes = arm_meshes();
  meshes.push_back(tessellate_box(Eigen::Vector3d(0.07, 0.025, 0.08)));
  meshes.push_back(tessellate_cylinder(0.025, 0.16, 16));
  HypothesisRenderer software(meshes, static_cast<int>(state.range(0)), RenderBackend::kOsmesa,
                              Rasterizer::kSoftware);
  const HypothesisBatch plain = arm_batch();
  HypothesisBatch occluded = plain;
  Eigen::Isometry3d other_hand = Eigen::Isometry3d::Identity();
  other_hand.translation() = Eigen::Vector3d(0.28, -0.02, -0.04);
  other_hand.linear() = Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitX()).toRotationMatrix();
  Eigen::Isometry3d other_forearm = other_hand;
  other_forearm.translate(Eigen::Vector3d(0.0, 0.0, -0.12));
  occluded.occluders = {{5, other_hand}, {6, other_forearm}};
  HypothesisBatchOptions options;
  options.contour = true;
  options.inner_contours = true;
  in_alternation(
      state, "plain", [&] { return software.render(plain, options); }, "occluded",
      [&] { return software.render(occluded, options); });
}
BENCHMARK(BM_OccludersOverPlain)
    ->ArgNames({"workers"})
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime();

// Baseline: every hypothesis and eye rendered alone at full size by SceneRenderer, reading back
// only the id mask (the "drew no pixel" check off), on one thread.
void BM_FullRenderPerHypothesis(benchmark::State& state) {
  OsmesaContext context;
  SceneRenderer scene(context.gl());
  for (const TriangleMesh& mesh : arm_meshes()) scene.upload(mesh);
  const HypothesisBatch batch = arm_batch();
  RenderOptions options;
  options.read_rgb = options.read_depth = options.check_drawn = false;
  std::vector<DrawItem> items(batch.meshes.size());
  for (auto _ : state) {
    for (const Hypothesis& poses : batch.hypotheses)
      for (const Camera& camera : batch.cameras) {
        for (std::size_t m = 0; m < items.size(); ++m)
          items[m] = {MeshHandle{batch.meshes[m]}, poses[m], Eigen::Vector3f::Ones(),
                      static_cast<std::int32_t>(m + 1)};
        benchmark::DoNotOptimize(scene.render(items, camera, options));
      }
  }
  state.counters["hypotheses/s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * kHypotheses, benchmark::Counter::kIsRate);
  state.counters["views/s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * kHypotheses * 2, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_FullRenderPerHypothesis)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
